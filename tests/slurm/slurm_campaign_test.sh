#!/usr/bin/env bash
# A campaign through a real Slurm, interrupted twice and resumed, must equal an uninterrupted run.
#
#   bash tests/slurm/slurm_campaign_test.sh RIGID JOB.toml
#
# Brings up the project's single-node Slurm on localhost (slurm/local-cluster.sh, installing
# slurm-wlm and munge when missing), runs the reference `mpirun -np 2 RIGID campaign JOB` outside
# Slurm, then submits slurm/rigid-campaign.sbatch with 2 ranks and
#   1. sends USR1 to its batch shell as the time-limit warning does: the campaign must checkpoint,
#      exit 75 and the script requeue the job itself;
#   2. once it runs again, requeues it from outside (`scontrol requeue`: SIGTERM to the job);
# each time it lifts Slurm's 2-minute requeue delay, then waits for COMPLETED and compares the
# output with the reference (tests/python/compare_cubes.py, wall times excepted). When to
# interrupt is read from /proc (the campaign's rank processes) and the job log (the batch
# script's exit lines), never from polled job states. On fresh CI machines Slurm calls made while
# the campaign ran on both cores did not return until it ended (scontrol 8-20 s late, a scancel
# and a `scontrol update` 45 s late), so before each interruption the test holds the campaign's
# ranks (SIGSTOP) and releases them (SIGCONT) once the batch shell has logged the signal, and the
# call that starts a requeued job runs in the background: the interruption lands mid-campaign
# however late Slurm answers. On one CI run the test itself then stalled for 19 s between seeing
# the ranks and holding them, and the campaign ended first: from the submission on, its shell runs
# at a real-time priority, and it finds the ranks without reading their command lines (a read
# that waits for a busy process's memory-map lock). tests/slurm/slurm_campaign.toml runs about 25 s at 2 ranks
# (the whole test about a minute and a half).
# Skips (exit 0) when not root or when the Slurm packages cannot be installed. Every wait is
# bounded; the whole test stops after RIGID_SLURM_TEST_TIMEOUT s (default 480), and the cluster
# is always brought down. The last line is `N passed, N failed`.
# Environment: RIGID_SLURM_TEST_PROGRESS  seconds of work before each interruption (default 3)
#              RIGID_COMPARE              comparison command (default: /usr/bin/python3 compare_cubes.py)
#              RIGID_SLURM_TEST_KEEP=1    keep the work directory (logs, cubes) after a pass too
#              RIGID_LAUNCHER             passed on to the batch script (mpirun or srun)
set -uo pipefail

repo=$(cd "$(dirname "$0")/../.." && pwd)
passed=0 failed=0
pass() { echo "PASS: $*"; passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }
note() { echo "[$(printf '%3d' "$SECONDS") s] $*"; }
skip() { echo "SKIP: $*"; echo "0 passed, 0 failed"; exit 0; }

[[ $# == 2 ]] || { echo "usage: $0 RIGID JOB.toml" >&2; exit 2; }
[[ $(id -u) == 0 ]] || skip "needs root to run slurmctld, slurmd and munged"
rigid=$(realpath "$1") job=$(realpath "$2")
[[ -x $rigid && -f $job ]] || { fail "missing $1 or $2"; echo "$passed passed, $failed failed"; exit 1; }
read -ra compare <<<"${RIGID_COMPARE:-/usr/bin/python3 $repo/tests/python/compare_cubes.py}"
progress=${RIGID_SLURM_TEST_PROGRESS:-3}
deadline=$((SECONDS + ${RIGID_SLURM_TEST_TIMEOUT:-480}))

work=$(mktemp -d /tmp/rigid-slurm-test.XXXXXX)
chmod 755 "$work"
export RIGID_SLURM_DIR=$work/cluster
jid=""
finish() {
  trap - EXIT INT TERM
  release
  if ((failed)); then
    echo "--- job log $work/job.out"; cat "$work/job.out" 2>/dev/null
    echo "--- slurmctld.log (tail)"; tail -n 15 "$RIGID_SLURM_DIR/log/slurmctld.log" 2>/dev/null
    echo "--- slurmd.log (tail)"; tail -n 10 "$RIGID_SLURM_DIR/log/slurmd.log" 2>/dev/null
    echo "--- load: $(cat /proc/loadavg)"
  fi
  [[ -n $jid ]] && scancel "$jid" 2>/dev/null
  bash "$repo/slurm/local-cluster.sh" down --keep >/dev/null 2>&1
  if ((failed)) || [[ -n ${RIGID_SLURM_TEST_KEEP:-} ]]; then echo "kept $work"; else rm -rf "$work"; fi
  note "done"
  echo "$passed passed, $failed failed"
  exit $((failed > 0))   # a bare exit in a trap would return the status from before the trap
}
trap finish EXIT
trap 'fail "interrupted"; exit' INT TERM

# wait_until SECONDS DESCRIPTION COMMAND...: poll COMMAND every 0.2 s, within the overall deadline
wait_until() {
  local limit=$((SECONDS + $1)) desc=$2
  shift 2
  ((limit > deadline)) && limit=$deadline
  until "$@"; do
    ((SECONDS >= limit)) && { fail "timed out waiting for $desc (state ${state:-?})"; return 1; }
    sleep 0.2
  done
}
# a bounded query: a slurmctld starved of CPU must not stall the test's clock
job_field() { timeout 10 scontrol show job -o "$jid" 2>/dev/null | grep -o "\b$1=[^ ]*" | cut -d= -f2; }
# state_is STATE...: the job is in one of them; gives up the wait (exit) if it ended otherwise
state_is() {
  state=$(job_field JobState)
  [[ " $* " == *" $state "* ]] && return 0
  case $state in COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | PREEMPTED | OUT_OF_MEMORY | BOOT_FAIL | DEADLINE)
    local hint=""
    [[ $state == COMPLETED ]] && hint=": it finished before it could be interrupted (JOB too small?)"
    fail "job $jid ended $state (exit code $(job_field ExitCode)) while waiting for $*$hint"
    exit ;;
  esac
  return 1
}
pending_with_restarts() { state_is PENDING && [[ $(job_field Restarts) == "$1" ]]; }
log_has() { grep -q -- "$1" "$work/job.out" 2>/dev/null; }
# log_count PATTERN: matching lines of the job log, 0 while Slurm has not created it yet
log_count() { cat "$work/job.out" 2>/dev/null | grep -c -- "$1"; }
# run_ended N: the batch script has logged the exit of its Nth campaign run
run_ended() { (($(log_count 'rigid-campaign: exit status') >= $1)); }
# the campaign's rank processes: `rigid` processes (not mpirun) running in the job's folder. Read
# from /proc/PID/comm and the cwd link only: reading a busy process's cmdline (as pgrep does) waits
# for its memory-map lock, and on a CI machine such a read did not return until the campaign ended.
campaign_ranks() {
  local d comm
  for d in /proc/[0-9]*; do
    { read -r comm <"$d/comm"; } 2>/dev/null || continue
    [[ $comm == rigid && $(readlink "$d/cwd" 2>/dev/null) == "$work" ]] && echo "${d#/proc/}"
  done
}
# ranks_up: both ranks of a new campaign run exist (none of them held before)
held=() seen=" "
ranks_up() {
  local p fresh=0
  for p in $(campaign_ranks); do [[ $seen == *" $p "* ]] || fresh=$((fresh + 1)); done
  ((fresh >= 2))
}
# hold the ranks (SIGSTOP) so that the campaign cannot end before a late signal reaches it
hold() {
  read -ra held <<<"$(campaign_ranks | paste -sd' ')"
  ((${#held[@]})) && kill -STOP "${held[@]}" 2>/dev/null
  seen+="${held[*]} "
  note "held ${#held[@]} ranks (SIGSTOP)"
}
release() {
  ((${#held[@]})) || return 0
  kill -CONT "${held[@]}" 2>/dev/null
  held=()
}
# let run N of the campaign work PROGRESS s, hold it and check it still runs. Its start is seen
# in /proc and its journal, not in the job log: mpirun relays the ranks' output, and a starved
# mpirun or Slurm call must not delay the hold.
# The ranks being up is not the campaign at work: under load their start (MPI, reading the job
# and the checkpoint) took over 3 s on one CI run, and the interruption then hit a run that had
# not begun. The journal, written as results arrive and read here by its time stamp, says it has.
journal_written_since_ranks_up() { [[ -n $(find "$work/out.h5.journal" -newer "$work/ranks_up.mark" 2>/dev/null) ]]; }
work_then_hold() {
  wait_until 60 "the ranks of campaign run #$1" ranks_up || exit
  touch "$work/ranks_up.mark"
  note "campaign run #$1: ranks up"
  wait_until 120 "campaign run #$1 to record results in its journal" journal_written_since_ranks_up || exit
  sleep "$progress"
  hold
  if ((${#held[@]} == 0)) || run_ended "$1"; then
    fail "campaign run #$1 ended before interruption #$1: JOB must run longer at 2 ranks"
    exit
  fi
}
# timed CMD...: run a Slurm command and say how long slurmctld took to answer it
timed() {
  local t0=$SECONDS rc=0
  "$@" || rc=$?
  note "$* (answered in $((SECONDS - t0)) s, exit $rc)"
  return "$rc"
}
# the batch shell has logged signal SIG for the Nth time, i.e. Slurm delivered it
signal_logged() { (($(log_count "rigid-campaign: SIG$1 at") >= $2)); }
release_after_signal() {
  if wait_until 120 "SIG$1 #$2 to reach the batch shell" signal_logged "$1" "$2"; then
    note "SIG$1 reached the batch shell; released the ranks (SIGCONT)"
    release
  else exit; fi
}
# lift the ~2 min delay of a requeued job, but not within the second of the requeue: a job that
# starts then is killed with "Job credential revoked". In the background: on fresh CI machines
# this call, answered by slurmctld at once, returned only when the campaign it started had ended.
start_now() { (sleep 2 && timed scontrol update JobId="$jid" StartTime=now) & }

# cluster (its own directory; a busy port pair makes it take the next one)
had_slurm=1
command -v slurmctld >/dev/null && command -v munged >/dev/null || had_slurm=0
if ! env_sh=$(bash "$repo/slurm/local-cluster.sh" up --install); then
  if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    trap - EXIT
    rm -rf "$work"
    skip "slurm-wlm/munge could not be installed"
  fi
  fail "local Slurm did not come up"
  exit
fi
((had_slurm)) || note "installed slurm-wlm and munge"
# shellcheck disable=SC1090
source "$env_sh"
pass "local Slurm up ($SLURM_CONF)"

# reference, outside Slurm
note "reference: mpirun -np 2 $rigid campaign $job"
if timeout $((deadline - SECONDS)) mpirun --oversubscribe -np 2 "$rigid" campaign "$job" --out "$work/ref.h5" \
  >"$work/ref.log" 2>&1; then
  pass "uninterrupted reference run"
else
  fail "reference run failed (exit $?): $(tail -n 3 "$work/ref.log")"
  exit
fi

# From here on the test's own processes run at a real-time priority: a campaign busy on both
# cores must not keep them off the CPU between seeing the ranks and holding them. The cluster and
# the reference run were started before, so neither Slurm nor the job's ranks inherit it.
if chrt -f -p 10 $$ 2>/dev/null; then note "test shell at real-time priority (SCHED_FIFO 10)"
else note "could not raise the test shell's priority (chrt): timing then depends on the scheduler"; fi

# the campaign through sbatch
jid=$(cd "$work" && RIGID=$rigid RIGID_GRACE=5 RIGID_CAMPAIGN_ARGS="--checkpoint-interval 1 --progress log" \
  sbatch --parsable -n 2 -o "$work/job.out" "$repo/slurm/rigid-campaign.sbatch" "$job" "$work/out.h5") \
  || { fail "sbatch refused the job"; exit; }
note "submitted job $jid"
work_then_hold 1

# 1. the time-limit warning: USR1 to the batch shell only
timed scancel --batch --signal=USR1 "$jid" || { fail "scancel --signal=USR1 refused"; exit; }
release_after_signal USR1 1
if wait_until 90 "the job to requeue itself" pending_with_restarts 1; then
  pass "USR1: campaign stopped and the job requeued itself"
else exit; fi
if log_has "exit status 75" && log_has "requeueing job $jid"; then
  pass "first run exited 75 (interrupted, resumable)"
else fail "no 'exit status 75' and requeue in the log"; fi
if [[ -s $work/out.h5 ]]; then pass "checkpoint written before the requeue"; else fail "no $work/out.h5 after the stop"; fi
start_now

# 2. an outside requeue: TERM to every process of the job
work_then_hold 2
timed scontrol requeue "$jid" || { fail "scontrol requeue refused"; exit; }
release_after_signal TERM 1
if wait_until 90 "the requeued job to be pending" pending_with_restarts 2; then
  pass "scontrol requeue while running"
else exit; fi
start_now

wait_until $((deadline - SECONDS)) "the job to complete" state_is COMPLETED || exit
if [[ $(job_field ExitCode) == 0:0 ]]; then
  pass "job COMPLETED after $(job_field Restarts) restarts"
else
  fail "job COMPLETED with exit code $(job_field ExitCode)"
fi
if log_has "SLURM_RESTART_COUNT=2" && [[ $(grep 'exit status' "$work/job.out" | tail -n 1) == *"exit status 0 "* ]]; then
  pass "log shows the restarts and a final exit status 0"
else fail "log lacks SLURM_RESTART_COUNT=2 or a final exit status 0"; fi

# rigid's start line: "rigid campaign: N tasks, K already done, ..."; each restart must resume
done_counts=$(grep -o '[0-9]* already done' "$work/job.out" | cut -d' ' -f1 | paste -sd' ')
read -ra counts <<<"$done_counts"
if ((${#counts[@]} == 3 && counts[0] == 0 && counts[1] > 0 && counts[2] > counts[1])); then
  pass "each restart resumed (tasks already done at the starts: $done_counts)"
else
  fail "expected 3 starts with 0 < K1 < K2 tasks 'already done', got: ${done_counts:-none}"
fi

if "${compare[@]}" "$work/out.h5" "$work/ref.h5" >"$work/compare.log" 2>&1; then
  pass "resumed output equals the uninterrupted reference"
else
  fail "outputs differ: $(tail -n 5 "$work/compare.log")"
fi
