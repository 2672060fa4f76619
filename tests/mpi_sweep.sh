#!/usr/bin/env bash
# Sweeps under MPI (SPEC section 12): `mpirun -n 3` gives byte for byte the file of one process
# (linear 200 x 200, nonlinear 15 x 15, three parameters 9 x 9 x 9, CSV and HDF5); a rank
# killed midway makes the job fail with FILE.partial intact, and the rerun resumes it to the
# identical file; bad input fails once, with status 2, and writes nothing.
source "$(dirname "$0")/harness.sh"
mpi=("${mpirun[@]}" --allow-run-as-root --oversubscribe -n 3)
plate=(--config "$(dirname "$0")/../examples/asymmetric-plate.toml")

same() {  # name, then the sweep's arguments: serial and 3 ranks write the same bytes
  local name=$1; shift
  "$H" sweep "$@" --output "serial-$name" && "${mpi[@]}" "$H" sweep "$@" --output "mpi-$name" 2>mpi.err
  check "$name: mpirun exit 0" test $? -eq 0
  check "$name: byte-identical to one process" cmp -s "serial-$name" "mpi-$name"
  check "$name: no partial left" test ! -e "mpi-$name.partial" -a ! -e "mpi-$name.partial.args"
}
same linear.csv "${plate[@]}" --vary B/A=1:3:200 --vary spin=0:3:200
same nonlinear.csv "${plate[@]}" --vary B/A=1:3:15 --vary spin=0.5:3:15 --model nonlinear --theta0 0.01 --horizon 50
same three.csv "${plate[@]}" --vary B/A=1:2.2:9 --vary C/A=1.2:2:9 --vary spin=0:4:9 --model nonlinear --theta0 0.01 --horizon 20
same three.h5 "${plate[@]}" --vary B/A=1:2.2:9 --vary C/A=1.2:2:9 --vary spin=0:4:9 --format hdf5
check "three-parameter CSV rows" test "$(wc -l < mpi-three.csv)" -eq $((1 + 9 * 9 * 9))

# An independent route to a slice: the three-parameter map's rows at C/A = 2 are the
# two-parameter map with C = 2 A given outright.
"$H" sweep "${plate[@]}" --C 0.02 --vary B/A=1:2.2:9 --vary spin=0:4:9 --model nonlinear --theta0 0.01 --horizon 20 \
  --output slice.csv
check "slice of the three-parameter map = the two-parameter map" python3 - mpi-three.csv slice.csv <<'PY'
import csv, sys
three = [r for r in csv.reader(open(sys.argv[1]))]
two = [r for r in csv.reader(open(sys.argv[2]))]
assert three[0][:3] == ["B/A", "C/A", "spin"] and two[0][:2] == ["B/A", "spin"]
held = [r[:1] + r[2:] for r in three[1:] if float(r[1]) == 2.0]
assert len(held) == 81 and held == two[1:], (held[:3], two[1:4])
PY

# A rank killed midway: the job fails, FILE.partial holds whole rows; rerun, the same file.
# dopri5 point by point: 6 s of work (the default batched Taylor integrator does it in 0.2 s,
# before the kill could land).
slow=("${plate[@]}" --vary B/A=1:3:40 --vary spin=1.5:6:40 --model nonlinear --theta0 0.01 --horizon 200
      --integrator dopri5)
"$H" sweep "${slow[@]}" --output whole.csv
"${mpi[@]}" "$H" sweep "${slow[@]}" --output killed.csv 2>killed.err &
job=$!
for _ in $(seq 600); do  # until some rows are written (at most 60 s)
  [ -e killed.csv.partial ] && [ "$(wc -l < killed.csv.partial)" -gt 20 ] && break
  sleep 0.1
done
victim=$(pgrep -x heavytop-mpi | sort -n | sed -n 2p)
kill -9 "$victim"
wait $job
status=$?
check "killed rank: the job exits non-zero" test $status -ne 0
check "killed rank: the partial file is kept" test -s killed.csv.partial -a ! -e killed.csv
rows_before=$(wc -l < killed.csv.partial)
"${mpi[@]}" "$H" sweep "${slow[@]}" --output killed.csv 2>resume.err
check "resumed: exit 0" test $? -eq 0
check "resumed: said where it resumed" grep -q "resuming the sweep at row" resume.err
check "resumed: byte-identical to an uninterrupted run" cmp -s whole.csv killed.csv
check "resumed: it did not start over ($rows_before rows kept)" test "$rows_before" -gt 20

# The same for HDF5, whose journal is packed verdicts.
"$H" sweep "${slow[@]}" --format hdf5 --output whole.h5
"${mpi[@]}" "$H" sweep "${slow[@]}" --format hdf5 --output killed.h5 2>/dev/null &
job=$!
for _ in $(seq 600); do
  [ -e killed.h5.partial ] && [ "$(stat -c %s killed.h5.partial)" -gt 200 ] && break
  sleep 0.1
done
kill -9 "$(pgrep -x heavytop-mpi | sort -n | sed -n 3p)"
wait $job
check "hdf5, killed rank: non-zero, partial kept" test $? -ne 0 -a -s killed.h5.partial -a ! -e killed.h5
"${mpi[@]}" "$H" sweep "${slow[@]}" --format hdf5 --output killed.h5 2>/dev/null
check "hdf5 resumed: byte-identical" cmp -s whole.h5 killed.h5

# Bad input: once on stderr, status 2 as for one process, nothing written.
"${mpi[@]}" "$H" sweep "${plate[@]}" --vary B/A=1:3:0 --output bad.csv 2>bad.err
check "bad input under mpirun: status 2" test $? -eq 2
check "bad input under mpirun: said once" test "$(grep -c 'error: --vary' bad.err)" -eq 1
check "bad input under mpirun: nothing written" test ! -e bad.csv -a ! -e bad.csv.partial
"${mpi[@]}" "$H" sweep "${plate[@]}" --vary B/A=1:3:5 --format hdf5 > /dev/null 2>bad.err
check "hdf5 to stdout under mpirun: status 2" test $? -eq 2
check "hdf5 to stdout: says why" grep -q "hdf5 format needs a regular file" bad.err
finish
