#!/usr/bin/env bash
# Installs heavytop's build and test dependencies from Debian 12's packages.
# Does nothing (and needs no network) when they are all present already.
set -euo pipefail

# What the main job needs: the core, io, the report (gnuplot draws its figures; node bundles
# its page script) and the command line.
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libboost-dev          # linear algebra; Boost.Odeint and Boost.Math (header-only)
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libfmt-dev
  gnuplot-nox fonts-dejavu-core       # figures (PNG and SVG)
  libassimp-dev                       # CAD meshes (STL, OBJ, PLY) for [[body.part]] shape = "mesh"
  libhdf5-dev                         # big maps as HDF5 (sweep --format hdf5)
  nodejs                              # the report's page script (npm packages, bundled at build time)
)
# `install-deps.sh --tests`: the rest, for the test command (scripts/build.sh --tests).
if [ "${1:-}" = "--tests" ] || [ "${1:-}" = "--peers" ]; then
  packages+=(
    libgtest-dev libgmock-dev libbenchmark-dev
    libginac-dev libcln-dev             # computer algebra for the symbolic target
    texlive-latex-base                  # pdflatex: the test that derive's LaTeX compiles
    python3 python3-dev pybind11-dev python3-numpy python3-pytest python3-matplotlib
    python3-pandas                      # to_dataframe() (python/tests/test_notebook.py)
    jupyter-nbconvert python3-ipykernel # the notebook test (examples/notebooks/tour.ipynb)
    python3-venv python3-pip python3-setuptools python3-wheel  # the pip install test (python_pip)
    libopenmpi-dev openmpi-bin          # heavytop-mpi: sweeps across the ranks of an MPI job (mpirun)
    strace                              # tests/startup.sh: what a command opens before its work
    valgrind                            # tests/other_processors.sh: the command where AVX-512 is absent
    clang-14 libclang-rt-14-dev         # libFuzzer and the sanitizers' runtimes (scripts/fuzz.sh)
    chromium                            # the report's and the page's browser tests
  )
fi
# npm: Debian's package, unless a node install (e.g. NodeSource's nodejs) already brings its own.
command -v npm >/dev/null 2>&1 || packages+=(npm)

# `install-deps.sh --web`: the explorer page (web/, `heavytop explore`): Emscripten's em++, node,
# and chromium for its browser test (scripts/build.sh --web); --tests takes them too.
case "${1:-}" in --web | --tests) packages+=(emscripten nodejs chromium) ;; esac

# bench/peers/ (run by hand, not in CI): `install-deps.sh --peers` adds the other libraries.
[ "${1:-}" = "--peers" ] && packages+=(libgsl-dev python3-scipy libmujoco-dev)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -ne 0 ]; then
  SUDO=sudo
else
  SUDO=
fi
echo "install-deps: installing ${missing[*]}" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
