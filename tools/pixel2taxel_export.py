#!/usr/bin/env python3
"""Writes a V-Touching scan directory in the authors' published raw layout (wmtlab/Pixel2Taxel
"Raw_Data"), the inverse of tools/pixel2taxel_import.py, so that the authors' own pipeline
(Process_Code/run.py) can run on the project's scans (synthetic ones with ground truth).

    python3 tools/pixel2taxel_export.py SCAN_DIR --out RAW_ROOT [--index N]

RAW_ROOT/name.json, RAW_ROOT/PerspectiveTransform{1,2}.npy (scan.json's perspective matrix) and
RAW_ROOT/N/: img_0001.png (the photo), positions_1.csv and select_points_0001.txt (the
calibration points, metres like the logs), transform_to_crop.txt (scan.json's crop as four
corners) and sensor_data/NN.npy, one pickled dict per scan line (sorted names in scan order):
"aubo_pos_data_list" (robot rows pass, t_s, x, y, z) and "acc_sensor_data_list" (accelerometer
rows pass, t_s, ax, ay, az, with the clock offset added: the raw data has one clock), each a list
of per-sample lists of floats.

What the raw layout cannot say is refused: lines along X (their code scans along Y only), a scan
without a perspective matrix or crop (their run.py always warps and crops), a photo that is not
PNG or JPEG. Their warp writes a (width, 2 x height) image before the crop, whatever size scan.json
gives; the crop must lie inside it.

Needs only Debian's python3-numpy.
"""
import argparse
import json
import os
import shutil
import sys

import numpy as np

from pixel2taxel_import import ImportError_, image_size


def read_log(path):
    """A CSV log (optional header line) or an .npy log of our scan format, as an N x 5 array."""
    if path.endswith(".npy"):
        return np.load(path, allow_pickle=False).astype(np.float64).reshape(-1, 5)
    with open(path) as f:
        first = f.readline()
        skip = 1 if first[:1].isalpha() else 0
    return np.loadtxt(path, delimiter=",", skiprows=skip, ndmin=2)


def export_scan(scan_dir, root, index=1):
    """Writes the raw layout of SCAN_DIR into ROOT as object `index`; returns the object name."""
    with open(os.path.join(scan_dir, "scan.json")) as f:
        scan = json.load(f)
    if "perspective" not in scan or "crop" not in scan:
        raise ImportError_(f"{scan_dir}/scan.json: the authors' run.py always warps and crops; "
                           "a scan without 'perspective' and 'crop' has no raw-layout equivalent")
    if any(line.get("axis", "y") != "y" for line in scan["lines"]):
        raise ImportError_(f"{scan_dir}/scan.json: lines along X have no raw-layout equivalent (their code scans along Y)")
    photo = os.path.join(scan_dir, scan["photo"])
    width, height = image_size(photo)
    x, y, w, h = scan["crop"]
    if x + w > width or y + h > 2 * height:
        raise ImportError_(f"{scan_dir}/scan.json: crop {scan['crop']} lies outside the authors' {width}x{2 * height} warp")
    folder = os.path.join(root, str(index))
    os.makedirs(os.path.join(folder, "sensor_data"), exist_ok=True)
    names = {}
    if os.path.exists(os.path.join(root, "name.json")):
        with open(os.path.join(root, "name.json")) as f:
            names = json.load(f)
    names[str(index)] = scan["name"]
    with open(os.path.join(root, "name.json"), "w") as f:
        json.dump(names, f)
    matrix = np.array(scan["perspective"]["matrix"], dtype=np.float64).reshape(3, 3)
    for file in ("PerspectiveTransform1.npy", "PerspectiveTransform2.npy"):  # run.py picks one by index
        np.save(os.path.join(root, file), matrix)
    shutil.copyfile(photo, os.path.join(folder, "img_0001" + os.path.splitext(photo)[1].lower()))
    calibration = read_calibration_rows(os.path.join(scan_dir, scan["calibration"]))
    with open(os.path.join(folder, "positions_1.csv"), "w") as f:
        f.write("x,y\n")
        for xm, ym, _, _ in calibration:
            f.write(f"{xm!r},{ym!r}\n")
    with open(os.path.join(folder, "select_points_0001.txt"), "w") as f:
        for _, _, u, v in calibration:
            f.write(f"{u!r},{v!r}\n")
    with open(os.path.join(folder, "transform_to_crop.txt"), "w") as f:
        f.write(f"{x},{y};{x + w},{y}\n{x},{y + h};{x + w},{y + h}\n")
    offset = float(scan.get("accel_clock_offset_s", 0.0))
    digits = max(2, len(str(len(scan["lines"]) - 1)))
    for k, line in enumerate(scan["lines"]):
        robot = read_log(os.path.join(scan_dir, line["robot"]))
        accel = read_log(os.path.join(scan_dir, line["accel"]))
        accel[:, 1] += offset
        data = {"acc_sensor_data_list": accel.tolist(), "aubo_pos_data_list": robot.tolist()}
        np.save(os.path.join(folder, "sensor_data", f"{k:0{digits}d}.npy"), np.array(data, dtype=object), allow_pickle=True)
    return scan["name"]


def read_calibration_rows(path):
    """Calibration CSV rows x_m, y_m, u_px, v_px (optional header line)."""
    with open(path) as f:
        return [tuple(float(v) for v in row.split(",")) for row in f.read().splitlines()
                if row.strip() and not row[:1].isalpha()]


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scan", help="a scan directory (docs/scan-format.md)")
    parser.add_argument("--out", required=True, help="the raw-data root to write (Raw_Data)")
    parser.add_argument("--index", type=int, default=1, help="object index (folder name), default 1")
    args = parser.parse_args(argv)
    try:
        name = export_scan(args.scan, args.out, args.index)
    except (ImportError_, OSError, KeyError, ValueError) as e:
        print(f"pixel2taxel_export: error: {e}", file=sys.stderr)
        return 1
    print(f"{name}: raw layout -> {os.path.join(args.out, str(args.index))}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
