#!/usr/bin/env bash
# A real single-node Slurm on localhost (munged + slurmctld + slurmd), without systemd, for tests
# and trying the batch scripts. Needs root. Everything lives in one directory; nothing in /etc.
#
#   bash slurm/local-cluster.sh up [--install]   start (idempotent); prints the path of env.sh
#   source "$(bash slurm/local-cluster.sh up)"   ... then sbatch, squeue, scontrol as usual
#   bash slurm/local-cluster.sh status           exit 0 when up and the node answers
#   bash slurm/local-cluster.sh down [--keep]    cancel jobs, stop the daemons, remove the directory
#
# Environment:
#   RIGID_SLURM_DIR       directory (default /tmp/rigid-slurm); its parents must not be
#                         group/world-writable unless sticky (munged checks)
#   RIGID_SLURM_PORT      slurmctld port, slurmd uses the next one; default: the first free pair
#                         of 6817/6818, 6827/6828, ... 6907/6908
#   RIGID_SLURM_CPUS      CPUs the node advertises (default: nproc, at least 2)
#   RIGID_SLURM_KILLWAIT  seconds from SIGTERM to SIGKILL on cancel, requeue, time limit (default 30)
#   RIGID_SLURM_INSTALL=1 same as --install: apt-get install slurm-wlm munge when missing
# env.sh exports SLURM_CONF and, as root, Open MPI's root flags (sbatch passes them to jobs).
set -euo pipefail

dir=${RIGID_SLURM_DIR:-/tmp/rigid-slurm}
conf=$dir/etc/slurm.conf
run=$dir/run
log() { echo "local-cluster: $*" >&2; }
die() { log "$*"; exit 1; }

# pid_of NAME: the pid in $run/NAME.pid if that process is alive (not a zombie) and is NAME,
# so a stale pid file never makes us signal an unrelated process.
pid_of() {
  local p
  p=$(cat "$run/$1.pid" 2>/dev/null) || return 1
  [[ $p =~ ^[0-9]+$ && $(cat "/proc/$p/comm" 2>/dev/null) == "$1" ]] || return 1
  [[ $(awk '{print $3}' "/proc/$p/stat" 2>/dev/null) != Z ]] && echo "$p"
}

node_state() { SLURM_CONF=$conf timeout 10 sinfo -h -n localhost -o %T 2>/dev/null | head -n1; }

healthy() {
  pid_of munged >/dev/null && pid_of slurmctld >/dev/null && pid_of slurmd >/dev/null || return 1
  case $(node_state) in idle | mixed | allocated | completing) return 0 ;; esac
  return 1
}

stop_daemon() {
  local p
  p=$(pid_of "$1") || return 0
  kill -TERM "$p" 2>/dev/null || return 0
  for _ in $(seq 100); do pid_of "$1" >/dev/null || { log "$1 ($p) stopped"; return 0; }; sleep 0.1; done
  log "$1 ($p) still alive after 10 s, SIGKILL"
  kill -KILL "$p" 2>/dev/null || true
}

down() {
  if pid_of slurmctld >/dev/null; then
    local jobs
    jobs=$(SLURM_CONF=$conf squeue -h -o %i 2>/dev/null | tr '\n' ' ')
    if [[ -n ${jobs// /} ]]; then
      log "cancelling jobs $jobs"
      # shellcheck disable=SC2086
      SLURM_CONF=$conf scancel $jobs 2>/dev/null || true
      for _ in $(seq 300); do   # up to 60 s: KillWait plus slack
        [[ -z $(SLURM_CONF=$conf squeue -h -t R,CG,S -o %i 2>/dev/null) ]] && break
        sleep 0.2
      done
    fi
  fi
  stop_daemon slurmd
  stop_daemon slurmctld   # SIGTERM: it saves its state (SIGKILL can leave a drained node)
  stop_daemon munged
}

port_busy() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }

install_packages() {
  local made_policy=0
  # no service may start during the install (no systemd: invoke-rc.d would run /etc/init.d/munge)
  if [[ ! -e /usr/sbin/policy-rc.d ]]; then
    printf '#!/bin/sh\nexit 101\n' >/usr/sbin/policy-rc.d
    chmod 755 /usr/sbin/policy-rc.d
    made_policy=1
  fi
  local rc=0
  { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
      --no-install-recommends slurm-wlm munge >/dev/null; } || rc=$?
  ((made_policy)) && rm -f /usr/sbin/policy-rc.d
  return "$rc"
}

up() {
  [[ $(id -u) == 0 ]] || die "needs root (SlurmUser=root)"
  local b missing=0
  for b in munged mungekey slurmctld slurmd sbatch; do command -v "$b" >/dev/null || missing=1; done
  if ((missing)); then
    [[ ${install:-0} == 1 ]] || die "slurm-wlm/munge not installed; use 'up --install' or: apt-get install slurm-wlm munge"
    log "installing slurm-wlm munge"
    install_packages || die "apt-get install slurm-wlm munge failed"
  fi

  if [[ -f $conf ]] && healthy; then
    log "already up ($conf)"
    echo "$dir/env.sh"
    return 0
  fi
  down   # whatever is left of an earlier start, by pid file

  local port
  if [[ -n ${RIGID_SLURM_PORT:-} ]]; then
    port=$RIGID_SLURM_PORT
    if port_busy "$port" || port_busy $((port + 1)); then die "port $port or $((port + 1)) is in use"; fi
  else
    for port in $(seq 6817 10 6907) none; do
      [[ $port == none ]] && die "no free port pair in 6817..6908; set RIGID_SLURM_PORT"
      ! port_busy "$port" && ! port_busy $((port + 1)) && break
    done
  fi

  local cpus=${RIGID_SLURM_CPUS:-$(nproc)}
  ((cpus >= 2)) || cpus=2   # the tests run 2 ranks; config_overrides allows more than the hardware
  rm -rf "$dir/state" "$dir/spool" "$run"
  mkdir -p "$dir"/{etc,state,spool,log,munge} "$run"
  chmod 755 "$dir" "$run"   # clients must reach the munge socket
  chmod 700 "$dir/munge"

  [[ -s $dir/munge/munge.key ]] || mungekey -c -k "$dir/munge/munge.key"
  chmod 600 "$dir/munge/munge.key"
  munged -S "$run/munge.sock" --key-file="$dir/munge/munge.key" --pid-file="$run/munged.pid" \
    --log-file="$dir/log/munged.log" --seed-file="$dir/munge/seed" </dev/null >>"$dir/log/munged.out" 2>&1
  munge -S "$run/munge.sock" -n | unmunge -S "$run/munge.sock" >/dev/null || die "munge does not work: $dir/log/munged.log"

  cat >"$conf" <<EOF
# written by rigid slurm/local-cluster.sh
ClusterName=rigidci
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$run/munge.sock
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$run/slurmctld.pid
SlurmdPidFile=$run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SlurmdParameters=config_overrides
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MailProg=/bin/true
MpiDefault=pmix
ReturnToService=2
KillWait=${RIGID_SLURM_KILLWAIT:-30}
MinJobAge=600
NodeName=localhost NodeAddr=127.0.0.1 NodeHostname=localhost CPUs=$cpus State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
  # both daemonize and write their pid files; no stdio is left attached to the caller
  slurmctld -c -f "$conf" </dev/null >>"$dir/log/slurmctld.out" 2>&1
  slurmd -N localhost -f "$conf" </dev/null >>"$dir/log/slurmd.out" 2>&1

  local st=""
  for _ in $(seq 150); do   # 30 s
    st=$(node_state)
    [[ $st == idle ]] && break
    sleep 0.2
  done
  if [[ $st != idle ]]; then
    tail -n 5 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" >&2 || true
    down
    die "node not idle after 30 s (state '$st')"
  fi

  {
    echo "export SLURM_CONF=$conf RIGID_SLURM_DIR=$dir"
    echo "export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1   # mpirun refuses root without them"
  } >"$dir/env.sh"
  log "up: node localhost, $cpus CPUs, ports $port/$((port + 1)), source $dir/env.sh"
  echo "$dir/env.sh"
}

cmd=${1:-}
shift || true
install=${RIGID_SLURM_INSTALL:-0}
keep=0
for a in "$@"; do
  case $a in
    --install) install=1 ;;
    --keep) keep=1 ;;
    *) die "unknown option $a" ;;
  esac
done
case $cmd in
  up) up ;;
  status) healthy ;;
  down)
    down
    # remove only a directory this script made
    if ((!keep)) && [[ -d $dir ]]; then
      if grep -qs 'written by rigid slurm/local-cluster.sh' "$conf" || [[ -z $(ls -A "$dir") ]]; then
        rm -rf "$dir"
      else
        log "not removing $dir: no slurm.conf of ours in it"
      fi
    fi
    ;;
  *) die "usage: local-cluster.sh up [--install] | status | down [--keep]" ;;
esac
