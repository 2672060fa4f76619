#!/usr/bin/env bash
# Builds heavytop's libFuzzer targets with clang into build-fuzz/ (every library instrumented:
# -fsanitize=fuzzer-no-link,address,undefined; the targets -fsanitize=fuzzer,address,undefined)
# and runs each for SECONDS (default 60) on a copy of its seed corpus, fuzz/corpus/NAME.
# Fails on any finding (crash, sanitizer report, leak, timeout, exception, out of memory); the
# input that found it is left in build-fuzz/fuzz/run-NAME/artifacts/.
#
#   scripts/fuzz.sh [SECONDS [TARGET...]]      TARGET: config, cli, mesh, decay, map (default all)
#
# Reproduce a finding: build-fuzz/fuzz/fuzz_NAME build-fuzz/fuzz/run-NAME/artifacts/crash-...
# (fuzz_cli's input is the argument list, one per line; HEAVYTOP_FUZZ_VERBOSE=1 shows its output).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(config cli mesh decay map)

./scripts/install-deps.sh
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
echo "fuzz: configuring build-fuzz/ (clang-14, $flags)"
cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
      -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
      -DCMAKE_CXX_FLAGS="$flags" -DHEAVYTOP_BUILD_FUZZ=ON -DHEAVYTOP_BUILD_PYTHON=OFF \
      -DHEAVYTOP_BUILD_BENCHMARKS=OFF -DHEAVYTOP_BUILD_TESTS=ON -DHEAVYTOP_INSTALL=OFF \
      -DHEAVYTOP_FUZZ_SECONDS="$seconds" >/dev/null
echo "fuzz: building ${targets[*]/#/fuzz_}"
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]/#/fuzz_}"

failed=0
for t in "${targets[@]}"; do
  echo "fuzz: fuzz_$t for $seconds s on fuzz/corpus/$t ($(ls fuzz/corpus/$t | wc -l) seeds, dictionary fuzz/$t.dict)"
  bash fuzz/run_fuzzer.sh "build-fuzz/fuzz/fuzz_$t" "fuzz/corpus/$t" "fuzz/$t.dict" \
       "build-fuzz/fuzz/run-$t" "$seconds" || failed=1
done
[ $failed -eq 0 ] && echo "fuzz: no findings" || echo "fuzz: FINDINGS (above)"
exit $failed
