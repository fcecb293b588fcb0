#!/usr/bin/env bash
# `lodforge info` as a whole process beside Coin3D's SoDB::readAll alone on
# the same file (vrml1_parse_bench's generated 50 MB VRML 1.0 file), runs
# alternating so both see the same machine: the best and the median of RUNS
# runs each, and their ratios (target: info >= 5x faster than readAll).
#   bench/info_vs_coin.sh [-r RUNS] BUILD_DIR
set -euo pipefail
runs=5
if [ "${1:-}" = "-r" ]; then runs=$2; shift 2; fi
[ $# -eq 1 ] || { echo "usage: $0 [-r RUNS] BUILD_DIR" >&2; exit 2; }
build=$1
file=${TMPDIR:-/tmp}/lodforge_vrml1_bench_50mb.wrl
# The parse benchmark writes the file the first time it runs.
[ -f "$file" ] || "$build/bench/vrml1_parse_bench" --benchmark_filter=BM_coin_readAll >/dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
coin=() info=()
for ((r = 0; r < runs; r++)); do
  "$build/bench/vrml1_parse_bench" --benchmark_filter='^BM_coin_readAll' \
    --benchmark_out="$work/coin.json" --benchmark_out_format=json >/dev/null 2>&1
  coin+=("$(python3 -c 'import json,sys; print(min(b["real_time"] for b in json.load(open(sys.argv[1]))["benchmarks"]) / 1000)' "$work/coin.json")")
  start=$(date +%s.%N)
  "$build/lodforge" info "$file" >/dev/null
  info+=("$(echo "$(date +%s.%N) - $start" | bc -l)")
done
python3 - "${coin[*]}" "${info[*]}" <<'PY'
import statistics, sys
coin = [float(x) for x in sys.argv[1].split()]
info = [float(x) for x in sys.argv[2].split()]
print("| | Coin3D SoDB::readAll (s) | lodforge info, whole process (s) | ratio |")
print("|---|---|---|---|")
for name, f in (("best", min), ("median", statistics.median)):
    print(f"| {name} of {len(coin)} | {f(coin):.3f} | {f(info):.3f} | {f(coin) / f(info):.1f}x |")
PY
