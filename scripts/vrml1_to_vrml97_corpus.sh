#!/usr/bin/env bash
# VRML 1.0 / Inventor corpus -> `lodforge lod --format x3dv` and `--format
# vrml97`, judged by their readers: Castle Model Viewer (view3dscene, drawing
# under xvfb) reports no X3D warning or error on the .x3dv output, and Coin3D
# (tests/tools/coin_probe, every LOD at child 0) counts on the .wrl output the
# level-0 triangles `lodforge info` counts on the input.
#
# usage: scripts/vrml1_to_vrml97_corpus.sh [BUILD_DIR] [DATA_DIR] > table.tsv
# Columns: file, lod exit (x3dv), Castle complaints, input triangles, Coin
# triangles of the VRML97 output, agree.
set -u
build=${1:-build}
data=${2:-../shared/data/vrml1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf 'file\texit\tcastle\tinput_tris\tcoin_tris\tagree\n'
find "$data" -type f \( -name '*.wrl' -o -name '*.iv' -o -name '*.wrl.gz' -o -name '*.iv.gz' \) |
  sort | while read -r in; do
    rel=${in#"$data"/}
    rm -rf "$work/out" "$work/home"
    mkdir -p "$work/out" "$work/home"
    "$build/lodforge" lod -q "$in" -o "$work/out/o.x3dv" 2>"$work/err" </dev/null
    rc=$?
    castle=-
    if [ $rc -eq 0 ]; then
      HOME="$work/home" timeout 120 xvfb-run -a view3dscene "$work/out/o.x3dv" \
        --screenshot 0 "$work/shot.png" >/dev/null 2>&1 </dev/null
      castle=$(grep -E '^(Warning|Error).*(X3D|VRML)|Error' \
        "$work/home/.config/view3dscene/view3dscene.log" | grep -vc 'to load from disk')
    elif [ -e "$work/out/o.x3dv" ]; then
      castle="output-left-behind"
    fi
    tris=$("$build/lodforge" info --json "$in" 2>/dev/null </dev/null |
      python3 -c 'import json,sys; print(json.load(sys.stdin)["triangles"])' 2>/dev/null || echo -)
    coin=-
    if [ $rc -eq 0 ] && "$build/lodforge" lod -q "$in" --format vrml97 -o "$work/out/o.wrl" \
      2>/dev/null </dev/null; then
      coin=$(timeout 300 "$build/tests/tools/coin_probe" "$work/out/o.wrl" 0 2>/dev/null </dev/null |
        python3 -c 'import json,sys
j=json.loads(sys.stdin.read().strip().splitlines()[-1])
print(sum(j.get("shape_triangles",{}).values()) if j.get("ok") else "rejected")' 2>/dev/null ||
        echo crashed)
    fi
    agree=$([ "$tris" = "$coin" ] && echo yes || echo no)
    [ $rc -ne 0 ] && agree="n/a ($(grep -m1 error: "$work/err" | cut -c1-120))"
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$rel" "$rc" "$castle" "$tris" "$coin" "$agree"
  done
