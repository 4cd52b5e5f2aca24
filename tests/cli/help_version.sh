#!/usr/bin/env bash
# The command line users meet first.
#   help     `stentor --help`: exit 0, Stentor's usage first (not Kokkos's 40 lines; Kokkos's
#            own help stays behind --kokkos-help), --version listed; a deck given with it
#            is not run
#   version  `stentor --version`: exit 0, "stentor X.Y.Z[ (git DESCRIBE)]", then the
#            Trilinos, Kokkos and HDF5 versions it was built with
#   times    a run of 10 steps of 0.1: the log shows t 0.3 (not 0.30000000000000004),
#            no time with noise digits, and the history CSV writes 0.1 as 0.1; the run's
#            header names the version (the --version text on one line)
# usage: help_version.sh MODE STENTOR WORKDIR [DECK]
set -u
. "$(dirname "$0")/lib.sh"
mode=$1 stentor=$2 work=$3 deck=${4:-}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
case $mode in
  help)
    "$stentor" --help "$deck" > out.txt 2> err.txt
    rc=$?
    cat out.txt err.txt
    [ "$rc" -eq 0 ] || fail "--help: exit status $rc"
    head -n 1 out.txt | grep -q "^usage: stentor " || fail "--help: the first line is not Stentor's usage"
    grep -q "Kokkos command line arguments" out.txt err.txt && fail "--help prints Kokkos's help"
    grep -q -- "--version" out.txt || fail "--help does not list --version"
    grep -q -- "--kokkos-help" out.txt || fail "--help does not point to --kokkos-help"
    [ -e results ] && fail "--help ran the deck"
    "$stentor" --kokkos-help > kokkos.txt 2>&1
    grep -q "Kokkos command line arguments" kokkos.txt || fail "--kokkos-help no longer reaches Kokkos"
    ;;
  version)
    "$stentor" --version > out.txt 2> err.txt
    rc=$?
    cat out.txt err.txt
    [ "$rc" -eq 0 ] || fail "--version: exit status $rc"
    head -n 1 out.txt | grep -Eq '^stentor [0-9]+\.[0-9]+\.[0-9]+( \(git [^ )]+\))?$' ||
      fail "--version: first line is not 'stentor X.Y.Z (git ...)'"
    sed -n 2p out.txt | grep -Eq '^Trilinos [0-9]+\.[0-9]+, Kokkos [0-9]+\.[0-9]+\.[0-9]+, HDF5 [0-9]+\.[0-9]+\.[0-9]+$' ||
      fail "--version: second line does not name the Trilinos, Kokkos and HDF5 versions"
    [ "$(wc -l < out.txt)" -eq 2 ] || fail "--version: expected 2 lines"
    ;;
  times)
    "$stentor" --output results "$deck" > log.txt 2>&1
    rc=$?
    cat log.txt
    [ "$rc" -eq 0 ] || fail "exit status $rc"
    grep -Eq '^  step +3  t 0\.3 +dt 0\.1 ' log.txt || fail "step 3 is not logged as 't 0.3  dt 0.1'"
    grep -E '(^| )(t|dt|t =|t=) ?[0-9]+\.[0-9]{7,}' log.txt && fail "the log prints a time with noise digits"
    want="  version  $("$stentor" --version | paste -sd';' | sed 's/;/; /')"
    grep -qxF "$want" log.txt || fail "the run's header does not name the version ('$want')"
    csv=$(ls results/*_history.csv)
    awk -F, 'NR == 2 && $2 != "0.1" { print "history time " $2 ", expected 0.1"; exit 1 }
             NR == 4 && $2 != "0.30000000000000004" { print "history time " $2 ", expected 0.30000000000000004 (t = 0.1 + 0.1 + 0.1, exact)"; exit 1 }' "$csv" ||
      fail "$csv: times not in the shortest exact form"
    ;;
  *) fail "unknown mode $mode" ;;
esac
echo OK
