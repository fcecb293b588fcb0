#!/usr/bin/env bash
# VRML 1.0 / Inventor corpus -> `lodforge lod --format x3dv` and `--format
# vrml97`, judged by their readers: Castle Model Viewer (view3dscene, drawing
# under xvfb) reports no X3D warning or error on the .x3dv output (but a
# texture file the input names that is nowhere in the corpus), and
# Coin3D (tests/tools/coin_probe, every LOD at child 0) counts on the .wrl
# output the level-0 triangles `lodforge info` counts on the input, or, when
# the input has zero-area triangles (two corners at one index) that Coin's
# VRML97 IndexedFaceSet does not draw, the triangles Coin draws of the input.
#
# usage: scripts/vrml1_to_vrml97_corpus.sh [BUILD_DIR] [DATA_DIR] > table.tsv
# Columns: file, lod exit (x3dv), Castle complaints, input triangles
# (lodforge info), Coin triangles of the input (drawn / with three distinct
# corners), Coin triangles of the VRML97 output, agree.
set -u
build=${1:-build}
data=${2:-../shared/data/vrml1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Castle's warnings and errors on a file, drawn under xvfb.
complaints() {
  rm -rf "$work/home"
  mkdir -p "$work/home"
  HOME="$work/home" timeout 120 xvfb-run -a view3dscene "$1" --screenshot 0 "$work/shot.png" \
    >/dev/null 2>&1 </dev/null
  grep -E '^(Warning|Error).*(X3D|VRML)|Error' "$work/home/.config/view3dscene/view3dscene.log" |
    grep -v 'to load from disk'
}
# Coin's triangles (drawn/distinct corners) from coin_probe's JSON.
count='import json,sys
j=json.loads(sys.stdin.read().strip().splitlines()[-1])
d=lambda k: sum(j.get(k,{}).values())
print("%d/%d" % (d("shape_triangles"), d("distinct_triangles")) if j.get("ok") else "rejected")'
printf 'file\texit\tcastle\tinput_tris\tcoin_in\tcoin_out\tagree\n'
find "$data" -type f \( -name '*.wrl' -o -name '*.iv' -o -name '*.wrl.gz' -o -name '*.iv.gz' \) |
  sort | while read -r in; do
    rel=${in#"$data"/}
    rm -rf "$work/out"
    mkdir -p "$work/out"
    "$build/lodforge" lod -q "$in" -o "$work/out/o.x3dv" 2>"$work/err" </dev/null
    rc=$?
    castle=-
    if [ $rc -eq 0 ]; then
      complaints "$work/out/o.x3dv" >"$work/out.log"
      # A texture the input names that is nowhere in its corpus project is
      # the input's problem (Castle does not always say so of VRML 1.0).
      project="$data/${rel%%/*}"
      castle=0
      while read -r line; do
        name=$(printf '%s' "$line" | grep -o 'texture from URL "[^"]*"' | sed 's|.*/||; s|"$||')
        if [ -n "$name" ] && [ -z "$(find "$project" -name "$name" -print -quit)" ]; then continue; fi
        castle=$((castle + 1))
      done <"$work/out.log"
    elif [ -e "$work/out/o.x3dv" ]; then
      castle="output-left-behind"
    fi
    tris=$("$build/lodforge" info --json "$in" 2>/dev/null </dev/null |
      python3 -c 'import json,sys; print(json.load(sys.stdin)["triangles"])' 2>/dev/null || echo -)
    coin_in=$(timeout 300 "$build/tests/tools/coin_probe" "$in" 2>/dev/null </dev/null |
      python3 -c "$count" 2>/dev/null || echo crashed)
    coin=-
    if [ $rc -eq 0 ] && "$build/lodforge" lod -q "$in" --format vrml97 -o "$work/out/o.wrl" \
      2>/dev/null </dev/null; then
      coin=$(timeout 300 "$build/tests/tools/coin_probe" "$work/out/o.wrl" 0 2>/dev/null </dev/null |
        python3 -c "$count" 2>/dev/null | cut -d/ -f1 || echo crashed)
    fi
    agree=no
    if [ "$tris" = "$coin" ]; then
      agree=yes
    elif [ "${coin_in%/*}" = "$tris" ] && [ "${coin_in#*/}" = "$coin" ]; then
      agree="yes (zero-area triangles not drawn)"
    fi
    [ $rc -ne 0 ] && agree="n/a ($(grep -m1 error: "$work/err" | cut -c1-120))"
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$rel" "$rc" "$castle" "$tris" "$coin_in" "$coin" "$agree"
  done
