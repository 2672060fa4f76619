#!/usr/bin/env bash
# `heavytop derive --format latex` compiles: every route, sequence and order, the rotations
# and the check table, each \input into a minimal amsmath document and run through pdflatex.
set -u
H=$(realpath "${HEAVYTOP:?set HEAVYTOP to the heavytop binary}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
passes=0
compile() {  # compile NAME: wraps NAME.tex in a document and runs pdflatex on it
  printf '\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n\\input{%s.tex}\n\\end{document}\n' "$1" > "doc-$1.tex"
  if pdflatex -interaction=nonstopmode -halt-on-error "doc-$1.tex" > "$1.log" 2>&1 && [ -s "doc-$1.pdf" ]; then
    passes=$((passes + 1))
  else
    echo "FAIL: $1: $(grep -m1 '^!' "$1.log")"; failures=$((failures + 1))
  fi
}
for method in euler-moving euler-fixed euler-body lagrange; do
  for sequence in phi-theta theta-phi; do
    for order in 1 2; do
      "$H" derive --method $method --sequence $sequence --order $order --format latex > "$method-$sequence-$order.tex"
      compile "$method-$sequence-$order"
    done
  done
done
for order in 1 2; do "$H" derive --rotations --order $order --format latex > "rotations-$order.tex"; compile "rotations-$order"; done
"$H" derive --check --format latex > check.tex
compile check
echo "$passes passed, $failures failed"
[ $failures -eq 0 ]
