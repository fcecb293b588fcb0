# Sourced by scripts/test.sh --sanitize and scripts/fuzz.sh: the one build
# folder both use, build-sanitize/, configured alike so that each builds on
# the other's objects (the libraries are compiled once for the fuzzers and
# the sanitized tests). clang with AddressSanitizer + UndefinedBehaviorSanitizer
# everywhere, libFuzzer's coverage in the libraries (fuzz/CMakeLists.txt),
# -O1 -g1: the sanitizers' own advice (usable speed, line numbers in reports).
sanitized_build=build-sanitize
configure_sanitized_build() {
  # Ninja for a new build folder; one made before keeps its own generator.
  local generator=(-G Ninja)
  [ -f "$sanitized_build/CMakeCache.txt" ] && generator=()
  cmake -S . -B "$sanitized_build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
    -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang \
    -DLODFORGE_SANITIZE=address,undefined -DLODFORGE_FUZZ=ON -DLODFORGE_BENCH=OFF >/dev/null
}
