#!/usr/bin/env bash
# What a command does before its work (issue 17): heavytop and heavytop-derive load no shared
# library (linked static when HEAVYTOP_STATIC=1, as HEAVYTOP_STATIC_CLI builds them), and a
# verdict or a simulation opens no file at all: no locale, font, gnuplot, Python or GiNaC
# work at start-up (strace). The timing itself is bench/bench_startup, not a test.
source "$(dirname "$0")/harness.sh"
D=$(dirname "$H")/heavytop-derive
# A sanitized build is linked to its runtime (libasan, libubsan), which opens files of its own
# at start-up, and LeakSanitizer cannot run under strace: nothing here applies (skip, 77).
if [ -n "${HEAVYTOP_SANITIZED:-}" ]; then echo "skipped: a sanitized build (scripts/sanitize.sh)"; exit 77; fi

# No program interpreter and no DT_NEEDED entry: nothing for a dynamic loader to do.
no_shared_libraries() {
  ! readelf -lW "$1" | grep -q 'INTERP' && ! readelf -dW "$1" | grep -q '(NEEDED)'
}
if [ "${HEAVYTOP_STATIC:-0}" = 1 ]; then
  check "heavytop is static" no_shared_libraries "$H"
fi
if [ "${HEAVYTOP_DERIVE_STATIC:-0}" = 1 ]; then
  check "heavytop-derive is static" no_shared_libraries "$D"
fi

# The files a command opens (open, openat, stat and the like, not the execve of a program),
# its children included.
opened() {
  strace -f -qq -e trace=%file -o trace.txt "$@" > out.txt 2>/dev/null
  grep -v ' execve(' trace.txt | grep -oE '^[0-9]+ +[a-z0-9_]+\((AT_FDCWD, )?"[^"]*"' |
    sed -E 's/.*"([^"]*)"$/\1/' | sort -u
}
for args in "stability --format json" "stability --format text" "simulate --model nonlinear --t-end 1e-3" \
            "simulate --model first-order --samples 101" "compare --t-end 0.01"; do
  # shellcheck disable=SC2086
  files=$(opened "$H" $args | grep -v '^/proc/self/exe$')  # static glibc reads its own path
  check "$args opens no file (got: $(echo $files))" test -z "$files"
  # shellcheck disable=SC2086
  check "$args still works" test -s out.txt
done

# derive: heavytop runs heavytop-derive and nothing else; with the static build no shared
# library is opened either (CLN's own static initializer opens /dev/tty, its debug stream).
files=$(opened "$H" derive --format json)
check "derive prints its JSON" python3 -c 'import json,sys; json.load(open("out.txt"))'
check "derive runs heavytop-derive" grep -q "execve(\"$D\"" trace.txt
if [ "${HEAVYTOP_DERIVE_STATIC:-0}" = 1 ]; then
  check "derive opens no shared library (got: $(echo $files))" bash -c "! grep -q '\.so' <<< '$files'"
fi
finish
