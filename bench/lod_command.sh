#!/usr/bin/env bash
# The whole `lodforge lod` command as a user runs it: wall time and peak
# memory per input (median of RUNS runs), for one build or two builds side by
# side (runs alternate, so both see the same machine), as a Markdown table.
#   bench/lod_command.sh [-r RUNS] LODFORGE [OTHER_LODFORGE] -- SCENE...
# A mesh file (PLY, OBJ, OFF, STL) is first made a VRML 1.0 scene of one
# IndexedFaceSet (`lodforge format` does not do that, so a small converter here).
set -euo pipefail
runs=3
if [ "${1:-}" = "-r" ]; then runs=$2; shift 2; fi
bins=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do bins+=("$1"); shift; done
[ "${1:-}" = "--" ] && shift
[ ${#bins[@]} -ge 1 ] && [ $# -ge 1 ] || { echo "usage: $0 [-r RUNS] LODFORGE [OTHER] -- SCENE..." >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

as_scene() {  # a mesh file -> VRML 1.0 scene of one IndexedFaceSet
  case "$1" in
    *.wrl|*.wrl.gz|*.iv|*.iv.gz) echo "$1" ;;
    *.ply|*.obj|*.off|*.stl)
      # Any mesh format lodforge reads (binary PLY too), through OBJ: `simplify
      # --ratio 1` writes the mesh as it is.
      out="$work/$(basename "$1").wrl"
      "${bins[0]}" simplify "$1" --ratio 1 -o "$work/mesh.obj" -q >/dev/null 2>&1
      python3 - "$work/mesh.obj" "$out" <<'PY'
import sys
v, f = [], []
for line in open(sys.argv[1]):
    w = line.split()
    if w and w[0] == 'v':
        v.append(' '.join(w[1:4]))
    elif w and w[0] == 'f':
        f.append(', '.join(str(int(x.split('/')[0]) - 1) for x in w[1:]))
with open(sys.argv[2], 'w') as o:
    o.write('#VRML V1.0 ascii\nSeparator {\nCoordinate3 { point [\n')
    o.write(''.join(p + ',\n' for p in v))
    o.write('] }\nIndexedFaceSet { coordIndex [\n')
    o.write(''.join(t + ', -1,\n' for t in f))
    o.write('] }\n}\n')
PY
      echo "$out" ;;
    *) echo "unsupported input $1 (VRML 1.0, Inventor, PLY, OBJ, OFF or STL)" >&2; exit 2 ;;
  esac
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
