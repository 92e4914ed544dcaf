#!/usr/bin/env bash
# Installs every build, run and test dependency from Debian 12 packages (run as root).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
packages=(
  cmake ninja-build g++ pkg-config ccache git
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools vulkan-tools
  libglfw3-dev libglm-dev libtinygltf-dev libimgui-dev libhidapi-dev libstb-dev libdeflate-dev libjpeg62-turbo-dev nlohmann-json3-dev
  libopenxr-dev libopenxr-loader1 libopenxr-utils
  catch2 libbenchmark-dev libembree-dev libeigen3-dev
  xvfb xauth clang lld libclang-rt-14-dev python3 python3-numpy python3-opencv
  iproute2 libsodium-dev nodejs ffmpeg
  libdbus-1-dev rtkit libasound2-dev liblo-dev
  dbus-daemon python3-dbus python3-gi
  pybind11-dev python3-dev python3-pytest python3-matplotlib
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# The Khronos glTF Validator for the glTF export test (tests/app/gltf_export_validate.sh) runs on
# Node from npm. Debian's nodejs needs its npm package; NodeSource's nodejs ships npm itself.
if ! command -v npm >/dev/null 2>&1; then
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends npm >/dev/null
fi
if [ ! -d "$(npm root -g)/gltf-validator" ]; then
  npm install -g --no-fund --no-audit gltf-validator >/dev/null
fi
