#!/usr/bin/env bash
# `heavytop derive` as a script uses it: its JSON parses, its strings are expressions a CAS
# (sympy) reads, they are the paper's model (4) and condition (9), and --check succeeds.
# Usage: HEAVYTOP=/path/to/heavytop bash derive_cli.sh
set -euo pipefail
: "${HEAVYTOP:?set HEAVYTOP to the heavytop binary}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "derive_cli: FAIL: $*" >&2; exit 1; }

"$HEAVYTOP" derive --format json > "$work/model4.json" || fail "derive --format json exited $?"
"$HEAVYTOP" derive --method euler-body --sequence theta-phi --order 2 --format json \
  > "$work/model5.json" || fail "derive --method euler-body exited $?"
"$HEAVYTOP" derive --method lagrange --order 2 --output "$work/lagrange.json" --format json \
  || fail "derive --method lagrange --output exited $?"
"$HEAVYTOP" derive --rotations --order 2 --format json > "$work/rotations.json" \
  || fail "derive --rotations exited $?"

# Plain JSON with exactly SPEC's keys.
python3 - "$work" <<'EOF' || fail "JSON shape"
import json, sys, os
work = sys.argv[1]
for name in ("model4.json", "model5.json", "lagrange.json"):
    d = json.load(open(os.path.join(work, name)))
    assert list(d) == ["M", "G", "K", "characteristic_polynomial", "stability_condition"], list(d)
    for key in ("M", "G", "K"):
        assert len(d[key]) == 2 and all(len(r) == 2 and all(isinstance(x, str) for x in r)
                                        for r in d[key]), d[key]
r = json.load(open(os.path.join(work, "rotations.json")))
assert list(r) == ["A1", "A2", "A3", "A1A2", "A2A1", "commutator"], list(r)
assert all(len(m) == 3 and all(len(row) == 3 for row in m) for m in r.values())
print("derive_cli: JSON shape ok")
EOF

# The strings as sympy reads them. `lambda` is a Python keyword, so it is renamed first.
if python3 -c "import sympy" 2>/dev/null; then
  python3 - "$work" <<'EOF' || fail "sympy check"
import json, os, re, sys
import sympy as sp
from sympy.parsing.sympy_parser import parse_expr

work = sys.argv[1]
A, B, C, m, g, R, w0, lam = sp.symbols("A B C m g R omega0 lamda", positive=True)
phi, theta, psi = sp.symbols("phi theta psi")
names = {"A": A, "B": B, "C": C, "m": m, "g": g, "R": R, "omega0": w0, "lamda": lam,
         "phi": phi, "theta": theta, "psi": psi}

def read(s):
    s = re.sub(r"\blambda\b", "lamda", s).replace("^", "**")
    return parse_expr(s, local_dict=names)

def matrix(rows):
    return sp.Matrix([[read(x) for x in row] for row in rows])

def same(a, b):
    d = sp.simplify(sp.expand(a - b))
    return d.is_zero_matrix if isinstance(d, sp.MatrixBase) else d == 0

k = m * g * R
for name, G in (("model4.json", sp.Matrix([[0, C * w0], [-C * w0, 0]])),
                ("lagrange.json", sp.Matrix([[0, C * w0], [-C * w0, 0]])),
                ("model5.json", sp.Matrix([[0, (C - B) * w0], [-(C - A) * w0, 0]]))):
    d = json.load(open(os.path.join(work, name)))
    M, Gd, K = matrix(d["M"]), matrix(d["G"]), matrix(d["K"])
    assert M == sp.diag(A, B), (name, M)
    assert same(Gd, G), (name, Gd)
    assert K == sp.diag(-k, -k), (name, K)
    P = read(d["characteristic_polynomial"])
    assert same(P, (M * lam**2 + Gd * lam + K).det()), (name, P)

# Model (4): the polynomial is A B times the paper's (8), the condition is (9), strictly.
d = json.load(open(os.path.join(work, "model4.json")))
P = read(d["characteristic_polynomial"])
paper8 = lam**4 + (C**2 * w0**2 - (A + B) * k) / (A * B) * lam**2 + k**2 / (A * B)
assert same(P, A * B * paper8), P
cond = read(d["stability_condition"])
assert isinstance(cond, sp.StrictGreaterThan), cond
assert same(cond.lhs, w0**2) and same(cond.rhs, (sp.sqrt(A) + sp.sqrt(B))**2 * k / C**2), cond

# Model (5): two requirements joined by &.
cond5 = read(json.load(open(os.path.join(work, "model5.json")))["stability_condition"])
assert isinstance(cond5, sp.And) and len(cond5.args) == 2, cond5

# Rotations: the commutator at second order is matrix (1)'s phi theta terms.
r = json.load(open(os.path.join(work, "rotations.json")))
comm = matrix(r["commutator"])
assert comm == sp.Matrix([[0, -phi * theta, 0], [phi * theta, 0, 0], [0, 0, 0]]), comm
assert same(matrix(r["A1A2"]) - matrix(r["A2A1"]), comm)
print("derive_cli: sympy reads every string; model (4), (8), (9) and (5) as the paper")
EOF
else
  echo "derive_cli: sympy missing, skipping the CAS check"
fi

# --check runs every route and sequence and succeeds; --format json is machine-readable.
"$HEAVYTOP" derive --check > "$work/check.txt" || fail "derive --check exited $?"
grep -q "euler-body" "$work/check.txt" || fail "--check table lacks euler-body"
"$HEAVYTOP" derive --check --format json | python3 -c '
import json, sys
d = json.load(sys.stdin)
assert d["all_as_expected"] is True
assert len(d["rows"]) == 16
body = [r for r in d["rows"] if r["method"] == "euler-body"]
assert body and all(r["model"] == "model (5)" for r in body)
' || fail "--check --format json"

# LaTeX: balanced equation blocks.
"$HEAVYTOP" derive --format latex > "$work/model.tex" || fail "--format latex exited $?"
[ "$(grep -c '\\begin{equation}' "$work/model.tex")" = "$(grep -c '\\end{equation}' "$work/model.tex")" ] \
  || fail "unbalanced equation blocks"

# Bad input: exit 2, one line on stderr naming the option, no output file.
for args in "--order 3" "--method euler" "--sequence psi-phi" "--format yaml" "--rotations --check"; do
  set +e
  # shellcheck disable=SC2086
  "$HEAVYTOP" derive $args --output "$work/bad.json" 2> "$work/err.txt"
  status=$?
  set -e
  [ "$status" = 2 ] || fail "derive $args: exit $status, expected 2"
  [ "$(wc -l < "$work/err.txt")" = 1 ] || fail "derive $args: stderr is not one line"
  [ ! -e "$work/bad.json" ] || fail "derive $args: wrote an output file"
done
echo "derive_cli: all checks passed"
