#!/usr/bin/env bash
# The plots of a run (src/run/ResultPlots.hpp) carry units and readable legends, and exist
# only for data the run produced: a static deck in mm-N-s with a probe and a moving
# Dirichlet set (reactions vs time and vs prescribed displacement, probes; no energy
# plot), and a dynamic SI contact deck with friction and a probe (energy with every term of
# the balance, balance per step, contact forces, probes; no reaction plot: no Dirichlet
# set). Each PNG is checked to be a 1200x800 PNG of real content; each gnuplot script beside
# it for its labels and legends; time axes start at t = 0.
# usage: plots.sh STENTOR WORKDIR DECK_DIR
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 decks=$3
command -v gnuplot > /dev/null || fail "gnuplot is not installed (ci/setup.sh installs gnuplot-nox)"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"

# is_png FILE: PNG signature, IHDR 1200 x 800, and more than a blank canvas (> 10 kB).
is_png() {
  [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || fail "$1 is not a PNG"
  [ "$(head -c 24 "$1" | tail -c 8 | od -An -tx1 | tr -d ' \n')" = "000004b000000320" ] || fail "$1 is not 1200 x 800"
  [ "$(stat -c %s "$1")" -gt 10000 ] || fail "$1 is too small to hold a plot ($(stat -c %s "$1") bytes)"
}
# has SCRIPT TEXT...: every TEXT is a line (or part of one) of the gnuplot script.
has() {
  local f=$1
  shift
  for t in "$@"; do grep -qF -- "$t" "$f" || fail "$f lacks: $t"; done
}
# first_row SCRIPT: the first data row ($data begins at t = 0: the initial state).
first_row() { sed -n '/^\$data << EOD$/{n;p;q}' "$1"; }

"$stentor" --output s "$decks/plots_static.xml" > s.log 2>&1 || { cat s.log; fail "static run failed"; }
for p in reactions reaction_pull probes; do is_png "s/static_$p.png"; done
for p in energy balance contact reaction_clamp; do
  [ -e "s/static_$p.png" ] && fail "static run wrote static_$p.png (no such data)"
done
has s/static_reactions.gp "set xlabel 'time [s]'" "set ylabel 'reaction force [N/mm]'" "title 'pull: reaction x'" \
  "title 'clamp: reaction y'" "set xrange [0:*]"
has s/static_reaction_pull.gp "set xlabel 'prescribed displacement [mm]'" "set ylabel 'reaction force [N/mm]'" \
  "title 'pull: reaction x vs prescribed u_x'"
has s/static_probes.gp "set ylabel 'displacement [mm]'" "title 'corner: u_x'" "title 'corner: u_y'"
grep -q "title 'reaction_\|title 'u_corner" s/*.gp && fail "a raw column name as a legend"
# History plots start at the initial state: t = 0, u = 0, reactions 0 (at rest, unloaded).
[ "$(first_row s/static_probes.gp)" = "0 0 0" ] || fail "probes do not start at t = 0, u = 0: $(first_row s/static_probes.gp)"
first_row s/static_reactions.gp | awk '{ for (i = 1; i <= NF; ++i) if ($i != 0) exit 1 }' ||
  fail "reactions do not start at t = 0 with 0: $(first_row s/static_reactions.gp)"
# Reaction vs prescribed displacement: u_x = 0.2 t (linear ramp) in the x column.
awk '/^\$data/ { on = 1; next } /^EOD/ { on = 0 } on { n++; x = $1 } END { exit !(n == 5 && x > 0.2 - 1e-12 && x < 0.2 + 1e-12) }' \
  s/static_reaction_pull.gp || fail "static_reaction_pull.gp: not 5 rows ending at the prescribed 0.2"

# Two moving Dirichlet sets: a reaction-vs-displacement plot each. MALLOC_PERTURB_ makes
# glibc fill freed memory (with its per-thread cache off, which would skip that), so reading
# a freed vector fails every time instead of by chance.
GLIBC_TUNABLES=glibc.malloc.tcache_count=0 MALLOC_PERTURB_=165 "$stentor" --output two "$decks/plots_two_sets.xml" > two.log 2>&1 || { cat two.log; fail "two-set run failed"; }
for p in reactions reaction_pull reaction_lift; do is_png "two/two_$p.png"; done
has two/two_reaction_lift.gp "title 'lift: reaction y vs prescribed u_y'"
awk '/^\$data/ { on = 1; next } /^EOD/ { on = 0 } on { n++; x = $1 } END { exit !(n == 5 && x > 0.1 - 1e-12 && x < 0.1 + 1e-12) }' \
  two/two_reaction_lift.gp || fail "two_reaction_lift.gp: not 5 rows ending at the prescribed 0.1"

"$stentor" --output d "$decks/plots_dynamic.xml" > d.log 2>&1 || { cat d.log; fail "dynamic run failed"; }
for p in energy balance contact probes; do is_png "d/dynamic_$p.png"; done
ls d/dynamic_reaction*.png > /dev/null 2>&1 && fail "dynamic run wrote a reaction plot without Dirichlet sets"
has d/dynamic_energy.gp "set xlabel 'time [s]'" "set ylabel 'energy [J/m]'" "title 'kinetic energy'" \
  "title 'strain energy'" "title 'total energy E (kinetic + strain)'" "title 'external work W_ext'" \
  "title 'support work W_sup (Dirichlet reactions)'" "title 'viscous dissipation'" "title 'contact work W_contact'" \
  "title 'frictional dissipation D_friction'" \
  "title 'balance error E - E_0 - (W_ext + W_sup + W_contact - D - D_friction)'"
has d/dynamic_balance.gp "set ylabel 'balance residual [J/m]'" \
  "title 'E_{n+1} - E_n - (W_ext + W_sup + W_contact - D - D_friction) of the step'"
has d/dynamic_contact.gp "set ylabel 'normal force [N/m]'" "title 'floor'" "Normal contact force of each pair (compression > 0)"
has d/dynamic_probes.gp "set ylabel 'displacement [m]'" "title 'corner: u_y'"
[ "$(first_row d/dynamic_energy.gp | cut -d' ' -f1)" = "0" ] || fail "the energy plot does not start at t = 0"
[ "$(first_row d/dynamic_probes.gp | cut -d' ' -f1)" = "0" ] || fail "the probe plot does not start at t = 0"
# With every term shown the balance closes: the last column (balance error) stays below
# 1e-9 of the largest energy term in the plot.
awk '/^\$data/ { on = 1; next } /^EOD/ { on = 0 }
     on { for (i = 2; i < NF; ++i) { a = $i < 0 ? -$i : $i; if (a > big) big = a }
          e = $NF < 0 ? -$NF : $NF; if (e > err) err = e; n++ }
     END { printf "energy plot: %d rows, largest term %.4g, largest balance error %.3g\n", n, big, err
           exit !(n == 26 && big > 0 && err <= 1e-9 * big) }' d/dynamic_energy.gp || fail "the energy plot's balance does not close"
# The scripts are self-contained: they redo the plot after the folder moved.
mv d moved && rm moved/dynamic_energy.png && (cd moved && gnuplot dynamic_energy.gp) && is_png moved/dynamic_energy.png ||
  fail "dynamic_energy.gp does not redo the plot in a moved folder"
echo "PASS"
