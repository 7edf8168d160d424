#!/usr/bin/env bash
# Rigid set-up: installs the Debian dependencies (idempotent), builds, then runs what you ask for.
#   bash setup.sh demo    install, build, run the main job (the demo)
#   bash setup.sh test    install, build, run every test (what CI runs)
#   bash setup.sh build   install and build only
# Environment: BUILD_DIR (default build), JOBS (default nproc), RIGID_CMAKE_ARGS (extra cmake args).
set -euo pipefail
cd "$(dirname "$0")"
action=${1:-build}
build_dir=${BUILD_DIR:-build}
jobs=${JOBS:-$(nproc)}

packages=(build-essential cmake git pkg-config
  openmpi-bin libopenmpi-dev libeigen3-dev libhdf5-dev hdf5-tools libcli11-dev
  googletest libgtest-dev libtomlplusplus-dev libbenchmark-dev
  python3 python3-numpy python3-h5py python3-matplotlib
  slurm-wlm munge)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""; [[ $(id -u) -ne 0 ]] && sudo="sudo"
  echo "setup: installing ${missing[*]}"
  # no service may start during the install (munge's postinst would, on machines without systemd);
  # the Slurm test brings up its own daemons (slurm/local-cluster.sh)
  made_policy=0
  if [[ ! -e /usr/sbin/policy-rc.d ]]; then
    printf '#!/bin/sh\nexit 101\n' | $sudo tee /usr/sbin/policy-rc.d >/dev/null
    $sudo chmod 755 /usr/sbin/policy-rc.d
    made_policy=1
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  if ((made_policy)); then $sudo rm -f /usr/sbin/policy-rc.d; fi
fi

# Open MPI refuses root unless told (CI and containers run as root).
if [[ $(id -u) -eq 0 ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi

# shellcheck disable=SC2086
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release ${RIGID_CMAKE_ARGS:-} >/dev/null
cmake --build "$build_dir" -j "$jobs"

case "$action" in
  build) ;;
  test)
    ctest --test-dir "$build_dir" --output-on-failure -j "$jobs"
    ;;
  demo)
    # The main job: a small real campaign on the bundled models and generated waveforms, on two
    # ranks. It resumes if interrupted (run the command again); delete out/ to start over.
    rigid="$build_dir/bin/rigid"
    "$rigid" campaign jobs/demo.toml --dry-run
    mpirun --oversubscribe -np 2 "$rigid" campaign jobs/demo.toml
    ;;
  *) echo "usage: bash setup.sh demo|test|build" >&2; exit 2 ;;
esac
