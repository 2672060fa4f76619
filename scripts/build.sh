#!/usr/bin/env bash
# Builds heavytop into build/, installing its Debian 12 packages first (once).
#   ./scripts/build.sh           the main job only: the core, io, the report and the command line
#   ./scripts/build.sh --tests   everything: also the tests, benchmarks, Python, the symbolic
#                                derivations and the browser page, with their packages
set -euo pipefail
cd "$(dirname "$0")/.."
all=OFF
case "${1:-}" in
  "") ;;
  --tests | --all) all=ON ;;
  *) echo "usage: scripts/build.sh [--tests]" >&2; exit 2 ;;
esac
if [ "$all" = ON ]; then ./scripts/install-deps.sh --tests; else ./scripts/install-deps.sh; fi
# ccache, when present, makes rebuilds cheap; the build never needs it.
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
  -DHEAVYTOP_BUILD_TESTS=$all -DHEAVYTOP_BUILD_BENCHMARKS=$all -DHEAVYTOP_BUILD_PYTHON=$all \
  -DHEAVYTOP_BUILD_SYMBOLIC=$all -DHEAVYTOP_INSTALL=$all >/dev/null
if [ "$all" = ON ]; then
  cmake --build build -j"$(nproc)"
else
  cmake --build build -j"$(nproc)" --target heavytop
fi
