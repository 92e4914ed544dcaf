#!/usr/bin/env python3
"""Round trip for tools/pixel2taxel_import.py: a synthetic scan is written in the published
raw layout (pickled .npy dicts, mm calibration CSV, pixel TXT, crop corners, perspective
.npy; rows shuffled and one duplicated), imported back, and both scans must give the same
statistics through `vtouching acquire`.

    python3 tools/test_pixel2taxel_import.py PATH/TO/vtouching WORK_DIR
Exit 77 (skipped) when numpy is missing.
"""
import csv
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


def run(*cmd):
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"FAILED: {' '.join(cmd)}\n{result.stdout}{result.stderr}")
    return result.stdout


def read_rows(path):
    with open(path) as f:
        return [[float(v) for v in row] for row in list(csv.reader(f))[1:] if row]


def make_raw(scan_dir, raw):
    with open(os.path.join(scan_dir, "scan.json")) as f:
        scan = json.load(f)
    obj = os.path.join(raw, "1")
    os.makedirs(os.path.join(obj, "sensor_data"))
    with open(os.path.join(raw, "name.json"), "w") as f:
        json.dump({"1": scan["name"]}, f)
    shutil.copyfile(os.path.join(scan_dir, scan["photo"]), os.path.join(obj, "img_0001.png"))
    calib = read_rows(os.path.join(scan_dir, scan["calibration"]))
    with open(os.path.join(obj, "positions_1.csv"), "w") as f:
        f.write("x,y\n")
        for x, y, _, _ in calib:
            f.write(f"{x * 1e3:.4f},{y * 1e3:.4f}\n")  # millimetres: exercises --calib-unit auto
    with open(os.path.join(obj, "select_points_0001.txt"), "w") as f:
        for _, _, u, v in calib:
            f.write(f"{u},{v}\n")
    x, y, w, h = scan["crop"]
    with open(os.path.join(obj, "transform_to_crop.txt"), "w") as f:
        f.write(f"{x},{y};{x + w},{y}\n{x},{y + h};{x + w},{y + h}\n")
    np.save(os.path.join(raw, "PerspectiveTransform2.npy"), np.array(scan["perspective"]["matrix"]).reshape(3, 3))
    rng = np.random.default_rng(5)
    for k, line in enumerate(scan["lines"]):
        acc = np.array(read_rows(os.path.join(scan_dir, line["accel"])))
        pos = np.array(read_rows(os.path.join(scan_dir, line["robot"])))
        acc[:, 1] += scan["accel_clock_offset_s"]  # the raw data has both logs on one clock
        acc = np.vstack([acc, acc[10:11]])  # a duplicated sample
        rng.shuffle(acc)
        rng.shuffle(pos)
        data = {"acc_sensor_data_list": acc.tolist(), "aubo_pos_data_list": pos.tolist()}
        np.save(os.path.join(obj, "sensor_data", f"{k:02d}.npy"), np.array(data, dtype=object), allow_pickle=True)
    return scan["name"]


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
