#!/usr/bin/env bash
# Campaign determinism: the same job gives identical cube datasets (all but wall_s) with 1, 2 and
# 3 ranks, and after being killed with SIGKILL at random moments and resumed each time; likewise
# a variant-axis job (tests/campaign/variants_small.toml: the uncertainty demo's sweep, 6 variants)
# on 1 and 2 ranks and killed and resumed; the uncertainty demo itself is dry-run.
# Usage: determinism_test.sh RIGID_EXECUTABLE SOURCE_DIR
set -u
rigid=$1
src=$2
job=$src/jobs/ci_small.toml
compare="/usr/bin/python3 $src/tests/python/compare_cubes.py"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
# shellcheck source=checks.sh
source "$src/tests/campaign/checks.sh"

"$rigid" campaign "$job" --out ref.h5 --progress none > ref.log 2>&1
check "single process completes" test -f ref.h5
for n in 1 2 3; do
  timeout 300 mpirun --oversubscribe -np "$n" "$rigid" campaign "$job" --out "np$n.h5" --progress none > "np$n.log" 2>&1
  check "mpirun -np $n completes" test $? -eq 0
  check "mpirun -np $n equals the single process" $compare ref.h5 "np$n.h5"
done

# kill -9 the whole MPI job at random moments, resume each time, until it completes; a run that
# completes before its second kill (a fast machine, a short job) starts over from nothing with
# shorter delays, so the check tests resumes, not the machine's speed.
# Usage: kill_and_resume JOB OUT REF LABEL FIRST_DELAY_S
kill_and_resume() {
  local job=$1 out=$2 ref=$3 label=$4 first=$5
  local kills=0 scale=1.0 attempt pid delay
  for attempt in $(seq 1 30); do
    setsid mpirun -np 2 "$rigid" campaign "$job" --out "$out" --progress none >> "$out.log" 2>&1 &
    pid=$!
    delay=$(awk -v s="$RANDOM" -v k="$scale" -v f="$first" 'BEGIN { srand(s); printf "%.2f", k * f * (0.35 + rand() * 0.5) }')
    sleep "$delay"
    if kill -0 "$pid" 2> /dev/null; then
      kill -9 -- "-$pid" 2> /dev/null
      wait "$pid" 2> /dev/null
      kills=$((kills + 1))
      [ "$kills" -ge 4 ] && break
    else
      wait "$pid"
      [ "$kills" -ge 2 ] && break
      rm -f "$out" "$out.journal"
      kills=0
      scale=$(awk -v k="$scale" 'BEGIN { printf "%.3f", k * 0.7 }')
    fi
  done
  echo "$label: killed $kills times"
  check "$label: killed at least twice" test "$kills" -ge 2
  timeout 600 mpirun -np 2 "$rigid" campaign "$job" --out "$out" --progress none >> "$out.log" 2>&1
  check "$label: resumed campaign completes after $kills kills" test $? -eq 0
  check "$label: killed and resumed equals uninterrupted" $compare "$ref" "$out"
  check "$label: no journal left after completion" test ! -e "$out.journal"
}
kill_and_resume "$job" killed.h5 ref.h5 "ci_small" 1.0

# variants of one rock (the uncertainty demo's sweep at a size that runs in seconds): 1 and 2
# ranks, and killed and resumed; the demo job itself (1248 cells) through --dry-run only
"$rigid" campaign "$src/jobs/uncertainty_demo.toml" --out udemo.h5 --dry-run > udemo.log 2>&1
check "uncertainty demo: dry run accepts the job" test $? -eq 0
variants=$src/tests/campaign/variants_small.toml
"$rigid" campaign "$variants" --out uref.h5 --progress none > uref.log 2>&1
check "variants: single process completes" test $? -eq 0
check "variants: the stop rule inferred cells" /usr/bin/python3 -c "
import sys, h5py, numpy as np
f = h5py.File('uref.h5', 'r')
sys.exit(0 if sum((f['objects'][n]['outcome'][...] == 3).sum() for n in f['objects']) > 0 else 1)"
timeout 600 mpirun --oversubscribe -np 2 "$rigid" campaign "$variants" --out unp2.h5 --progress none > unp2.log 2>&1
check "variants: mpirun -np 2 completes" test $? -eq 0
check "variants: 2 ranks equal the single process" $compare uref.h5 unp2.h5
kill_and_resume "$variants" ukilled.h5 uref.h5 "variants" 2.0

# SIGTERM: to one process, exit 75 after a final checkpoint, and the resume equals the
# uninterrupted run; to mpirun (Open MPI forwards it to every rank), the ranks checkpoint at once
# and end cleanly (mpirun's own status after a signal is its own: 1 with Open MPI 4.1)
"$rigid" campaign "$job" --out term1.h5 --progress none > term1.log 2>&1 &
pid=$!
sleep 2
kill -TERM "$pid"
wait "$pid"
status=$?
if grep -q "stopped; checkpoint written" term1.log; then
  check "SIGTERM to one process: exit 75" test "$status" -eq 75
  check "SIGTERM to one process: cube written" test -f term1.h5
else
  echo "note: the single-process campaign finished before the signal ($status)"
fi
"$rigid" campaign "$job" --out term1.h5 --progress none >> term1.log 2>&1
check "resumed after SIGTERM completes" test $? -eq 0
check "SIGTERM and resume equals uninterrupted" $compare ref.h5 term1.h5
# (the demo job: long enough to be running when the signal comes)
mpirun -np 2 "$rigid" campaign "$src/jobs/demo.toml" --out term.h5 --progress none > term.log 2>&1 &
pid=$!
sleep 4
kill -TERM "$pid"
wait "$pid"
check "SIGTERM to mpirun: the ranks get it" grep -q "signal 15" term.log
check "SIGTERM to mpirun: the ranks checkpoint and stop" grep -q "stopped; checkpoint written" term.log
check "SIGTERM to mpirun: the cube holds simulated cells" /usr/bin/python3 -c "
import sys, h5py, numpy as np
f = h5py.File('term.h5', 'r')
sys.exit(0 if sum(np.isin(f['objects'][n]['outcome'][...], [1, 2]).sum() for n in f['objects']) > 0 else 1)"

# a changed job is refused without --force, accepted with it
sed 's/seed = 7/seed = 8/' "$job" > changed.toml
sed -i "s#\.\./#$src/#g" changed.toml
"$rigid" campaign changed.toml --out ref.h5 --progress none > changed.log 2>&1
status=$?
check "changed job refused with exit 2" test "$status" -eq 2
check "refusal names the output" grep -q "ref.h5" changed.log
"$rigid" campaign changed.toml --out ref.h5 --force --progress none > forced.log 2>&1
check "changed job accepted with --force" test $? -eq 0

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
