#!/usr/bin/env bash
# Campaign determinism: the same job gives identical cube datasets (all but wall_s) with 1, 2 and
# 3 ranks, and after being killed with SIGKILL at random moments and resumed each time.
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

# kill -9 the whole MPI job at random moments, resume each time, until it completes
kills=0
for attempt in $(seq 1 20); do
  setsid mpirun -np 2 "$rigid" campaign "$job" --out killed.h5 --progress none >> killed.log 2>&1 &
  pid=$!
  delay=$(awk -v s="$RANDOM" 'BEGIN { srand(s); printf "%.2f", 0.35 + rand() * 0.5 }')
  sleep "$delay"
  if kill -0 "$pid" 2> /dev/null; then
    kill -9 -- "-$pid" 2> /dev/null
    wait "$pid" 2> /dev/null
    kills=$((kills + 1))
    [ "$kills" -ge 4 ] && break
  else
    wait "$pid"
    break
  fi
done
echo "killed $kills times"
check "killed at least twice" test "$kills" -ge 2
timeout 300 mpirun -np 2 "$rigid" campaign "$job" --out killed.h5 --progress none >> killed.log 2>&1
check "resumed campaign completes after $kills kills" test $? -eq 0
check "killed and resumed equals uninterrupted" $compare ref.h5 killed.h5
check "no journal left after completion" test ! -e killed.h5.journal

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
