#!/usr/bin/env bash
# The installed heavytop as outside projects use it (run by ctest; tests/package/CMakeLists.txt):
#   package_test.sh MODE BUILD_DIR SOURCE_DIR CONFIG SYMBOLIC CXX
# MODE: cmake | pkgconfig | relocate | subdirectory (see CMakeLists.txt); CONFIG: the build's
# configuration (may be empty); SYMBOLIC: ON if heavytop_symbolic is built; CXX: the compiler.
# HEAVYTOP_LIBDIR, HEAVYTOP_INCLUDEDIR, HEAVYTOP_PREFIX: the build's CMAKE_INSTALL_LIBDIR,
# _INCLUDEDIR and _PREFIX (default lib, include, none). Everything happens in a temporary
# folder, removed on exit.
set -euo pipefail

mode=$1
build=$(realpath "$2")
source=$(realpath "$3")
config=$4
symbolic=$5
cxx=$6
consumer=$source/tests/package/consumer
lib=${HEAVYTOP_LIBDIR:-lib}
inc=${HEAVYTOP_INCLUDEDIR:-include}

work=$(mktemp -d "${TMPDIR:-/tmp}/heavytop-package.XXXXXX")
trap 'rm -rf "$work"' EXIT
# No outside settings leak in: the prefix is found only where this script says.
unset CMAKE_PREFIX_PATH CMAKE_BUILD_TYPE CMAKE_GENERATOR PKG_CONFIG_PATH CXXFLAGS LDFLAGS

fail() { echo "FAIL: $*" >&2; exit 1; }

install_into() {  # prefix
  cmake --install "$build" --prefix "$1" ${config:+--config "$config"} >/dev/null
  local expected=("$inc/heavytop/heavytop.hpp" "$inc/heavytop/version.hpp"
                  "$lib/libheavytop_core.a" "$lib/pkgconfig/heavytop.pc"
                  "$lib/cmake/heavytop/heavytopConfig.cmake" "$lib/cmake/heavytop/heavytopConfigVersion.cmake"
                  "$lib/cmake/heavytop/heavytopCoreTargets.cmake")
  [[ $symbolic == ON ]] && expected+=("$inc/heavytop/symbolic/derive.hpp" "$lib/libheavytop_symbolic.a"
                                      "$lib/pkgconfig/heavytop-symbolic.pc"
                                      "$lib/cmake/heavytop/heavytopSymbolicTargets.cmake")
  for file in "${expected[@]}"; do
    [[ -f $1/$file ]] || fail "not installed: $file"
  done
  # The umbrella header names every public header of the core.
  for header in "$1/$inc"/heavytop/*.hpp; do
    name=heavytop/$(basename "$header")
    [[ $name == heavytop/heavytop.hpp ]] || grep -q "#include \"$name\"" "$1/$inc/heavytop/heavytop.hpp" ||
      fail "heavytop.hpp does not include $name"
  done
}

build_consumer() {  # prefix folder
  cmake -S "$consumer" -B "$2" -DCMAKE_PREFIX_PATH="$1" -DCMAKE_CXX_COMPILER="$cxx" \
        -DCONSUMER_SYMBOLIC="$symbolic" ${config:+-DCMAKE_BUILD_TYPE="$config"} >"$2.log" ||
    { cat "$2.log"; fail "configuring the consumer against $1"; }
  grep -q "^heavytop_DIR:PATH=$1/" "$2/CMakeCache.txt" || fail "the consumer did not find heavytop in $1"
  cmake --build "$2" >>"$2.log" || { cat "$2.log"; fail "building the consumer against $1"; }
  "$2/app"
}

case $mode in
  cmake)
    install_into "$work/prefix"
    build_consumer "$work/prefix" "$work/consumer"
    ;;

  pkgconfig)
    install_into "$work/prefix"
    modules=(heavytop) defines=()
    [[ $symbolic == ON ]] && modules+=(heavytop-symbolic) defines+=(-DHEAVYTOP_CONSUMER_SYMBOLIC)
    export PKG_CONFIG_PATH=$work/prefix/$lib/pkgconfig
    version=$(pkg-config --modversion heavytop)
    # Compiled once; linked with the plain flags (what a user types) and with --static. The
    # flags are split into words on purpose, as in a makefile.
    # shellcheck disable=SC2046
    {
      "$cxx" -std=c++20 -c "$consumer/main.cpp" -o "$work/main.o" "${defines[@]}" \
             -DHEAVYTOP_CONSUMER_EXPECTED_VERSION="\"$version\"" $(pkg-config --cflags "${modules[@]}")
      "$cxx" "$work/main.o" -o "$work/app" $(pkg-config --libs "${modules[@]}")
      "$cxx" "$work/main.o" -o "$work/app-static" $(pkg-config --libs --static "${modules[@]}")
    }
    "$work/app"
    "$work/app-static"
    ;;

  relocate)
    install_into "$work/prefix"
    mkdir "$work/moved"
    mv "$work/prefix" "$work/moved/prefix"  # the original prefix no longer exists
    # No installed package file names where it was built, from what, where it was installed,
    # or the prefix configured at build time (here the files went elsewhere).
    paths=("$build" "$source" "$work/prefix")
    configured=${HEAVYTOP_PREFIX:-}
    [[ -n ${configured%/} ]] && paths+=("${configured%/}/")  # not for a prefix of /
    for path in "${paths[@]}"; do
      if grep -rlF "$path" "$work/moved/prefix/$lib/cmake" "$work/moved/prefix/$lib/pkgconfig"; then
        fail "the installed files above name $path"
      fi
    done
    build_consumer "$work/moved/prefix" "$work/consumer"
    includedir=$(PKG_CONFIG_PATH=$work/moved/prefix/$lib/pkgconfig pkg-config --variable=includedir heavytop)
    [[ $(realpath "$includedir") == "$work/moved/prefix/$inc" ]] ||
      fail "heavytop.pc does not follow the move: includedir=$includedir"
    ;;

  subdirectory)
    cmake -S "$source/tests/package/parent" -B "$work/parent" -DHEAVYTOP_SOURCE_DIR="$source" \
          -DCMAKE_CXX_COMPILER="$cxx" -DCONSUMER_SYMBOLIC="$symbolic" >"$work/parent.log" ||
      { cat "$work/parent.log"; fail "configuring the parent project"; }
    cmake --build "$work/parent" -j"$(nproc)" >>"$work/parent.log" ||
      { cat "$work/parent.log"; fail "building the parent project"; }
    "$work/parent/app"
    ;;

  *) fail "unknown mode $mode" ;;
esac
echo "package_$mode: ok"
