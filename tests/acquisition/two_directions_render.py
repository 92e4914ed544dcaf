#!/usr/bin/env python3
"""Two scan directions at run time, through the real binary: a synthetic scan with lines along Y
and along X (`acquire --synthetic --both-directions`) is acquired into a dataset, and an offscreen
`render --trajectory` slides the index fingertip over it first along the image's u axis (the main
map's scan direction), then along v (the across map's). traces.csv's across_weight must follow the
fingertip's direction of motion: near 0 on the first slide, near 1 on the second; and the slide
across is felt (its map values and intensities are not zero: the across map was once normalised
with the main map's range, all of its values below that range's minimum, and played silence).
Usage: two_directions_render.py VTOUCHING WORK_DIR
"""
import json
import os
import statistics
import sys

from acquire_steps import run, synthetic_dataset


def main():
    exe, work = sys.argv[1], sys.argv[2]
    _, dataset = synthetic_dataset(exe, work, "plastic_grid", "--length-mm", "50", "--lines", "25",
                                   "--both-directions", "--scale", "2")
    meta = json.load(open(os.path.join(dataset, "plastic_grid", "plastic_grid_map.json")))
    along, across = meta["scan_direction_uv"], meta["across"]["scan_direction_uv"]
    assert abs(along[0]) > 0.99 and abs(across[1]) > 0.99, f"scan directions {along} / {across}: expected u / v"

    # One plate, centred on the table (top at y = 4 mm). Palm positions: the index fingertip lies
    # about 4 cm left of and 13 cm ahead of the palm (docs/trajectory-format.md); press ~2 mm.
    tip = (-0.04, -0.13)
    press, lift = 0.010, 0.030
    keys = [(0.0, -0.018, 0.0, lift), (0.3, -0.018, 0.0, press), (1.8, 0.018, 0.0, press), (2.1, 0.018, 0.0, lift),  # along u
            (2.4, 0.0, -0.018, lift), (2.7, 0.0, -0.018, press), (4.2, 0.0, 0.018, press), (4.5, 0.0, 0.018, lift)]  # along v
    trajectory = os.path.join(work, "cross.csv")
    with open(trajectory, "w") as f:
        f.write("t_s,x_m,y_m,z_m\n")
        for t, x, z, y in keys:
            f.write(f"{t},{x - tip[0]:.4f},{y:.4f},{z - tip[1]:.4f}\n")
    out = os.path.join(work, "render")
    run(exe, "render", "--trajectory", trajectory, "--out", out, "--fps", "0", "--dataset", dataset)

    slides = {"u": [], "v": []}
    felt = []  # (map value, intensity) sliding across
    with open(os.path.join(out, "traces.csv")) as f:
        header = f.readline().strip().split(",")
        assert header[-1] == "across_weight", header
        for row in f:
            r = dict(zip(header, row.strip().split(",")))
            if r["finger"] != "index" or r["contact"] != "1" or r["material"] != "plastic_grid":
                continue
            t = float(r["time_s"])
            if 0.6 < t < 1.5:
                slides["u"].append(float(r["across_weight"]))
            elif 3.0 < t < 3.9:
                slides["v"].append(float(r["across_weight"]))
                felt.append((float(r["map_value"]), float(r["intensity"])))
    for name, weights in slides.items():
        assert len(weights) > 300, f"the index fingertip touched the object on only {len(weights)} ticks of the {name} slide"
    u, v = statistics.median(slides["u"]), statistics.median(slides["v"])
    print(f"across_weight median: {u:.3f} sliding along u (the main scan direction), {v:.3f} along v "
          f"({len(slides['u'])} and {len(slides['v'])} ticks)")
    assert u < 0.1, f"sliding along the main scan direction gave across_weight {u:.3f} (expected near 0)"
    assert v > 0.9, f"sliding across it gave across_weight {v:.3f} (expected near 1)"
    values = statistics.median(m for m, _ in felt)
    loud = sum(1 for _, i in felt if i > 0) / len(felt)
    print(f"sliding across: median map value {values:.4f}, intensity above 0 on {100 * loud:.0f} % of the ticks")
    assert values > 0, "sliding across the grid plays silence (map value 0)"
    assert loud > 0.9, f"sliding across the grid is felt on only {100 * loud:.0f} % of the ticks"
    print("PASS")


if __name__ == "__main__":
    main()
