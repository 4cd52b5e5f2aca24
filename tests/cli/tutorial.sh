#!/usr/bin/env bash
# docs/tutorial.md runs as written: its ```bash tutorial blocks, in order, in one bash
# (set -e: a failing command fails the test) in a fresh folder laid out like a clone
# (build/stentor, a copy of inputs/, tests/cli/decks/ and tools/); then the files and log lines
# the text promises exist. The build block (```bash, no "tutorial") is what CI itself runs.
# usage: tutorial.sh STENTOR WORKDIR SOURCE_DIR
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 src=$3
rm -rf "$work" && mkdir -p "$work/build" "$work/tests/cli" && cd "$work" || fail "cannot make $work"
ln -s "$stentor" build/stentor
cp -r "$src/inputs" inputs && cp -r "$src/tests/cli/decks" tests/cli/decks && cp -r "$src/tools" tools ||
  fail "cannot copy inputs/, tests/cli/decks/ and tools/"
awk '/^```bash tutorial$/ { on = 1; n++; print "echo \"=== tutorial block " n "\""; next }
     on && /^```$/ { on = 0; next }
     on { print }' "$src/docs/tutorial.md" > tutorial_commands.sh
blocks=$(grep -c '^```bash tutorial$' "$src/docs/tutorial.md")
[ "$blocks" -ge 15 ] || fail "docs/tutorial.md has $blocks \`\`\`bash tutorial blocks, expected at least 15"
# The pictures' pvbatch draws on an X server of the test's own (lib.sh start_xvfb).
command -v pvbatch >/dev/null && command -v Xvfb >/dev/null || fail "the tutorial needs ParaView's pvbatch and Xvfb (bash ci/setup.sh installs them)"
start_xvfb "$work"
# Debian's python3 (python3-meshio) first; Open MPI as root in CI.
export PATH=/usr/bin:$PATH OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
start=$(date +%s)
bash -e -o pipefail tutorial_commands.sh > tutorial.out 2>&1
rc=$?
cat tutorial.out
[ "$rc" -eq 0 ] || fail "a tutorial command failed (exit $rc) after block $(grep -c '^=== tutorial block' tutorial.out)"
[ "$(grep -c '^=== tutorial block' tutorial.out)" -eq "$blocks" ] || fail "not every block ran"
# The files the text names.
for f in results/artery_ring/artery_ring.xdmf results/artery_ring/artery_ring.h5 \
         results/artery_ring/artery_ring_history.csv results/artery_ring/artery_ring_probes.png \
         results/artery_ring/artery_ring_reactions.png results/artery_ring/artery_ring_deck.xml \
         results/artery_ring/artery_ring.log results/artery_ring/stentor-manifest.txt \
         mywork/results/coarse/artery_ring_history.csv mywork/results/stiff/artery_ring_history.csv \
         results/par_s4/par_s4.xdmf results/par_s4/par_s4_obstacles.xdmf results/par_s4/par_s4_energy.csv \
         results/par_s4/par_s4_energy.png results/par_s4/par_s4_metrics.csv results/par_s4/par_s4_stages.csv \
         results/par_s4/par_s4_radii.png results/par_s4/par_s4_stresses.png results/par_s4/par_s4_contact.png \
         results/s4_mu0/par_s4_stages.csv results/axi_cylinder/axi_cylinder_history.csv \
         mywork/results/continued/artery_ring_history.csv results/axi_np2/axi_cylinder_history.csv \
         results/artery_ring_vtu/artery_ring_0.vtu results/artery_ring_vtu/artery_ring.pvd \
         results/artery_ring_pictures/artery_ring_von_mises.png results/par_s4_pictures/par_s4_von_mises_0.png \
         results/par_s4_pictures/par_s4_von_mises_3.png results/s6_ring_quarter/s6_ring_quarter_metrics.csv results/s6_ring_quarter/s6_ring_quarter_force_diameter_cylinder.png \
         results/s6_ring_quarter_pictures/s6_ring_quarter_equivalent_plastic_strain.png; do
  [ -s "$f" ] || fail "the tutorial promises $f"
done
# The log lines and messages the text quotes.
for pat in "^Summary: 10 steps" "lumen gain at t = 1: 18.06 %" "^coarse  lumen gain" "^stiff   lumen gain" \
           "^stage 2/3 'inflation'" "metrics at the end of 'extraction'" "restart  from results/half/artery_ring_checkpoint.h5: step 5" \
           "parallel 2 MPI rank" "unknown parameter 'Materials->artery->C_1'; did you mean 'C1'" "^exit status 2$" \
           "every line-search trial inverted elements; where: cell [0-9]* of 'artery'" "^FAILED: Newton failed" "the failed step's last iterate (t = .*) is in results/burst.partial/artery_ring_failed.xdmf" \
           "^exit status 3$" "max |u| = " "2D, 5785 nodes, 2505 cells (artery: 988 tri6, stent: 1517 tri6)" \
           "^  0    |          3.0000 |          3.8071 |          3.7637 |   25.456 |           1.141 |            9.422 |           - | 0.0716"; do
  grep -q -- "$pat" tutorial.out || fail "the tutorial's output lacks '$pat'"
done
grep -q 'W 1.551834e-01' mywork/continued.log || fail "the restarted run does not end at W = 1.551834e-01"
[ -d mywork/results/burst.partial ] && [ ! -e mywork/results/burst ] || fail "the failed run's partial folder"
[ -s mywork/results/burst.partial/artery_ring_failed.xdmf ] || fail "the failed run's last iterate (burst_failed.xdmf)"
[ ! -e mywork/results/typo ] && [ ! -e mywork/results/typo.partial ] || fail "the refused deck wrote something"
echo "PASS ($blocks blocks, $(( $(date +%s) - start )) s)"
