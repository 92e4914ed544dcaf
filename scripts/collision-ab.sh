#!/usr/bin/env bash
# Two revisions of the collision library side by side in one process (bench/ab/): the haptics
# suite's scene and queries, in alternating passes; prints the median of the per-round ratios.
#   scripts/collision-ab.sh [--count [--embree] [--lines FILE] [--instr FILE]] REV_A REV_B [--kind rays|batch16|spheres|spheres12|build]
#                           [--slices N] [--queries N] [--rounds N]
# REV: a git revision, or "worktree" for the working tree's collision/ folder, optionally with
# "+FILE": a patch (paths collision/...) applied on top, for changes tried and not committed. Each side is
# compiled with the flags the build uses for the collision library, against this checkout's
# core and scene headers. Needs a configured build (BUILD_DIR, default build) with vt_core,
# vt_scene and vt_bench_results built (scripts/build.sh).
# --count: instead of timing, counts one pass per query with valgrind's cachegrind, side by
# side: instructions, conditional branches and their mispredictions (valgrind's predictor
# model: compare sides with each other only) and misses of an 8 MiB last-level cache; with
# --embree, Embree 3's single-ray / point queries (as vt_bench haptics times them) beside them;
# with --lines, both sides compile with -g and FILE gets side A's counts per source line (two
# passes, cg_annotate), to see where a query's instructions and misses go; with --instr, FILE
# gets side A's collision functions disassembled with each instruction's count per query
# (callgrind, two passes minus one), to see which part of a walk's machine code they are.
# --kind build times (or counts) whole builds of the scene instead, then checks the rays'
# answers of the last builds.
# CXX_B=COMPILER: side B's collision library (and its side of the harness) compiled by another
# compiler with the same options, e.g. CXX_B=clang++ HEAD HEAD: the compilers compared on one tree.
# EXTRA_FLAGS="...": added to both sides' compiles, e.g. "-falign-functions=64 -falign-loops=64" to
# see whether a difference is the code's or where the linker happened to place it.
# Prints one JSON object; timing runs add each side's revision (commit, and whether the working
# tree's collision/ differed from HEAD).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build}
count=0 embree=0 lines= instr=
if [[ ${1:-} == --count ]]; then count=1; shift; fi
if [[ $count == 1 && ${1:-} == --embree ]]; then embree=1; shift; fi
if [[ $count == 1 && ${1:-} == --lines ]]; then lines=$(realpath -m "${2:?--lines needs a file}"); shift 2; fi
if [[ $count == 1 && ${1:-} == --instr ]]; then instr=$(realpath -m "${2:?--instr needs a file}"); shift 2; fi
if [[ $# -lt 2 ]]; then sed -n 2,20p "$0" >&2; exit 2; fi
rev_a=$1 rev_b=$2
shift 2
[[ -f $build_dir/bench/libvt_bench_results.a ]] ||
  { echo "collision-ab: $build_dir/bench/libvt_bench_results.a missing: run scripts/build.sh first" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

export_side() {  # REV[+PATCH] DIR
  local rev=${1%%+*} patch=
  [[ $1 == *+* ]] && patch=${1#*+}
  mkdir -p "$2"
  if [[ $rev == worktree ]]; then
    cp -r collision "$2/"
  else
    git rev-parse --verify --quiet "$rev^{commit}" >/dev/null || { echo "collision-ab: no revision '$rev'" >&2; exit 2; }
    git archive "$rev" collision | tar -x -C "$2"
  fi
  if [[ -n $patch ]]; then
    [[ -f $patch ]] || { echo "collision-ab: no patch file '$patch'" >&2; exit 2; }
    local file
    file=$(realpath "$patch")
    (cd "$2" && git apply "$file") || { echo "collision-ab: $patch does not apply to $rev's collision/" >&2; exit 2; }
  fi
}
export_side "$rev_a" "$work/a"
export_side "$rev_b" "$work/b"

# The compiler and options of the collision library's own compile command (includes, outputs
# and the source left out).
read -r -a compile < <(python3 - "$build_dir/compile_commands.json" <<'PY'
import json, shlex, sys
try:
    commands = json.load(open(sys.argv[1]))
except OSError as e:
    sys.exit(f"collision-ab: {sys.argv[1]}: {e.strerror} (configure with scripts/build.sh first)")
for c in commands:
    if c["file"].endswith("collision/src/kernels_avx2.cpp"):
        args = shlex.split(c["command"])
        out, skip = [args[0]], False
        for a in args[1:]:
            if skip:
                skip = False
            elif a in ("-o", "-c", "-MF", "-MT"):
                skip = True
            elif not (a.startswith("-I") or a == "-MD" or a.endswith(".cpp")):
                out.append(a)
        print(" ".join(out))
        break
else:
    sys.exit(f"collision-ab: no compile command for collision/src/kernels_avx2.cpp in {sys.argv[1]}")
PY
)
[[ -n $lines ]] && compile+=(-g)
read -ra extra_flags <<< "${EXTRA_FLAGS:-}"
compile+=("${extra_flags[@]}")
common=(-Icore/include -Iscene/include -Ibench -Ibench/ab)
pids=()
compile_side() {  # SIDE DIR [extra flags]
  local side=$1 dir=$2
  shift 2
  local cc=("${compile[@]}")
  [[ $side == B && -n ${CXX_B:-} ]] && cc[0]=$CXX_B
  mkdir -p "$work/obj$side"
  for source in "$dir"/collision/src/*.cpp; do
    "${cc[@]}" "$@" -I"$dir/collision/include" -I"$dir/collision/src" "${common[@]}" -c "$source" \
      -o "$work/obj$side/$(basename "$source").o" &
    pids+=($!)
  done
  "${cc[@]}" "$@" -DSIDE="$side" -I"$dir/collision/include" "${common[@]}" -c bench/ab/side.cpp \
    -o "$work/obj$side/side.o" &
  pids+=($!)
}
# Side B's every `vt` becomes `vtb`. Each side compiles what it uses from core and scene, so the
# program does not depend on how the build compiled those libraries (unity batches pull in
# their other sources' dependencies).
compile_side A "$work/a"
compile_side B "$work/b" -Dvt=vtb
for source in core/src/error.cpp scene/src/scene.cpp; do
  "${compile[@]}" "${common[@]}" -c "$source" -o "$work/objA/$(basename "$source").o" &
  pids+=($!)
  "${compile[@]}" -Dvt=vtb "${common[@]}" -c "$source" -o "$work/objB/$(basename "$source").o" &
  pids+=($!)
done
for source in scene/src/mesh.cpp scene/src/demo_scene.cpp; do  # ab_main's test scenes
  "${compile[@]}" "${common[@]}" -c "$source" -o "$work/objA/$(basename "$source").o" &
  pids+=($!)
done
"${compile[@]}" -I"$work/a/collision/include" "${common[@]}" -c bench/ab/ab_main.cpp -o "$work/ab_main.o" &
pids+=($!)
for pid in "${pids[@]}"; do wait "$pid"; done
"${compile[@]}" "$work"/ab_main.o "$work"/objA/*.o "$work"/objB/*.o -o "$work/ab" \
  "$build_dir/bench/libvt_bench_results.a" -lembree3 -lpthread

describe() {  # REV[+PATCH] COMPILER: the commit, the patch, the compiler, and for the working tree whether collision/ differs from HEAD
  local patch= compiler
  [[ $1 == *+* ]] && patch=", \"patch\": \"${1#*+}\", \"patch_sha1\": \"$(sha1sum "${1#*+}" | cut -c1-40)\""
  compiler=", \"compiler\": \"$("$2" --version | head -1)\""
  [[ -n ${EXTRA_FLAGS:-} ]] && compiler+=", \"extra_flags\": \"$EXTRA_FLAGS\""
  patch+=$compiler
  set -- "${1%%+*}"
  if [[ $1 == worktree ]]; then
    local dirty=false
    git diff --quiet HEAD -- collision || dirty=true
    echo "{\"revision\": \"worktree\", \"commit\": \"$(git rev-parse HEAD)\", \"collision_differs_from_commit\": $dirty$patch}"
  else
    echo "{\"revision\": \"$1\", \"commit\": \"$(git rev-parse "$1^{commit}")\"$patch}"
  fi
}
if [[ $count == 0 ]]; then
  status=0
  "$work/ab" "$@" >"$work/out.json" || status=$?
  [[ -s $work/out.json ]] || exit "$status"
  python3 - "$work/out.json" "$(describe "$rev_a" "${compile[0]}")" "$(describe "$rev_b" "${CXX_B:-${compile[0]}}")" <<'PY'
import json, sys
out = json.load(open(sys.argv[1]))
out["a"], out["b"] = json.loads(sys.argv[2]), json.loads(sys.argv[3])
print(json.dumps(out))
PY
  exit "$status"
fi
command -v valgrind >/dev/null || { echo "collision-ab: --count needs valgrind (apt-get install valgrind)" >&2; exit 2; }
# One pass = the counts of two passes minus those of one (setup cancels).
sides=(a b)
[[ $embree == 1 ]] && sides+=(embree)
for side in "${sides[@]}"; do
  for passes in 1 2; do
    valgrind --tool=cachegrind --cache-sim=yes --branch-sim=yes --LL=8388608,16,64 \
      --cachegrind-out-file="$work/cg.$side.$passes" "$work/ab" "$@" --only $side --passes $passes \
      >/dev/null 2>"$work/cg.$side.$passes.log" || { cat "$work/cg.$side.$passes.log" >&2; exit 1; }
  done
done
python3 - "$work" "$(describe "$rev_a" "${compile[0]}")" "$(describe "$rev_b" "${CXX_B:-${compile[0]}}")" "$@" <<'PY'
import json, os, sys
work, rev_a, rev_b, args = sys.argv[1], json.loads(sys.argv[2]), json.loads(sys.argv[3]), sys.argv[4:]
queries = int(args[args.index("--queries") + 1]) if "--queries" in args else 200000
if "build" in args:  # one pass is one build: counts per build
    queries = 1
def totals(path):
    events = summary = None
    for line in open(path):
        if line.startswith("events:"):
            events = line.split()[1:]
        elif line.startswith("summary:"):
            summary = [int(x) for x in line.split()[1:]]
    return dict(zip(events, summary))
names = {"Ir": "instructions", "Bc": "conditional_branches", "Bcm": "mispredicted_model", "DLmr": "ll_read_misses"}
out = {"queries": queries, "args": " ".join(args)}
for side, rev in (("a", rev_a), ("b", rev_b), ("embree", {"revision": "embree 3"})):
    if not os.path.exists(f"{work}/cg.{side}.1"):
        continue
    one, two = totals(f"{work}/cg.{side}.1"), totals(f"{work}/cg.{side}.2")
    out[side] = {**rev, **{names[k]: round((two[k] - one[k]) / queries, 2) for k in names}}
print(json.dumps(out))
PY
if [[ -n $lines ]]; then
  cg_annotate --show=Ir,DLmr,Bcm --context=0 "$work/cg.a.2" >"$lines" 2>&1 ||
    { echo "collision-ab: cg_annotate failed (see $lines)" >&2; exit 1; }
fi
if [[ -n $instr ]]; then
  for passes in 1 2; do
    valgrind --tool=callgrind --dump-instr=yes --callgrind-out-file="$work/cg.instr.$passes" "$work/ab" "$@" --only a \
      --passes $passes >/dev/null 2>"$work/cg.instr.log" || { cat "$work/cg.instr.log" >&2; exit 1; }
  done
  objdump -d --no-show-raw-insn -C "$work/ab" >"$work/ab.s"
  python3 - "$work/cg.instr" "$work/ab.s" "$instr" "$@" <<'PY'
import collections, re, sys
cg_prefix, disassembly, out_path, args = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
queries = int(args[args.index("--queries") + 1]) if "--queries" in args else 200000
def self_costs(cg):
    """Self cost per instruction address of every function (callgrind's compressed format: names
    once, positions relative to the line before; a call's inclusive cost line follows "calls=")."""
    names, self_cost = {}, collections.defaultdict(collections.Counter)
    fn, position, after_call = None, [0, 0], False
    for raw in open(cg):
        m = re.match(r"(c?fn)=\((\d+)\)(?: (.*))?", raw)
        if m:
            if m.group(3):
                names[m.group(2)] = m.group(3)
            if m.group(1) == "fn":
                fn = names[m.group(2)]
            continue
        if raw.startswith("calls="):
            after_call = True
            continue
        fields = raw.split()
        if not fields or not re.match(r"^(0x[0-9a-f]+|[+-]\d+|\*)$", fields[0]):
            continue
        for i in range(2):
            token = fields[i]
            if token[0] in "+-":
                position[i] += int(token)
            elif token != "*":
                position[i] = int(token, 0)
        if after_call:
            after_call = False
            continue
        if fn and len(fields) > 2:
            self_cost[fn][position[0]] += int(fields[2])
    return self_cost
# One pass of queries: two passes' counts minus one's (the build cancels).
one, two = self_costs(f"{cg_prefix}.1"), self_costs(f"{cg_prefix}.2")
self_cost = {f: collections.Counter({a: n - one.get(f, {}).get(a, 0) for a, n in c.items()}) for f, c in two.items()}
wanted = {f: c for f, c in self_cost.items() if "vt::collision::" in f and sum(c.values()) >= queries}
with open(out_path, "w") as out:
    out.write(f"# side A's collision functions with at least one instruction a query: each function's total, then each\n"
              f"# instruction's count, per query ({queries} queries: two passes' counts minus one pass's)\n")
    current = None
    for line in open(disassembly):
        m = re.match(r"^([0-9a-f]+) <(.*)>:$", line)
        if m:
            current = m.group(2) if m.group(2) in wanted else None
            if current:
                out.write(f"\n{sum(wanted[current].values()) / queries:9.1f}  {current}\n")
            continue
        m = re.match(r"^\s+([0-9a-f]+):\s+(.*)$", line)
        if current and m:
            out.write(f"{wanted[current].get(int(m.group(1), 16), 0) / queries:9.2f}  {m.group(1)}: {m.group(2)}\n")
PY
fi
