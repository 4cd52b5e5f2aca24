#!/usr/bin/env bash
# S7's short procedure in dynamics (tests/cli/decks/s7_dynamic.xml): the rigid balloon
# expands the strut into the layered artery and is withdrawn, Gonzalez with persistence
# contact; the lumen's nodes on the symmetry planes press on the stent.
# Checks: the run ends at t = 1.5; the wall's pair carries load; the energy identity
# E_{n+1} - E_n = W_ext + W_sup - D + W_contact - D_friction per step to 1e-10 of the
# largest total energy (measured: 1.8e-11; 1.5e-6 with the default plastic step when the
# master received the planes' reaction); both pairs frictionless, so the friction dissipation stays 0 (to
# 1e-10 of it): the force the master receives from a slave on a symmetry plane is the
# contact force, not the plane's reaction (docs/contact.md, "Prescribed components").
# usage: s7_dynamic_energy.sh STENTOR WORKDIR DECK
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
"$stentor" --output out "$deck" > log.txt 2>&1 || { tail -30 log.txt; fail "the run failed"; }
e=out/s7_dynamic_energy.csv h=out/s7_dynamic_history.csv
[ -s $e ] || fail "no $e"
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { t = $c["time"]; E = $c["total"]; if (E > m) m = E; b = $c["balance_residual"]; if (b < 0) b = -b; if (b > bmax) bmax = b
    f = $c["friction_dissipation"]; if (f < 0) f = -f; if (f > fmax) fmax = f }
  END { printf "t %s, largest E %.6e, largest |balance| %.3e (%.2e of E), |D_friction| %.3e\n", t, m, bmax, bmax / m, fmax
        exit !(t > 1.5 - 1e-12 && t < 1.5 + 1e-12 && bmax <= 1e-10 * m && fmax <= 1e-10 * m) }' $e ||
  fail "the energy identity or the friction dissipation"
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "contact_wall_active") k = i; next } $k > a { a = $k }
  END { exit !(a > 0) }' $h || fail "the stent never pressed on the wall"
echo "PASS"
