#!/usr/bin/env python3
"""Compile CPU seconds per target from ninja's own logs (.ninja_log: start and end ms of each step).
Usage: ninja-sums.py BUILD_DIR [BUILD_DIR...]: one column per build, one row per target."""
import collections, sys

def sums(build_dir):
    out = collections.Counter()
    for line in open(f"{build_dir}/.ninja_log"):
        if line.startswith("#"):
            continue
        start, end, _, path, _ = line.rstrip("\n").split("\t")
        target = path.split("/CMakeFiles/")[1].split("/")[0].removesuffix(".dir") if "/CMakeFiles/" in path else "(links, shaders)"
        out[target] += (int(end) - int(start)) / 1000
    return out

columns = [sums(d) for d in sys.argv[1:]]
print("target\t" + "\t".join(sys.argv[1:]))
for target in sorted(set().union(*columns), key=lambda t: -columns[0].get(t, 0)):
    print(target + "\t" + "\t".join("%.1f" % c.get(target, 0) for c in columns))
print("TOTAL\t" + "\t".join("%.1f" % sum(c.values()) for c in columns))
