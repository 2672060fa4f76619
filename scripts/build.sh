#!/usr/bin/env bash
# Installs the dependencies (Debian 12 packages, once) and builds heavytop into build/.
#   ./scripts/build.sh --web   also the core in WebAssembly and the explorer page that
#                              `heavytop explore` writes (Emscripten; about 5 minutes more from clean)
set -euo pipefail
cd "$(dirname "$0")/.."
web=OFF
[ "${1:-}" = "--web" ] && web=ON
if [ "$web" = ON ]; then ./scripts/install-deps.sh --web; else ./scripts/install-deps.sh; fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DHEAVYTOP_BUILD_WEB=$web >/dev/null
cmake --build build -j"$(nproc)"
