#!/usr/bin/env bash
# `heavytop derive --format latex` compiles: every route, sequence and order, the rotations
# and the check table, each \input into a minimal amsmath document and run through pdflatex.
source "$(dirname "$0")/../../tests/harness.sh"
compiles() {  # compiles NAME: NAME.tex inside a minimal document goes through pdflatex
  printf '\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n\\input{%s.tex}\n\\end{document}\n' "$1" > "doc-$1.tex"
  pdflatex -interaction=nonstopmode -halt-on-error "doc-$1.tex" > "$1.log" 2>&1 && [ -s "doc-$1.pdf" ] ||
    { grep -m1 '^!' "$1.log"; return 1; }
}
for method in euler-moving euler-fixed euler-body lagrange; do
  for sequence in phi-theta theta-phi; do
    for order in 1 2; do
      "$H" derive --method $method --sequence $sequence --order $order --format latex > "$method-$sequence-$order.tex"
      check "$method $sequence $order" compiles "$method-$sequence-$order"
    done
  done
done
for order in 1 2; do "$H" derive --rotations --order $order --format latex > "rotations-$order.tex"; check "rotations $order" compiles "rotations-$order"; done
"$H" derive --check --format latex > check.tex
check "check table" compiles check
finish
