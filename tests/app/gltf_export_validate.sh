#!/bin/sh
# `vtouching export` of the default dataset and of the hand template as .glb and .gltf, checked by the Khronos glTF
# Validator (npm gltf-validator) through Node. Exit 77 (skipped) only when Node is absent.
set -eu
vtouching=$1 source_dir=$2 out=$3
if ! command -v node >/dev/null 2>&1; then
  echo "SKIP: Node.js is not installed (scripts/install-deps.sh installs nodejs, npm and gltf-validator)"
  exit 77
fi
rm -rf "$out" && mkdir -p "$out/gltf"
"$vtouching" export "$source_dir/assets/dataset" --out "$out/scene.glb"
"$vtouching" export "$source_dir/assets/dataset" --out "$out/gltf/scene.gltf"
"$vtouching" export --hand-template --out "$out/hand.glb"
"$vtouching" export --hand-template --out "$out/gltf/hand.gltf"
NODE_PATH="$(npm root -g 2>/dev/null || true)${NODE_PATH:+:$NODE_PATH}" \
  node "$source_dir/tests/scene/gltf_validate.js" "$out/scene.glb" "$out/gltf/scene.gltf" "$out/hand.glb" \
    "$out/gltf/hand.gltf"
