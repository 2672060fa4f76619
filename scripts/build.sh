#!/usr/bin/env bash
# Builds heavytop into build/, installing its Debian 12 packages first (once).
#   ./scripts/build.sh           the main job only: the core, io, the report and the command line
#   ./scripts/build.sh --tests   everything: also the tests, benchmarks, Python, the symbolic
#                                derivations and the browser page, with their packages; and the
#                                explorer page (the core in WebAssembly, Emscripten) as --web
#   ./scripts/build.sh --web     the main job and the explorer page that `heavytop explore` writes
#                                (Emscripten; 5 to 8 minutes more from clean on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
all=OFF
web=OFF
case "${1:-}" in
  "") ;;
  --tests | --all) all=ON web=ON ;;
  --web) web=ON ;;
  *) echo "usage: scripts/build.sh [--tests | --web]" >&2; exit 2 ;;
esac
if [ "$all" = ON ]; then ./scripts/install-deps.sh --tests; elif [ "$web" = ON ]; then ./scripts/install-deps.sh --web;
else ./scripts/install-deps.sh; fi
# ccache, when present, makes rebuilds cheap; the build never needs it.
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
  -DHEAVYTOP_BUILD_TESTS=$all -DHEAVYTOP_BUILD_BENCHMARKS=$all -DHEAVYTOP_BUILD_PYTHON=$all \
  -DHEAVYTOP_BUILD_SYMBOLIC=$all -DHEAVYTOP_INSTALL=$all -DHEAVYTOP_BUILD_WEB=$web \
  -DCMAKE_DISABLE_FIND_PACKAGE_MPI=$([ "$all" = ON ] && echo OFF || echo ON) >/dev/null  # heavytop-mpi: tests only
if [ "$all" = ON ]; then
  cmake --build build -j"$(nproc)"
elif [ "$web" = ON ]; then
  cmake --build build -j"$(nproc)" --target heavytop heavytop_web
else
  cmake --build build -j"$(nproc)" --target heavytop
fi
