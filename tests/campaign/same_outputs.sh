#!/usr/bin/env bash
# Runs the jobs whose outputs a behaviour-neutral change must leave as they are, so that two
# builds can be compared:
#
#   bash tests/campaign/same_outputs.sh RIGID OUTDIR            # run everything into OUTDIR
#   SAME_OUTPUTS_ONLY=shaketable bash tests/campaign/same_outputs.sh RIGID OUTDIR   # only the shake-table part
#   bash tests/campaign/same_outputs.sh --compare DIR_A DIR_B   # compare two such folders
#
# Runs jobs/demo.toml, jobs/validation_ci.toml (3D, and 2D with --model rocking2d) and
# jobs/uncertainty_demo.toml on 1 and on 2 MPI ranks, then `rigid fragility --json/--csv` and
# `rigid hazard --json` on the demo cube; then the shake-table commands on a small test list of
# ../shared/shaketable (18 tests of 3 motions): `shaketable calibrate` (a 2 x 4-heading design,
# --flatten-mm, the old spelling), `predict` and `fragility` on 2 ranks, in one fixed folder
# (/tmp/rigid_same_outputs_shaketable, moved to OUTDIR/shaketable after), so that the paths their
# designed jobs state, and so the jobs' hashes, are the same for both builds. --compare checks every
# cube dataset bit for bit (tests/python/compare_cubes.py: wall times excepted), the
# fragility/hazard text outputs, the shake-table jobs, scenes, predictions and fragility table byte
# for byte, and the calibration JSON but for its wall time. About 12 minutes on 2 cores. Exit
# status: 0 same, 1 different, 2 bad usage.
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
      [[ -f $2/$f || -f $3/$f ]] || continue  # a shake-table-only run
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
    [[ -f $a/$t || -f $b/$t ]] || continue
    if diff <(sed "s|$a/|OUT/|g" "$a/$t") <(sed "s|$b/|OUT/|g" "$b/$t") >/tmp/same_outputs.diff.$$; then
      echo "same: $t"
    else
      echo "DIFFERENT: $t"; head -n 12 /tmp/same_outputs.diff.$$; status=1
    fi
    rm -f /tmp/same_outputs.diff.$$
  done
  # the shake-table commands: every file of the fixed folder
  if [[ -d $2/shaketable || -d $3/shaketable ]]; then
    while IFS= read -r rel; do
      fa=$2/shaketable/$rel fb=$3/shaketable/$rel
      # the fit's input of the model's probabilities (model.csv; members.json before the ensemble
      # rule moved to C++): its results are the fragility table, compared below
      [[ $rel == */model.csv || $rel == */members.json ]] && continue
      if [[ ! -f $fb ]]; then echo "DIFFERENT: shaketable/$rel missing in $3"; status=1; continue; fi
      case $rel in
        *.h5) /usr/bin/python3 "$repo/tests/python/compare_cubes.py" --other-build "$fa" "$fb" >/dev/null 2>&1 ;;
        *.calibration.json) diff <(grep -v '"wall_s"' "$fa") <(grep -v '"wall_s"' "$fb") >/dev/null ;;
        *.toml | *.csv | *.json) cmp -s "$fa" "$fb" ;;
        *) true ;;  # figures, logs and journals: not results
      esac && echo "same: shaketable/$rel" || { echo "DIFFERENT: shaketable/$rel"; status=1; }
    done < <(cd "$2/shaketable" && find . -type f | sed 's|^\./||' | sort)
  fi
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
only=${SAME_OUTPUTS_ONLY:-all}
for ranks in 1 2; do
  [[ $only == shaketable ]] && break
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
[[ $only == shaketable ]] || {
"$rigid" fragility "$demo" --json >"$out/fragility.json" 2>/dev/null || { echo "FAILED: fragility --json"; exit 1; }
"$rigid" fragility "$demo" --csv "$out/fragility.csv" >/dev/null 2>&1 || { echo "FAILED: fragility --csv"; exit 1; }
"$rigid" hazard "$demo" --object block_a03 --curve models/hazard/synthetic_pga_curve.csv --age 10000 --json \
  >"$out/hazard.json" 2>/dev/null || { echo "FAILED: hazard --json"; exit 1; }
}

# the shake-table commands, in a folder whose path both builds share
st=/tmp/rigid_same_outputs_shaketable shared=$(realpath ../shared)
rm -rf "$st" "$out/shaketable" && mkdir -p "$st"
/usr/bin/python3 - "$shared/shaketable/tests.csv" "$st" <<'PY'
import csv, os, sys
src, st = sys.argv[1], sys.argv[2]
rows = [r for r in csv.DictReader(open(src)) if r["record"] in ("RSN147_COYOTELK", "RSN722_SUPER", "RSN1840_HECTOR_WHD090.AT2")]
for r in rows:
    r["file"] = os.path.join(os.path.dirname(src), r["file"])
for name, keep in (("tests.csv", rows), ("holdout.csv", rows[::3])):
    with open(os.path.join(st, name), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(keep)
PY
for spec in "calibrate $shared/scans/sp1_rock.obj --tests $st/tests.csv --out $st/cal/sp1 --flatten-mm 5 --contact-models rigid,5e5 --damping 4,2 --friction 0.6 --restitution 0 --headings 4" \
    "predict $st/cal/sp1.toml --tests $st/holdout.csv --out $st/predictions.csv" \
    "fragility $st/cal/sp1.toml --tests $st/tests.csv --out $st/frag/sp1 --bootstrap 50 --per-decade 6"; do
  read -ra a <<<"$spec"
  echo "$(date +%T) shaketable ${a[0]}"
  launch 2 shaketable "${a[@]}" --progress none >"$out/shaketable_${a[0]}.log" 2>&1 ||
    { echo "FAILED: shaketable ${a[0]}: $(tail -n 3 "$out/shaketable_${a[0]}.log")"; exit 1; }
done
mv "$st" "$out/shaketable"
echo "outputs in $out"
