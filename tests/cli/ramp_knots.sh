#!/usr/bin/env bash
# A step never steps over a point of a table ramp (docs/deck.md, Stepping): the top of the
# block is pulled by a Dirichlet table (0, 0) -> (0.3, 1) -> (1, 0) with steps of 0.25, and
# again with the same table inside the second of two stages. The history must have a row at
# t = 0.3 (stage: 1.3), the largest reaction there, and the steps after it back to 0.25. A
# monotone table (0, 0.3, 0.6, 1 -> 0, 0.2, 0.5, 1) keeps the step grid: it turns only at
# its ends.
# usage: ramp_knots.sh STENTOR WORKDIR DECK
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
table='<Parameter name="ramp" type="string" value="table"/><Parameter name="ramp times" type="Array(double)" value="{0, 0.3, 1}"/><Parameter name="ramp factors" type="Array(double)" value="{0, 1, 0}"/>'
sed -e "s|<Parameter name=\"values\" type=\"Array(double)\" value=\"{0.1}\"/>|&$table|" \
    -e 's|<Parameter name="steps" type="int" value="2"/>|<Parameter name="steps" type="int" value="4"/>|' \
    -e 's|<ParameterList name="Mesh">|<ParameterList name="Output"><Parameter name="basename" type="string" value="knots"/></ParameterList>\n  &|' \
    -e "s|\.\./\.\./\.\./inputs/|$(cd "$(dirname "$deck")/../../../inputs" && pwd)/|" "$deck" > one.xml || fail "sed"
grep -q 'value="{0, 0.3, 1}"' one.xml || fail "the table was not put into the deck"
"$stentor" --output one one.xml > one.log 2>&1 || { cat one.log; fail "the run failed"; }
# time column 2; the reaction of 'pull' in y
check() {  # check CSV T_PEAK TIMES...
  local csv=$1 tpeak=$2
  shift 2
  awk -F, -v tpeak="$tpeak" -v want="$*" '
    NR == 1 { for (i = 1; i <= NF; ++i) if ($i ~ /^reaction_pull_y/) c = i; next }
    { t[NR - 1] = $2; r = $c < 0 ? -$c : $c; if (r > best) { best = r; at = $2 } }
    END {
      n = split(want, w, " ")
      if (NR - 1 != n) { printf "%d rows, expected %d (%s)\n", NR - 1, n, want; exit 1 }
      for (k = 1; k <= n; ++k) if ((t[k] - w[k]) > 1e-12 || (w[k] - t[k]) > 1e-12) { printf "row %d at t = %s, expected %s\n", k, t[k], w[k]; exit 1 }
      d = at - tpeak; if (d < 0) d = -d
      if (d > 1e-12) { printf "largest reaction at t = %s, expected %s\n", at, tpeak; exit 1 }
      printf "%s: rows at %s; largest reaction at t = %s\n", FILENAME, want, at }' "$csv"
}
check one/knots_history.csv 0.3 0.25 0.3 0.55 0.8 1 || fail "one interval: the step did not end at the table's point"
# The same table as the second stage's Ramps entry (stage-local time).
stages='<ParameterList name="Stages"><ParameterList name="hold"><Parameter name="duration" type="double" value="1"/><Parameter name="steps" type="int" value="2"/><Parameter name="loads" type="string" value="clamp"/></ParameterList><ParameterList name="cycle"><Parameter name="duration" type="double" value="1"/><Parameter name="steps" type="int" value="4"/><ParameterList name="Ramps"><ParameterList name="pull">'$table'</ParameterList></ParameterList></ParameterList></ParameterList>'
sed -e "s|$table||" -e "s|<ParameterList name=\"Stepping\">|$stages\n  &|" -e '/^ *<Parameter name="steps" type="int" value="4"\/>$/d' one.xml > two.xml || fail "sed"
"$stentor" --output two two.xml > two.log 2>&1 || { cat two.log; fail "the staged run failed"; }
check two/knots_history.csv 1.3 0.5 1 1.25 1.3 1.55 1.8 2 || fail "stages: the step did not end at the table's point"
# A monotone table (a measured curve) only turns at its ends: the step grid stays.
sed -e 's|value="{0, 0.3, 1}"/><Parameter name="ramp factors" type="Array(double)" value="{0, 1, 0}"|value="{0, 0.3, 0.6, 1}"/><Parameter name="ramp factors" type="Array(double)" value="{0, 0.2, 0.5, 1}"|' one.xml > mono.xml || fail "sed"
grep -q 'value="{0, 0.2, 0.5, 1}"' mono.xml || fail "the monotone table was not put into the deck"
"$stentor" --output mono mono.xml > mono.log 2>&1 || { cat mono.log; fail "the monotone run failed"; }
check mono/knots_history.csv 1 0.25 0.5 0.75 1 || fail "a monotone table's interior points shortened steps"
echo PASS
