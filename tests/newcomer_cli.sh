#!/usr/bin/env bash
# A command line without surprises (issue 25): --version, defaults and units in --help, unused
# options refused (never silently ignored), a partial body says what it was combined with, one
# rule for the motion's defaults, sweep says what it wrote.
source "$(dirname "$0")/harness.sh"
refused() {  # refused KEY CMD...: exit 2, one line naming KEY, nothing on stdout
  local key=$1; shift
  "$H" "$@" > out 2> err
  [ $? -eq 2 ] && [ "$(wc -l < err)" -eq 1 ] && grep -q -- "$key" err && [ ! -s out ]
}

check "--version prints 'heavytop VERSION'" bash -c "'$H' --version | grep -Eqx 'heavytop [0-9]+\.[0-9]+\.[0-9]+'"
check "--version exits 0" "$H" --version
"$H" stability --help > help.txt
check "stability --help gives the spin's default" grep -Eq -- '--spin NUM=0; toy top alone: 200' help.txt
check "... and its unit" grep -Eq -- 'rad/s, spin w0' help.txt
check "... the body's defaults (the toy top's) and units" grep -Eq -- '--A NUM=4.35e-05 \(toy top\) +kg m\^2' help.txt
check "... --horizon's unit and default" grep -Eq -- '--horizon FLOAT=100 +s, ' help.txt
check "report --help says it writes a folder" bash -c "'$H' report --help | grep -q 'DIR/report.html'"
check "the deprecated integrator name 'adaptive' is not listed" bash -c "! '$H' simulate --help | grep -q adaptive"
check "... but accepted" "$H" simulate --model nonlinear --integrator adaptive --t-end 0.01 --samples 2 --output o.csv

check "body refuses --spin" refused -- "--spin" body --spin 3
check "body refuses --transverse-damping" refused -- "--transverse-damping" body --transverse-damping 1
check "fit-decay refuses --spin" refused -- "--spin" fit-decay --data x.csv --spin 3
check "sweep refuses --integrator without --model nonlinear" refused -- "--integrator" sweep --vary spin=0:1:3 --integrator dopri5
check "sweep refuses --horizon without --model nonlinear" refused -- "--horizon" sweep --vary spin=0:1:3 --horizon 5
check "sweep refuses --rtol without --model nonlinear" refused -- "--rtol" sweep --vary spin=0:1:3 --rtol 1e-6
check "simulate refuses --rtol for a linear model" refused -- "--rtol" simulate --model first-order --rtol 1e-6

check "a partial body names what it was combined with" refused "body.A: .*B = 4.35e-05, C = 1.2e-05.*built-in toy top" stability --A 1

# One rule for the motion: the built-in example alone brings its motion; a described body, on
# the command line or in a file without [motion], starts from rest (every motion key 0).
"$H" stability --format json > example.json
printf '[body]\nA = 1\nB = 1\nC = 2\nmass = 1\ngravity = 1\nlength = 1\n' > nomotion.toml
"$H" stability --config nomotion.toml --format json > file.json
"$H" stability --A 1 --B 1 --C 2 --mass 1 --gravity 1 --length 1 --format json > options.json
check "the example alone spins at 200 rad/s" python3 -c 'import json; assert json.load(open("example.json"))["spin"] == 200'
check "a file without [motion] and options alone give the same" cmp file.json options.json
check "... spin 0" python3 -c 'import json; assert json.load(open("file.json"))["spin"] == 0'

"$H" sweep --vary spin=0:300:7 --output map.csv 2> sweep.err
check "sweep says on stderr what it wrote" grep -Eq 'sweep wrote 7 points \(stable: first-order [0-9]+, body-fixed [0-9]+, linearized [0-9]+, lyapunov [0-9]+\) to map.csv' sweep.err
check "... and the counts are the file's" python3 -c '
import csv, re
rows = list(csv.DictReader(open("map.csv")))
said = dict((k, int(v)) for k, v in re.findall(r"([a-z-]+) (\d+)", open("sweep.err").read().split("(stable: ")[1]))
for k in ("first-order", "body-fixed", "linearized", "lyapunov"):
    assert said[k] == sum(int(r[k]) for r in rows), (k, said[k])'
"$H" > bare.out
check "a bare heavytop writes the example report and says where" bash -c "test -e heavytop-report/report.html && grep -q 'wrote heavytop-report/report.html' bare.out"
finish
