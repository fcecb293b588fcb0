#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (in build-sanitize/, beside the
# sanitized tests: scripts/sanitized-build.sh) and runs each for a while.
#   scripts/fuzz.sh [SECONDS_PER_TARGET]   (default 20)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
seconds=${1:-20}
source scripts/sanitized-build.sh
configure_sanitized_build
targets=$(cd fuzz && ls *_fuzz.cpp | sed 's/\.cpp$//')
cmake --build "$sanitized_build" -j2 --target $targets
status=0
for t in $targets; do
  corpus=fuzz/corpus/${t%_fuzz}
  work=$(mktemp -d)
  [ -d "$corpus" ] && cp -r "$corpus"/. "$work"/
  log=$(mktemp)
  if "$sanitized_build/fuzz/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
      -print_final_stats=1 -artifact_prefix="$sanitized_build/$t-" "$work" >"$log" 2>&1; then
    echo "fuzz $t: ${seconds}s, $(grep -m1 number_of_executed_units "$log" | awk '{print $2}') runs, no failure"
  else
    echo "fuzz $t: FAILED"; tail -n 40 "$log"; status=1
  fi
  rm -rf "$work" "$log"
done
exit $status
