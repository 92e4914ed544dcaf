#!/usr/bin/env python3
"""tools/reference_pipeline.py (the paper's method re-run in Python, the yardstick of `vt_bench
acquire`) keeps giving the map `vtouching acquire` gives, on a small synthetic scan, in both of its
styles (--style numpy, vectorised; --style authors, the authors' per-sample and per-bin loops).

Tolerance: the two maps cover the same pixels except at most 0.2 % of them (a pixel centre within
rounding of a taxel's edge, or a warp weight within rounding of one half, may go either way), and
on the pixels both cover the values agree within 1e-4 g on 99.9 % of them and within 2 % of the
map's range everywhere (the C++ accumulates in float32, numpy in float64; np.polyfit and our
centred fit round differently).
Usage: test_reference_pipeline.py VTOUCHING WORK_DIR   (exit 77: numpy missing)
"""
import json
import os
import sys

from acquire_steps import run, synthetic_dataset

try:
    import numpy as np
except ImportError:
    print("SKIPPED: numpy is not installed (python3-numpy)")
    sys.exit(77)

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "tools", "reference_pipeline.py")


def compare(style, ours, theirs):
    """Asserts the tolerance above between our map and the `style` reference's."""
    assert theirs.shape == ours.shape, f"--style {style}: map sizes differ: {theirs.shape} vs ours {ours.shape}"

    a, b = ours != 0, theirs != 0
    differ = np.count_nonzero(a != b) / a.size
    both = a & b
    diff = np.abs(ours[both].astype(float) - theirs[both])
    span = float(ours[a].max() - ours[a].min())
    p999 = float(np.quantile(diff, 0.999))
    print(f"--style {style}: coverage {a.mean():.3f} (ours) / {b.mean():.3f} (reference), differing pixels {100 * differ:.3f} %; "
          f"|V diff| p99.9 {p999:.2e} g, max {diff.max():.2e} g (map range {span:.3f} g)")
    assert a.mean() > 0.5, f"our map covers only {a.mean():.3f} of the image"
    assert differ <= 0.002, f"--style {style}: {100 * differ:.3f} % of pixels covered by one map only (limit 0.2 %)"
    assert p999 <= 1e-4, f"--style {style}: 99.9th percentile of |V diff| {p999:.2e} g (limit 1e-4 g)"
    assert diff.max() <= 0.02 * span, f"--style {style}: largest |V diff| {diff.max():.2e} g over 2 % of the range {span:.3f} g"


def main():
    exe, work = sys.argv[1], sys.argv[2]
    scan, dataset = synthetic_dataset(exe, work, "relief_ceramic_tile", "--length-mm", "30", "--lines", "10", "--seed", "5")
    obj = os.path.join(dataset, "relief_ceramic_tile")
    meta = json.load(open(os.path.join(obj, "relief_ceramic_tile_map.json")))
    ours = np.fromfile(os.path.join(obj, "relief_ceramic_tile_map.f32"), dtype="<f4").reshape(meta["height"], meta["width"])
    for style in ("numpy", "authors"):
        out = os.path.join(work, f"reference_map_{style}.npy")
        calibration = os.path.join(obj, "relief_ceramic_tile_calibration.json")
        print(run(sys.executable, SCRIPT, scan, calibration, "--out", out, "--style", style).strip())
        compare(style, ours, np.load(out))
    print("PASS")


if __name__ == "__main__":
    main()
