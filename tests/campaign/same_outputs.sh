#!/usr/bin/env bash
# Runs the jobs whose outputs a behaviour-neutral change must leave as they are, so that two
# builds can be compared:
#
#   bash tests/campaign/same_outputs.sh RIGID OUTDIR            # run everything into OUTDIR
#   bash tests/campaign/same_outputs.sh --compare DIR_A DIR_B   # compare two such folders
#
# Runs jobs/demo.toml, jobs/validation_ci.toml (3D, and 2D with --model rocking2d) and
# jobs/uncertainty_demo.toml on 1 and on 2 MPI ranks, then `rigid fragility --json/--csv` and
# `rigid hazard --json` on the demo cube. --compare checks every cube dataset bit for bit
# (tests/python/compare_cubes.py: wall times excepted) and the fragility/hazard text outputs
# byte for byte. About 10 minutes on 2 cores. Exit status: 0 same, 1 different, 2 bad usage.
set -uo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
cubes=(demo validation_ci_3d validation_ci_2d uncertainty_demo)
texts=(fragility.json fragility.csv hazard.json)

if [[ ${1:-} == --compare ]]; then
  [[ $# == 3 ]] || { echo "usage: $0 --compare DIR_A DIR_B" >&2; exit 2; }
  status=0
  for ranks in 1 2; do
    for c in "${cubes[@]}"; do
      f=$c.np$ranks.h5
      if /usr/bin/python3 "$repo/tests/python/compare_cubes.py" --other-build "$2/$f" "$3/$f" >/dev/null 2>&1; then
        echo "same: $f"
      else
        echo "DIFFERENT: $f"; /usr/bin/python3 "$repo/tests/python/compare_cubes.py" --other-build "$2/$f" "$3/$f" | head -n 12
        status=1
      fi
    done
  done
  # the JSON outputs name their cube: compared with each folder's path replaced by OUT
  a=$(realpath "$2") b=$(realpath "$3")
  for t in "${texts[@]}"; do
    if diff <(sed "s|$a/|OUT/|g" "$a/$t") <(sed "s|$b/|OUT/|g" "$b/$t") >/tmp/same_outputs.diff.$$; then
      echo "same: $t"
    else
      echo "DIFFERENT: $t"; head -n 12 /tmp/same_outputs.diff.$$; status=1
    fi
    rm -f /tmp/same_outputs.diff.$$
  done
  exit $status
fi

[[ $# == 2 ]] || { echo "usage: $0 RIGID OUTDIR | --compare DIR_A DIR_B" >&2; exit 2; }
rigid=$(realpath "$1")
mkdir -p "$2" && out=$(realpath "$2")
[[ $(id -u) == 0 ]] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$repo"
[[ -d ../shared/waveforms/peer ]] || { echo "needs ../shared beside the checkout (jobs/validation_ci.toml reads its PEER records)" >&2; exit 2; }
launch() {  # launch RANKS ARGS...: rigid on RANKS MPI ranks (1: no launcher)
  local n=$1; shift
  if ((n == 1)); then "$rigid" "$@"; else mpirun --oversubscribe -np "$n" "$rigid" "$@"; fi
}
for ranks in 1 2; do
  for spec in "demo jobs/demo.toml" "validation_ci_3d jobs/validation_ci.toml" \
      "validation_ci_2d jobs/validation_ci.toml --model rocking2d" "uncertainty_demo jobs/uncertainty_demo.toml"; do
    read -ra a <<<"$spec"
    f=$out/${a[0]}.np$ranks.h5
    rm -f "$f"
    echo "$(date +%T) ${a[0]} on $ranks rank(s)"
    launch "$ranks" campaign "${a[@]:1}" --out "$f" --progress none >"$out/${a[0]}.np$ranks.log" 2>&1 ||
      { echo "FAILED: ${a[0]} on $ranks rank(s): $(tail -n 3 "$out/${a[0]}.np$ranks.log")"; exit 1; }
  done
done
demo=$out/demo.np2.h5
"$rigid" fragility "$demo" --json >"$out/fragility.json" 2>/dev/null || { echo "FAILED: fragility --json"; exit 1; }
"$rigid" fragility "$demo" --csv "$out/fragility.csv" >/dev/null 2>&1 || { echo "FAILED: fragility --csv"; exit 1; }
"$rigid" hazard "$demo" --object block_a03 --curve models/hazard/synthetic_pga_curve.csv --age 10000 --json \
  >"$out/hazard.json" 2>/dev/null || { echo "FAILED: hazard --json"; exit 1; }
echo "outputs in $out"
