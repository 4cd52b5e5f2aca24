#!/usr/bin/env bash
# Contact pairs' c_nu / c_tau: the automatic default (c normal = c tangent = 0) against the
# talk's fixed c_nu = 1e4, c_tau = 100 (per unit area) on every shipped contact deck whose
# pairs use the default; one line per run (exit status, steps, cut-backs, Newton
# iterations, CPU seconds). docs/contact.md, "c_nu, c_tau", has the table.
#   usage: perf/studies/contact_c_default.sh [build-dir] [work-dir]   (default build, /tmp/cstudy)
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
EXE=${1:-$ROOT/build}/stentor
WORK=${2:-/tmp/cstudy}
mkdir -p "$WORK" && cd "$WORK" || exit 1
for deck in balloon_ring balloon_stages contact_block_impact contact_block_static contact_patch2d hertz hertz_cylinders ironing s1_ring s3_ring_foundation signorini two_bars s2_torus; do
  for mode in auto talk; do
    src=$ROOT/inputs/$deck.xml
    out=${deck}_$mode
    # absolute mesh paths (the .geo next to the deck)
    sed -e "s|name=\"file\" type=\"string\" value=\"\([^/\"][^\"]*\)\"|name=\"file\" type=\"string\" value=\"$ROOT/inputs/\1\"|" "$src" > $out.xml
    if [ $mode = talk ]; then
      python3 - "$out.xml" <<'PY'
import re,sys
p=sys.argv[1]; s=open(p).read()
# add c normal / c tangent to every pair sublist of Contact
i=s.index('<ParameterList name="Contact">'); j=s.index('</ParameterList>\n  </ParameterList>', i) if False else None
head, rest = s[:i], s[i:]
depth=0; out=''; k=0
lines=rest.split('\n')
res=[]; d=0; done=False
for ln in lines:
    if not done:
        if '<ParameterList' in ln and '/>' not in ln:
            d+=1
            res.append(ln)
            if d==2: res.append('      <Parameter name="c normal" type="double" value="1e4"/><Parameter name="c tangent" type="double" value="100"/>')
            continue
        if '</ParameterList>' in ln:
            d-=1
            if d==0: done=True
    res.append(ln)
open(p,'w').write(head+'\n'.join(res))
PY
    fi
    rm -rf o_$out
    /usr/bin/time -f "%U" -o t_$out.txt timeout 600 $EXE --output o_$out $out.xml > $out.log 2>&1
    rc=$?
    summ=$(grep "^Summary" $out.log | sed 's/Summary: //')
    echo "$deck | $mode | rc $rc | $summ | cpu $(tail -1 t_$out.txt)"
  done
done
# S4 sets the talk's values in the deck: shipped (talk) against the lines removed (auto).
for mode in talk auto; do
  out=s4_stent_artery_$mode
  sed -e "s|value=\"s4_stent_artery.geo\"|value=\"$ROOT/inputs/s4_stent_artery.geo\"|" "$ROOT/inputs/s4_stent_artery.xml" > $out.xml
  [ $mode = auto ] && sed -i -e '/name="c normal"/d' -e '/name="c tangent"/d' $out.xml
  rm -rf o_$out
  /usr/bin/time -f "%U" -o t_$out.txt timeout 900 $EXE --output o_$out $out.xml > $out.log 2>&1
  rc=$?
  echo "s4_stent_artery | $mode | rc $rc | $(grep "^Summary" $out.log | sed 's/Summary: //') | cpu $(tail -1 t_$out.txt)"
done
