#!/usr/bin/env python3
"""Round trip for tools/pixel2taxel_export.py and tools/pixel2taxel_import.py: a synthetic scan
is written in the published raw layout (pickled .npy dicts, pixel TXT, crop corners,
perspective .npy; then a mm calibration CSV, rows shuffled and one duplicated), imported back,
and both scans must give the same statistics through `vtouching acquire`.

    python3 tools/test_pixel2taxel_import.py PATH/TO/vtouching WORK_DIR
Exit 77 (skipped) when numpy is missing.
"""
import json
import os
import shutil
import subprocess
import sys

try:
    import numpy as np
except ImportError:
    print("skipped: python3-numpy not installed")
    sys.exit(77)

HERE = os.path.dirname(os.path.abspath(__file__))
IMPORTER = os.path.join(HERE, "pixel2taxel_import.py")
sys.path.insert(0, HERE)
from pixel2taxel_export import export_scan  # noqa: E402


def run(*cmd):
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"FAILED: {' '.join(cmd)}\n{result.stdout}{result.stderr}")
    return result.stdout


def make_raw(scan_dir, raw):
    """The scan in the raw layout (tools/pixel2taxel_export.py), then made as untidy as the
    published files: calibration in millimetres (exercises --calib-unit auto), rows shuffled and
    one accelerometer sample duplicated per line."""
    name = export_scan(scan_dir, raw)
    obj = os.path.join(raw, "1")
    with open(os.path.join(obj, "positions_1.csv")) as f:
        rows = [line.split(",") for line in f.read().splitlines()[1:] if line]
    with open(os.path.join(obj, "positions_1.csv"), "w") as f:
        f.write("x,y\n")
        for x, y in rows:
            f.write(f"{float(x) * 1e3:.4f},{float(y) * 1e3:.4f}\n")
    rng = np.random.default_rng(5)
    sensor = os.path.join(obj, "sensor_data")
    for file in sorted(os.listdir(sensor)):
        path = os.path.join(sensor, file)
        data = np.load(path, allow_pickle=True).item()
        acc, pos = np.array(data["acc_sensor_data_list"]), np.array(data["aubo_pos_data_list"])
        acc = np.vstack([acc, acc[10:11]])  # a duplicated sample
        rng.shuffle(acc)
        rng.shuffle(pos)
        data = {"acc_sensor_data_list": acc.tolist(), "aubo_pos_data_list": pos.tolist()}
        np.save(path, np.array(data, dtype=object), allow_pickle=True)
    return name


def stats(dataset, name):
    with open(os.path.join(dataset, name, name + "_map.json")) as f:
        return json.load(f)["statistics"]


def main():
    vtouching, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    syn, raw, imported = os.path.join(work, "synthetic"), os.path.join(work, "raw"), os.path.join(work, "imported")
    run(vtouching, "acquire", "--synthetic", "plastic_grid", "--out", syn, "--lines", "4", "--length-mm", "20",
        "--photo", "320x240", "--scale", "4", "--quiet")
    name = make_raw(syn, raw)
    out = run(sys.executable, IMPORTER, raw, "--all", "--out", imported)
    assert "4 duplicate samples dropped" in out, out  # one per line
    run(vtouching, "acquire", syn, "--out", os.path.join(work, "ds_a"), "--quiet")
    run(vtouching, "acquire", os.path.join(imported, name), "--out", os.path.join(work, "ds_b"), "--quiet")
    a, b = stats(os.path.join(work, "ds_a"), name), stats(os.path.join(work, "ds_b"), name)
    for key in ("v_scale_g", "v_mean_g", "v_std_g", "taxels"):
        if abs(a[key] - b[key]) > 1e-6 * max(1.0, abs(a[key])):
            sys.exit(f"FAILED: {key} differs: synthetic {a[key]} imported {b[key]}")
    # A broken raw folder gives one clear line and a non-zero exit.
    os.remove(os.path.join(raw, "1", "transform_to_crop.txt"))
    bad = subprocess.run([sys.executable, IMPORTER, raw, "--index", "1", "--out", imported], capture_output=True, text=True)
    assert bad.returncode == 1 and "no *crop.txt found" in bad.stderr, bad.stderr
    print(f"pixel2taxel_import round trip OK ({name}: V_mean {b['v_mean_g']:.4f} g, {b['taxels']} taxels)")


if __name__ == "__main__":
    main()
