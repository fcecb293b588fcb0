#!/usr/bin/env bash
# Installs the npm packages of `lodforge studio` (three.js and CodeMirror 5 for its page,
# puppeteer-core for its browser test) into the repository's node_modules,
# at the versions pinned in package-lock.json. Idempotent: says nothing and
# does nothing when they are installed at those versions already.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v npm >/dev/null; then
  echo "install-web-deps: npm is missing (scripts/install-deps.sh installs it)" >&2
  exit 1
fi
stamp=node_modules/.package-lock.json
if [ -f "$stamp" ] && [ "$stamp" -nt package-lock.json ] && [ -f node_modules/three/build/three.module.js ] && [ -f node_modules/codemirror/lib/codemirror.js ]; then
  exit 0
fi
npm ci --no-audit --no-fund --loglevel=error >/dev/null
