#!/usr/bin/env bash
# Generates the malformed-input corpus from inputs/ into WORKDIR/corpus and runs stentor
# on it (tests/cli/corpus/gen_corpus.py, run_corpus.py); exit 1 if any case is BAD.
# usage: corpus.sh STENTOR INPUTS_DIR WORKDIR [run_corpus.py options, e.g. --subset 24]
# Needs python3 (standard library only; h5py and numpy, where they import, for the scan
# of the HDF5 results: Debian's /usr/bin/python3 with python3-h5py is preferred); without
# python3 the test is skipped (exit 77).
set -u
here=$(cd "$(dirname "$0")" && pwd)
stentor=$1 inputs=$2 work=$3
shift 3
py=python3
/usr/bin/python3 -c "import h5py, numpy" 2> /dev/null && py=/usr/bin/python3
command -v $py > /dev/null || { echo "SKIP: no python3"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || { echo "FAIL: cannot make $work"; exit 1; }
$py "$here/gen_corpus.py" "$inputs" "$work/corpus" || { echo "FAIL: generator"; exit 1; }
$py "$here/run_corpus.py" "$stentor" "$work/corpus" "$work/cases" --report "$work/report.txt" "$@"
