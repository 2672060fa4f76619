#!/usr/bin/env bash
# A build where npm cannot fetch the page's packages (no network) must still build: the
# asset step (report/web/build_assets.cmake) then writes a C++ source without the files and
# with the reason, which compiles, and the report shows its static figures with that note.
# Usage: report_web_fallback.sh CMAKE CXX SOURCE_DIR
set -u
cmake=$1 cxx=$2 src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { local name=$1; shift; if "$@"; then echo "ok   $name"; else echo "FAIL $name"; failures=$((failures + 1)); fi; }

# npm that fails as it does offline.
printf '#!/bin/sh\necho "npm error code ENOTFOUND: getaddrinfo ENOTFOUND registry" >&2\nexit 1\n' > "$work/npm"
chmod +x "$work/npm"
"$cmake" -DNODE=/bin/false -DNPM="$work/npm" -DSRC="$src/report/web" -DWORK="$work/web" -DOUT="$work/web_assets.cpp" \
  -P "$src/report/web/build_assets.cmake" > "$work/log" 2>&1
check "the asset step succeeds without npm" test $? -eq 0
check "it says why, in the build log" grep -q "no interactive page in this build" "$work/log"
check "the source has no files" grep -q "return {};" "$work/web_assets.cpp"
check "and the reason for the page" grep -q "npm ci failed.*ENOTFOUND" "$work/web_assets.cpp"
check "it compiles" "$cxx" -std=c++20 -fsyntax-only -I "$src/report/src" "$work/web_assets.cpp"
check "the next build tries npm again" test ! -e "$work/web/package-lock.json"
[ $failures -eq 0 ]
