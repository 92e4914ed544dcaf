#!/usr/bin/env python3
"""The authors' own pipeline, live: a synthetic scan with their camera orientation is written in
their raw layout (tools/pixel2taxel_export.py), run through their unchanged run.py
(tools/run_pixel2taxel.py), imported back with the camera their code calibrates
(tools/pixel2taxel_import.py --authors-camera), and `vtouching acquire --compat reference` must
draw their map: >= 99.9 % of the 8-bit pixels equal. Skipped (exit 77) without a checkout of
wmtlab/Pixel2Taxel in VT_PIXEL2TAXEL_DIR or without numpy and cv2 (python3-numpy, python3-opencv).
Usage: authors_pipeline.py VTOUCHING WORK_DIR
"""
import os
import shutil
import sys

from acquire_steps import run

try:
    import cv2
    import numpy as np
except ImportError:
    print("SKIPPED: numpy or cv2 missing (python3-numpy, python3-opencv)")
    sys.exit(77)

TOOLS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools")


def main():
    exe, work = sys.argv[1], sys.argv[2]
    checkout = os.environ.get("VT_PIXEL2TAXEL_DIR", "")
    if not os.path.isfile(os.path.join(checkout, "Process_Code", "run.py")):
        print("SKIPPED: set VT_PIXEL2TAXEL_DIR to a checkout of wmtlab/Pixel2Taxel")
        sys.exit(77)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    scan, raw, imported, dataset = (os.path.join(work, d) for d in ("scan", "raw", "imported", "dataset"))
    run(exe, "acquire", "--synthetic", "pattern_board", "--authors-rig", "--length-mm", "60", "--lines", "15",
        "--out", scan, "--quiet")
    run(sys.executable, os.path.join(TOOLS, "pixel2taxel_export.py"), scan, "--out", raw)
    run(sys.executable, os.path.join(TOOLS, "run_pixel2taxel.py"), checkout, raw, "1")
    run(sys.executable, os.path.join(TOOLS, "pixel2taxel_import.py"), raw, "--all", "--out", imported, "--authors-camera")
    run(exe, "acquire", os.path.join(imported, "pattern_board"), "--compat", "reference", "--out", dataset, "--quiet",
        "--no-waveforms")
    theirs = cv2.imread(os.path.join(raw, "1", "out", "pattern_board", "pattern_board_acc.png"), cv2.IMREAD_UNCHANGED)
    ours = cv2.imread(os.path.join(dataset, "pattern_board", "pattern_board_acc.png"), cv2.IMREAD_UNCHANGED)
    theirs = theirs[..., 0] if theirs.ndim == 3 else theirs
    assert theirs.shape == ours.shape, f"map sizes differ: theirs {theirs.shape}, ours {ours.shape}"
    equal = float(np.mean(theirs == ours))
    covered = float(np.mean(theirs > 0))
    print(f"--compat reference: {100 * equal:.3f} % of the 8-bit pixels equal to the authors' run.py "
          f"(their map covers {100 * covered:.1f} %)")
    assert covered > 0.5, "the authors' map is (nearly) empty"
    assert equal >= 0.999, f"only {100 * equal:.3f} % of the pixels equal (goal 99.9 %)"
    print("PASS")


if __name__ == "__main__":
    main()
