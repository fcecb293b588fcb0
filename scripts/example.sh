#!/usr/bin/env bash
# Builds lodforge and runs it on the example scene of the repository.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2 --target lodforge_cli
mkdir -p out
./build/lodforge info examples/scene.wrl
./build/lodforge format examples/scene.wrl -o out/scene.formatted.wrl
echo "wrote out/scene.formatted.wrl" >&2
