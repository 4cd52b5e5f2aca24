#!/usr/bin/env bash
# What a deck WITHOUT a `Contact` sublist pays for the contact code (issue 9).
#
# Runs the same decks with two stentor executables, OLD (e.g. built from f491e99^, the last
# commit before any contact code) and NEW (e.g. today's main), and compares their times.
# The runs are interleaved (rep 1: old, new; rep 2: new, old; rep 3: old, new; ...) so that a
# change of machine load affects both alike, one stentor at a time (1 MPI rank, serial Kokkos).
# Each run is timed with `/usr/bin/time -f "%e %U %S"` (wall, user and system CPU seconds,
# children included: NEW meshes the .geo in a child process of its own, `--gmsh-helper`).
# Printed: the load average at start and end; per deck and executable the medians of wall,
# user CPU and system time and of the run's own timers `newton` (the Newton solves of the
# step loop: assembly, contact if any, linear solves; no start-up, meshing or output),
# `assembly` and `mesh`; dofs, steps and Newton iterations; the Summary line of the last run
# (to see that both solved the same problem); the ratios NEW/OLD and a Markdown table.
#
# Usage:
#   perf/contact_overhead.sh OLD_STENTOR NEW_STENTOR DECK [DECK ...]
#     DECK   a deck both executables accept, or OLD_DECK:NEW_DECK when the new executable
#            needs a parameter the old schema does not know (e.g. Stepping->predictor to
#            reproduce the old Newton path)
#   env: REPS=5 (runs per deck and executable), KEEP=1 keeps the temporary output folder.
# Example (docs/performance.md, "Decks without contact"):
#   perf/contact_overhead.sh /work/wt/old/build-old/stentor build/stentor \
#     perf/decks/nocontact_static3d.xml \
#     perf/decks/nocontact_static3d.xml:perf/decks/nocontact_static3d_extrapolate.xml \
#     perf/decks/nocontact_dynamic2d.xml inputs/block2d.xml
# Output folders go to a temporary directory (mktemp -d), never into the repository.
set -euo pipefail

if [ $# -lt 3 ]; then
  awk 'NR > 1 && /^#/ {sub(/^# ?/, ""); print; next} NR > 1 {exit}' "$0"
  exit 2
fi
OLD=$(readlink -f "$1")
NEW=$(readlink -f "$2")
shift 2
REPS=${REPS:-5}
for exe in "$OLD" "$NEW"; do
  [ -x "$exe" ] || { echo "not an executable: $exe" >&2; exit 2; }
done
[ -x /usr/bin/time ] || { echo "/usr/bin/time is needed (Debian package 'time')" >&2; exit 2; }

TMP=$(mktemp -d "${TMPDIR:-/tmp}/contact_overhead.XXXXXX")
if [ "${KEEP:-0}" = 1 ]; then
  echo "output kept in $TMP"
else
  trap 'rm -rf "$TMP"' EXIT
fi

median() { sort -g | awk '{a[NR] = $1} END {if (NR == 0) {print "nan"; exit} if (NR % 2) print a[(NR + 1) / 2]; else printf "%.3f\n", (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

# run KIND EXE DECK REP: one timed run, its log in $TMP/<deck>/<kind>/<rep>.log
run() {
  local kind=$1 exe=$2 deck=$3 rep=$4 dir=$5
  local out="$dir/$kind/run$rep"
  mkdir -p "$dir/$kind"
  if ! /usr/bin/time -f "%e %U %S" -o "$dir/$kind/time$rep" "$exe" --output "$out" "$deck" >"$dir/$kind/$rep.log" 2>&1; then
    echo "FAILED: $kind $exe $deck (log $dir/$kind/$rep.log):" >&2
    tail -5 "$dir/$kind/$rep.log" >&2
    KEEP=1
    trap - EXIT
    exit 1
  fi
  tail -1 "$dir/$kind/time$rep" >>"$dir/$kind/times"
  # the run's own timers (the block after "Summary:"): "  newton   2.73 s", "  mesh   0.04 s"
  awk '$1 == "newton" && $3 == "s" {print $2; exit}' "$dir/$kind/$rep.log" >>"$dir/$kind/newton"
  awk '$1 == "mesh" && $3 == "s" {print $2; exit}' "$dir/$kind/$rep.log" >>"$dir/$kind/mesh"
  awk '$1 == "assembly" && $3 == "s" {print $2; exit}' "$dir/$kind/$rep.log" >>"$dir/$kind/assembly"
  rm -rf "$out" "$out.partial"
}

echo "contact_overhead: $(date -u '+%Y-%m-%d %H:%M:%S UTC') on $(hostname), $(nproc) cores, REPS=$REPS"
echo "  OLD $OLD"
echo "  NEW $NEW"
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"

TABLE=()
n=0
for spec in "$@"; do
  n=$((n + 1))
  if [[ "$spec" == *:* ]]; then
    old_deck=${spec%%:*}
    new_deck=${spec#*:}
  else
    old_deck=$spec
    new_deck=$spec
  fi
  old_deck=$(readlink -f "$old_deck")
  new_deck=$(readlink -f "$new_deck")
  dir="$TMP/deck$n"
  mkdir -p "$dir"
  "$OLD" --check "$old_deck" >"$dir/check_old.log" 2>&1 || { echo "OLD rejects $old_deck:"; cat "$dir/check_old.log"; exit 1; }
  "$NEW" --check "$new_deck" >"$dir/check_new.log" 2>&1 || { echo "NEW rejects $new_deck:"; cat "$dir/check_new.log"; exit 1; }
  echo
  echo "== deck $n: $(basename "$old_deck")$([ "$old_deck" = "$new_deck" ] || echo " (old) / $(basename "$new_deck") (new)")"
  for rep in $(seq 1 "$REPS"); do
    if [ $((rep % 2)) = 1 ]; then
      run old "$OLD" "$old_deck" "$rep" "$dir"
      run new "$NEW" "$new_deck" "$rep" "$dir"
    else
      run new "$NEW" "$new_deck" "$rep" "$dir"
      run old "$OLD" "$old_deck" "$rep" "$dir"
    fi
    echo "  rep $rep: old $(tail -1 "$dir/old/times")  new $(tail -1 "$dir/new/times")   (wall, user, sys s)  load $(cut -d' ' -f1 /proc/loadavg)"
  done
  declare -A W C S L M A
  for kind in old new; do
    W[$kind]=$(cut -d' ' -f1 "$dir/$kind/times" | median)
    C[$kind]=$(cut -d' ' -f2 "$dir/$kind/times" | median)
    S[$kind]=$(cut -d' ' -f3 "$dir/$kind/times" | median)
    L[$kind]=$(median <"$dir/$kind/newton")
    M[$kind]=$(median <"$dir/$kind/mesh")
    A[$kind]=$(median <"$dir/$kind/assembly")
    log="$dir/$kind/$REPS.log"
    dofs=$(awk '$1 == "dofs" {print $2; exit}' "$log")
    summary=$(grep '^Summary:' "$log" | tail -1)
    echo "  $kind: median wall ${W[$kind]} s, user ${C[$kind]} s, sys ${S[$kind]} s; timers newton ${L[$kind]} s (assembly ${A[$kind]} s), mesh ${M[$kind]} s; dofs $dofs"
    echo "       $summary"
    grep -E '^Energy balance' "$log" | sed 's/^/       /' || true
  done
  steps=$(grep '^Summary:' "$dir/new/$REPS.log" | tail -1 | awk '{print $2}')
  it_old=$(grep '^Summary:' "$dir/old/$REPS.log" | tail -1 | sed -E 's/.* ([0-9]+) Newton iterations.*/\1/')
  it_new=$(grep '^Summary:' "$dir/new/$REPS.log" | tail -1 | sed -E 's/.* ([0-9]+) Newton iterations.*/\1/')
  rw=$(awk -v a="${W[new]}" -v b="${W[old]}" 'BEGIN {printf "%.3f", a / b}')
  rc=$(awk -v a="${C[new]}" -v b="${C[old]}" 'BEGIN {printf "%.3f", a / b}')
  rl=$(awk -v a="${L[new]}" -v b="${L[old]}" 'BEGIN {printf "%.3f", a / b}')
  echo "  NEW/OLD: wall $rw, user CPU $rc, newton timer $rl"
  name=$(basename "$old_deck")
  [ "$old_deck" = "$new_deck" ] || name="$name / $(basename "$new_deck")"
  TABLE+=("| $name | $dofs | $steps / $it_old / $it_new | ${W[old]} / ${C[old]} / ${L[old]} | ${W[new]} / ${C[new]} / ${L[new]} | $rw / $rc / $rl |")
  unset W C S L M A
done

echo
echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "Medians of $REPS runs each (seconds; CPU = user CPU; newton = the run's own newton timer):"
echo "| deck | dofs | steps / Newton it. old / new | old wall / CPU / newton | new wall / CPU / newton | NEW/OLD wall / CPU / newton |"
echo "|---|---|---|---|---|---|"
printf '%s\n' "${TABLE[@]}"
