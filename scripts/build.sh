#!/usr/bin/env bash
# Installs the dependencies (Debian 12 packages, once) and builds heavytop into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
