#!/usr/bin/env python3
"""Runs the authors' own pipeline (wmtlab/Pixel2Taxel, Process_Code/run.py) unchanged, without a
display, on a raw-data root (theirs, or one written by tools/pixel2taxel_export.py):

    /usr/bin/python3 tools/run_pixel2taxel.py PIXEL2TAXEL_CHECKOUT RAW_ROOT [INDEX]

Their run.py shows every intermediate image with cv2.imshow and waits for a key press
(cv2.waitKey(0)) before it goes on; here those two (and cv2.destroyAllWindows) do nothing, so
it runs start to end unattended. Everything else is theirs as shipped: their loader of pickled
per-line dicts, calibration, binning, drawing, warp, crop and PNG writing, in this process.

os.listdir returns names sorted: the order in which run.py draws the scan lines (later lines
overwrite earlier ones where they overlap) is the directory's order, which on Linux depends on
the file system; on the authors' Windows machine (their README's paths) NTFS lists names sorted.

The checkout is not part of this repository: fetch it yourself (read their licence). Needs
Debian's python3-numpy and python3-opencv (scripts/install-deps.sh). Output: RAW_ROOT/INDEX/out/.
"""
import os
import runpy
import sys


def main(argv):
    if len(argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    checkout, root = argv[0], argv[1]
    index = argv[2] if len(argv) == 3 else "1"
    script = os.path.join(checkout, "Process_Code", "run.py")
    if not os.path.isfile(script):
        print(f"run_pixel2taxel: error: {script}: not found (expected a wmtlab/Pixel2Taxel checkout)", file=sys.stderr)
        return 1
    import cv2  # noqa: E402  (after the argument check: a missing checkout is reported first)

    def nothing(*_args, **_kwargs):
        return -1

    cv2.imshow = nothing
    cv2.waitKey = nothing
    cv2.destroyAllWindows = nothing
    listdir = os.listdir
    os.listdir = lambda path=".": sorted(listdir(path))
    sys.path.insert(0, os.path.dirname(script))
    sys.argv = [script, "--root", root, "--index", index]
    runpy.run_path(script, run_name="__main__")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
