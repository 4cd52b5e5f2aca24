#!/usr/bin/env bash
# Hostile checkpoints: a checkpoint is untrusted input. Each case below is a checkpoint of
# restart_bars edited by hand (checkpoint_edit writes it back with a valid checksum, so
# the restart's own checks must find the problem; the raw cases change the HDF5 file
# itself with h5py or by its bytes). Every case must end in exit status 2 with a message
# naming the dataset, on NP ranks, within 60 s: never a crash (SIGSEGV, an ASan report),
# never a hang, never exit 0. The output folder of a refused restart is not created.
# usage: restart_hostile.sh STENTOR CHECKPOINT_EDIT MPIEXEC NPFLAG WORKDIR DECK NP
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 edit=$2 mpiexec=$3 npflag=$4 work=$5 deck=$6 np=$7
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
flags=$(mpi_flags "$mpiexec")
# A checkpoint at step 20, in contact (the run kills itself writing its 3rd checkpoint).
STENTOR_TEST_KILL_CHECKPOINT=3 "$stentor" --output src "$deck" > src.log 2>&1
base=$(basename "$deck" .xml)
cp "src.partial/${base}_checkpoint.h5" base.h5 || { cat src.log; fail "no checkpoint from $deck"; }
pair=contact_impact
np_cases="nan_u step_overflow negative_dt u_one_column facet_range contact_state bit_flip truncated time_array ids_twice huge_table"
fails=0 cases=0
# case NAME FRAGMENT FILE: a restart from FILE must give exit 2 and FRAGMENT.
case_run() {
  local name=$1 fragment=$2 file=$3
  # On several ranks a subset: the checks whose data differ per rank (node tables, contact
  # rows) and one of each kind of file damage.
  [ "$np" -gt 1 ] && ! echo " $np_cases " | grep -q " $name " && return 0
  cases=$((cases + 1))
  # shellcheck disable=SC2086
  if [ "$np" -eq 1 ]; then  # no launcher: a second less per case
    timeout 60 "$stentor" --output "out_$name" --restart "$file" "$deck" > "$name.log" 2>&1
  else
    timeout 60 "$mpiexec" $npflag "$np" $flags "$stentor" --output "out_$name" --restart "$file" "$deck" > "$name.log" 2>&1
  fi
  local rc=$?
  if [ "$rc" -ne 2 ] || ! grep -qF -- "$fragment" "$name.log" || grep -q "AddressSanitizer\|runtime error:" "$name.log"; then
    echo "FAIL: $name: exit status $rc (expected 2), expected the message: $fragment"
    tail -5 "$name.log"
    fails=$((fails + 1))
  else
    echo "ok: $name: $(grep -m1 'error' "$name.log")"
  fi
  [ -e "out_$name" ] && { echo "FAIL: $name: out_$name was created"; fails=$((fails + 1)); }
}
# edited NAME FRAGMENT EDIT...: the checkpoint with EDIT applied (valid checksum).
edited() {
  local name=$1 fragment=$2
  shift 2
  [ "$np" -gt 1 ] && ! echo " $np_cases " | grep -q " $name " && return 0
  "$edit" base.h5 "$name.h5" "$@" || fail "checkpoint_edit $* failed"
  case_run "$name" "$fragment" "$name.h5"
}
edited nan_u "/tables/u/values holds a non-finite number" cell u 3 1 nan
edited inf_velocity "holds a non-finite number" cell u_before_last 0 0 inf
edited nan_time "/reals: attribute time is not a finite number" real time nan
edited time_past_end "/reals/time = 1000 is out of range" real time 1000
edited negative_dt "/reals/dt_next = -0.001 is out of range" real dt_next -0.001
edited zero_dt_min "/reals/dt_min = 0 is out of range" real dt_min 0
edited step_overflow "/ints/step = 4294967296 is out of range" int step 4294967296 int attempts 4294967296
edited negative_step "/ints/step = -1 is out of range" int step -1
edited attempts_below_step "/ints/attempts = 3 is less than /ints/step" int attempts 3
edited stage_range "/ints/stage = 7 is out of range" int stage 7
edited cuts_overflow "/ints/cuts_total = 3000000000 is out of range" int cuts_total 3000000000
edited missing_dt "/reals/dt_next is missing" drop-real dt_next
edited u_one_column "/tables/u/values has 1 columns, expected 2" cols u 1
edited contact_columns "no contact history for 'Contact->impact'" cols $pair 3
edited facet_range "column 6 (master facet) is not a facet of the master" cell $pair 0 6 1000000
edited facet_negative "column 4 (previous master facet) is not a facet of the master" cell $pair 0 4 -7
edited facet_fraction "column 6 (master facet) is not a facet of the master" cell $pair 0 6 0.5
edited contact_state "column 3 (state) is not a contact state" cell $pair 0 3 99
edited no_u "missing table 'u'" drop u
# Raw changes to the file: a checksum that no longer matches, a truncated file, HDF5
# objects of another shape or type than Stentor writes.
cp base.h5 flipped.h5
off=$(/usr/bin/python3 -c "import h5py; print(h5py.File('base.h5','r')['tables/u/values'].id.get_offset())")
printf '\x5a' | dd of=flipped.h5 bs=1 seek="$off" conv=notrunc status=none
case_run bit_flip "the checksum of its data does not match" flipped.h5
head -c $(($(stat -c %s base.h5) / 2)) base.h5 > truncated.h5
case_run truncated "cannot restart from" truncated.h5
h5edit() {  # h5edit NAME FRAGMENT PYTHON: base.h5 copied to NAME.h5, changed by PYTHON (f: the file)
  [ "$np" -gt 1 ] && ! echo " $np_cases " | grep -q " $1 " && return 0
  cp base.h5 "$1.h5"
  /usr/bin/python3 -c "import h5py, numpy as np; f = h5py.File('$1.h5', 'r+'); $3; f.close()" || fail "h5py edit $1 failed"
  case_run "$1" "$2" "$1.h5"
}
h5edit time_array "attribute time is not a floating-point number (one value)" \
  "g = f['reals']; del g.attrs['time']; g.attrs['time'] = np.zeros(1000)"
h5edit step_string "attribute step is not an integer" "g = f['ints']; del g.attrs['step']; g.attrs['step'] = 'many'"
h5edit ids_negative "/tables/u/ids: id -5 is negative" "f['tables/u/ids'][0] = -5"
h5edit ids_twice "appears twice" "d = f['tables/u/ids']; d[1] = d[0]"
h5edit values_int "/tables/u/values is not of floating-point type" \
  "v = f['tables/u/values'][...]; del f['tables/u/values']; f['tables/u/values'] = v.astype(np.int64)"
h5edit huge_table "more than the file holds" \
  "del f['tables/u/values']; f.create_dataset('tables/u/values', shape=(10**12, 2), dtype='f8')"
h5edit three_dims "has 3 dimensions" \
  "v = f['tables/u/values'][...]; del f['tables/u/values']; f['tables/u/values'] = v.reshape(v.shape[0], v.shape[1], 1)"
h5edit no_checksum "no 'checksum' attribute" "del f.attrs['checksum']"
echo "$cases cases, $((cases - fails)) refused cleanly (exit 2, the message), $fails not"
[ "$fails" -eq 0 ] || fail "$fails of $cases hostile checkpoints not refused cleanly"
echo "PASS"
