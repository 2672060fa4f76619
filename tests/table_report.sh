#!/usr/bin/env bash
# `heavytop report` for a body on a table (SPEC section 16), as a user runs it: the folder of the
# tippe top (the table's answer in words, the tilt and track figures, the run's table columns,
# the 3D view's table data), the rolling coin's, the refusal of a map, and the pivot's report
# unchanged by the table's branch.
examples=$(realpath "$(dirname "$0")/../examples")
source "$(dirname "$0")/harness.sh"

# The tippe top: "Turns over." first, as `stability` says it, then the figures and the data.
check "tippe report" "$H" report --config "$examples/tippe-top.toml" --output tippe
check "answer's words" grep -q "<b>Turns over.</b>" tippe/report.html
check "same words as stability" bash -c "'$H' stability --config '$examples/tippe-top.toml' | head -1 | cut -c 13- | \
  sed 's/&/\&amp;/g; s/</\&lt;/g; s/>/\&gt;/g' | head -c 80 > words && grep -qF -f words tippe/report.html"
check "spinning states" grep -q "inverted (tilt pi): stable, asymptotically" tippe/report.html
for f in tilt.png tilt.svg track.png track.svg trajectories.csv stability.json; do
  check "tippe $f" [ -s "tippe/$f" ]
done
check "figures on the page" bash -c "grep -q \"src='tilt.svg'\" tippe/report.html && grep -q \"src='track.svg'\" tippe/report.html"
check "table columns" [ "$(head -1 tippe/trajectories.csv)" = "t,theta,phi,theta_rate,phi_rate,tilt,azimuth,x,y,height,normal_force,slip_speed,spin,energy,jellett,vertical_momentum" ]
# The run goes past the turn-over (twice its time) and the tilt ends beyond a quarter turn.
check "past the turn-over" python3 -c "
import csv, json, math, sys
rows = list(csv.DictReader(open('tippe/trajectories.csv')))
turn = json.load(open('tippe/stability.json'))['answer']['table']['turns_over_at']
ok = len(rows) == 4001 and abs(float(rows[-1]['t']) - 2 * turn) < 1e-9 * turn and float(rows[-1]['tilt']) > math.pi / 2
sys.exit(0 if ok else 1)"
check "stability.json as stability's" bash -c "'$H' stability --config '$examples/tippe-top.toml' --format json | cmp -s - tippe/stability.json"
# The 3D view's data (a build with the page script): O's position and P's track at every sample.
if [ -f tippe/report-data.js ]; then
  check "view data" python3 -c "
import json, sys
text = open('tippe/report-data.js').read()
d = json.loads(text[text.index('{'):text.rindex('}') + 1])
t = d['table']
ok = t['tip_radius'] == 0.015 and len(t['track']['x']) == 4001 and len(t['origin']['z']) == len(d['t'])
ok = ok and all(abs(z - 0.015) < 1e-9 for z in t['origin']['z']) and t['track']['x'][0] == 0
sys.exit(0 if ok else 1)"
fi

# The rolling coin (no event): the first 10 s of the answer's horizon, its track in metres.
check "coin report" "$H" report --config "$examples/rolling-coin.toml" --output coin
check "coin words" grep -q "<b>Stays up for the horizon.</b>" coin/report.html
check "coin shown" grep -q "the first 10 s of the answer" coin/report.html
check "coin track" [ -s coin/track.png ]

# A map is the pivot's: refused on a table (exit 2 naming --map), nothing written.
"$H" report --config "$examples/tippe-top.toml" --map nothing.csv --output refused 2> err.txt
check "map refused" [ $? -eq 2 ]
check "map named" grep -q -- "--map" err.txt
check "nothing written" [ ! -e refused/report.html ]

# The pivot's report is the pivot's: its files (no track figure), and the same bytes with the
# table named as the pivot in the file or on the command line.
check "pivot report" "$H" report --config "$examples/toy-top.toml" --output pivot
{ cat "$examples/toy-top.toml"; printf '\n[table]\ncontact = "pivot"\n'; } > pivot-table.toml
check "pivot named" "$H" report --config pivot-table.toml --output pivot-named
check "pivot on the command line" "$H" report --config "$examples/toy-top.toml" --contact pivot --output pivot-flag
# (explore.html is there too when the build has the explorer page: --web or --tests.)
check "pivot files" [ "$(cd pivot && ls | grep -v '^explore.html$' | tr '\n' ' ')" = "angles.png angles.svg axis-path.png axis-path.svg comparison.csv comparison.json errors.png errors.svg $( [ -f pivot/heavytop-report.js ] && echo 'heavytop-report.js report-data.js ')report.html stability-diagram.png stability-diagram.svg stability-map.csv stability-map.png stability-map.svg stability.json tilt.png tilt.svg trajectories.csv wander.png wander.svg " ]
check "pivot heading" grep -q "<h2>Does it stay up?</h2>" pivot/report.html
# Only the title names the configuration file: the rest is the same bytes.
check "pivot named same" bash -c "diff <(sed 's/pivot-table.toml/X/' pivot-named/report.html) <(sed 's#$examples/toy-top.toml#X#' pivot/report.html) > /dev/null && \
  for f in \$(ls pivot); do [ \$f = report.html ] || cmp -s pivot/\$f pivot-named/\$f || exit 1; done"
check "pivot flag same" diff -r pivot pivot-flag
finish
