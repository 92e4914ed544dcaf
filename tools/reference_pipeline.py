#!/usr/bin/env python3
"""The paper's pixel-to-taxel method (Sec. III; docs/scan-format.md, "The method"), re-run on a
scan directory the way a research script would: numpy only, logs read with np.loadtxt (or np.load
for .npy logs), one line and one pass at a time.

  reference_pipeline.py SCAN_DIR CALIBRATION_JSON --out MAP.npy [--style numpy|authors] [--quiet]

It was the yardstick of issue 18; `vt_bench acquire` now times it as a second, labelled column
(`reference_authors`, `reference_numpy`) beside the authors' own pipeline (tools/run_pixel2taxel.py),
and tests/acquisition/test_reference_pipeline.py keeps its map equal to ours.

What it does, per scan line and pass: the constant-velocity window Ybar +- w l (l = max - min of
the pass), the nearest robot samples i1, i2, a least-squares line Y = m t + b over them
(np.polyfit), the accelerometer samples j1 = nearest(t_i1) + 1 .. j2 = nearest(t_i2) - 1 placed at
m t + b, V = |a - gravity|; the passes pooled and sorted, V averaged in whole bins over the
measured span (n = round(span / taxel size)); each taxel drawn into a photo-sized map as the
projected segment widened by stretch_px to both sides (pixels covered by several taxels take the
mean); the perspective warp (bilinear over covered neighbours) and the crop of scan.json.

What it does NOT re-implement: Zhang's camera calibration (homography, Levenberg-Marquardt).
The world -> pixel mapping is taken from our NAME_calibration.json (fx, fy, cx, cy, k1, k2, rvec,
t_m), so the comparison covers everything after the calibration. Nor does it load or warp the
photo, write PNGs or a preview: `vtouching acquire` does all of those on top, so timing the two
end to end flatters this script, not ours.

Two styles compute the same map (tests/acquisition/test_reference_pipeline.py checks both):

  --style numpy (default): a competent numpy script, as above; logs read with np.loadtxt, per-pass
    boolean masks, np.polyfit, vectorised placement and np.bincount whole bins.
  --style authors: the computational structure of the authors' published pipeline (Pixel2Taxel,
    Process_Code/src/DataProcess.py and run.py), in our own code: each log is brought into
    their in-memory form, a list of per-sample rows of Python floats, and then into an array
    with np.array(rows) as their loader does (see load_log_rows); each pass is cut out of the
    line with boolean masks; the window ends come from a full argsort of |y - target|; the
    accelerometer samples are placed by a Python loop over every sample that builds one
    [t, y, a] list each, made into an array afterwards; the pooled samples are argsort-ed; and
    every bin is a Python iteration doing np.where over all of the line's samples and a mean.
    The segment end points are listed point by point in a Python loop before projection.
    Rasterising (a Python iteration per taxel drawing with numpy), warp and crop are the numpy
    style's: the authors draw with cv2.rectangle and warp with cv2.warpPerspective (OpenCV is
    not a dependency here), so the drawing is slower here than theirs (a few tenths of a second
    on a 100 x 100 mm scan) and the warp about as fast.

Output: MAP.npy, float32 (height x width) in g, 0 where no taxel, the same grid as our
NAME_map.f32.
"""
import argparse
import json
import os
import sys
import time

import numpy as np


DEFAULTS = {"window_w": 0.45, "accel_trim": [1, 1], "taxel_size_m": 0.001, "stretch_px": 3.0, "accel_axis": "z",
            "gravity_g": 1.0, "accel_clock_offset_s": 0.0}


def load_log(path):
    if path.endswith(".npy"):
        return np.load(path, allow_pickle=False)
    return np.loadtxt(path, delimiter=",", skiprows=1)


def load_log_rows(path):
    """The authors' loading: their logs hold each sample as a list of Python floats (a pickled
    dict of such lists) and their loader turns the lists into an array with np.array(rows). Our
    logs are CSV or plain .npy, so the rows are parsed in C (np.loadtxt / np.load) and turned into
    that list form first; the three steps cost about what their np.load + np.array costs on the
    same samples (docs/PERFORMANCE.md, "Acquisition")."""
    rows = load_log(path).tolist()
    return np.array(rows)


def rodrigues(rvec):
    rvec = np.asarray(rvec, dtype=float)
    angle = np.linalg.norm(rvec)
    if angle < 1e-15:
        return np.eye(3)
    k = rvec / angle
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def project(cam, X, Y):
    """World (X, Y, 0) in metres -> distorted pixel (u, v), arrays."""
    R = rodrigues(cam["rvec"])
    t = np.asarray(cam["t_m"])
    P = np.stack([X, Y, np.zeros_like(X)])
    C = R @ P + t[:, None]
    x, y = C[0] / C[2], C[1] / C[2]
    r2 = x * x + y * y
    d = 1 + cam["k1"] * r2 + cam["k2"] * r2 * r2
    return cam["fx"] * x * d + cam["cx"], cam["fy"] * y * d + cam["cy"]


def line_params(axis, cfg):
    """The robot log's along/across columns for a scan axis, and the method's settings for a line."""
    along, across = (3, 2) if axis == 1 else (2, 3)
    trim0, trim1 = cfg["accel_trim"]
    return along, across, cfg["window_w"], trim0, trim1, cfg["accel_clock_offset_s"], 2 + "xyz".index(cfg["accel_axis"])


def process_line(robot, accel, axis, cfg):
    """One line: per-pass window, fit and placement; pooled whole-bin taxels (across, y0, y1, V)."""
    along, across, w, trim0, trim1, offset, acol = line_params(axis, cfg)
    positions, values, xs = [], [], []
    for p in range(int(robot[:, 0].max()) + 1):
        r = robot[robot[:, 0] == p]
        a = accel[accel[:, 0] == p]
        y, t = r[:, along], r[:, 1]
        ybar, l = y.mean(), y.max() - y.min()
        ia = np.argmin(np.abs(y - (ybar - w * l)))
        ib = np.argmin(np.abs(y - (ybar + w * l)))
        i1, i2 = min(ia, ib), max(ia, ib)
        m, b = np.polyfit(t[i1:i2 + 1], y[i1:i2 + 1], 1)
        ta = a[:, 1] + offset
        j1 = np.argmin(np.abs(ta - t[i1])) + trim0
        j2 = np.argmin(np.abs(ta - t[i2])) - trim1
        positions.append(m * ta[j1:j2 + 1] + b)
        values.append(np.abs(a[j1:j2 + 1, acol] - cfg["gravity_g"]))
        xs.append(r[:, across].mean())
    pos = np.concatenate(positions)
    val = np.concatenate(values)
    order = np.argsort(pos, kind="stable")
    pos, val = pos[order], val[order]
    y0, span = pos[0], pos[-1] - pos[0]
    bins = int(max(1.0, np.round(span / cfg["taxel_size_m"])))
    width = span / bins if span > 0 else cfg["taxel_size_m"]
    k = np.minimum(bins - 1, ((pos - y0) / width).astype(np.int64))
    sums = np.bincount(k, weights=val, minlength=bins)
    counts = np.bincount(k, minlength=bins)
    keep = counts > 0
    lo = y0 + np.arange(bins) * width
    hi = lo + width
    hi[-1] = y0 + span
    return np.mean(xs), lo[keep], hi[keep], sums[keep] / counts[keep]


def process_line_authors(robot, accel, axis, cfg):
    """process_line in the authors' structure: per-sample and per-bin Python loops."""
    along, across, w, trim0, trim1, offset, acol = line_params(axis, cfg)
    samples, xs = [], []
    for p in range(int(robot[:, 0].max()) + 1):
        r = robot[robot[:, 0] == p]
        a = accel[accel[:, 0] == p]
        y, t = r[:, along], r[:, 1]
        ybar, l = y.mean(), y.max() - y.min()
        ia = np.argsort(np.abs(y - (ybar - w * l)), kind="stable")[0]
        ib = np.argsort(np.abs(y - (ybar + w * l)), kind="stable")[0]
        i1, i2 = min(ia, ib), max(ia, ib)
        m, b = np.polyfit(t[i1:i2 + 1], y[i1:i2 + 1], 1)
        ta = a[:, 1] + offset
        j1 = np.argmin(np.abs(ta - t[i1])) + trim0
        j2 = np.argmin(np.abs(ta - t[i2])) - trim1
        placed = []
        for j in range(j1, j2 + 1):
            tj = ta[j]
            placed.append([tj, m * tj + b, a[j, acol]])  # time, position, acceleration
        samples.append(np.array(placed)[:, 1:])
        xs.append(r[:, across].mean())
    pooled = np.concatenate(samples, axis=0)
    pooled = pooled[np.argsort(pooled[:, 0], kind="stable")]
    pos, val = pooled[:, 0], np.abs(pooled[:, 1] - cfg["gravity_g"])
    y0, span = pos[0], pos[-1] - pos[0]
    bins = int(max(1.0, np.round(span / cfg["taxel_size_m"])))
    width = span / bins if span > 0 else cfg["taxel_size_m"]
    q = (pos - y0) / width  # a sample's bin is floor(q), the last bin closed
    lo, hi, v = [], [], []
    for k in range(bins):
        idx = np.where((q >= k) & ((q < k + 1) | (k == bins - 1)))[0]
        if len(idx) == 0:
            continue
        lo.append(y0 + k * width)
        hi.append(y0 + span if k == bins - 1 else y0 + k * width + width)
        v.append(val[idx].mean())
    return np.mean(xs), np.array(lo), np.array(hi), np.array(v)


def segment_ends_authors(taxels, cam):
    """Projected segment ends, the world points built one by one as the authors do."""
    ends = []
    for axis, x, lo, hi, v in taxels:
        points = []
        for y in np.stack([lo, hi], axis=1).reshape(-1):
            points.append([x, y] if axis == 1 else [y, x])
        points = np.array(points)
        u, vv = project(cam, points[:, 0], points[:, 1])
        ends.append((u[0::2], vv[0::2], u[1::2], vv[1::2], v))
    return ends


def segment_ends(taxels, cam):
    ends = []
    for axis, x, lo, hi, v in taxels:
        if axis == 1:
            u0, v0 = project(cam, np.full_like(lo, x), lo)
            u1, v1 = project(cam, np.full_like(hi, x), hi)
        else:
            u0, v0 = project(cam, lo, np.full_like(lo, x))
            u1, v1 = project(cam, hi, np.full_like(hi, x))
        ends.append((u0, v0, u1, v1, v))
    return ends


def rasterise(ends, width, height, stretch):
    total = np.zeros((height, width))
    count = np.zeros((height, width), dtype=np.int64)
    for u0, v0, u1, v1, v in ends:
        for i in range(len(v)):
            dx, dy = u1[i] - u0[i], v1[i] - v0[i]
            length = np.hypot(dx, dy)
            if not length > 1e-9:
                continue
            ex, ey = dx / length, dy / length
            pad = stretch + 1
            xa = max(0, int(np.floor(min(u0[i], u1[i]) - pad)))
            xb = min(width - 1, int(np.ceil(max(u0[i], u1[i]) + pad)))
            ya = max(0, int(np.floor(min(v0[i], v1[i]) - pad)))
            yb = min(height - 1, int(np.ceil(max(v0[i], v1[i]) + pad)))
            if xa > xb or ya > yb:
                continue
            gx, gy = np.meshgrid(np.arange(xa, xb + 1) - u0[i], np.arange(ya, yb + 1) - v0[i])
            s = gx * ex + gy * ey
            n = gx * -ey + gy * ex
            inside = (s >= 0) & (s < length) & (np.abs(n) <= stretch)
            total[ya:yb + 1, xa:xb + 1][inside] += v[i]
            count[ya:yb + 1, xa:xb + 1][inside] += 1
    covered = count > 0
    value = np.zeros((height, width))
    value[covered] = total[covered] / count[covered]
    return value, covered


def warp(value, covered, H, width, height):
    """Bilinear inverse warp; a pixel is covered when most of its interpolation weight is."""
    Hinv = np.linalg.inv(np.asarray(H, dtype=float).reshape(3, 3))
    gx, gy = np.meshgrid(np.arange(width, dtype=float), np.arange(height, dtype=float))
    w = Hinv[2, 0] * gx + Hinv[2, 1] * gy + Hinv[2, 2]
    sx = (Hinv[0, 0] * gx + Hinv[0, 1] * gy + Hinv[0, 2]) / w
    sy = (Hinv[1, 0] * gx + Hinv[1, 1] * gy + Hinv[1, 2]) / w
    fx, fy = np.floor(sx), np.floor(sy)
    ax, ay = sx - fx, sy - fy
    x0, y0 = fx.astype(np.int64), fy.astype(np.int64)
    sh, sw = value.shape
    acc, weight, total = np.zeros((height, width)), np.zeros((height, width)), np.zeros((height, width))
    for dx, dy, wt in ((0, 0, (1 - ax) * (1 - ay)), (1, 0, ax * (1 - ay)), (0, 1, (1 - ax) * ay), (1, 1, ax * ay)):
        xs, ys = x0 + dx, y0 + dy
        ok = (wt > 0) & (xs >= 0) & (ys >= 0) & (xs < sw) & (ys < sh)
        xs, ys = np.where(ok, xs, 0), np.where(ok, ys, 0)
        wt = np.where(ok, wt, 0.0)
        total += wt
        c = covered[ys, xs] & ok
        acc += np.where(c, wt * value[ys, xs], 0.0)
        weight += np.where(c, wt, 0.0)
    out_cov = (weight > 0) & (weight >= 0.5 * total)
    out = np.zeros((height, width))
    out[out_cov] = acc[out_cov] / weight[out_cov]
    return out, out_cov


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scan")
    ap.add_argument("calibration", help="NAME_calibration.json written by `vtouching acquire` (world -> pixel)")
    ap.add_argument("--out", required=True, help="MAP.npy: float32 map in g")
    ap.add_argument("--style", choices=["numpy", "authors"], default="numpy",
                    help="numpy: a vectorised script; authors: the authors' per-sample and per-bin loops")
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args()
    start = time.perf_counter()

    doc = json.load(open(os.path.join(args.scan, "scan.json")))
    cfg = {k: doc.get(k, v) for k, v in DEFAULTS.items()}
    calib = json.load(open(args.calibration))
    cam = dict(calib["intrinsics"], **calib["distortion"], rvec=calib["rvec"], t_m=calib["t_m"])
    # The photo's size from its PNG header (IHDR: width and height, big-endian, at bytes 16..24).
    with open(os.path.join(args.scan, doc["photo"]), "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"reference_pipeline: {doc['photo']}: only PNG photos are supported")
    width, height = int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")

    main_axis = 1 if any(l.get("axis", "y") == "y" for l in doc["lines"]) else 0
    authors = args.style == "authors"
    read = load_log_rows if authors else load_log
    process = process_line_authors if authors else process_line
    taxels = []
    for line in doc["lines"]:
        axis = 0 if line.get("axis", "y") == "x" else 1
        if axis != main_axis:
            continue  # the across map is not part of the paper's method
        robot = read(os.path.join(args.scan, line["robot"]))
        accel = read(os.path.join(args.scan, line["accel"]))
        taxels.append((axis, *process(robot, accel, axis, cfg)))

    ends = segment_ends_authors(taxels, cam) if authors else segment_ends(taxels, cam)
    value, covered = rasterise(ends, width, height, float(cfg["stretch_px"]))
    if "perspective" in doc:
        size = doc["perspective"].get("size", [0, 0])
        w, h = (size[0] or width), (size[1] or height)
        value, covered = warp(value, covered, doc["perspective"]["matrix"], w, h)
    if "crop" in doc:
        x, y, cw, ch = doc["crop"]
        value, covered = value[y:y + ch, x:x + cw], covered[y:y + ch, x:x + cw]
    value = np.where(covered, value, 0.0).astype(np.float32)
    np.save(args.out, value)
    if not args.quiet:
        n = sum(len(t[4]) for t in taxels)
        print(f"reference_pipeline: {len(taxels)} lines, {n} taxels, {value.shape[1]}x{value.shape[0]} map, "
              f"{covered.mean():.3f} covered -> {args.out} ({time.perf_counter() - start:.2f} s)")


if __name__ == "__main__":
    main()
