#!/usr/bin/env bash
# Builds all of heavytop with AddressSanitizer (leaks included) and UndefinedBehaviorSanitizer
# (gcc: -fsanitize=address,undefined -fno-omit-frame-pointer) into build-asan/ and runs the
# ctest suite there. Exits non-zero on a failing test or on any sanitizer report: every report
# is also written to build-asan/sanitizer-logs/ (log_path), so that one is found even where a
# test discards the program's stderr or expects a failing exit status.
#
#   scripts/sanitize.sh [CTEST ARGS...]        e.g. scripts/sanitize.sh -R hostile_input
#
# Then every fuzzer runs for 60 s (HEAVYTOP_FUZZ_SECONDS) through scripts/fuzz.sh, and the
# Python argument fuzzer (fuzz/fuzz_python.py) on the sanitized module.
#
# Left out (by label): `package` (package_test.sh installs the libraries and builds consumers
# without -fsanitize, and the instrumented static libraries cannot link there) and `pip` (pip
# compiles a separate, unsanitized copy of the module; minutes). The Python tests (python,
# python_example, and readme_commands, which runs the README's Python session) run the
# sanitized module inside Debian's unsanitized /usr/bin/python3, with libasan preloaded and
# leak detection off (the interpreter does not free its own memory at exit); mpirun's ranks run
# with leak detection off too (OpenMPI's own, in plugins it unloads: tests/harness.sh);
# everything else runs with detect_leaks=1. scripts/lsan.supp names the one leak that is not
# heavytop's (libcln's static initializer). `startup` skips itself (strace and a sanitizer's
# runtime do not mix), and hostile_input_3's time limit is scaled by 4.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
./scripts/install-deps.sh

start=$(date +%s)
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
logs=$root/build-asan/sanitizer-logs
# The build runs test programs too (gtest_discover_tests lists each suite's tests).
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:exitcode=99:log_path=$logs/asan:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:exitcode=99:log_path=$logs/ubsan"
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"
# The tests skip what cannot work under a sanitizer (hostile_input's ulimit -v check).
export HEAVYTOP_SANITIZED=1
# read_map's HDF5 child (io/src/map_file.cpp: libhdf5 reads a map in a forked process, so that
# its overreads on a corrupted file stay there) reports here; each report must be inside libhdf5.
child_logs=$root/build-asan/sanitizer-logs-hdf5-child
export HEAVYTOP_CHILD_REPORT_PATH=$child_logs/report

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
echo "sanitize: configuring build-asan/ (gcc, $flags)"
cmake -S . -B build-asan "${launcher[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
      -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" \
      -DCMAKE_MODULE_LINKER_FLAGS="$flags" -DHEAVYTOP_BUILD_BENCHMARKS=OFF -DHEAVYTOP_TEST_SUBDIRECTORY=OFF -DHEAVYTOP_TEST_TIMEOUT_SCALE=4 \
      >/dev/null
rm -rf "$logs" "$child_logs"
mkdir -p "$logs" "$child_logs"
echo "sanitize: building"
cmake --build build-asan -j"$(nproc)"
built=$(date +%s)

status=0
# Reports that reached a test's output rather than the log files (ctest keeps every output).
outputs=$root/build-asan/sanitizer-logs-ctest
rm -rf "$outputs"
mkdir -p "$outputs"
keep_output() { cp build-asan/Testing/Temporary/LastTest.log "$outputs/$1.log" 2>/dev/null || true; }
# readme_commands runs the README's Python session as well as its commands: with the Python tests.
python_tests='^python|^readme_commands$'
echo "sanitize: ctest, everything but the Python tests (labels package, pip left out)"
ctest --test-dir build-asan --output-on-failure -LE 'package|pip' -E "$python_tests" "$@" || status=1
keep_output main
echo "sanitize: ctest, the Python tests (libasan preloaded, detect_leaks=0)"
LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)" \
  ASAN_OPTIONS="${ASAN_OPTIONS/detect_leaks=1/detect_leaks=0}" \
  ctest --test-dir build-asan --output-on-failure -LE 'package|pip' -R "$python_tests" "$@" || status=1
keep_output python
# The Python module's argument conversion (fuzz/fuzz_python.py, a seeded random driver: every
# failure a ValueError or TypeError in one line, never a crash), sanitized module, same preload.
echo "sanitize: fuzz_python for ${HEAVYTOP_FUZZ_SECONDS:-60} s (the sanitized module)"
LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)" \
  ASAN_OPTIONS="${ASAN_OPTIONS/detect_leaks=1/detect_leaks=0}" PYTHONPATH="$root/build-asan/python" \
  /usr/bin/python3 fuzz/fuzz_python.py --seconds "${HEAVYTOP_FUZZ_SECONDS:-60}" --seed "$(date +%s)" || status=1

# A short run of every fuzzer (issue 30: the configuration, the command line, mesh files, the
# decay CSV, maps and sweep journals), each HEAVYTOP_FUZZ_SECONDS (60) under ASan and UBSan
# with libFuzzer (clang-14; build-fuzz/). Its findings fail the script like a test's.
echo "sanitize: the fuzzers, ${HEAVYTOP_FUZZ_SECONDS:-60} s each (scripts/fuzz.sh)"
if command -v clang++-14 >/dev/null; then
  ./scripts/fuzz.sh "${HEAVYTOP_FUZZ_SECONDS:-60}" || status=1
else
  echo "sanitize: clang++-14 not found: the fuzzers were not run"
  status=1
fi

end=$(date +%s)
reports=$(find "$logs" -type f | wc -l)
pattern='runtime error:|ERROR: (Address|Leak|UndefinedBehavior)Sanitizer'
in_outputs=$({ grep -h -E "$pattern" "$outputs"/*.log || true; } | wc -l)
if [ "$in_outputs" -ne 0 ]; then
  echo "sanitize: $in_outputs sanitizer report(s) in the tests' output:"
  grep -h -A12 -E "$pattern" "$outputs"/*.log | head -80
  reports=$((reports + in_outputs))
fi
if [ "$(find "$logs" -type f | wc -l)" -ne 0 ]; then
  echo "sanitize: sanitizer reports in $logs:"
  for f in "$logs"/*; do
    echo "---- $f"
    head -60 "$f"
  done
fi
# The HDF5 child's reports: each one's first frame past the sanitizer's own is libhdf5's (H5...).
contained=0
for f in "$child_logs"/*; do
  [ -e "$f" ] || continue
  if grep -E '^ +#[0-9]+ ' "$f" | grep -v -E 'interceptor|sanitizer|libasan|libubsan' | head -1 | grep -q ' in H5'; then
    contained=$((contained + 1))
  else
    echo "sanitize: a report of the HDF5 child outside libhdf5: $f"
    head -30 "$f"
    reports=$((reports + 1))
  fi
done
[ "$contained" -eq 0 ] || echo "sanitize: $contained report(s) inside libhdf5, in read_map's child (corrupted HDF5 files, refused as such): $child_logs"
[ "$reports" -eq 0 ] || status=1
echo "sanitize: build $((built - start)) s, tests $((end - built)) s;" \
     "$([ $status -eq 0 ] && echo clean || echo FAILED), $reports sanitizer report(s)"
exit $status
