#!/usr/bin/env bash
# Installs the Debian packages gibench needs and builds it (Release, tests and benchmarks on).
# Usage: ci/setup.sh [--no-build]
set -euo pipefail
cd "$(dirname "$0")/.."

PKGS=(
  build-essential cmake pkg-config
  libvulkan-dev vulkan-tools mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libopenexr-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev
  libtinygltf-dev libstb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  chromium
)
# Node.js and npm for the glTF validator below: Debian's, unless the machine already has them.
command -v npm >/dev/null 2>&1 || PKGS+=(nodejs npm)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The Khronos glTF validator (npm gltf-validator, pinned in tools/gltf_validator/package-lock.json)
# for tests/test_gltf_validator.cpp, which skips itself without it.
npm ci --prefix tools/gltf_validator --no-audit --no-fund --loglevel=error ||
  echo "setup.sh: npm ci in tools/gltf_validator failed; the glTF validator test will skip itself" >&2

[ "${1:-}" = "--no-build" ] && exit 0
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DGIB_WERROR=ON
cmake --build build -j"$(nproc)"
