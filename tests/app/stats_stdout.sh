#!/bin/sh
# `vtouching stats DIR` prints CSV (or JSON) and writes nothing into DIR; --out writes the files.
set -eu
vtouching=$1 source=$2 out=$3
rm -rf "$out" && mkdir -p "$out" && cp -r "$source/assets/dataset" "$out/dataset"
rm -f "$out/dataset/statistics.csv" "$out/dataset/statistics.json"
before=$(ls -R "$out/dataset" | wc -l)
"$vtouching" stats "$out/dataset" > "$out/stdout.csv"
head -1 "$out/stdout.csv" | grep -q "^name,source,v_scale"
"$vtouching" stats "$out/dataset" --json | grep -q '"v_scale"'
test "$(ls -R "$out/dataset" | wc -l)" = "$before"
"$vtouching" stats "$out/dataset" --out "$out/saved" --quiet
test -s "$out/saved/statistics.csv" && test -s "$out/saved/statistics.json"
echo PASS
