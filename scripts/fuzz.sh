#!/usr/bin/env bash
# Builds the libFuzzer targets with clang and runs each for a while.
#   scripts/fuzz.sh [SECONDS_PER_TARGET]   (default 20)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
seconds=${1:-20}
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang \
  -DLODFORGE_FUZZ=ON -DLODFORGE_TESTS=OFF -DLODFORGE_BENCH=OFF >/dev/null
targets=$(cd fuzz && ls *_fuzz.cpp | sed 's/\.cpp$//')
cmake --build build-fuzz -j2 --target $targets
status=0
for t in $targets; do
  corpus=fuzz/corpus/${t%_fuzz}
  work=$(mktemp -d)
  [ -d "$corpus" ] && cp -r "$corpus"/. "$work"/
  log=$(mktemp)
  if build-fuzz/fuzz/$t -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
      -print_final_stats=1 -artifact_prefix="build-fuzz/$t-" "$work" >"$log" 2>&1; then
    echo "fuzz $t: ${seconds}s, $(grep -m1 number_of_executed_units "$log" | awk '{print $2}') runs, no failure"
  else
    echo "fuzz $t: FAILED"; tail -n 40 "$log"; status=1
  fi
  rm -rf "$work" "$log"
done
exit $status
