#!/usr/bin/env bash
# Campaign trust: a resume never mixes inputs, a failed write never aborts or loses
# results, one campaign per output, journal records checked one by one. The oracle is always an
# uninterrupted run of the same inputs (compare_cubes.py), never numbers copied from the code.
# Usage: trust_test.sh MODE RIGID_EXECUTABLE SOURCE_DIR
#   MODE inputs      change one byte of each input kind after an interrupted run: refused, exit 2,
#                    one line naming the file, cube and journal untouched; --force starts anew
#   MODE journal     a flipped byte in one record / in the header: reported, the rest kept
#   MODE lock        a second campaign on the same --out while the first runs: exit 2, one line
#   MODE physics     two objects with different frictions and models: each object's own physics is
#                    in the cube (its physics_json attribute), read back with h5py; cells that fail
#                    (a 1e200 g scale drives the state to Inf) keep their message in the cube and
#                    are listed by rigid campaign
#   MODE checkpoint  a full disk (small tmpfs) at a resume, mid-run under mpirun -np 2 and after
#                    SIGUSR1: exit 1, one line, no abort, cube and journal intact, resume exact
set -u
mode=$1
rigid=$2
src=$3
compare="/usr/bin/python3 $src/tests/python/compare_cubes.py"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d)
mounted=""
cleanup() {
  [ -n "$mounted" ] && umount "$mounted" 2> /dev/null
  rm -rf "$work"
}
trap cleanup EXIT
# shellcheck source=checks.sh
source "$src/tests/campaign/checks.sh"
finish() {
  echo "$passed passed, $failed failed"
  [ "$failed" -eq 0 ]
  exit
}
lines() { wc -l < "$1"; }
# exactly one line in LOG, matching the extended regex
one_line() { [ "$(lines "$1")" -eq 1 ] && grep -Eq "$2" "$1"; }
# the log holds no abort, crash or HDF5 error stack
clean_exit() { ! grep -Eq "terminate called|Segmentation|core dumped|HDF5-DIAG|Aborted|MPI_ABORT" "$1"; }
jsize() { stat -c %s "$1" 2> /dev/null || echo 0; }
# waits (up to 20 s) until FILE holds at least N bytes or process PID has ended
wait_size() {
  local file=$1 n=$2 pid=$3
  for _ in $(seq 1 2000); do
    [ "$(jsize "$file")" -ge "$n" ] && return 0
    kill -0 "$pid" 2> /dev/null || return 1
    sleep 0.01
  done
  return 1
}
header=76  # journal header and record sizes (src/campaign/journal.cpp)
record=300  # 288-byte TaskResult (with its failure message and solver count) + fingerprint + CRC
done_count() { sed -n 's/.* tasks, \([0-9]*\) already done.*/\1/p' "$1" | tail -1; }

# A tiny campaign whose every input kind is a file of its own: a TOML scene naming a model file,
# two STLs and a saved state; a record list naming AT2 records (16 short tasks, ~2 s).
in=$work/in
mkdir -p "$in/w"
cp "$src"/models/demo/block_a02.toml "$src"/models/demo/block_a02.model "$src"/models/demo/block_a02.state.toml \
   "$src"/models/demo/block_a02_block.stl "$src"/models/demo/block_a02_pedestal.stl "$in/"
cp "$src"/waveforms/demo/pulse_sine_0p5s-X.AT2 "$src"/waveforms/demo/mp_pulse_1s-X.AT2 \
   "$src"/waveforms/demo/mp_pulse_1s-Y.AT2 "$in/w/"
printf 'Pulse\t2000\t6.0\tw/pulse_sine_0p5s-X.AT2\t0\t1e9\t\t\t\nMP\t2001\t6.5\tx=w/mp_pulse_1s-X.AT2,y=w/mp_pulse_1s-Y.AT2\t0\t1e9\t\t\t\n' \
  > "$in/list.tsv"
cat > "$in/job.toml" << 'EOF'
records = "list.tsv"

[campaign]
seed = 11
scales = [0.1, 0.2, 0.3, 0.4]
rotations = 2
stop_after = 0
checkpoint_interval_s = 60

[[object]]
scene = "block_a02.toml"

[run]
free_time_s = 1.0
EOF
cd "$in" || exit 1
campaign() { "$rigid" campaign job.toml --progress none "$@"; }

# the oracle: one uninterrupted run
campaign --out "$work/ref.h5" > "$work/ref.log" 2>&1
check "uninterrupted run completes" test $? -eq 0

# An interrupted run: killed (SIGKILL) once its journal holds at least N results, so the cube
# (written at start) holds none and the journal the rest. Leaves OUT and OUT.journal.
interrupted() {  # OUT N
  local out=$1 n=$2
  rm -f "$out" "$out.journal"
  "$rigid" campaign job.toml --progress none --out "$out" > /dev/null 2>&1 &  # not via a function: $! must be rigid
  local pid=$!
  wait_size "$out.journal" $((header + n * record)) "$pid"
  kill -9 "$pid" 2> /dev/null
  wait "$pid" 2> /dev/null
  rm -f "$out.lock"  # a killed holder's lock file stays; the lock itself died with it
}

case "$mode" in
physics)
  # a second copy of the scene with friction 0.9 and the penalty model
  sed -e 's/^friction = 0.6/friction = 0.9/' -e 's/^contact = "rigid"/contact = "penalty"/' block_a02.toml > other.toml
  check "the copy differs in friction and model" grep -q 'friction = 0.9' other.toml
  printf '\n[[object]]\nname = "other"\nscene = "other.toml"\n' >> job.toml
  campaign --out "$work/two.h5" > "$work/two.log" 2>&1
  check "two-object campaign completes" test $? -eq 0
  /usr/bin/python3 - "$work/two.h5" > "$work/phys.txt" 2>&1 << 'PY'
import json, sys, h5py
with h5py.File(sys.argv[1]) as f:
    for name in f["objects"]:
        p = json.loads(f["objects"][name].attrs["physics_json"])
        print(name, f"{p['friction']:g}", p["contact"], f"{p['density']:g}", p["failure_rule"], p["step_s"] > 0)
PY
  check "object block_a02: friction 0.6, rigid contact" grep -q "^block_a02 0.6 rigid 2600 below True" "$work/phys.txt"
  check "object other: friction 0.9, penalty contact" grep -q "^other 0.9 penalty 2600 below True" "$work/phys.txt"
  cat "$work/phys.txt"
  # a drive no earthquake makes (1e200 g, past the 50 g limit) is refused when the job loads,
  # naming the record: it once ran and failed cell by cell. That a failed cell keeps its message in
  # the journal and the cube is checked by tests/campaign/failure_message_test.cpp and
  # tests/io/cube_test.cpp
  sed 's/^scales = .*/scales = [0.1, 1e200]/' job.toml > fail.toml
  "$rigid" campaign fail.toml --progress none --out "$work/fail.h5" > "$work/fail.log" 2>&1
  check "a campaign of absurd drives is refused (exit 2)" test $? -eq 2
  check "the refusal names the record, the scale and the limit" grep -q "list.tsv:1: .*1e+200 g.*beyond 50 g" "$work/fail.log"
  check "nothing is written" test ! -e "$work/fail.h5"
  ;;
inputs)
  interrupted "$work/part.h5" 2
  cp "$work/part.h5" "$work/snap.h5"
  cp "$work/part.h5.journal" "$work/snap.h5.journal"
  restore() {
    cp "$work/snap.h5" "$work/part.h5"
    cp "$work/snap.h5.journal" "$work/part.h5.journal"
  }
  journalled=$((($(jsize "$work/snap.h5.journal") - header) / record))
  echo "interrupted with $journalled results in the journal"
  # NAME FILE PYTHON-EXPRESSION: one byte of FILE changed (b = its bytes), the rest as before
  kind() {
    local name=$1 file=$2 expr=$3
    restore
    cp "$file" "$work/orig"
    /usr/bin/python3 -c "import sys; p=sys.argv[1]; b=bytearray(open(p,'rb').read()); $expr; open(p,'wb').write(b)" "$file"
    check "$name: exactly one byte changed" test "$(cmp -l "$work/orig" "$file" | wc -l)" -eq 1
    campaign --out "$work/part.h5" > "$work/k.log" 2>&1
    local status=$?
    check "$name: resume refused with exit 2" test "$status" -eq 2
    check "$name: one line naming $file" one_line "$work/k.log" \
      "^rigid: error: (.*/)?$file: changed since the campaign started \(resume refused; --force starts anew\)$"
    check "$name: cube untouched" cmp -s "$work/part.h5" "$work/snap.h5"
    check "$name: journal untouched" cmp -s "$work/part.h5.journal" "$work/snap.h5.journal"
    campaign --out "$work/part.h5" --force > "$work/f.log" 2>&1
    status=$?
    check "$name: --force completes" test "$status" -eq 0
    check "$name: --force starts anew (0 already done)" test "$(done_count "$work/f.log")" = 0
    if [ "$name" = "scene TOML" ]; then
      # a physics change: the forced cube is what a fresh campaign on the new inputs gives
      campaign --out "$work/fresh.h5" > /dev/null 2>&1
      check "$name: --force equals a fresh run on the changed inputs" $compare "$work/fresh.h5" "$work/part.h5"
    fi
    cp "$work/orig" "$file"
  }
  b_of() { echo "b.index(b'$1')"; }  # python: offset of a byte string in the file
  kind "scene TOML" block_a02.toml "i=$(b_of 'friction = 0.6')+13; b[i]=ord('7')"
  kind "model file" block_a02.model "b[-1]=ord(' ')"
  kind "STL" block_a02_block.stl "b[b.index(b'solid')+6]^=1"
  # the 17th digit of the block's last quaternion component: the smallest change a state can have
  kind "saved state" block_a02.state.toml "i=b.rindex(b']')-1; b[i]=ord('1') if b[i]!=ord('1') else ord('2')"
  kind "AT2 record" w/mp_pulse_1s-Y.AT2 "i=b.index(b'E-0', 400)-1; b[i]=ord('9') if b[i]!=ord('9') else ord('8')"
  kind "record list" list.tsv "i=b.index(b'1e9'); b[i]=ord('2')"
  kind "job file" job.toml "i=b.index(b'seed = 11')+8; b[i]=ord('2')"

  # untouched inputs resume exactly as before
  restore
  campaign --out "$work/part.h5" > "$work/r.log" 2>&1
  check "untouched inputs: resume completes" test $? -eq 0
  check "untouched inputs: resume replays the journal" test "$(done_count "$work/r.log")" -eq "$journalled"
  check "untouched inputs: resumed equals uninterrupted" $compare "$work/ref.h5" "$work/part.h5"
  ;;

journal)
  interrupted "$work/j.h5" 4
  n=$((($(jsize "$work/j.h5.journal") - header) / record))
  check "interrupted with at least 4 journalled results" test "$n" -ge 4
  cp "$work/j.h5" "$work/snap.h5"
  cp "$work/j.h5.journal" "$work/snap.journal"
  flip() {  # OFFSET
    /usr/bin/python3 -c "import sys; p=sys.argv[1]; b=bytearray(open(p,'rb').read()); b[int(sys.argv[2])]^=0x10; open(p,'wb').write(b)" \
      "$work/j.h5.journal" "$1"
  }
  # a byte in the middle of record 1 (its failure time)
  flip $((header + record + 20))
  campaign --out "$work/j.h5" > "$work/j.log" 2>&1
  check "bad record: resume completes" test $? -eq 0
  check "bad record: reported in one line" test "$(grep -c 'journal' "$work/j.log")" -eq 1
  check "bad record: names record 1 and its checksum" grep -q "j.h5.journal: record 1 (byte $((header + record))): bad checksum, skipped" "$work/j.log"
  check "bad record: the other $((n - 1)) kept" test "$(done_count "$work/j.log")" -eq $((n - 1))
  check "bad record: resumed equals uninterrupted" $compare "$work/ref.h5" "$work/j.h5"

  cp "$work/snap.h5" "$work/j.h5"
  cp "$work/snap.journal" "$work/j.h5.journal"
  flip 20  # inside the header's key
  campaign --out "$work/j.h5" > "$work/h.log" 2>&1
  check "bad header: resume completes" test $? -eq 0
  check "bad header: reported in one line" test "$(grep -c 'journal' "$work/h.log")" -eq 1
  check "bad header: names the damaged header" grep -q "j.h5.journal: damaged header" "$work/h.log"
  check "bad header: all $n records kept" test "$(done_count "$work/h.log")" -eq "$n"
  check "bad header: resumed equals uninterrupted" $compare "$work/ref.h5" "$work/j.h5"
  ;;

lock)
  rm -f "$work/l.h5"
  "$rigid" campaign job.toml --progress none --out "$work/l.h5" > "$work/first.log" 2>&1 &
  pid=$!
  wait_size "$work/l.h5.journal" $((header + record)) "$pid"
  # held still while the second one tries, so the first cannot finish in between however slow
  # this machine is
  kill -STOP "$pid"
  check "first campaign holds the lock" test -e "$work/l.h5.lock"
  campaign --out "$work/l.h5" > "$work/second.log" 2>&1
  check "second campaign refused with exit 2" test $? -eq 2
  check "one line naming the lock and the running campaign" one_line "$work/second.log" \
    "^rigid: error: .*l\.h5\.lock: another campaign is running on .*l\.h5"
  check "cube and journal left to the first campaign" test -e "$work/l.h5.journal"
  kill -CONT "$pid"
  wait "$pid"
  check "first campaign completes undisturbed" test $? -eq 0
  check "first campaign's cube equals uninterrupted" $compare "$work/ref.h5" "$work/l.h5"
  check "lock file removed at the end" test ! -e "$work/l.h5.lock"
  ;;

checkpoint)
  mnt=$work/mnt
  mkdir -p "$mnt"
  if ! mount -t tmpfs -o size=2m tmpfs "$mnt" 2> /dev/null; then
    echo "SKIP: cannot mount a tmpfs here (needs root and mount rights); checkpoint-failure cases not run"
    exit 77
  fi
  mounted=$mnt
  fill() {  # fills the tmpfs, then frees KB kilobytes
    dd if=/dev/zero of="$mnt/fill" bs=4k > /dev/null 2>&1
    [ "$1" -gt 0 ] && truncate -s "-$1K" "$mnt/fill"
    sync
  }
  failure_line='^rigid: error: .*c\.h5: checkpoint failed: .* \(results kept in the journal; run again to resume\)$'
  any_failure='^rigid: error: .*c\.h5(\.journal)?: (checkpoint failed|journal write failed): .*run again to resume\)$'
  errors() { grep '^rigid: error:' "$1" > "$1.err"; echo "$1.err"; }
  failed_cleanly() {  # NAME STATUS LOG LINE-REGEX
    if grep -q "^fragility cube" "$3"; then
      echo "note: $1: the campaign finished before the disk filled; case not exercised"
      return
    fi
    check "$1: exit 1" test "$2" -eq 1
    check "$1: one line" one_line "$(errors "$3")" "$4"
    check "$1: no abort, crash or HDF5 trace" clean_exit "$3"
    check "$1: no temporary cube left" test ! -e "$mnt/c.h5.tmp"
  }

  # 1. full at a resume: the journal (one page) fits, the cube does not
  interrupted "$mnt/c.h5" 2
  n=$((($(jsize "$mnt/c.h5.journal") - header) / record))
  cp "$mnt/c.h5" "$work/snap.h5"
  cp "$mnt/c.h5.journal" "$work/snap.journal"
  fill 8
  campaign --out "$mnt/c.h5" > "$work/c1.log" 2>&1
  status=$?
  cat "$work/c1.log"
  check "full disk at resume: exit 1" test "$status" -eq 1
  check "full disk at resume: one line" one_line "$(errors "$work/c1.log")" "$failure_line"
  check "full disk at resume: no abort, crash or HDF5 trace" clean_exit "$work/c1.log"
  check "full disk at resume: previous cube intact" cmp -s "$mnt/c.h5" "$work/snap.h5"
  # its n whole records as they were (a record torn by the kill may be dropped)
  check "full disk at resume: journal intact" cmp -s -n $((header + n * record)) "$mnt/c.h5.journal" "$work/snap.journal"
  check "full disk at resume: no temporary file left" test ! -e "$mnt/c.h5.tmp"
  check "full disk at resume: no lock left" test ! -e "$mnt/c.h5.lock"
  rm -f "$mnt/fill"
  campaign --out "$mnt/c.h5" > "$work/c1r.log" 2>&1
  check "space back: resume completes" test $? -eq 0
  check "space back: the journal's $n results replayed" test "$(done_count "$work/c1r.log")" -eq "$n"
  check "space back: resumed equals uninterrupted" $compare "$work/ref.h5" "$mnt/c.h5"

  # 2. full mid-run under mpirun -np 2: master thread, local worker and a worker rank all busy
  rm -f "$mnt/c.h5" "$mnt/c.h5.journal"
  timeout 120 mpirun --oversubscribe -np 2 "$rigid" campaign job.toml --out "$mnt/c.h5" --progress none \
    --checkpoint-interval 0.2 > "$work/c2.log" 2>&1 &
  pid=$!
  wait_size "$mnt/c.h5.journal" $((header + 2 * record)) "$pid"
  fill 0
  wait "$pid"
  status=$?
  cat "$work/c2.log"
  failed_cleanly "full disk mid-run (2 ranks)" "$status" "$work/c2.log" "$any_failure"
  rm -f "$mnt/fill"
  timeout 120 mpirun --oversubscribe -np 2 "$rigid" campaign job.toml --out "$mnt/c.h5" --progress none > "$work/c2r.log" 2>&1
  check "space back (2 ranks): resume completes" test $? -eq 0
  check "space back (2 ranks): resumed equals uninterrupted" $compare "$work/ref.h5" "$mnt/c.h5"

  # 3. full, then SIGUSR1: the final checkpoint fails
  rm -f "$mnt/c.h5" "$mnt/c.h5.journal"
  "$rigid" campaign job.toml --progress none --out "$mnt/c.h5" > "$work/c3.log" 2>&1 &
  pid=$!
  wait_size "$mnt/c.h5.journal" $((header + 2 * record)) "$pid"
  kill -STOP "$pid"  # so it cannot finish before the disk is full
  fill 0
  kill -USR1 "$pid"
  kill -CONT "$pid"
  wait "$pid"
  status=$?
  cat "$work/c3.log"
  failed_cleanly "full disk after SIGUSR1" "$status" "$work/c3.log" "$failure_line"
  rm -f "$mnt/fill"
  campaign --out "$mnt/c.h5" > "$work/c3r.log" 2>&1
  check "space back after SIGUSR1: resume completes" test $? -eq 0
  check "space back after SIGUSR1: resumed equals uninterrupted" $compare "$work/ref.h5" "$mnt/c.h5"

  # 4. an output directory mounted read-only: refused before any work, nothing touched
  mkdir -p "$work/ro"
  cp "$work/snap.h5" "$work/ro/c.h5"
  if mount --bind -o ro "$work/ro" "$mnt" 2> /dev/null || { mount --bind "$work/ro" "$mnt" && mount -o remount,bind,ro "$mnt"; } 2> /dev/null; then
    campaign --out "$mnt/c.h5" > "$work/c4.log" 2>&1
    status=$?
    umount "$mnt"
    check "read-only output: exit 2" test "$status" -eq 2
    check "read-only output: one line" one_line "$work/c4.log" "^rigid: error: .*c\.h5.*Read-only file system"
    check "read-only output: cube intact" cmp -s "$work/ro/c.h5" "$work/snap.h5"
  else
    echo "note: bind mounts unavailable; read-only case not run"
  fi
  ;;
*)
  echo "unknown mode $mode" >&2
  exit 2
  ;;
esac
finish
