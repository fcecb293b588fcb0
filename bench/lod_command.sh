#!/usr/bin/env bash
# The whole `lodforge lod` command as a user runs it: wall time and peak
# memory per input (median of RUNS runs), for one build or two builds side by
# side (runs alternate, so both see the same machine), as a Markdown table.
#   bench/lod_command.sh [-r RUNS] LODFORGE [OTHER_LODFORGE] -- SCENE...
# A mesh file (PLY, OBJ, OFF, STL) is first made a VRML 1.0 scene of one
# IndexedFaceSet by lod_error_check.py's as_scene (`lodforge format` does not do that).
set -euo pipefail
runs=3
if [ "${1:-}" = "-r" ]; then runs=$2; shift 2; fi
bins=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do bins+=("$1"); shift; done
[ "${1:-}" = "--" ] && shift
[ ${#bins[@]} -ge 1 ] && [ $# -ge 1 ] || { echo "usage: $0 [-r RUNS] LODFORGE [OTHER] -- SCENE..." >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

as_scene() {  # a mesh file -> VRML 1.0 scene of one IndexedFaceSet (lod_error_check.py's)
  python3 -c 'import sys; sys.path.insert(0, sys.argv[1]); from lod_error_check import as_scene
print(as_scene(*sys.argv[2:]))' "$(dirname "$0")" "${bins[0]}" "$1" "$work"
}

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

header="| input | size |"
rule="|---|---|"
for b in "${bins[@]}"; do header+=" $(basename "$(dirname "$b")")/$(basename "$b"): time | peak RSS |"; rule+="---|---|"; done
[ ${#bins[@]} -eq 2 ] && { header+=" time ratio (2nd / 1st) |"; rule+="---|"; }
echo "$header"; echo "$rule"
for input in "$@"; do
  scene=$(as_scene "$input")
  row="| $(basename "$input") | $(du -k "$scene" | cut -f1) KB |"
  times=()
  for i in "${!bins[@]}"; do : > "$work/t$i"; : > "$work/m$i"; done
  for ((r = 0; r < runs; ++r)); do
    for i in "${!bins[@]}"; do
      /usr/bin/time -f "%e %M" -o "$work/one" "${bins[$i]}" lod "$scene" -o "$work/out.wrl" -q \
        2>/dev/null >/dev/null
      read -r t m < "$work/one"
      echo "$t" >> "$work/t$i"; echo "$m" >> "$work/m$i"
    done
  done
  for i in "${!bins[@]}"; do
    t=$(median < "$work/t$i"); m=$(median < "$work/m$i")
    times+=("$t")
    row+=" $t s | $((m / 1024)) MB |"
  done
  [ ${#bins[@]} -eq 2 ] && row+=" $(awk -v a="${times[0]}" -v b="${times[1]}" 'BEGIN {printf "%.2f", b / a}') |"
  echo "$row"
done
