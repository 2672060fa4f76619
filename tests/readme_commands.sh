#!/usr/bin/env bash
# The README's examples must never rot: every command it shows ("    $ ./build/heavytop ..."
# and the Python session's ">>> " lines) runs and exits 0, and the README keeps its promises
# to a newcomer: under 1,500 words, and no link out of the repository.
# Usage: HEAVYTOP=build/heavytop [PYTHONPATH=build/python] readme_commands.sh SOURCE_DIR
source "$(dirname "$0")/harness.sh"
src=$(realpath "${1:?give the source folder}")
readme="$src/README.md"
ln -s "$src/examples" examples

# The two set-up commands' main job: a bare heavytop writes the example's report and says where.
"$H" > bare.log 2>&1
check "bare heavytop exits 0" test $? -eq 0
check "bare heavytop says where the report is" grep -q "heavytop-report/report.html" bare.log
check "bare heavytop gives the answer first" test "$(head -c 9 bare.log)" = "Stays up."

n=0
while IFS= read -r line; do
  cmd=${line#    \$ ./build/heavytop}
  n=$((n + 1))
  eval "\"\$H\" $cmd" > "cli-$n.out" 2> "cli-$n.err"
  status=$?
  check "README command exits 0: heavytop$cmd (status $status: $(head -c 300 "cli-$n.err"))" test $status -eq 0
done < <(grep -E '^    \$ \./build/heavytop' "$readme")
check "the README shows at least five commands" test $n -ge 5

if [ -n "${PYTHONPATH:-}" ]; then
  grep -E '^    >>> ' "$readme" | sed -e 's/^    >>> //' > session.py
  check "the README shows a Python session" test -s session.py
  PYTHONDONTWRITEBYTECODE=1 MPLBACKEND=Agg /usr/bin/python3 session.py > python.out 2>&1
  status=$?
  check "the README's Python session runs (status $status: $(tail -c 400 python.out))" test $status -eq 0
fi

words=$(wc -w < "$readme")
check "the README is under 1,500 words ($words)" test "$words" -lt 1500
# Nothing links out of the repository: no ../ above its root, no absolute path of a machine.
check "the README links nothing outside the repository" bash -c "! grep -nE '\]\(\.\./|\]\(/' '$readme'"
finish
