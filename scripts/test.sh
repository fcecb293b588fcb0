#!/usr/bin/env bash
# Builds lodforge and runs the whole test suite (installing what it needs).
#   scripts/test.sh              Release build in build/
#   scripts/test.sh --sanitize   AddressSanitizer + UndefinedBehaviorSanitizer build (clang) in
#                                build-sanitize/, shared with the fuzzers (scripts/sanitized-build.sh)
#                                (all tests but the bunny-scale quality runs, which take 4-10x
#                                longer under the sanitizers; their code paths run there on
#                                smaller inputs, and the Release run has them all; the two
#                                browser tests (three.js drawing every glTF output, the studio
#                                page), whose point is Chromium's verdict on the files and
#                                pages the Release run serves, while the sanitized code writes
#                                the same glTF files in LodGltf.* and serves the same API in
#                                StudioServer.*; and the ulimit -v run, since
#                                AddressSanitizer reserves far more address space than any
#                                such limit)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/install-web-deps.sh

build=build
args=(-DCMAKE_BUILD_TYPE=Release)
exclude=()
if [ "${1:-}" = "--sanitize" ]; then
  source scripts/sanitized-build.sh
  build=$sanitized_build
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  slow=(ExtractMcMesh.BunnyCrackFreeBudgetsAndQuality
        QuadricCollapseBunny.MeanDeviationNoWorseThanMeshoptimizer
        QuadricCollapseBunny.RegionalFirstPhaseCostsLittleQuality
        BuildMcOctree.BunnyHolesStayOpen
        GenerateLod.BunnySceneLevelsStayWithinTheErrorRangeOnScreen
        RangeScan.StanfordBunnyFromScansCoversBunZipper
        VertexDecimation.BunnyRegionalFirstPhaseCostsLittleQuality
        VertexDecimation.BunnyBeatsTheThesis
        VertexClustering.BunnyBeatsTheThesis
        NodeDistanceSums.DistanceMetricBeatsAreaOnTheBunny
        CompareMeshes.StanfordBunnyAgreesWithBruteForce
        "SharedMeshes/MeasuredErrorTest[ -~]*"
        "SharedMeshes/ErrorBudgetTest[ -~]*"
        SimplifyOutOfCore.StreamsUnderAMemoryLimitTheInMemoryPathExceeds
        lod_gltf_threejs
        studio_browser)
  exclude=(-E "^($(IFS='|'; echo "${slow[*]}" | sed 's/\./\\./g'))\$")
fi
if [ "$build" = "${sanitized_build:-}" ]; then
  configure_sanitized_build
else
  # Ninja for a new build folder; one made before keeps its own generator.
  generator=(-G Ninja)
  [ -f "$build/CMakeCache.txt" ] && generator=()
  cmake -S . -B "$build" "${generator[@]}" "${args[@]}" >/dev/null
fi
cmake --build "$build" -j2
ctest --test-dir "$build" --output-on-failure -j2 "${exclude[@]}"
