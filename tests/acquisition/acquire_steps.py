"""Steps the Python acquisition tests share: run a command of the real binary (one failure line
with its stderr tail), and turn a fresh synthetic scan into a dataset."""
import os
import shutil
import subprocess
import sys


def run(*cmd):
    """Runs `cmd` (VT_LOG=warn) and returns its stdout; exits the test with the command's stderr on failure."""
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=dict(os.environ, VT_LOG="warn"))
    if p.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {p.returncode}: {p.stderr[-800:]}")
    return p.stdout


def synthetic_dataset(exe, work, kind, *scan_options):
    """Empties `work`, simulates a `kind` scan with `scan_options` into work/scan and acquires it
    (no waveforms) into work/dataset; returns (scan, dataset)."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    scan, dataset = os.path.join(work, "scan"), os.path.join(work, "dataset")
    run(exe, "acquire", "--synthetic", kind, "--out", scan, *scan_options, "--quiet")
    run(exe, "acquire", scan, "--out", dataset, "--no-waveforms", "--quiet")
    return scan, dataset
