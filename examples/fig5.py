#!/usr/bin/env python3
"""The paper's Fig. 5 from a recording, with matplotlib: the touch path drawn over the touched
object's photo (left) beside each finger's vibration intensity over time (right).

  vtouching render --trajectory assets/trajectories/slide.csv --out out/slide --fps 0
  python3 examples/fig5.py out/slide/traces.csv --dataset assets/dataset --out fig5.png

The recording is the traces.csv of `render --trajectory` (read with vtouching.read_traces); the
object is the one touched most (or --object NAME), its photo from the dataset folder.
"""
import argparse
import collections
import sys

import matplotlib

if "matplotlib.pyplot" not in sys.modules and not matplotlib.get_backend().lower().startswith(("qt", "tk", "gtk", "wx", "macosx")):
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import vtouching  # noqa: E402

COLOURS = {"thumb": "tab:purple", "index": "tab:red", "middle": "tab:green", "ring": "tab:blue", "little": "tab:orange",
           "pinky": "tab:orange"}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("traces", help="traces.csv from vtouching render --trajectory")
    parser.add_argument("--dataset", required=True, help="dataset folder holding NAME/NAME.png and NAME_acc.png")
    parser.add_argument("--object", help="object to draw the path over (default: the one touched most)")
    parser.add_argument("--out", required=True, help="output image (.png, .svg, .pdf)")
    args = parser.parse_args(argv)

    fingers = vtouching.read_traces(args.traces)
    touches = collections.Counter()
    for columns in fingers.values():
        for material, contact in zip(columns["material"], columns["contact"]):
            if contact:
                touches[str(material)] += 1
    objects = vtouching.dataset_objects(args.dataset)
    name = args.object or next((m for m, _ in touches.most_common() if m in objects), None)
    if name is None:
        raise vtouching.Error(f"fig5: no object of dataset '{args.dataset}' is touched in '{args.traces}' (give --object)")
    photo = vtouching.open_dataset(args.dataset, name)["photo"]
    height, width = photo.shape[:2]

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2), gridspec_kw={"width_ratios": [width / height, 1.6]})
    left.imshow(photo)
    left.set_title(name.replace("_", " "))
    left.set_axis_off()
    for finger, c in fingers.items():
        on = (c["contact"] == 1) & (c["material"] == name)
        # Map UV: origin bottom-left, v up (the vibration map's convention).
        left.plot(np.where(on, c["u"] * width, np.nan), np.where(on, (1 - c["v"]) * height, np.nan),
                  color=COLOURS.get(finger, "black"), lw=2, label=finger)
        intensity = np.where(c["contact"] == 1, c["intensity"], np.nan)
        right.plot(c["time_s"], intensity, color=COLOURS.get(finger, "black"), lw=1.2, label=finger)
    right.set_ylim(0, 0.8)
    right.set_xlabel("time (s)")
    right.set_ylabel("vibration intensity")
    right.legend(loc="upper right", fontsize=8)
    left.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}: {name}, {len(fingers)} finger(s)")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except vtouching.Error as e:
        print(f"fig5: error: {e}", file=sys.stderr)
        sys.exit(1)
