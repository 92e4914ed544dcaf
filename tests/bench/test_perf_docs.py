#!/usr/bin/env python3
"""scripts/perf-docs.py fails when a doc's table no longer matches its stored runs.

Usage: test_perf_docs.py PERF_DOCS_SCRIPT. Builds a scratch repository (results/ + a doc) and
checks: a regenerated doc passes; a changed figure, a missing figure, a missing run and an
incomplete results file each fail with a message naming the cause.
"""
import json
import os
import subprocess
import sys
import tempfile

SCRIPT = sys.argv[1]


def run(root, *args):
    p = subprocess.run([sys.executable, SCRIPT, "--root", root, *args], capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def results(root, name, figures, **overrides):
    doc = {"suite": "demo", "command": f"vt_bench demo --json --out results/{name}", "exit_code": 0,
           "date": "2026-01-31T12:00:00Z", "wall_s": 1.0,
           "load_average": {"before": [0.5, 0.4, 0.3], "after": [0.6, 0.4, 0.3]},
           "source": {"commit": "0123456789abcdef0123456789abcdef01234567", "dirty": False},
           "build": {"type": "Release", "compiler": "gcc"},
           "machine": {"cpu_model": "Test CPU", "cpu_flags": ["sse2"], "logical_cores": 2, "cores_available": 2},
           "figures": figures}
    doc.update(overrides)
    with open(os.path.join(root, "results", name), "w") as f:
        json.dump(doc, f)


def expect(condition, what):
    if not condition:
        print(f"FAIL: {what}")
        sys.exit(1)


with tempfile.TemporaryDirectory() as root:
    os.mkdir(os.path.join(root, "results"))
    results(root, "demo-a.json", {"ratio": 1.02, "nested": {"ms": 20.5}, "met": True})
    # Written elsewhere and then stored: the doc's command must name the stored file.
    results(root, "demo-b.json", {"ratio": 0.98, "nested": {"ms": 21.5}, "met": True},
            command="vt_bench demo --json --out /tmp/scratch/run5.json")
    doc = os.path.join(root, "DOC.md")
    with open(doc, "w") as f:
        f.write("# Demo\n\n<!-- results: results/demo-*.json\ncolumns: figure | value\n"
                "row: ratio | {ratio:.2f}x\nrow: time | {nested/ms:.1f} ms\nrow: goal met | {met}\n-->\n"
                "stale text\n<!-- end results -->\n\nProse stays.\n")
    code, out = run(root, "--check", doc)
    expect(code == 1 and "differ" in out, f"a stale block must fail the check:\n{out}")
    code, out = run(root, "--write", doc)
    expect(code == 0, f"--write must succeed:\n{out}")
    text = open(doc).read()
    expect("| ratio | 0.98 - 1.02x |" in text, f"the range over both runs:\n{text}")
    expect("| time | 20.5 - 21.5 ms |" in text and "| goal met | yes |" in text, text)
    expect("`build/bench/vt_bench demo --json --out results/demo-a.json`" in text, "the reproducing command")
    expect("--out results/demo-b.json`" in text and "/tmp/scratch" not in text,
           f"the command of a run stored after names the stored file:\n{text}")
    expect("Prose stays." in text and "stale text" not in text, "only the block is rewritten")
    code, out = run(root, "--check", doc)
    expect(code == 0, f"a regenerated doc passes:\n{out}")

    def fails_with(doc_text, message, what):
        with open(doc, "w") as f:
            f.write(doc_text)
        code, out = run(root, "--check", doc)
        expect(code == 1 and message in out, f"{what} must fail the check:\n{out}")

    fails_with(text.replace("0.98 - 1.02x", "1.07 - 1.12x"), "1.07 - 1.12x", "a figure edited by hand")
    results(root, "demo-c.json", {"ratio": 0.78, "nested": {"ms": 20.0}, "met": False})
    fails_with(text, "0.78 - 1.02x", "a new run not regenerated")
    os.remove(os.path.join(root, "results", "demo-c.json"))
    fails_with(text.replace("{nested/ms:.1f}", "{nested/us:.1f}"), "no figure 'nested/us'", "a figure the runs lack")
    fails_with(text.replace("results/demo-*.json", "results/gone-*.json"), "no stored run matches", "a block without runs")

    partial = os.path.join(root, "results", "demo-b.json")
    data = json.load(open(partial))
    del data["machine"]["cpu_model"]
    json.dump(data, open(partial, "w"))
    fails_with(text, "lacks 'machine/cpu_model'", "an incomplete results file")
    code, out = run(root, "--validate", partial)
    expect(code == 1, "--validate must fail on it")

print("PASS: the docs check catches changed, missing and unbacked figures")
