#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time on a fresh copy of its seed corpus and fails on
# any finding (crash, sanitizer report, leak, timeout, out of memory). Used by ctest (fuzz/
# CMakeLists.txt) and scripts/fuzz.sh.
#
#   run_fuzzer.sh FUZZER SEEDS DICT WORK [SECONDS]
#
# WORK (removed first) receives corpus/ (the seeds and what the run adds), artifacts/ (the
# input of a finding, if any) and log (libFuzzer's output). The seeds are only read.
set -euo pipefail
fuzzer=$1 seeds=$2 dict=$3 work=$4 seconds=${5:-20}

rm -rf "$work"
mkdir -p "$work/corpus" "$work/artifacts"
cp "$seeds"/* "$work/corpus/"
seeded=$(ls "$work/corpus" | wc -l)

args=(-max_total_time="$seconds" -rss_limit_mb=2048 -timeout=30 -print_final_stats=1
      -artifact_prefix="$work/artifacts/")
[ -f "$dict" ] && args+=(-dict="$dict")
# Any sanitizer report ends the run with a non-zero status.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$(cd "$(dirname "$0")/.." && pwd)/scripts/lsan.supp}

name=$(basename "$fuzzer")
set +e
"$fuzzer" "${args[@]}" "$work/corpus" > "$work/log" 2>&1
rc=$?
set -e

stat() { sed -n "s/^stat::$1: *//p" "$work/log" | tail -1; }
findings=$(ls "$work/artifacts" | wc -l)
echo "$name: ${seconds} s, $(stat number_of_executed_units) executions ($(stat average_exec_per_sec)/s)," \
     "corpus $seeded seeds -> $(ls "$work/corpus" | wc -l) inputs, $(grep -o 'cov: [0-9]*' "$work/log" | tail -1)," \
     "peak RSS $(stat peak_rss_mb) MB, exit $rc, findings $findings"
if [ "$rc" -ne 0 ] || [ "$findings" -ne 0 ]; then
  echo "$name: FINDING (log: $work/log; input: $work/artifacts/)"
  grep -E -m1 -A40 'ERROR: |runtime error|==ERROR|deadly signal|uncaught|timeout|out-of-memory|fuzz_(cli|config|mesh|decay|map):' \
    "$work/log" || tail -40 "$work/log"
  ls -l "$work/artifacts"
  exit 1
fi
