#!/usr/bin/env bash
# heavytop on a processor other than this one: under valgrind, whose virtual processor has no
# AVX-512, so the kernels are chosen again at run time (the Taylor recurrence's and the
# batch's: AVX2 or SSE2 there, where this machine's batch runs AVX-512). Nothing compiled for a
# wider instruction set may run before that choice (a static constructor in an AVX-512 file
# once did: SIGILL at start-up on every processor without it), and every kernel promises the
# same bits, so the outputs must be byte-identical to the native run's.
C=$(realpath "$(dirname "$0")/../examples")
source "$(dirname "$0")/harness.sh"
if ! command -v valgrind >/dev/null 2>&1; then echo "skipped: valgrind is not installed"; exit 77; fi
if [ -n "${HEAVYTOP_SANITIZED:-}" ]; then echo "skipped: a sanitized build (scripts/sanitize.sh)"; exit 77; fi

# valgrind --tool=none translates every instruction (an unknown one stops the run) and checks
# nothing else: the fastest of its tools.
elsewhere() { valgrind --tool=none --error-exitcode=3 -q "$@" 2> valgrind.txt; }

# The Taylor integrator (the plain recurrence on the asymmetric plate, the spin-factored one on
# the toy top) and the batch's tilt verdicts (a small nonlinear map of the plate).
runs=("simulate --config $C/asymmetric-plate.toml --model nonlinear --integrator taylor --t-end 5 --samples 21 --format csv"
      "simulate --config $C/toy-top.toml --model nonlinear --integrator taylor --t-end 0.5 --samples 21 --format csv"
      "sweep --config $C/asymmetric-plate.toml --vary B/A=1.05:2.95:6 --vary spin=0.5:4:6 --model nonlinear --horizon 10 --max-tilt 0.5 --output -")
for args in "${runs[@]}"; do
  # shellcheck disable=SC2086
  "$H" $args > native.txt
  # shellcheck disable=SC2086
  elsewhere "$H" $args > other.txt
  rc=$?
  check "$args runs without AVX-512 (rc $rc: $(head -c 300 valgrind.txt))" test $rc -eq 0
  check "$args: the same bytes without AVX-512" cmp -s native.txt other.txt
  check "$args wrote something" test -s native.txt
done
finish
