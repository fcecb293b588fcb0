#!/usr/bin/env bash
# Issue check of `lodforge lod` at scale: the whole command on the 36-bunny
# scene (scripts/make_bunny_scene.py) against its peer, 36 meshopt_simplify
# calls to 50 % on the bunny (simplify_bench's row, median of 3 repetitions),
# in alternating runs so both see the same machine. Prints each run, then the
# ratio at the medians and between the extremes, and lod's peak memory
# against the file (targets: time <= 10x the peer, peak RSS <= 4x the file).
#   bench/lod_scale.sh [-r RUNS] BUILD_DIR SCENE.wrl
set -euo pipefail
runs=6
if [ "${1:-}" = "-r" ]; then runs=$2; shift 2; fi
[ $# -eq 2 ] || { echo "usage: $0 [-r RUNS] BUILD_DIR SCENE.wrl" >&2; exit 2; }
build=$1 scene=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
bytes=$(stat -c %s "$scene")
echo "| run | lod wall | lod peak RSS | peer: one meshopt_simplify (median of 3) | 36 x peer | ratio |"
echo "|---|---|---|---|---|---|"
for ((r = 1; r <= runs; ++r)); do
  /usr/bin/time -f "%e %M" -o "$work/time" "$build/lodforge" lod "$scene" -o "$work/out.wrl" \
    --quiet=all
  read -r wall kb < "$work/time"
  peer_ms=$("$build/bench/simplify_bench" --no-quality \
    --benchmark_filter='meshopt_simplify_bun_zipper.ply_50' --benchmark_repetitions=3 2>/dev/null |
    awk '/_median/ {print $2}')
  echo "$wall" >> "$work/lod"; echo "$peer_ms" >> "$work/peer"; echo "$kb" >> "$work/rss"
  awk -v r="$r" -v w="$wall" -v kb="$kb" -v p="$peer_ms" 'BEGIN {
    printf "| %d | %.2f s | %d MB | %.1f ms | %.2f s | %.1fx |\n", r, w, kb / 1024, p, 36 * p / 1000,
      w * 1000 / (36 * p) }'
done
lod_med=$(median < "$work/lod"); peer_med=$(median < "$work/peer")
lod_min=$(sort -g "$work/lod" | head -1); lod_max=$(sort -g "$work/lod" | tail -1)
peer_min=$(sort -g "$work/peer" | head -1); peer_max=$(sort -g "$work/peer" | tail -1)
rss_max=$(sort -g "$work/rss" | tail -1)
awk -v lm="$lod_med" -v pm="$peer_med" -v l0="$lod_min" -v l1="$lod_max" -v p0="$peer_min" \
  -v p1="$peer_max" -v rss="$rss_max" -v b="$bytes" 'BEGIN {
  printf "\nlod %.2f s (median; %.2f-%.2f), peer 36 x %.1f ms (median; %.1f-%.1f):\n", lm, l0, l1, pm, p0, p1
  printf "ratio %.1fx at the medians, %.1f-%.1fx between the extremes (target <= 10x: %s)\n",
    lm * 1000 / (36 * pm), l0 * 1000 / (36 * p1), l1 * 1000 / (36 * p0),
    lm * 1000 / (36 * pm) <= 10 ? "met" : "not met"
  printf "peak RSS %.0f MB = %.2fx the file (target <= 4x: %s)\n", rss / 1024, rss * 1024 / b,
    rss * 1024 / b <= 4 ? "met" : "not met"
}'
