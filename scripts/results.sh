#!/usr/bin/env bash
# Regenerates the tables of docs/RESULTS.md: one section per capability, each
# the exact commands that print its tables, run on one Release build.
#
#   scripts/results.sh [--build-dir DIR] [--list] [SECTION...]
#
#   --build-dir DIR  the Release build to use (default: build/ of the
#                    repository; configured if it has no CMakeCache.txt)
#   --list           print the sections and their commands, run nothing
#   SECTION...       the sections to run (default: all; --list names them)
#
# Only the targets the chosen sections need are built (-j2). Each section
# prints `## SECTION`, then before each command the date (UTC), the commit,
# `uptime` and the command line, then the command's output. The shared corpus
# is the repository's ../shared/data, or $LODFORGE_SHARED_DATA (the test
# executables read the one CMake set at configure time). The octree section
# rewrites the pictures in docs/images.
set -euo pipefail

usage() { sed -n '2,10s/^# \{0,1\}//p' "$0"; }

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
parent=$(dirname "$repo")
build_arg=$repo/build
list=0
chosen=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) [ $# -ge 2 ] || { usage >&2; exit 2; }; build_arg=$2; shift 2 ;;
    --build-dir=*) build_arg=${1#--build-dir=}; shift ;;
    --list) list=1; shift ;;
    -h|--help) usage; exit 0 ;;
    -*) echo "unknown option $1" >&2; usage >&2; exit 2 ;;
    *) chosen+=("$1"); shift ;;
  esac
done

all_sections=(compare clustering octree simplify reader inventor lod outcome scale out_of_core qem batches formats)
[ ${#chosen[@]} -gt 0 ] || chosen=("${all_sections[@]}")
for s in "${chosen[@]}"; do
  case " ${all_sections[*]} " in
    *" $s "*) ;;
    *) echo "unknown section $s (sections: ${all_sections[*]})" >&2; exit 2 ;;
  esac
done

# Absolute paths, shown relative to the repository (where commands run) when
# they lie in it or beside it.
absolute() { case "$1" in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }
shown() {
  local p
  p=$(realpath -m "$1")
  case "$p" in
    "$repo") echo . ;;
    "$repo"/*) echo "${p#"$repo"/}" ;;
    "$parent"/*) echo "../${p#"$parent"/}" ;;
    *) echo "$p" ;;
  esac
}
q() { printf '%q' "$(shown "$1")"; }

build_abs=$(realpath -m "$(absolute "$build_arg")")
data_abs=$(realpath -m "$(absolute "${LODFORGE_SHARED_DATA:-$parent/shared/data}")")
export LODFORGE_SHARED_DATA=$data_abs
cd "$repo"

if [ $list -eq 1 ]; then
  # shellcheck disable=SC2016  # printed as is: a temporary folder made when the commands run
  work='$WORK'
else
  work=$(mktemp -d "${TMPDIR:-/tmp}/lodforge_results.XXXXXX")
  trap 'rm -rf "$work"' EXIT
fi
B=$(q "$build_abs")
D=$(q "$data_abs")
W=$work
[ $list -eq 1 ] || W=$(printf '%q' "$work")
# lod_bench and simplify_error_check.py look for ../shared/data from their
# working directory: the repository, or a folder whose ../shared/data links
# to $LODFORGE_SHARED_DATA.
if [ "$data_abs" = "$(realpath -m "$parent/shared/data")" ]; then
  beside_data=""
  B_beside=$B
  error_check=bench/simplify_error_check.py
else
  beside_data="cd $W/run && "
  B_beside=$(printf '%q' "$build_abs")
  error_check=$(printf '%q' "$repo/bench/simplify_error_check.py")
  if [ $list -eq 0 ]; then
    mkdir -p "$work/shared" "$work/run"
    ln -s "$data_abs" "$work/shared/data"
  fi
fi
time_fmt="-f '%e s wall, %U s user, %S s system, %M KB peak RSS'"
parse_file="${TMPDIR:-/tmp}/lodforge_vrml1_bench_50mb.wrl"  # written by vrml1_parse_bench
vrml1=$D/vrml1
lod_files="$D/meshes/bun_zipper.ply examples/scene.wrl \
$vrml1/castle-engine__malfunction/data/vrmls/lake_bl.wrl \
$vrml1/YvesBoyadjian__Koin3D/jExample/examples_iv/ejemplos-ve3d/modelos/metralleta.wrl \
$vrml1/castle-engine__demo-models/lights_materials/vrml_1/forest-fog/forest.wrl"

# Sets `targets` (build targets) and `commands` (shell command lines) of a section.
section() {
  targets=()
  commands=()
  case "$1" in
    compare)  # speed beside brute force; Stanford's bunny resolutions
      targets=(compare_bench lodforge_cli)
      commands=(
        "$B/bench/compare_bench"
        "/usr/bin/time $time_fmt $B/lodforge compare $D/meshes/bun_zipper.ply $D/meshes/bun_zipper_res2.ply --samples 1000000 --json"
        "/usr/bin/time $time_fmt $B/lodforge compare $D/meshes/bun_zipper.ply $D/meshes/bun_zipper_res2.ply --samples 1000000 --json --threads 1"
      )
      for r in res2 res3 res4; do
        commands+=("$B/lodforge compare $D/meshes/bun_zipper.ply $D/meshes/bun_zipper_$r.ply --json"
                   "$B/lodforge compare $D/meshes/bun_zipper.ply $D/meshes/bun_zipper_$r.ply --json --smooth-normals")
      done ;;
    clustering)  # quality against the thesis; the chain beside meshopt_simplifySloppy
      targets=(test_simplify vertex_clustering_bench)
      commands=(
        "$B/tests/test_simplify --gtest_filter='VertexClustering.BunnyBeatsTheThesis'"
        "$B/bench/vertex_clustering_bench --benchmark_min_time=3 --benchmark_filter='OverSloppy/[02]/'"
      ) ;;
    octree)  # marching-cube octree: quality, pictures, resolutions, speed, memory, scans, checks
      targets=(mcoctree_quality mcoctree_bench mcoctree_query_bench lodforge_cli test_mcoctree)
      commands=(
        "$B/bench/mcoctree_quality --out docs/images"
        "$B/bench/mcoctree_quality --metric distance"
      )
      for r in 64 160 256; do
        commands+=("$B/bench/mcoctree_quality --resolution $r --samples 200000")
      done
      commands+=("$B/bench/mcoctree_bench --benchmark_filter='BM_McoExtract/|BM_McoMemory|BM_McoBuildBesideMeshopt'")
      commands+=("$B/bench/mcoctree_query_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true")
      commands+=("$B/bench/mcoctree_bench --benchmark_filter='BM_McoViewExtract|BM_McoUniformAtViewCount' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true")
      for m in horse.ply fandisk.obj cow.obj rocker-arm.obj nefertiti.obj igea.ply bun_zipper.ply teapot.obj suzanne.obj; do
        commands+=("$B/lodforge mco build $D/meshes/$m -o $W/${m%.*}.mco -q --threads 2")
        for r in 100 200 400; do
          commands+=("$B/lodforge mco build $D/meshes/$m -o $W/${m%.*}_$r.mco -q --threads 2 --resolution $r")
        done
      done
      commands+=(
        "$B/lodforge mco build $D/range/bunny/bun.conf --resolution 200 -o $W/scans200.mco -q && ls -l $W/scans200.mco"
        "$B/lodforge mco extract $W/scans200.mco --percent 100 -o $W/scans200.ply && $B/lodforge compare $D/meshes/bun_zipper.ply $W/scans200.ply --samples 50000 --json"
        "$B/lodforge compare $W/scans200.ply $D/meshes/bun_zipper.ply --samples 50000 --colored $W/scans200_deviation.ply --color-max 0.0088 -q && $B/lodforge render $W/scans200_deviation.ply -o docs/images/scan_bunny_deviation_side.png --size 400x400 && $B/lodforge render $W/scans200_deviation.ply -o docs/images/scan_bunny_deviation_bottom.png --size 400x400 --view 0,-90"
        "$B/lodforge mco build $D/range/bunny/bun.conf -o $W/scans.mco -q && $B/lodforge mco extract $W/scans.mco --percent 100 -o $W/scans.ply && $B/lodforge compare $D/meshes/bun_zipper.ply $W/scans.ply --samples 50000 --json"
        "$B/lodforge compare $D/meshes/bun_zipper.ply $D/meshes/bun_zipper_res2.ply --samples 50000 --json"
        "$B/lodforge render $W/scans.ply -o docs/images/scan_bunny_smooth.png --size 560x420 --no-colors --flat --view 60,10"
        "$B/tests/test_mcoctree"
      ) ;;
    simplify)  # the three simplifiers beside meshoptimizer; reported against measured error
      targets=(simplify_bench lodforge_cli)
      commands=(
        "$B/bench/simplify_bench --markdown=$W/simplify_bench.md"
        "${beside_data}python3 $error_check $B_beside"
      )
      for m in qem decimate cluster; do
        commands+=("$B/lodforge simplify $D/meshes/bun_zipper.ply -o $W/error_$m.ply --error 0.002 --method $m --json")
      done ;;
    reader)  # VRML 1.0 parse speed and memory beside Coin3D; conformance
      targets=(vrml1_parse_bench lodforge_cli test_vrml1)
      commands=(
        "$B/bench/vrml1_parse_bench"
        "/usr/bin/time $time_fmt $B/lodforge info $parse_file"
        "bench/info_vs_coin.sh -r 5 $B"
        "$B/tests/test_vrml1 --gtest_filter='*CoinConformance*:*CoinTriangulation*:*RoundTrip*'"
      ) ;;
    inventor)  # the Inventor corpus through info and lod, checked with Coin3D
      targets=(test_lod test_vrml1)
      commands=(
        "$B/tests/test_lod --gtest_filter='*Inventor*'"
        "$B/tests/test_vrml1 --gtest_filter='InventorRead*'"
      ) ;;
    lod)  # the whole lod command; thread scaling; the corpus
      targets=(lodforge_cli lod_bench test_lod)
      commands=(
        "bench/lod_command.sh -r 3 $B/lodforge -- $lod_files"
        "${beside_data}$B_beside/bench/lod_bench"
        "n=0; failed=0; in=0; out=0; while IFS= read -r f; do n=\$((n + 1)); if $B/lodforge lod \"\$f\" -o $W/corpus_out.wrl -q; then in=\$((in + \$(stat -c %s \"\$f\"))); out=\$((out + \$(stat -c %s $W/corpus_out.wrl))); else failed=\$((failed + 1)); echo \"failed: \$f\"; fi; done < <(find $vrml1 -name '*.wrl' | sort); echo \"\$n files, \$failed failures, output \$in -> \$out bytes\""
        "$B/tests/test_lod --gtest_filter='*LodCorpus*:GenerateLod*'"
        "python3 bench/lod_error_check.py $B/lodforge $(for m in bun_zipper.ply horse.ply igea.ply nefertiti.obj rocker-arm.obj cow.obj fandisk.obj teapot.obj; do printf '%s ' "$D/meshes/$m"; done)"
      ) ;;
    outcome)  # triangles drawn by distance beside a meshopt_simplify chain
      targets=(lod_outcome)
      commands=(
        "$B/bench/lod_outcome $D/meshes/bun_zipper.ply examples/scene.wrl"
        "$B/bench/lod_outcome \$(find $vrml1 -name '*.wrl' | sort)"
      ) ;;
    scale)  # lod on a 94 MB scene of 36 bunnies; the peer: 36 meshopt_simplify calls
      targets=(lodforge_cli simplify_bench)
      commands=(
        "python3 scripts/make_bunny_scene.py $D/meshes/bun_zipper.ply $W/bunnies.wrl && ls -l $W/bunnies.wrl"
        "$B/lodforge info $W/bunnies.wrl"
        "/usr/bin/time $time_fmt $B/lodforge lod $W/bunnies.wrl -o $W/bunnies_lod.wrl -q && ls -l $W/bunnies_lod.wrl"
        "bench/lod_scale.sh -r 6 $B $W/bunnies.wrl"
      ) ;;
    out_of_core)  # simplify streaming a 20 M-triangle PLY under ulimit -v 1 GiB; the peer: the in-memory path
      targets=(lodforge_cli make_big_ply test_simplify)
      commands=(
        "$B/tests/tools/make_big_ply $W/big.ply 20000000 && ls -l $W/big.ply"
        "ulimit -v 1048576 && /usr/bin/time $time_fmt $B/lodforge simplify $W/big.ply -o $W/small.ply --method cluster --ratio 0.01 --json"
        "/usr/bin/time $time_fmt $B/lodforge compare $W/big.ply $W/small.ply"
        "/usr/bin/time $time_fmt $B/lodforge simplify $W/big.ply -o $W/small_in_memory.ply --method cluster --ratio 0.01 --max-memory 0 --json"
        "$B/lodforge compare $W/big.ply $W/small_in_memory.ply"
        "$B/tests/test_simplify --gtest_filter='OutOfCoreClustering*'"
      ) ;;
    qem)  # quadric collapse beside meshopt_simplify: speed and quality
      targets=(quadric_collapse_bench test_simplify)
      commands=(
        "$B/bench/quadric_collapse_bench --benchmark_filter='BM_MeshoptSimplify/|BM_QuadricCollapse' --benchmark_repetitions=5 --benchmark_report_aggregates_only=true"
        "$B/tests/test_simplify --gtest_filter='QuadricCollapseBunny.*'"
      ) ;;
    batches)  # a sharded batch through GNU parallel equals one process
      targets=(test_apps)
      commands=("$B/tests/test_apps --gtest_filter='Batch.*:SlurmExample.*'") ;;
    formats)  # VRML97 / X3D and glTF through lod, judged by their readers
      targets=(test_apps test_vrml97 test_gltf lodforge_cli)
      commands=(
        "$B/tests/test_apps --gtest_filter='Corpus/LodGltf.*:LodVrml1ToGltf.*:LodVrml97Corpus.*:LodVrml97ToGltf.*'"
        "$B/tests/test_vrml97"
        "$B/tests/test_gltf"
      ) ;;
  esac
}

if [ $list -eq 1 ]; then
  echo "build: $(shown "$build_abs"); shared data: $(shown "$data_abs"); \$WORK: a temporary folder"
  for s in "${chosen[@]}"; do
    section "$s"
    printf '\n## %s\ntargets: %s\n' "$s" "${targets[*]}"
    for c in "${commands[@]}"; do printf '  %s\n' "$c"; done
  done
  exit 0
fi

if [ ! -f "$build_abs/CMakeCache.txt" ]; then
  cmake -S "$repo" -B "$build_abs" -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
build_type=$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$build_abs/CMakeCache.txt")
[ "$build_type" = Release ] || echo "warning: $(shown "$build_abs") is a '$build_type' build, not Release" >&2

needed=()
for s in "${chosen[@]}"; do
  section "$s"
  for t in "${targets[@]}"; do
    case " ${needed[*]} " in *" $t "*) ;; *) needed+=("$t") ;; esac
  done
done
cmake --build "$build_abs" --target "${needed[@]}" -j2

commit=$(git rev-parse --short HEAD)
[ -z "$(git status --porcelain --untracked-files=no)" ] || commit+=" (with uncommitted changes)"
status=0
for s in "${chosen[@]}"; do
  section "$s"
  printf '\n## %s\n' "$s"
  for c in "${commands[@]}"; do
    printf '\ndate: %s\ncommit: %s\nuptime: %s\n$ %s\n\n' \
      "$(date -u '+%Y-%m-%d %H:%M:%S UTC')" "$commit" "$(uptime)" "$c"
    rc=0
    bash -c "$c" 2>&1 || rc=$?
    if [ $rc -ne 0 ]; then
      echo "(exit status $rc)"
      status=1
    fi
  done
done
exit $status
