#!/usr/bin/env bash
# Installs the Debian packages lodforge needs to build, test and benchmark.
# Idempotent: installs only what is missing, and says nothing when all is present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  clang clang-format clang-tidy libclang-rt-14-dev
  libcli11-dev libfmt-dev nlohmann-json3-dev libfast-float-dev zlib1g-dev
  libtbb-dev libeigen3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcoin-dev libmeshoptimizer-dev
  libosmesa6-dev libstb-dev libtinygltf-dev libpugixml-dev
  view3dscene xvfb xauth
  nodejs
  parallel
  libcpp-httplib-dev chromium
)
# `lodforge studio`'s page takes three.js from npm (scripts/install-web-deps.sh);
# Debian's npm only where no Node.js with its npm is installed already.
command -v npm >/dev/null || packages+=(nodejs npm)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
# The glTF tests run the Khronos validator with node; npm installs it
# (scripts/install-gltf-validator.sh). Some node packages bring their own npm.
command -v npm >/dev/null || missing+=(npm)
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq >/dev/null
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
