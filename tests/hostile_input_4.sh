#!/usr/bin/env bash
# Hostile input, round 4 (issue 46). Security: no text from a file or an option reaches an
# interpreter (gnuplot, the HTML page) unescaped; a map's keys are the sweep's keys or refused.
here=$(cd "$(dirname "$0")" && pwd)  # before the harness changes into its scratch folder
source "$here/hostile_harness.sh"

# ---- 1. A map whose key is not a sweep's: refused, exit 2, the key named, nothing run or written --
# gnuplot runs in a private folder that is then removed, so each command touches a file by an
# absolute path (or through $M, for names that cannot hold a slash).
export M="$work/MARKER"
check "a two-key map" run 0 sweep --vary B/A=0.8:1.2:3 --vary spin=0:300:4 --output good.csv
hostile_keys=(
  "B/A' ; system('touch $M') ; x='"  # the review's: a quote ends gnuplot's string
  "B/A\`touch $M\`"                  # command substitution (gnuplot does it outside single quotes)
  "@macro"                          # a gnuplot macro
  "B/A'"
  $'B/A\x1b[31m'                    # a control character
  "b/a"                             # close to a key is not a key
  "theta0"                          # a key of the configuration, not one a sweep varies
)
names_key() {  # KEY: err names it as a map's bad key, shown as printable() shows it, in one line
  python3 - "$1" <<'PY'
import sys
key = sys.argv[1]
shown = ''.join(c if 0x20 <= ord(c) != 0x7f else '\\x%02x' % ord(c) for c in (key[:40] + '...' if len(key) > 40 else key))
err = open('err').read()
assert f"--map: the axis key '{shown}' is not one a sweep varies (a map's keys are among A, B, C," in err, err
assert err.count('\n') == 1, err
PY
}
for i in "${!hostile_keys[@]}"; do
  key=${hostile_keys[$i]}
  python3 -c "import sys; t = open('good.csv').read(); open('evil.csv', 'w').write(sys.argv[1] + t[3:])" "$key"
  check "map key #$i is refused, exit 2 (the review's ran a command in gnuplot)" run 2 report --map evil.csv --output rep-$i
  check "... naming --map, the key (printable, its first 40 bytes) and the rule, in one line" names_key "$key"
  check "... no command ran" test ! -e "$M"
  check "... no output folder" test ! -e rep-$i
done
# The same for an HDF5 map (its keys are attributes), when the build reads HDF5 maps.
if "$H" sweep --vary B/A=0.8:1.2:3 --vary spin=0:300:4 --format hdf5 --output good.h5 > /dev/null 2>&1; then
  python3 -c "
d = open('good.h5', 'rb').read()
assert d.count(b'B/A') >= 1
open('evil.h5', 'wb').write(d.replace(b'B/A', b\"B'A\"))"
  check "an HDF5 map whose key is not a sweep's is refused, exit 2" run 2 report --map evil.h5 --output rep-h5
  check "... naming the key" says "--map: the axis key 'B'A' is not one a sweep varies"
  check "... in one line, no output folder" bash -c "[ \$(wc -l < err) -eq 1 ] && [ ! -e rep-h5 ]"
fi
# A three-key map sliced at a key given on the command line: the key must be the map's.
check "a three-key map" run 0 sweep --vary B/A=0.8:1.2:3 --vary spin=0:300:4 --vary C/A=1.2:1.6:2 --output three.csv
check "--slice with a hostile key is refused, exit 2" run 2 report --map three.csv --slice "B/A' ; system('touch $M') ; print '=1" --output rep-s
check "... naming it, no command ran, no output folder" bash -c "grep -qF \"is not a varied key of the map\" err && [ ! -e '$M' ] && [ ! -e rep-s ]"
check "--slice with a newline in its value: refused in one line" run 2 report --map three.csv --slice $'C/A=1\n2' --output rep-n
check "... one line" one_line

# ---- 2. Sweep keys, hostile names: the map's file, the output folder, the configuration --------
# None reaches a gnuplot script (figures are drawn on relative names in a private folder); in
# the page each is escaped.
name="m' ; system('touch \$M') ; x='\`touch \$M\`<img src=x onerror=alert(1)>"
cp good.csv "$name.csv"
printf '[body]\nA = 1.0\nB = 1.0\nC = 0.5\nmass = 1.0\ngravity = 9.81\nlength = 0.05\n[motion]\nspin = 60.0\n' > "$name.toml"
check "a report with a hostile map name, folder name and configuration name is written" \
  run 0 report --config "$name.toml" --map "$name.csv" --output "$name"
check "... and no command ran" test ! -e "$M"
check "... every figure drawn, the map's too" test -s "$name/map-1.svg"
check "... the names escaped in the page (no element of theirs)" python3 - "$name" <<'PY'
import sys
name = sys.argv[1]
page = open(f"{name}/report.html").read()
escaped = name.replace('&', '&amp;').replace('<', '&lt;').replace('>', '&gt;').replace("'", '&#39;').replace('"', '&quot;')
assert '<img src=x' not in page
assert f"The map {escaped}.csv</h2>" in page, "the map's name"
assert f"{escaped}.toml" in page, "the configuration's name in the title"
PY

# ---- 3. A map with a key twice: refused naming it (a sweep varies each key once) ----------------
python3 -c "t = open('good.csv').read(); open('twice.csv', 'w').write('spin' + t[3:])"
check "a map whose key is there twice is refused, exit 2" run 2 report --map twice.csv --output rep-twice
check "... saying so, in one line, no output folder" bash -c "grep -qF \"the axis key 'spin' is there twice\" err && [ \$(wc -l < err) -eq 1 ] && [ ! -e rep-twice ]"

# ---- 4. Every message is one line, whatever text went into it (a path, a key, a value) ---------
check "a configuration path holding a newline and an escape: one line" run 2 stability --config $'a\nb\x1b[2J.toml'
check "... one line" one_line
check "a sweep key holding a newline: one line" run 2 sweep --vary $'sp\nin=0:1:2'
check "... one line" one_line
check "an output folder holding a newline that cannot be made: one line" run 2 report --output $'/proc/no\nway'
check "... one line" one_line

# ---- 5. Each horizon under its own key, refused before it runs; the run states what it covered --
check "--lifetime-horizon 1e300 on a damped body: exit 2" run 2 stability --lifetime-horizon 1e300 --axial-damping 2e-7
check "... naming --lifetime-horizon (it named --horizon)" says "^heavytop: error: --lifetime-horizon: too long"
check "--horizon 1e300 on an undecided body: exit 2 at once (it ran 50 s)" run 2 stability --spin 100 --horizon 1e300
check "... naming --horizon" says "^heavytop: error: --horizon: too long"

# ---- 6. A start beyond the limit: what a fall means there is decided once and said -------------
check "a start past --max-tilt" run 0 stability --theta0 0.5 --max-tilt 0.1 --format json
check "... is not a fall at t = 0 (the review's said 'falls' at spin 100 or damped)" json "
a = d['answer']; assert a['falls_at'] is None and a['verdict'] == 'stays up', a"
check "... in words" run 0 stability --theta0 0.5 --max-tilt 0.1
check "... which say what a fall is there" grep -q "started beyond the 5.73 degrees (0.1 rad) limit of a fall, so a fall here is a tilt past 104 degrees (1.82 rad)" out
check "Woodhouse's top set off at 60 degrees (past the default 1 rad)" run 0 stability --A 1e-4 --B 1e-4 --C 1.2e-5 --mass 0.06 --length 0.025 --spin 175.089 --theta0 1.0472 --phi-rate0 -12.1305 --format json
check "... does not fall at t = 0" json "a = d['answer']; assert a['verdict'] != 'falls' and a['falls_at'] is None, a"
check "a top started upside down" run 0 stability --theta0 3.141592653589793 --format json
check "... is not 'stays up', proven" json "a = d['answer']; assert not (a['verdict'] == 'stays up' and a['proven']), a"
check "a damped top started past the limit (lifetime)" run 0 lifetime --axial-damping 2e-6 --theta0 1.2 --format json
check "... falls past halfway to upside down, not at t = 0" json "
f = d['fall']; import math; assert f['time'] > 0.5 and abs(f['max_tilt'] - (1.2 + math.pi) / 2) < 1e-15, f"

finish
