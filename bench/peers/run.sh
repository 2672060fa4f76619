#!/bin/bash
# heavytop against other libraries on issue 14's two problems, at equal error, and the nonlinear
# column of two 40 x 40 maps against a GSL loop (issue 31; maps.cpp), by hand, not CI.
#   bench/peers/run.sh [BUILD_DIR] [REPS] [MAP_REPS]      e.g. bench/peers/run.sh build 15 5
# BUILD_DIR is a configured Release build of heavytop (its libheavytop_core.a is built here).
# Needs libgsl-dev, Boost (odeint) and, for the SciPy and MuJoCo rows, python3-scipy and
# libmujoco-dev (scripts/install-deps.sh --peers installs them).
# Prints Markdown tables (the equal-error rows also go to BUILD_DIR/peers/peers.csv).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
reps=${2:-15}
map_reps=${3:-5}
cmake --build "$build" --target heavytop_core -j2 >/dev/null
mkdir -p "$build/peers"
mujoco=()
if [ -f /usr/include/mujoco/mujoco.h ]; then mujoco=(-DHEAVYTOP_PEERS_MUJOCO -lmujoco); else
  echo "MuJoCo rows: libmujoco-dev is not installed (scripts/install-deps.sh --peers)"; fi
g++ -std=c++20 -O3 -DNDEBUG -I"$root/include" -I"$build/include" -I/usr/include/eigen3 "$here/peers.cpp" \
    "$build/libheavytop_core.a" -lgsl -lgslcblas -lfmt -lpthread "${mujoco[@]}" -o "$build/peers/peers"
g++ -std=c++20 -O3 -DNDEBUG -I"$root/include" -I"$build/include" -I/usr/include/eigen3 "$here/paired.cpp" \
    "$build/libheavytop_core.a" -lgsl -lgslcblas -lfmt -lpthread -o "$build/peers/paired"  # by hand: paired [ROUNDS]
g++ -std=c++20 -O3 -DNDEBUG -I"$root/include" -I"$build/include" -I/usr/include/eigen3 "$here/maps.cpp" \
    "$build/libheavytop_core.a" -lgsl -lgslcblas -lfmt -lpthread -o "$build/peers/maps"
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
# From the build folder: MuJoCo writes MUJOCO_LOG.TXT (its warnings) into the current one.
(cd "$build/peers" && ./peers --reps "$reps" --csv "$build/peers/peers.csv" --reference "$build/peers/reference.txt")
if /usr/bin/python3 -c 'import scipy' 2>/dev/null; then
  /usr/bin/python3 "$here/scipy_peers.py" --reference "$build/peers/reference.txt" --heavytop "$build/peers/peers.csv" \
      --reps "$(( reps < 7 ? reps : 7 ))"
else
  echo "SciPy rows: python3-scipy is not installed"
fi
echo
echo "maps (load $(cut -d' ' -f1-3 /proc/loadavg)):"
"$build/peers/maps" --reps "$map_reps"
