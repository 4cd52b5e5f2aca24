#!/usr/bin/env bash
# Static stabilisation (Stepping->stabilization) of a body held only by contact:
# tests/cli/decks/float_block.xml, a block 0.05 above a rigid plane pushed onto it by a
# pressure (no support; friction 0.3), solved with GMRES.
#   - without stabilisation the first step fails (exit 3);
#   - with xi = 1e-6 every step converges without a cut-back, the history has a
#     non-negative stabilization_energy column and the log its summary line, and the
#     final contact force and strain energy equal those of the unstabilised run that the
#     direct solver manages from a 0.01 gap (float_block_direct.xml) to 1e-4: the
#     dashpot vanishes with the step's increment;
#   - with xi = 1e-4 the absorbed energy exceeds 1 % of the final strain energy (the block
#     falls 0.05 against the dashpot) and the run warns.
# usage: stabilization.sh STENTOR WORKDIR DECKDIR
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 decks=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
with_xi() {  # with_xi XI IN OUT: the deck with Stepping->stabilization = XI
  deck_copy "$2" "$3" -e "s#<Parameter name=\"steps\" type=\"int\" value=\"4\"/>#&<Parameter name=\"stabilization\" type=\"double\" value=\"$1\"/>#"
  grep -q stabilization "$3" || fail "could not add the parameter to $2"
}
last() { tail -n 1 "$1"/*_history.csv; }
col() { head -n 1 "$1"/*_history.csv | tr ',' '\n' | grep -nx "$2" | cut -d: -f1; }

"$stentor" --output none "$decks/float_block.xml" > none.log 2>&1
rc=$?
[ "$rc" -eq 3 ] || { cat none.log; fail "without stabilisation: exit $rc, expected 3 (the deck no longer floats?)"; }

"$stentor" --output ref "$decks/float_block_direct.xml" > ref.log 2>&1 || { cat ref.log; fail "the direct-solver reference failed"; }

with_xi 1e-6 "$decks/float_block.xml" small.xml
"$stentor" --output small small.xml > small.log 2>&1
rc=$?
cat small.log
[ "$rc" -eq 0 ] || fail "xi = 1e-6: exit $rc, expected 0"
grep -q "^Summary: 4 steps, 0 cut-backs" small.log || fail "xi = 1e-6: not 4 steps without a cut-back"
grep -q "^Static stabilisation: .* J absorbed" small.log || fail "no summary line of the stabilisation energy"
grep -q "warning: .*static stabilisation" small.log && fail "xi = 1e-6 warned"
c=$(col small stabilization_energy)
[ -n "$c" ] || fail "no stabilization_energy column"
awk -F, -v c="$c" 'NR > 1 && !($c >= 0) { exit 1 }' small/*_history.csv || fail "a negative stabilization energy"
fy=$(col small contact_floor_force_y) w=$(col small strain_energy)
python3 - "$(last small)" "$(last ref)" "$fy" "$w" <<'PY' || fail "the stabilised equilibrium differs from the reference"
import sys
a, b = [list(map(float, s.split(','))) for s in sys.argv[1:3]]
for name, k in (("contact force y", int(sys.argv[3]) - 1), ("strain energy", int(sys.argv[4]) - 1)):
    d = abs(a[k] - b[k]) / abs(b[k])
    print(f"{name}: {a[k]:.10g} stabilised, {b[k]:.10g} reference, relative difference {d:.2e}")
    if d > 1e-4: sys.exit(1)
PY

with_xi 1e-4 "$decks/float_block.xml" large.xml
"$stentor" --output large large.xml > large.log 2>&1 || { cat large.log; fail "xi = 1e-4 failed"; }
grep -q "^warning: the static stabilisation absorbed more than 1 % of the strain energy" large.log ||
  { cat large.log; fail "xi = 1e-4: no warning"; }
echo "PASS"
