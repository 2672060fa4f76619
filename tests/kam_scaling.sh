#!/usr/bin/env bash
# The KAM verdict does not depend on the unit of mass (issue 46): `heavytop stability --format
# json` for a body with A, B, C and the mass all scaled by 1e-16 and by 1e20 gives the unscaled
# body's Lyapunov verdict, certificate, normal-form frequencies and stable spins (1e-9
# relative), its D divided by the scale, and frequencies equal to its own linearized model's.
# Before the fix: [4.83, 4.59] against [5.605, 3.862] at 1e-16, 600 pieces and `undecided` at 1e20.
source "$(dirname "$0")/harness.sh"

# stability_json NAME SCALE A B C MGR SPIN: the JSON of the body scaled by SCALE, in NAME.json
# (g = 4 m/s^2 and R = m g R / 4: a body that can exist, its central moments positive).
stability_json() {
  local name=$1 scale=$2 A=$3 B=$4 C=$5 mgR=$6 spin=$7
  local args
  args=$(python3 -c "
s = $scale
print(repr($A * s), repr($B * s), repr($C * s), repr(s), repr($mgR / 4))")
  read -r a b c m R <<< "$args"
  "$H" stability --A "$a" --B "$b" --C "$c" --mass "$m" --length "$R" --gravity 4 --spin "$spin" \
    --format json --output "$name.json"
}

# same NAME SCALE: NAME-SCALE.json says what NAME-1.json says, as the file comment lists.
same() {
  python3 - "$1" "$2" <<'PY'
import json, sys
name, scale = sys.argv[1], float(sys.argv[2])
one = json.load(open(f"{name}-1.json"))["lyapunov"]
got_all = json.load(open(f"{name}-{sys.argv[2]}.json"))
got = got_all["lyapunov"]
def close(x, y, tol=1e-9):
    if x is None or y is None:
        return x is y
    return abs(x - y) <= tol * max(abs(x), abs(y))
problems = []
for key in ("verdict", "certificate", "energy_index"):
    if got[key] != one[key]:
        problems.append(f"{key}: {got[key]} against {one[key]}")
nf, nf1 = got["normal_form"], one["normal_form"]
if (nf is None) != (nf1 is None):
    problems.append(f"normal_form: {nf} against {nf1}")
elif nf is not None:
    if not all(close(x, y) for x, y in zip(nf["frequencies"], nf1["frequencies"])):
        problems.append(f"frequencies {nf['frequencies']} against {nf1['frequencies']}")
    if not close(nf["D"] * scale, nf1["D"]):
        problems.append(f"D x scale {nf['D'] * scale} against {nf1['D']}")
    if nf["resonance"] != nf1["resonance"]:
        problems.append(f"resonance {nf['resonance']} against {nf1['resonance']}")
    lin = sorted(got_all["models"]["linearized"]["frequencies"])
    if not all(abs(x - y) <= 1e-10 * max(nf["frequencies"]) for x, y in zip(sorted(nf["frequencies"]), lin)):
        problems.append(f"frequencies {nf['frequencies']} against the linearized model's {lin}")
iv, iv1 = got["stable_spin_intervals"], one["stable_spin_intervals"]
if len(iv) != len(iv1) or not all(close(x[0], y[0]) and close(x[1], y[1]) for x, y in zip(iv, iv1)):
    problems.append(f"stable spins ({len(iv)} pieces) {iv[:4]} against ({len(iv1)}) {iv1[:4]}")
for p in problems:
    print("  " + p)
sys.exit(1 if problems else 0)
PY
}

# E7's body at a KAM spin, and an oblate body whose stable spins have a D = 0 exception.
bodies=("e7 1 1.5 0.5 1 6" "oblate 1.52594 1.894034 1.59991 1 3")
for body in "${bodies[@]}"; do
  read -r name A B C mgR spin <<< "$body"
  check "$name unscaled" stability_json "$name-1" 1 "$A" "$B" "$C" "$mgR" "$spin"
  for scale in 1e-16 1e20; do
    check "$name, mass and moments x $scale: runs" stability_json "$name-$scale" "$scale" "$A" "$B" "$C" "$mgR" "$spin"
    check "$name, mass and moments x $scale: the unscaled verdict, frequencies, D and stable spins" same "$name" "$scale"
  done
done
check "the oblate body's stable spins have its D = 0 exception (more than one piece)" python3 -c "
import json; l = json.load(open('oblate-1.json'))['lyapunov']
assert len(l['stable_spin_intervals']) > 1, l['stable_spin_intervals']"
check "E7 at 1e20 is kam with one stable interval from 4.357" python3 -c "
import json; l = json.load(open('e7-1e20.json'))['lyapunov']
assert l['verdict'] == 'stable' and l['certificate'] == 'kam', l['verdict']
assert len(l['stable_spin_intervals']) == 1 and abs(l['stable_spin_intervals'][0][0] - 4.357388321) < 1e-8, l['stable_spin_intervals'][:3]"
finish
