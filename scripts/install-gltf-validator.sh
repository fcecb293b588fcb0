#!/usr/bin/env bash
# Installs the Khronos glTF-Validator (npm `gltf-validator`), the reader the
# glTF tests judge lodforge's output with, into the repository-local folder
# .tools/gltf-validator (not committed). Idempotent: says nothing and does
# nothing when the pinned version is present.
#   scripts/install-gltf-validator.sh   (needs node and npm: install-deps.sh)
set -euo pipefail
version=2.0.0-dev.3.10
dir="$(cd "$(dirname "$0")/.." && pwd)/.tools/gltf-validator"
installed="$dir/node_modules/gltf-validator/package.json"
if [ -f "$installed" ] && grep -q "\"version\": \"$version\"" "$installed"; then
  exit 0
fi
command -v npm >/dev/null || { echo "install-gltf-validator: npm is missing (scripts/install-deps.sh)" >&2; exit 1; }
echo "install-gltf-validator: installing gltf-validator@$version into $dir" >&2
mkdir -p "$dir"
npm install --prefix "$dir" --no-audit --no-fund --no-save --silent "gltf-validator@$version" >/dev/null
