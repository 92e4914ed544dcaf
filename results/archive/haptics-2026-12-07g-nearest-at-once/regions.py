# The AVX2 walk of rays-1m-instr.txt (5079640, gcc 12.2, as compiled there) in parts, by address range:
#   python3 results/archive/haptics-2026-12-07g-nearest-at-once/regions.py results/archive/haptics-2026-12-07g-nearest-at-once/rays-1m-instr.txt
# The ranges were read off the disassembly (which branch leads where); they fit this binary only.
import re, sys
rows = [(int(m.group(2), 16), float(m.group(1))) for m in
        (re.match(r"^\s+([\d.]+)\s+([0-9a-f]+):", l) for l in open(sys.argv[1])) if m]
parts = [("entry", 0x2ceb0, 0x2cfd3), ("re-broadcast after a pop", 0x2cfdb, 0x2d046), ("node tests", 0x2d04f, 0x2d107),
         ("one or two children", 0x2d10d, 0x2d22e), ("leaf set-up", 0x2d236, 0x2d37c), ("leaf steps", 0x2d380, 0x2d5a2),
         ("hits in a step", 0x2d5a8, 0x2d73f), ("leaf end", 0x2d745, 0x2d774), ("pop loop and exit", 0x2d77d, 0x2d804),
         ("three or more children", 0x2dfcc, 0x2e300), ("one child is a leaf", 0x2df77, 0x2dfcb)]
for name, lo, hi in parts:
    print(f"{name:26s} {sum(c for a, c in rows if lo <= a <= hi):7.1f}")
