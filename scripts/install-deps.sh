#!/usr/bin/env bash
# Installs the build, run and test dependencies from Debian 12 packages (run as root).
# `install-deps.sh run`: only what building and running the application needs (scripts/run.sh);
# without an argument also everything the test suite needs (scripts/test.sh).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
scope=${1:-all}
# Build and run: the configure step also needs catch2, benchmark and python3 (tests and benches
# are configured in the same build folder; scripts/test.sh builds them).
packages=(
  cmake ninja-build g++ pkg-config ccache git python3
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools vulkan-tools
  libglfw3-dev libx11-dev libxext-dev libglm-dev libtinygltf-dev libimgui-dev libhidapi-dev libstb-dev libdeflate-dev libjpeg62-turbo-dev nlohmann-json3-dev
  libopenxr-dev libopenxr-loader1 libeigen3-dev libsodium-dev libdbus-1-dev libasound2-dev liblo-dev
  pybind11-dev python3-dev
  catch2 libbenchmark-dev
)
if [ "$scope" != run ]; then
  packages+=(
    libopenxr-utils libembree-dev
    xvfb xauth clang lld libclang-rt-14-dev python3-numpy python3-opencv python3-pytest python3-matplotlib
    iproute2 nodejs ffmpeg
    rtkit dbus-daemon python3-dbus python3-gi
  )
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
[ "$scope" = run ] && exit 0
# The Khronos glTF Validator for the glTF export test (tests/app/gltf_export_validate.sh) runs on
# Node from npm. Debian's nodejs needs its npm package; NodeSource's nodejs ships npm itself.
if ! command -v npm >/dev/null 2>&1; then
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends npm >/dev/null
fi
if [ ! -d "$(npm root -g)/gltf-validator" ]; then
  npm install -g --no-fund --no-audit gltf-validator >/dev/null
fi
