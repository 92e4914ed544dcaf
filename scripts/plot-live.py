#!/usr/bin/env python3
"""Drawn against felt index contact over one reach-and-stop of the live desktop path (issue 25).

usage: plot-live.py DEFAULT.rec LATEST.rec OUT.png
The recordings are `vt_live --path desktop` runs (default pose sampling, and `--sampling latest`):
D records give where each displayed frame drew the index fingertip and when it was shown; C
records give the contact point each tick played (u along the grating plate: x = (u - 0.5) * 0.2 m),
felt one output latency (the simulated glove's 1 ms report period) after its tick.
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PLATE_M = 0.2
FELT_LATENCY_NS = 1_000_000
INDEX = 1


def read(path):
    drawn, felt, poses = [], [], []
    for line in open(path):
        f = line.split()
        if f[0] == "D":
            drawn.append((int(f[1]), float(f[4 + 3 * INDEX])))
        elif f[0] == "C" and int(f[2]) == INDEX and f[3] == "1":
            felt.append((int(f[1]) + FELT_LATENCY_NS, (float(f[6]) - 0.5) * PLATE_M))
        elif f[0] == "P":
            poses.append(int(f[1]))
    return poses[0], drawn, felt


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    fig, axes = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    # The fast re-touch reach: 10 cm in 0.375 s from 6.2 s of the motion, then still.
    window = (6.05, 7.0)
    for ax, path, label in zip(axes, sys.argv[1:3], ["predict (default)", "latest pose (baseline)"]):
        t0, drawn, felt = read(path)
        dt = [((t - t0) * 1e-9, x * 1000) for t, x in drawn if window[0] <= (t - t0) * 1e-9 <= window[1]]
        ft = [((t - t0) * 1e-9, x * 1000) for t, x in felt if window[0] <= (t - t0) * 1e-9 <= window[1]]
        ax.plot([t for t, _ in ft], [x for _, x in ft], color="tab:blue", lw=1.2, label="felt contact (each tick, at its felt moment)")
        ax.step([t for t, _ in dt], [x for _, x in dt], where="post", color="tab:red", lw=1.2,
                label="drawn fingertip (each frame, from its display time)")
        ax.plot([t for t, _ in dt], [x for _, x in dt], "o", color="tab:red", ms=3)
        ax.set_title(label)
        ax.set_ylabel("x on the plate (mm)")
        ax.grid(alpha=0.3)
        ax.legend(loc="lower right", fontsize=8)
    axes[1].set_xlabel("time since the run started (s)")
    fig.suptitle("A 0.5 m/s reach and stop, desktop preview under Xvfb on lavapipe", fontsize=11)
    fig.tight_layout()
    fig.savefig(sys.argv[3], dpi=110)


if __name__ == "__main__":
    main()
