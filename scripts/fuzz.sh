#!/usr/bin/env bash
# Builds every fuzz_* target with clang + libFuzzer (+ASan/UBSan, in build-asan) and runs each for a bounded
# time on a copy of its seed corpus, one per core at a time. Usage: scripts/fuzz.sh [SECONDS_PER_TARGET=20] [NAME_FILTER]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
filter=${2:-}
build_dir=${BUILD_DIR:-build-asan}
targets=()
for source in tests/fuzz/fuzz_*.cpp; do
  name=$(basename "$source" .cpp)
  [[ -n "$filter" && "$name" != *"$filter"* ]] && continue
  targets+=("$name")
done
# The sanitizer build instruments the libraries too (coverage + sanitizers), not only the fuzz
# entry points: otherwise libFuzzer would mutate blindly. After scripts/sanitize.sh this only links.
BUILD_DIR="$build_dir" bash scripts/build-asan.sh "${targets[@]}"
# One fuzzer per core at a time: each libFuzzer run is single-threaded.
run_one() {
  local name=$1 work="$build_dir/fuzz-corpus/$1"
  mkdir -p "$work"
  [ -d "tests/fuzz/corpus/$name" ] && cp -n tests/fuzz/corpus/"$name"/* "$work"/ 2>/dev/null || true
  "$build_dir/tests/fuzz/$name" -max_total_time="$seconds" -max_len=4096 -timeout=10 \
    -print_final_stats=1 -artifact_prefix="$build_dir/$name-" "$work" 2>"$build_dir/$name.log"
}
status=0
pids=()
names=()
report() {  # waits for the oldest running fuzzer and says how it went
  local name=${names[0]}
  if wait "${pids[0]}"; then
    echo "== $name: ${seconds}s $(grep -E "stat::number_of_executed_units" "$build_dir/$name.log" | tail -1)"
  else
    echo "FAILED: $name (see $build_dir/$name.log and $build_dir/$name-crash-*)"
    tail -30 "$build_dir/$name.log"
    status=1
  fi
  pids=("${pids[@]:1}")
  names=("${names[@]:1}")
}
for name in "${targets[@]}"; do
  [ ${#pids[@]} -ge "$(nproc)" ] && report
  run_one "$name" &
  pids+=($!)
  names+=("$name")
done
while [ ${#pids[@]} -gt 0 ]; do report; done
exit $status
