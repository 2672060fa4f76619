#!/usr/bin/env bash
# The report page in a real browser (browser_report.cjs: headless chromium, puppeteer-core from
# report/web's npm packages): the built-in example's report as `heavytop` writes it, and an
# asymmetric body whose approximate models diverge. Screenshots are kept in $ARTEFACTS.
# Skips (exit 77) when this build has no interactive page (npm was not reachable at build time).
source "$(dirname "$0")/harness.sh"
: "${CHROMIUM:?}" "${NODE:?}" "${NODE_MODULES:?}" "${ARTEFACTS:?}"
mkdir -p "$ARTEFACTS"
rm -f "$ARTEFACTS"/*.png

"$H" > example.log
check "the built-in example's report" test $? -eq 0 -a -e heavytop-report/report.html
if [ ! -e heavytop-report/heavytop-report.js ]; then
  echo "SKIP: this heavytop was built without the interactive page:"
  grep -o "No interactive view[^<]*" heavytop-report/report.html
  exit 77
fi
"$H" report --A 1 --B 1.5 --C 2 --mass 1 --gravity 1 --length 1 --spin 1.3 --theta0 0.01 --output asymmetric > /dev/null
check "an asymmetric body's report" test $? -eq 0

NODE_PATH="$NODE_MODULES" "$NODE" "$(dirname "$0")/browser_report.cjs" "$CHROMIUM" "$ARTEFACTS" \
  example="$PWD/heavytop-report" asymmetric="$PWD/asymmetric"
check "in the browser" test $? -eq 0
# The answer first (SPEC 14): the example (proven stable), a top too slow (falls), a damped one.
"$H" stability --format json > example.json
"$H" report --spin 100 --output falling > /dev/null && "$H" stability --spin 100 --format json > falling.json
check "a falling body's report" test $? -eq 0
"$H" report --axial-damping 2e-6 --output damped > /dev/null && "$H" stability --axial-damping 2e-6 --format json > damped.json &&
  "$H" lifetime --axial-damping 2e-6 --format json > damped-lifetime.json
check "a damped body's report" test $? -eq 0
NODE_PATH="$NODE_MODULES" "$NODE" "$(dirname "$0")/browser_answer.cjs" "$CHROMIUM" \
  example="$PWD/heavytop-report,example.json" falling="$PWD/falling,falling.json" \
  damped="$PWD/damped,damped.json,damped-lifetime.json"
check "the answer first, in the browser" test $? -eq 0
echo "screenshots: $ARTEFACTS"
finish
