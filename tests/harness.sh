# Shared by the shell tests: the binary in $H, a scratch folder as the working directory
# (removed at exit, with any background job), and check NAME COMMAND... counting results
# (HEAVYTOP_SHOW_PASSES=1 prints the passes too: to see which checks an older build passes).
set -u
H=$(realpath "${HEAVYTOP:?set HEAVYTOP to the heavytop binary}")
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$work"' EXIT
cd "$work"
failures=0
passes=0
check() {
  local name=$1; shift
  if "$@"; then passes=$((passes + 1)); if [ -n "${HEAVYTOP_SHOW_PASSES:-}" ]; then echo "ok: $name"; fi
  else echo "FAIL: $name"; failures=$((failures + 1)); fi
}
# mpirun, as the tests call it. OpenMPI does not free what MPI_Init allocates, much of it in
# plugins unloaded by exit (frames LeakSanitizer cannot name, so no suppression matches): under
# scripts/sanitize.sh its ranks run with leak detection off (ASan's other checks stay on).
mpirun=(mpirun)
if [ -n "${HEAVYTOP_SANITIZED:-}" ]; then mpirun=(env "ASAN_OPTIONS=${ASAN_OPTIONS/detect_leaks=1/detect_leaks=0}" mpirun); fi
finish() {
  echo "$passes passed, $failures failed"
  [ $failures -eq 0 ]
}
