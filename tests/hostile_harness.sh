# Shared by the hostile-input tests: harness.sh, and `run EXPECTED_RC ARGS...`, which runs
# heavytop, keeps its stderr in err and appends it to $messages (every message the test saw,
# checked at the end for library internals); `one_line`: err is one line.
source "$(dirname "${BASH_SOURCE[0]}")/harness.sh"
messages="$work/messages"
: > "$messages"
run() {
  local expected=$1; shift
  "$H" "$@" > out 2> err
  local rc=$?
  cat err >> "$messages"
  [ "$rc" -eq "$expected" ] || { echo "  exit $rc, expected $expected: $* :: $(head -c 300 err)"; return 1; }
}
one_line() { [ "$(wc -l < err)" -eq 1 ] || { echo "  not one line: $(cat err)"; return 1; }; }
says() { grep -q -- "$1" err || { echo "  stderr lacks '$1': $(cat err)"; return 1; }; }  # err holds $1
json() { python3 -c "import json,sys; d=json.load(open('out')); $1"; }  # a Python check of out's JSON as d
