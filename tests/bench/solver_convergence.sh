#!/usr/bin/env bash
# How often the rigid contact solve stops at its sweep cap, and what it costs, on the scenes where
# it was hard: a slender block (alpha 0.05, 2 m tall) under a recorded pair at 0.05, 0.2 and 1 g, the
# library's three-rock stack, a wide block (alpha 0.4), the scanned rock (../shared/scans, imported
# as the README says) and a reduced demo campaign. Each binary given runs every scene, so an old
# and a new build can be compared in one loaded-machine session (compare ratios, not seconds).
#
# usage: tests/bench/solver_convergence.sh [--reference] [--full-demo] [RIGID ...]
#   RIGID          rigid executables to compare (default: build/bin/rigid)
#   --reference    also run each scene with --accuracy reference (the oracle: expect no capped step)
#   --full-demo    run the whole jobs/demo.toml (300 cells; slow) instead of its reduced copy
# Prints one line per scene and binary: contact solves (steps with a contact; older builds that do
# not report them: contact evaluations), capped steps and their share, mean and most sweeps per
# solve, and the process's CPU time (user + system, s).
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
reference=0
full_demo=0
bins=()
for arg in "$@"; do
  case "$arg" in
    --reference) reference=1 ;;
    --full-demo) full_demo=1 ;;
    *) bins+=("$(realpath "$arg")") ;;
  esac
done
[ ${#bins[@]} -gt 0 ] || bins=("$repo/build/bin/rigid")
shared=$repo/../shared
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# the scenes, built once by the first binary (same files for every binary)
rigid=${bins[0]}
"$rigid" model block --alpha 0.05 --height 2.0 --depth 0.5 --out "$work/slender/slender" >/dev/null
"$rigid" model block --alpha 0.4 --height 1.0 --depth 0.5 --out "$work/wide/wide" >/dev/null
scenes=("slender:$work/slender/slender.toml" "wide:$work/wide/wide.toml"
        "stack3:$repo/models/library/three_stack_wedge/three_stack_wedge.toml")
if [ -f "$shared/scans/sp1_rock.obj" ]; then
  "$rigid" model import "$shared/scans/sp1_rock.obj" --out "$work/scan/sp1_rock" --flatten-base 0.005 >/dev/null
  scenes+=("scan:$work/scan/sp1_rock.toml")
else
  echo "(no ../shared/scans: the scanned rock is left out)"
fi
# a recorded pair (Chi-Chi, CHY028) when ../shared has it, else a bundled synthetic record
pair=$shared/waveforms/peer/CHICHI/RSN1197_CHICHI_CHY028-N.AT2,$shared/waveforms/peer/CHICHI/RSN1197_CHICHI_CHY028-E.AT2
window=(--start 20 --end 40)
if [ ! -f "${pair%%,*}" ]; then
  pair=$repo/waveforms/demo/stochastic_s1-X.AT2
  window=(--start 2 --end 12)
  echo "(no ../shared/waveforms: the synthetic record $pair stands in for the recorded pair)"
fi

# one `rigid run --json`: its figures and the process's CPU time
measure() {  # measure LABEL RIGID SCENE PGA [FLAGS...]
  local label=$1 bin=$2 scene=$3 pga=$4
  shift 4
  local json cpu
  json=$( { /usr/bin/time -f "%U %S" -o "$work/time" "$bin" run "$scene" --motion "$pair" "${window[@]}" \
              --target-pga "$pga" --json "$@"; } 2>/dev/null) || { echo "$label: run failed"; return; }
  cpu=$(awk '{print $1 + $2}' "$work/time")
  /usr/bin/python3 - "$label" "$cpu" "$json" <<'PY'
import json, sys
label, cpu, text = sys.argv[1], float(sys.argv[2]), sys.argv[3]
r = json.loads(text)
solves = r.get("solver_solves", r.get("effects", {}).get("contact_steps", 0))
capped = r.get("unconverged_steps", 0)
share = 100.0 * capped / solves if solves else 0.0
sweeps = r.get("solver_sweeps")
mean = f"{sweeps / solves:8.2f}" if sweeps is not None and solves else "       -"
print(f"{label:<44} {solves:9d} {capped:8d} {share:7.2f} % {mean} {r.get('max_solver_sweeps', 0):8d} {cpu:8.2f}")
PY
}

printf "%-44s %9s %8s %9s %8s %8s %8s\n" "scene / binary" "solves" "capped" "share" "mean sw" "max sw" "CPU s"
for entry in "${scenes[@]}"; do
  name=${entry%%:*}
  scene=${entry#*:}
  pgas=(0.2)
  [ "$name" = slender ] && pgas=(0.05 0.2 1.0)
  for pga in "${pgas[@]}"; do
    for i in "${!bins[@]}"; do
      measure "$name $pga g  [binary $((i + 1))]" "${bins[$i]}" "$scene" "$pga"
      if [ "$reference" = 1 ]; then
        measure "$name $pga g  [binary $((i + 1)), reference]" "${bins[$i]}" "$scene" "$pga" --accuracy reference
      fi
    done
  done
done

# the demo campaign (reduced: its objects under three of its records at two scales, one rotation)
job=$repo/jobs/demo.toml
if [ "$full_demo" = 0 ]; then
  job=$work/demo_reduced.toml
  /usr/bin/python3 - "$repo/jobs/demo.toml" "$job" <<'PY'
import re, sys
text = open(sys.argv[1]).read().replace('"../', '"' + sys.argv[1].rsplit("/jobs/", 1)[0] + "/")
text = re.sub(r'scales = "[^"]*"', 'scales = [0.3, 0.6]', text)
text = re.sub(r"rotations = \d+", "rotations = 1", text)
head, _, records = text.partition("[[record]]")
kept = "[[record]]".join(records.split("[[record]]")[:3])
open(sys.argv[2], "w").write(head + "[[record]]" + kept)
PY
fi
if [ ! -f "$repo/models/scans/sp1_rock/sp1_rock.toml" ] && [ -f "$shared/scans/sp1_rock.obj" ]; then
  echo "(the demo's scanned rock is imported by bash setup.sh demo; without it the campaign leaves it out)"
fi
for i in "${!bins[@]}"; do
  out=$work/demo_$i.h5
  /usr/bin/time -f "%U %S" -o "$work/time" "${bins[$i]}" campaign "$job" --out "$out" --progress none \
    >"$work/demo_$i.log" 2>&1 || { echo "demo [binary $((i + 1))]: campaign failed"; tail -3 "$work/demo_$i.log"; continue; }
  cpu=$(awk '{print $1 + $2}' "$work/time")
  line=$(grep -o "contact solver: [0-9]* steps in [0-9]* of [0-9]* cells" "$work/demo_$i.log" || true)
  printf "%-44s %s (CPU %.2f s)\n" "demo $(basename "$job") [binary $((i + 1))]" "${line:-contact solver: no capped step}" "$cpu"
done
