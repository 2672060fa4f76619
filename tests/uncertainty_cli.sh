#!/usr/bin/env bash
# Uncertain inputs from the command line (SPEC section 17), as a user drives them: the
# "uncertainty" object's keys exactly, the answer's added sentence, the file's [uncertainty]
# with --uncertain over it key by key, every refusal naming its key with exit 2 and no file
# written, and every output byte-identical to main's binary without an uncertainty
# (HEAVYTOP_BEFORE, when given: a build without SPEC 17).
examples=$(realpath "$(dirname "$0")/../examples")
source "$(dirname "$0")/harness.sh"

# The JSON: SPEC 17's keys, in its order, and the numbers' ranges.
"$H" stability --config "$examples/toy-top.toml" --uncertain A=2% --uncertain C=1e-7 --uncertain draws=2000 \
  --format json > u.json
check "uncertainty keys" python3 -c "
import json, sys
u = json.load(open('u.json'))['uncertainty']
ok = list(u) == ['method', 'draws', 'coverage', 'p_stays_up', 'p_stays_up_interval', 'critical_spin', 'falls_at',
                 'max_tilt', 'sensitivity']
ok = ok and list(u['critical_spin']) == ['value', 'standard_uncertainty', 'interval']
ok = ok and list(u['max_tilt']) == ['value', 'standard_uncertainty', 'interval', 'fraction']
ok = ok and u['falls_at'] is None and list(u['sensitivity']) == ['A', 'C']
ok = ok and u['method'] in ('linear', 'monte-carlo') and u['draws'] == 2000 and u['coverage'] == 0.95
lo, hi = u['p_stays_up_interval']
ok = ok and 0 <= lo <= u['p_stays_up'] <= hi <= 1
c = u['critical_spin']; ok = ok and c['interval'][0] < c['value'] < c['interval'][1]
sys.exit(0 if ok else 1)"
# The toy top at 200 rad/s, 2 % on A and 0.8 % on C: its critical spin ~133 rad/s moves by about
# 1.3 %, far below the spin, so every draw stays up (proven) and the law of propagation holds.
check "toy top stays up, linear" python3 -c "
import json, math, sys
u = json.load(open('u.json'))['uncertainty']
A, C, m, g, R = 4.35e-5, 1.2e-5, 0.06, 9.81, 0.025
wc = 2 * math.sqrt(A * m * g * R) / C
rel = math.sqrt(0.01 ** 2 + (1e-7 / C) ** 2)
c = u['critical_spin']
ok = u['p_stays_up'] == 1 and u['method'] == 'linear' and abs(c['value'] - wc) < 1e-9 * wc
ok = ok and abs(c['standard_uncertainty'] - rel * wc) < 1e-9 * wc
ok = ok and abs(u['sensitivity']['C'] + wc / C) < 1e-9 * wc / C
sys.exit(0 if ok else 1)"

# The answer's sentence, SPEC's form, in the text and the brief text.
"$H" stability --config "$examples/toy-top.toml" --uncertain A=2% --uncertain draws=1000 --brief > brief.txt
check "sentence" grep -Eq 'With these uncertainties it stays up with probability (1|0\.[0-9]{2}); the critical spin is [0-9]+ \+- [0-9]+ rpm \(95 %\)\.$' brief.txt
"$H" stability --config "$examples/toy-top.toml" --uncertain A=2% --uncertain draws=1000 > full.txt
check "sentence in the text's first paragraph" bash -c "head -1 full.txt | grep -q 'With these uncertainties it stays up with probability 1; the critical spin is 1273 +- 25 rpm (95 %).'"

# [uncertainty] in the file, and --uncertain over it key by key.
{ cat "$examples/toy-top.toml"; printf '\n[uncertainty]\nA = "50%%"\nlength = 0.0005\ndraws = 500\nseed = 3\n'; } > top.toml
"$H" stability --config top.toml --uncertain A=1% --format json > over.json
check "command line over the file" python3 -c "
import json, sys
u = json.load(open('over.json'))['uncertainty']
A, C, m, g, R = 4.35e-5, 1.2e-5, 0.06, 9.81, 0.025
wc = 2 * (A * m * g * R) ** 0.5 / C
rel = ((0.01 / 2) ** 2 + (0.0005 / R / 2) ** 2) ** 0.5
sys.exit(0 if u['draws'] == 500 and list(u['sensitivity']) == ['A', 'length']
         and abs(u['critical_spin']['standard_uncertainty'] - rel * wc) < 0.02 * rel * wc else 1)"
"$H" stability --config top.toml --format json > seeded1.json
"$H" stability --config top.toml --format json > seeded2.json
check "same seed, same result" cmp -s seeded1.json seeded2.json
# 50 % on A: w_c ~ sqrt(A) is far from linear over it; the Monte Carlo is reported.
check "large uncertainty: monte-carlo" python3 -c "
import json, sys
sys.exit(0 if json.load(open('seeded1.json'))['uncertainty']['method'] == 'monte-carlo' else 1)"

# Refusals: exit 2, one line naming the key, nothing written.
refused() {  # KEY-IN-MESSAGE ARGS...
  local key=$1; shift
  rm -f out.json
  "$H" stability --config "$examples/toy-top.toml" "$@" --format json --output out.json 2> err.txt
  local rc=$?
  [ $rc -eq 2 ] && [ ! -e out.json ] && grep -qF -e "$key" err.txt && [ "$(wc -l < err.txt)" -eq 1 ]
}
check "negative" refused uncertainty.A --uncertain A=-1e-6
check "abc%" refused uncertainty.A --uncertain A=abc%
check "negative percentage" refused uncertainty.C --uncertain C=-2%
check "unknown key" refused uncertainty.D --uncertain D=1
check "draws < 0" refused uncertainty.draws --uncertain draws=-1
check "unknown distribution" refused uncertainty.distribution --uncertain distribution=cauchy
check "relative of a zero" refused uncertainty.phi0 --uncertain phi0=1%
check "not KEY=VALUE" refused --uncertain --uncertain A
printf '[body]\nA = 4.35e-5\nB = 4.35e-5\nC = 1.2e-5\nmass = 0.06\nlength = 0.025\n[uncertainty]\nA = "abc%%"\n' > bad.toml
rm -f out.json
"$H" stability --config bad.toml --format json --output out.json 2> err.txt
check "file: abc%" bash -c "[ $? -eq 2 ] && [ ! -e out.json ] && grep -q uncertainty.A err.txt"
printf '[body]\nA = 4.35e-5\nB = 4.35e-5\nC = 1.2e-5\nmass = 0.06\nlength = 0.025\n[uncertainty]\nD = 1\n' > bad.toml
"$H" stability --config bad.toml --format json --output out.json 2> err.txt
check "file: unknown key" bash -c "[ $? -eq 2 ] && [ ! -e out.json ] && grep -q uncertainty.D err.txt"

# Without an uncertainty every output is as before, byte for byte.
if [ -n "${HEAVYTOP_BEFORE:-}" ] && [ -x "$HEAVYTOP_BEFORE" ]; then
  for example in toy-top equal-moments hanging-gyroscope lab-gyroscope asymmetric-plate; do
    for format in json text; do
      "$H" stability --config "$examples/$example.toml" --format $format > after.out 2>&1
      "$HEAVYTOP_BEFORE" stability --config "$examples/$example.toml" --format $format > before.out 2>&1
      check "$example $format unchanged" cmp -s before.out after.out
    done
  done
  for run in "stability --config $examples/tippe-top.toml --format json" \
             "stability --config $examples/toy-top.toml --brief" \
             "simulate --config $examples/toy-top.toml --model nonlinear --t-end 1 --samples 5 --format csv"; do
    $H $run > after.out 2>&1
    $HEAVYTOP_BEFORE $run > before.out 2>&1
    check "$run unchanged" cmp -s before.out after.out
  done
fi
finish
