#!/usr/bin/env bash
# The lab-to-field path on the shared shake-table data, each step timed (wall seconds) and its
# figure printed: calibrate the development rock (SP1) on its 161 tests, carry the calibration to
# the same scan with its heading unknown and with the weakest-direction rule, predict the 161 tests
# from each carried calibration, then a field campaign of the carried rock under the demo's nine
# records (GMRotI50 PGA 0.05-1.2 g, 4 rotations) beside the same scan on default physics, its
# fragility and its hazard. docs/validation-shaketable.md quotes what it prints.
#
#   bash tests/bench/shaketable_path.sh [OUT_DIR]      (from the checkout, after bash setup.sh build)
#
# Needs ../shared (RIGID_SHARED_DIR); 2 MPI ranks (NP). About 10 minutes on an idle 2-core machine.
set -euo pipefail
cd "$(dirname "$0")/../.."
shared=${RIGID_SHARED_DIR:-../shared}
[[ -d $shared/shaketable ]] || { echo "shaketable_path: skipped: no $shared/shaketable"; exit 0; }
rigid=$PWD/build/bin/rigid
out=${1:-/tmp/rigid_shaketable_path}
np=${NP:-2}
[[ $(id -u) -eq 0 ]] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$out"
scan=$(realpath "$shared/scans/sp1_rock.obj")
tests=$(realpath "$shared/shaketable/tests.csv")
log=$out/path.log
: >"$log"

step() {  # step NAME COMMAND...: runs it, its output into the log, prints its wall time
  local name=$1 start=$SECONDS
  shift
  "$@" >>"$log" 2>&1 || { echo "shaketable_path: $name failed (see $log)"; exit 1; }
  printf '%-34s %5d s   (load %s)\n' "$name" $((SECONDS - start)) "$(cut -d' ' -f1 /proc/loadavg)"
}
scores() {  # the scores line predict printed last
  grep -E "^accuracy|balanced" "$log" | tail -2 | tr '\n' ' '
  echo
}

step "calibrate (161 tests)" mpirun -np "$np" "$rigid" shaketable calibrate "$scan" --tests "$tests" \
  --out "$out/calib/sp1" --progress none
grep -E "^(physics|heading|in sample|cross-validated)" "$log" | tail -4 || true

step "transfer, heading unknown" mpirun -np "$np" "$rigid" shaketable transfer "$out/calib/sp1.calibration.json" \
  "$scan" --out "$out/self/sp1"
step "predict 161 tests (unknown)" mpirun -np "$np" "$rigid" shaketable predict "$out/self/sp1.toml" \
  --tests "$tests" --out "$out/self/predictions.csv" --progress none
scores
step "transfer, --heading weakest" mpirun -np "$np" "$rigid" shaketable transfer \
  "$out/calib/sp1.calibration.json" "$scan" --out "$out/weak/sp1" --heading weakest --heading-spread 20 --headings 36
grep "weakest rocking direction" "$log" | tail -1 || true
step "predict 161 tests (weakest)" mpirun -np "$np" "$rigid" shaketable predict "$out/weak/sp1.toml" \
  --tests "$tests" --out "$out/weak/predictions.csv" --progress none
scores

# the field campaign: the carried rock (heading irrelevant: rotations are random) and the scan on
# default physics, imported as the README imports a scan
step "import the scan (default physics)" "$rigid" model import "$scan" --out "$out/default/sp1" --flatten-base 0.005
records=""
for r in s1:2:12 s2:2:12 s4:1:11 s5:1:11 s6:1:11 s7:1:11 s8:1:11 s9:1:11; do
  IFS=: read -r name start end <<<"$r"
  records+=$'[[record]]\nmotion = "'$PWD/waveforms/demo/stochastic_$name-X.AT2$'"\nstart = '$start$'\nend = '$end$'\n'
done
records+=$'[[record]]\nmotion = "'$PWD/waveforms/demo/mp_pulse_1s-X.AT2$'"\n'
for kind in default calibrated; do
  if [[ $kind == default ]]; then object='scene = "default/sp1.toml"'; else object='calibration = "self/sp1.calibration.json"'; fi
  cat >"$out/$kind.toml" <<TOML
[campaign]
seed = 20261121
output = "$out/$kind.h5"
scales = "0.05:1.2:0.05"
rotations = 4
stop_after = 2
[[object]]
name = "sp1"
$object
$records
[run]
free_time_s = 2.0
TOML
  step "campaign ($kind)" mpirun -np "$np" "$rigid" campaign "$out/$kind.toml" --force --progress none
  step "fragility ($kind)" "$rigid" fragility "$out/$kind.h5" --csv "$out/$kind.fragility.csv"
  grep -iE "median|calibrat" "$log" | tail -3 || true
  step "hazard ($kind)" "$rigid" hazard "$out/$kind.h5" --curve models/hazard/synthetic_pga_curve.csv --age 10000
  grep -iE "rate|surviv" "$log" | tail -2 || true
done
echo "shaketable_path: outputs in $out, the commands' own output in $log"
