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
# One fuzzer per core at a time (each is one process); the reports in the
# targets' order.
fuzz_one() {
  local t=$1 corpus=fuzz/corpus/${1%_fuzz} work log
  work=$(mktemp -d)
  [ -d "$corpus" ] && cp -r "$corpus"/. "$work"/
  log=$(mktemp)
  if "$sanitized_build/fuzz/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
      -print_final_stats=1 -artifact_prefix="$sanitized_build/$t-" "$work" >"$log" 2>&1; then
    echo "fuzz $t: ${seconds}s, $(grep -m1 number_of_executed_units "$log" | awk '{print $2}') runs, no failure"
  else
    echo "fuzz $t: FAILED"; tail -n 40 "$log"; rm -rf "$work" "$log"; return 1
  fi
  rm -rf "$work" "$log"
}
export -f fuzz_one
export sanitized_build seconds
status=0
parallel --keep-order --jobs "$(nproc)" fuzz_one ::: $targets || status=1
exit $status
