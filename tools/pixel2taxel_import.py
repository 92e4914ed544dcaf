#!/usr/bin/env python3
"""Converts the published Pixel2Taxel raw data into V-Touching scan directories.

Raw layout (wmtlab/Pixel2Taxel, "Raw_Data"):
    ROOT/name.json                     {"1": "smooth_ceramic_tile", ...}
    ROOT/PerspectiveTransform1.npy     3x3, used by objects 2 and 3 (as the authors' run.py)
    ROOT/PerspectiveTransform2.npy     3x3, used by the others
    ROOT/N/img_*.png|jpg               the photo
    ROOT/N/pos*.csv                    calibration: header, then robot x, y per marked point
    ROOT/N/select_points_*.txt         calibration: pixel u, v per marked point (same order)
    ROOT/N/*crop.txt                   crop corners "x,y;x,y\\nx,y;x,y" (TL, TR / BL, BR)
    ROOT/N/sensor_data/*.npy           one file per scan line: a pickled dict with
        "acc_sensor_data_list": rows (pass, t_s, ax, ay, az, ...) in g
        "aubo_pos_data_list":   rows (pass, t_s, X, Y, Z) in m

Output: docs/scan-format.md (scan.json, photo, calibration.csv, lines/line_NNN_{robot,accel}.csv).

    python3 tools/pixel2taxel_import.py ROOT --index 1 --out scans/
    python3 tools/pixel2taxel_import.py ROOT --all --out scans/

Needs only Debian's python3-numpy. The raw .npy files hold pickled dicts, so they are
loaded with allow_pickle=True: only import raw data from a source you trust.
"""
import argparse
import csv
import json
import os
import shutil
import struct
import sys

import numpy as np


class ImportError_(Exception):
    """A problem with the raw data, naming the file."""


def image_size(path):
    """(width, height) of a PNG or JPEG, read from its header."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] == b"\x89PNG\r\n\x1a\n":
        return struct.unpack(">II", data[16:24])
    if data[:2] == b"\xff\xd8":
        i = 2
        while i + 9 < len(data):
            if data[i] != 0xFF:
                i += 1
                continue
            marker = data[i + 1]
            length = struct.unpack(">H", data[i + 2:i + 4])[0]
            if marker in (0xC0, 0xC1, 0xC2, 0xC3, 0xC5, 0xC6, 0xC7, 0xC9, 0xCA, 0xCB, 0xCD, 0xCE, 0xCF):
                h, w = struct.unpack(">HH", data[i + 5:i + 9])
                return w, h
            i += 2 + length
    raise ImportError_(f"{path}: not a PNG or JPEG image")


def find_file(folder, predicate, what):
    for name in sorted(os.listdir(folder)):
        if predicate(name):
            return os.path.join(folder, name)
    raise ImportError_(f"{folder}: no {what} found")


def read_crop(path):
    """The authors' crop: the rectangle inside the four marked corners -> [x, y, w, h]."""
    with open(path) as f:
        r = [int(float(v)) for v in f.read().replace(";", ",").replace("\n", ",").split(",") if v.strip()]
    if len(r) != 8:
        raise ImportError_(f"{path}: expected 8 numbers (four corners), got {len(r)}")
    left, top = max(r[0], r[4]), max(r[1], r[3])
    right, bottom = min(r[2], r[6]), min(r[5], r[7])
    if right <= left or bottom <= top:
        raise ImportError_(f"{path}: the corners do not enclose a rectangle")
    return [left, top, right - left, bottom - top]


def read_calibration(pos_path, pix_path, unit):
    """Marked points (x_m, y_m, u_px, v_px): robot coordinates converted to metres."""
    with open(pos_path) as f:
        rows = list(csv.reader(f))[1:]
    world = [(float(r[0]), float(r[1])) for r in rows if r]
    with open(pix_path) as f:
        pixels = [tuple(float(v) for v in line.strip().split(",")[:2]) for line in f if line.strip()]
    if len(world) != len(pixels):
        raise ImportError_(f"{pos_path} has {len(world)} points but {pix_path} has {len(pixels)}")
    scale = 1e-3 if calibration_unit(world, unit) == "mm" else 1.0
    return [(x * scale, y * scale, u, v) for (x, y), (u, v) in zip(world, pixels)]


def authors_camera(pos_path, pix_path, unit):
    """The camera the authors' run.py calibrates (their CaliBrateCamera: cv2.calibrateCamera on the
    marked points as float32, for a 1920 x 1080 image, OpenCV's five distortion terms), as
    scan.json's "camera" in metres. Needs Debian's python3-opencv."""
    import cv2  # only this option needs it
    with open(pos_path) as f:
        rows = [(float(r[0]), float(r[1])) for r in list(csv.reader(f))[1:] if r]
    world = np.array([[x, y, 0] for x, y in rows], dtype=np.float32)
    with open(pix_path) as f:
        pixels = np.array([[float(v) for v in line.strip().split(",")[:2]] for line in f if line.strip()], dtype=np.float32)
    _, k, dist, rvecs, tvecs = cv2.calibrateCamera([world], [pixels], (1920, 1080), None, None)
    scale = 1e-3 if calibration_unit(rows, unit) == "mm" else 1.0
    return {"fx": float(k[0, 0]), "fy": float(k[1, 1]), "cx": float(k[0, 2]), "cy": float(k[1, 2]),
            "distortion": [float(v) for v in dist.ravel()[:5]], "rvec": [float(v) for v in rvecs[0].ravel()],
            "t_m": [float(v) * scale for v in tvecs[0].ravel()],
            "comment": f"cv2.calibrateCamera {cv2.__version__} as the authors' CaliBrateCamera calls it"}


def calibration_unit(world, unit):
    """The robot coordinates' unit: as given, or (auto) mm if any |value| > 5."""
    if unit != "auto":
        return unit
    return "mm" if max(abs(v) for p in world for v in p) > 5.0 else "m"


def per_pass_rows(array, source):
    """Rows sorted by (pass, time), duplicate timestamps dropped; returns rows and drop count."""
    a = np.asarray(array, dtype=np.float64)
    if a.ndim != 2 or a.shape[1] < 5:
        raise ImportError_(f"{source}: expected rows of at least 5 columns, got shape {a.shape}")
    if not np.all(np.isfinite(a[:, :5])):
        raise ImportError_(f"{source}: NaN or infinite values")
    a = a[np.lexsort((a[:, 1], a[:, 0]))]
    keep = np.ones(len(a), dtype=bool)
    keep[1:] = ~((a[1:, 0] == a[:-1, 0]) & (a[1:, 1] == a[:-1, 1]))
    return a[keep], int((~keep).sum())


def write_log(path, header, rows):
    with open(path, "w") as f:
        f.write(header + "\n")
        for r in rows:
            f.write(f"{int(r[0])},{r[1]:.6f},{r[2]:.7f},{r[3]:.7f},{r[4]:.7f}\n")


def import_object(root, index, out_root, stretch, unit, with_camera=False):
    folder = os.path.join(root, str(index))
    with open(os.path.join(root, "name.json")) as f:
        name = json.load(f)[str(index)]
    out = os.path.join(out_root, name)
    os.makedirs(os.path.join(out, "lines"), exist_ok=True)

    photo = find_file(folder, lambda n: n.startswith("img"), "photo img_*")
    photo_name = "photo" + os.path.splitext(photo)[1].lower()
    shutil.copyfile(photo, os.path.join(out, photo_name))
    width, height = image_size(photo)

    pos_file = find_file(folder, lambda n: n.startswith("pos"), "positions_*.csv")
    pix_file = find_file(folder, lambda n: n.startswith("select_points"), "select_points_*.txt")
    points = read_calibration(pos_file, pix_file, unit)
    with open(os.path.join(out, "calibration.csv"), "w") as f:
        f.write("x_m,y_m,u_px,v_px\n")
        for x, y, u, v in points:
            f.write(f"{x:.7f},{y:.7f},{u:.3f},{v:.3f}\n")

    lines, dropped, passes = [], 0, None
    sensor = os.path.join(folder, "sensor_data")
    for k, file in enumerate(sorted(os.listdir(sensor))):
        source = os.path.join(sensor, file)
        data = np.load(source, allow_pickle=True).item()
        acc, d1 = per_pass_rows(data["acc_sensor_data_list"], source + " acc_sensor_data_list")
        pos, d2 = per_pass_rows(data["aubo_pos_data_list"], source + " aubo_pos_data_list")
        dropped += d1 + d2
        count = int(pos[:, 0].max()) + 1
        if passes is not None and count != passes:
            raise ImportError_(f"{source}: {count} passes, earlier lines have {passes}")
        passes = count
        robot_name, accel_name = f"lines/line_{k:03d}_robot.csv", f"lines/line_{k:03d}_accel.csv"
        write_log(os.path.join(out, robot_name), "pass,t_s,x_m,y_m,z_m", pos[:, :5])
        write_log(os.path.join(out, accel_name), "pass,t_s,ax_g,ay_g,az_g", acc[:, :5])
        lines.append({"robot": robot_name, "accel": accel_name})
    if not lines:
        raise ImportError_(f"{sensor}: no line files")

    matrix_file = "PerspectiveTransform1.npy" if index in (2, 3) else "PerspectiveTransform2.npy"
    matrix = np.load(os.path.join(root, matrix_file)).astype(np.float64).reshape(9)
    crop_file = find_file(folder, lambda n: n.endswith("crop.txt"), "*crop.txt")
    scan = {
        "name": name,
        "photo": photo_name,
        "calibration": "calibration.csv",
        "lines": lines,
        "passes_per_line": passes,
        "window_w": 0.45,
        "accel_trim": [1, 1],
        "taxel_size_m": 0.001,
        "stretch_px": stretch,
        "accel_axis": "z",
        "gravity_g": 1.0,
        "accel_clock_offset_s": 0.0,
        # The authors' warp writes a (width, 2 * height) image before cropping.
        "perspective": {"matrix": matrix.tolist(), "size": [width, 2 * height]},
        "crop": read_crop(crop_file),
        "comment": f"imported from {os.path.abspath(folder)} by tools/pixel2taxel_import.py",
    }
    if with_camera:
        scan["camera"] = authors_camera(pos_file, pix_file, unit)
    with open(os.path.join(out, "scan.json"), "w") as f:
        json.dump(scan, f, indent=2)
        f.write("\n")
    print(f"{name}: {len(lines)} lines x {passes} passes, {len(points)} calibration points"
          f"{f', {dropped} duplicate samples dropped' if dropped else ''} -> {out}")


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("root", help="the Raw_Data folder")
    group = parser.add_mutually_exclusive_group(required=True)
    group.add_argument("--index", type=int, help="object index (folder name) to import")
    group.add_argument("--all", action="store_true", help="import every object listed in name.json")
    parser.add_argument("--out", required=True, help="output folder; each object becomes OUT/NAME")
    parser.add_argument("--stretch", type=float, default=3.0, help="taxel stretch across the line, px (default 3)")
    parser.add_argument("--calib-unit", choices=["auto", "m", "mm"], default="auto",
                        help="unit of the robot coordinates in pos*.csv (auto: mm if any |value| > 5)")
    parser.add_argument("--authors-camera", action="store_true",
                        help="record the camera the authors' code calibrates (cv2.calibrateCamera; needs python3-opencv) "
                             "as scan.json 'camera', for `vtouching acquire --compat reference` to draw their map")
    args = parser.parse_args(argv)
    try:
        with open(os.path.join(args.root, "name.json")) as f:
            indices = sorted(int(k) for k in json.load(f)) if args.all else [args.index]
        for index in indices:
            import_object(args.root, index, args.out, args.stretch, args.calib_unit, args.authors_camera)
    except (ImportError_, OSError, KeyError, ValueError) as e:
        print(f"pixel2taxel_import: error: {e}", file=sys.stderr)
        return 1
    except ImportError as e:  # --authors-camera without OpenCV
        print(f"pixel2taxel_import: error: --authors-camera needs python3-opencv ({e})", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
