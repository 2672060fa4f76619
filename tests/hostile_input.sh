#!/usr/bin/env bash
# Hostile input and every output path (issue "nothing crashes, nothing is damaged, nothing
# wrong is said"): each class of failure, the example that found it and more of its own.
source "$(dirname "$0")/hostile_harness.sh"

# ---- 1. Output paths: never replace a device or pipe; atomic files; modes; locks ----------------
if [ -w /dev/null ] && [ "$(id -u)" -eq 0 ]; then
  check "/dev/null stays a device" bash -c "run() { \"$H\" \"\$@\"; }; run simulate --samples 11 --output /dev/null && test -c /dev/null"
fi
mkfifo fifo
(cat fifo > from_fifo) &
check "a FIFO is written directly" run 0 simulate --model first-order --samples 11 --output fifo
wait
check "the FIFO is still a FIFO with the rows through it" bash -c 'test -p fifo && [ "$(wc -l < from_fifo)" -eq 12 ]'
check "--output /dev/stdout redirected to a file writes the file, /dev/stdout stays a link" bash -c "
  '$H' simulate --model first-order --samples 11 --output /dev/stdout > redirected.csv && [ \$(wc -l < redirected.csv) -eq 12 ] && test -L /dev/stdout"
echo old > target.csv; ln -s target.csv link.csv
check "a symbolic link is written through: its target replaced, the link kept" bash -c "
  '$H' simulate --model first-order --samples 11 --output link.csv && test -L link.csv && [ \$(wc -l < target.csv) -eq 12 ]"
check "the same for a sweep" bash -c "'$H' sweep --vary spin=0:1:3 --output link.csv && test -L link.csv && head -1 target.csv | grep -q '^spin,'"
check "--output - is stdout" run 0 simulate --model first-order --samples 11 --output -
check "... with the rows" test "$(wc -l < out)" -eq 12
check "a missing folder is bad input" run 2 simulate --samples 11 --output no/such/folder.csv
check "... naming --output" says "--output"
check "... writing nothing" test ! -e no
check "a folder as --output is bad input" run 2 simulate --samples 11 --output .
umask 027
check "a new file gets the umask's mode" run 0 simulate --model first-order --samples 11 --output new.csv
check "... 0640" test "$(stat -c %a new.csv)" = 640
umask 022
chmod 600 new.csv
check "an overwritten file keeps its mode" run 0 simulate --model first-order --samples 21 --output new.csv
check "... 0600, and the new content" bash -c '[ "$(stat -c %a new.csv)" = 600 ] && [ "$(wc -l < new.csv)" -eq 22 ]'
check "the same for a sweep's file" bash -c "chmod 640 new.csv && '$H' sweep --vary spin=0:300:5 --output new.csv && [ \"\$(stat -c %a new.csv)\" = 640 ]"
# A second writer of the same output is refused while the first runs; nothing interleaves.
"$H" sweep --vary B/A=0.8:1.2:200 --vary spin=0:300:200 --model nonlinear --theta0 0.01 --horizon 5 --output map.csv 2> first.err &
first=$!
sleep 1
check "a second sweep to the same file is refused" run 2 sweep --vary B/A=0.8:1.2:200 --vary spin=0:300:200 --model nonlinear --theta0 0.01 --horizon 5 --output map.csv
check "... naming --output" says "--output: 'map.csv' is being written by another process"
kill -INT $first; wait $first
check "the first, interrupted, left a resumable partial file and no temporary" bash -c 'test -s map.csv.partial && ! ls -a | grep -q "tmp-\|\.lock"'
check "a second simulate to a file being written is refused" bash -c "
  '$H' simulate --model first-order --samples 30000000 --output big.csv & p=\$!; sleep 1
  '$H' simulate --samples 11 --output big.csv 2> e; rc=\$?; kill -INT \$p; wait \$p; [ \$rc -eq 2 ] && grep -q 'being written' e"
check "Ctrl-C in a long simulate leaves no file behind" bash -c '! ls -a | grep -q "big.csv"'
check "a second report into one folder is refused" bash -c "
  '$H' report --output rep >/dev/null 2>&1 & p=\$!; sleep 0.5
  '$H' report --output rep 2> e; rc=\$?; wait \$p; [ \$rc -eq 2 ] && grep -q \"'rep' is being written\" e"

# ---- 2. The report: every body, every folder name, all or nothing ------------------------------
check "the sleeping top (theta0 = 0) has a report" run 0 report --theta0 0 --output sleeping
check "... with all its figures" test "$(ls sleeping/*.svg | wc -l)" -eq 7
check "a folder name with quotes" run 0 report --output "it's \"here\"" --t-end 0.5
check "... has its figures" test -s "it's \"here\"/errors.png"
check "the hanging body's report does not explain a Jordan block at w0 = 0" bash -c "
  '$H' report --length -0.02 --output hang >/dev/null && ! grep -q 'w0 = 0 rad/s is not stable' hang/report.html"
cp -r sleeping before
check "a report that cannot draw fails with exit 1" bash -c "PATH=/nonexistent '$(realpath "$H")' report --output sleeping --spin 150 2> e; [ \$? -eq 1 ] && grep -q gnuplot e"
check "... and leaves the old report as it was" diff -r before sleeping

# ---- 3. Verdicts right at every scale --------------------------------------------------------
check "a slender body's distinct eigenvalues are no Jordan block" run 0 stability --A 1 --B 1 --C 1e-5 --mass 1 --gravity 1 --length 1 --spin 1252836.78 --format json
check "... it is stable, as C^2 w0^2 > 4 A m g R says" json 'm=d["models"]["linearized"]; assert m["stable"], m["reason"]; assert abs(m["critical_spin"]-2e5) < 1e-6*2e5'
check "a critical spin of 2e9 rad/s is found" run 0 stability --A 1 --B 1 --C 1e-9 --mass 1 --gravity 1 --length 1 --format json
check "... by every model that has one (4 A m g R / C^2 = 4e18)" json '
for n in ("first-order", "linearized"): c=d["models"][n]["critical_spin"]; assert c and abs(c-2e9) < 1e-9*2e9, (n, c)'
check "... and stable just above it" run 0 stability --A 1 --B 1 --C 1e-9 --mass 1 --gravity 1 --length 1 --spin 2.000001e9 --format json
check "... in both models" json 'assert all(d["models"][n]["stable"] for n in ("first-order", "linearized"))'
check "a critical spin of 1e14 rad/s" run 0 stability --A 1 --B 1 --C 2e-14 --mass 1 --gravity 1 --length 1 --format json
check "... for (4)" json 'c=d["models"]["first-order"]["critical_spin"]; assert abs(c-1e14) < 1e-9*1e14, c'
check "--spin 1e100 is refused, not NaN" run 2 stability --spin 1e100
check "... naming motion.spin" says "motion.spin: "
check "--spin 1e100 in JSON too" run 2 stability --spin 1e100 --format json
check "m g R = inf is refused" run 2 stability --mass 1e308 --gravity 1e308
check "... naming the key" says "body.mass: m g R overflows"
check "an overflowing length too" run 2 stability --length 1e300 --mass 1e10
check "g = 0 at w0 = 0: unstable there, stable at every spin above" run 0 stability --gravity 0 --spin 0
check "... and the text says so" bash -c 'grep first-order out | grep -q "UNSTABLE .*every spin > 0"'
check "a hanging body is stable at w0 = 0 and says every spin" run 0 stability --length -0.02 --spin 0
check "... text" bash -c 'grep first-order out | grep -q "stable .*every spin "'
check "the boundary of (9) is excluded in JSON's interval and in the verdict" run 0 stability --A 1 --B 1 --C 2 --mass 1 --gravity 1 --length 1 --spin 1 --format json
check "... (4A m g R = C^2 w0^2: a Jordan block)" json 'm=d["models"]["first-order"]; assert not m["stable"] and m["stable_spin_intervals"]==[[1.0, None]]'

# ---- 4. Numbers that mean something ----------------------------------------------------------
check "a linear model grown beyond a double is a numerical failure" run 1 simulate --model first-order --spin 0 --theta0 0.1 --t-end 50 --output nan.csv
check "... one line saying where" bash -c 'grep -q "theta is not a finite number at t = " err && [ "$(wc -l < err)" -eq 1 ]'
check "... and no file" test ! -e nan.csv
check "NaN never reaches stdout's CSV either" bash -c "'$H' simulate --model body-fixed --spin 0 --theta0 0.1 --t-end 60 2>/dev/null | grep -qi nan; [ \$? -eq 1 ]"
check "compare says diverges, not an error of 1e304" run 0 compare --spin 0 --theta0 0.1 --t-end 50 --samples 501 --format json
check "... with when" json '
m=d["models"]["first-order"]; assert m["diverged_at"] > 0 and m["final_angle_error"] is None and m["max_angle_error"] < 2, m
assert d["models"]["lagrange-exact"].get("diverged_at") is None'
check "compare text says diverges" run 0 compare --spin 0 --theta0 0.1 --t-end 50 --samples 501
check "... in words" grep -q "first-order .*diverges at t = " out
check "t = 1e300 is refused: no phase is left" run 2 simulate --model lagrange-exact --t-end 1e300 --samples 3
check "... naming --t-end" says "--t-end: too long"
check "the same for compare" run 2 compare --t-end 1e20
# (The closed form at the inverted rest of a hanging body is the rest itself: hostile_input_3.sh.)

# ---- 5. The configuration --------------------------------------------------------------------
cat > sim.toml <<'TOML'
[body]
A = 1.0
B = 1.0
C = 2.0
mass = 1.0
length = 1.0
[motion]
spin = 3.0
theta0 = 0.01
[simulate]
model = "first-order"
t_end = 2.0
samples = 11
TOML
check "a file with [simulate] serves stability" run 0 stability --config sim.toml
check "... compare" run 0 compare --config sim.toml --t-end 1 --samples 11
check "... and simulate" run 0 simulate --config sim.toml
check "... which uses it" test "$(wc -l < out)" -eq 12
sed 's/samples = 11/samples = 2.7/' sim.toml > frac.toml
check "samples = 2.7 is refused, not truncated" run 2 simulate --config frac.toml
check "... naming the key" says "simulate.samples: must be a whole number"
sed 's/t_end = 2.0/t_end = "2"/' sim.toml > str.toml
check "t_end = \"2\" is refused, not ignored" run 2 simulate --config str.toml
check "... naming the key" says "simulate.t_end: must be a number"
sed 's/model = "first-order"/model = 3/' sim.toml > num.toml
check "model = 3 is refused" run 2 simulate --config num.toml
grep -v '^A = ' sim.toml > noA.toml
check "[body] without A works when --A is given" run 0 stability --config noA.toml --A 1
check "and without --A the message is right" run 2 stability --config noA.toml
check "... (give --A)" says "body.A: is required in \[body\] (or give --A)"
check "--config on a folder" run 2 stability --config /tmp
check "... says so" says "it is a folder"
sed 's/^model = /modle = /' sim.toml > typo.toml
check "an unknown key is still refused" run 2 stability --config typo.toml
check "... naming it" says "simulate.modle: unknown key"

# ---- 6. Limits a user can see and set -------------------------------------------------------
# (Not under scripts/sanitize.sh: AddressSanitizer reserves terabytes of address space, which
# no ulimit -v admits.)
[ -n "${HEAVYTOP_SANITIZED:-}" ] ||
check "--samples 100000000 streams as CSV in flat memory (no bad_alloc)" bash -c "
  ulimit -v 400000; '$H' simulate --model first-order --samples 100000000 --output /dev/null"
check "... and is refused as JSON, with why" run 2 simulate --samples 100000000 --format json
check "... naming --samples" says "--samples: must be at most 2000000 with --format json"
check "a sweep of 1e10 points is refused at once" run 2 sweep --vary A=1:2:100000 --vary B=1:2:100000
check "... saying the cap" says "more than the 100000000 a sweep may have"
check "--max-steps exists and is obeyed" run 1 simulate --max-steps 10 --samples 11
check "... with a one-line message" one_line
check "--max-steps 0 is bad input" run 2 simulate --max-steps 0
check "--max-steps applies to nonlinear only" run 2 simulate --model first-order --max-steps 5
check "the splitting warns when its energy error passes the bound" run 0 simulate --integrator splitting --step 0.3 --t-end 2 --samples 11
check "... in one line" bash -c 'grep -q "warning: the splitting.s relative energy error reached" err && [ "$(wc -l < err)" -eq 1 ]'
check "and says nothing when the step is fine" run 0 simulate --integrator splitting --step 1e-4 --t-end 0.2 --samples 11
check "... nothing" test ! -s err

# ---- 7. Every message: one line, no library internals ----------------------------------------
check "no message leaks a library's internals" bash -c "! grep -E 'std::|boost::|filesystem error|what\(\)|terminate called' '$messages'"
finish
