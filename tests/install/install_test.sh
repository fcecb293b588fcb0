#!/bin/sh
# Installs the build into a fresh prefix and builds a user's project against it,
# once through find_package(lodforge) and once through pkg-config.
# Usage: install_test.sh BUILD_DIR SOURCE_DIR(tests/install) WORK_DIR CXX GENERATOR LIBDIR [FLAGS]
# FLAGS: compiler and linker flags the user's build needs too (the sanitizers
# of a LODFORGE_SANITIZE build).
set -eu
build=$1 src=$2 work=$3 cxx=$4 generator=$5 libdir=$6 extra=${7:-}
rm -rf "$work"
mkdir -p "$work"
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" >"$work/install.log" 2>&1 || { cat "$work/install.log"; exit 1; }

for f in bin/lodforge share/man/man1/lodforge.1 include/lodforge/mesh/mesh_io.h \
         include/lodforge/simplify/quadric_collapse.h "$libdir/cmake/lodforge/lodforgeConfig.cmake" \
         "$libdir/cmake/lodforge/lodforgeConfigVersion.cmake" "$libdir/pkgconfig/lodforge.pc" \
         "$libdir/liblodforge_core.a" "$libdir/liblodforge_mcoctree.a"; do
  [ -e "$prefix/$f" ] || { echo "not installed: $f"; exit 1; }
done
[ ! -e "$prefix/include/lodforge/apps" ] || { echo "apps/ headers installed"; exit 1; }
# The man page has a section for every command the installed binary lists.
commands=$("$prefix/bin/lodforge" --help | sed -n '/^Subcommands:/,$s/^  \([a-z]*\) .*/\1/p')
[ -n "$commands" ] || { echo "installed lodforge --help lists no commands"; exit 1; }
for c in $commands; do
  grep -qx "\.SS $c" "$prefix/share/man/man1/lodforge.1" || { echo "man page lacks: $c"; exit 1; }
done

# Every line of main.cpp's output must say this.
check() {
  grep -Eq '^triangles 128 -> ([1-9]|[1-2][0-9]|3[0-2]) \(read back \1\)$' "$1" ||
    { echo "unexpected output of $2:"; cat "$1"; exit 1; }
  magic=$(head -c 2 "$3" | od -An -tx1 | tr -d ' \n')
  [ "$magic" = 1f8b ] || { echo "$3 is not gzip ($magic)"; exit 1; }
}

# find_package(lodforge) through CMAKE_PREFIX_PATH.
cmake -S "$src" -B "$work/cmake" -G "$generator" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_CXX_FLAGS="$extra" -DCMAKE_EXE_LINKER_FLAGS="$extra" \
  -DCMAKE_PREFIX_PATH="$prefix" >"$work/cmake.log" 2>&1 ||
  { cat "$work/cmake.log"; exit 1; }
cmake --build "$work/cmake" >>"$work/cmake.log" 2>&1 || { cat "$work/cmake.log"; exit 1; }
"$work/cmake/user" "$work/cmake.ply.gz" >"$work/cmake.out"
check "$work/cmake.out" "the find_package build" "$work/cmake.ply.gz"

# pkg-config, from the installed lodforge.pc.
flags=$(PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig" pkg-config --cflags --libs lodforge)
# shellcheck disable=SC2086 # the flags are words
# No -std here: lodforge.pc carries it (the headers need C++20).
"$cxx" -O1 $extra "$src/main.cpp" -o "$work/pc_user" $flags
"$work/pc_user" "$work/pc.obj.gz" >"$work/pc.out"
check "$work/pc.out" "the pkg-config build" "$work/pc.obj.gz"

echo "install test: OK ($(cat "$work/cmake.out"))"
rm -rf "$work"
