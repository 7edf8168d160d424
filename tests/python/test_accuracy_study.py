"""`rigid study accuracy --quick` end to end (CTest `study_accuracy_quick`): the CSV has the
expected columns and one row per (case, setting); every case's converged reference row has error
zero; for at least one case the error against the converged reference falls as the time-step
safety factor falls (a property of the integrator, not a stored number); the Pareto PNG and the
markdown table are written. Also: an unknown --accuracy is refused by `run` and `campaign` with
exit status 2 and one error line, and a campaign cube is resumed with its own preset only.

    /usr/bin/python3 -m pytest tests/python/test_accuracy_study.py --rigid RIGID
"""
import csv
import os
import subprocess
import tempfile

import pytest

EXPECTED_COLUMNS = [
    "scene", "motion", "axis", "setting", "contact", "preset", "safety", "integrator", "stiffness_n_m", "rest_speed",
    "rest_time_s", "effects", "dt_s", "steps", "simulated_s", "overturned", "failure_time_s", "max_tilt_deg", "outcome_match",
    "failure_time_err_s", "max_tilt_err_deg", "traj_tilt_rms_deg", "traj_pos_rms_mm", "traj_rel_err", "error",
    "energy_err", "model_quantity", "model_value", "model_ref_err", "oracle", "oracle_value", "oracle_err", "wall_s",
    "search_wall_s", "repeats"]
QUICK_CASES = {("slender", "pulse"), ("stocky", "pulse"), ("sliding", "pulse"), ("geode", "drop")}


def fail(msg):
    pytest.fail(msg, pytrace=False)


def check_refused(exe, args, fragment):
    p = subprocess.run([exe] + args, capture_output=True, text=True, timeout=120)
    if p.returncode != 2:
        fail(f"{' '.join(args)}: exit {p.returncode}, expected 2\n{p.stderr}")
    lines = p.stderr.strip().splitlines()
    if len(lines) != 1 or not lines[0].startswith("rigid: error: ") or fragment not in lines[0]:
        fail(f"{' '.join(args)}: expected one error line with '{fragment}', got:\n{p.stderr}")


def test_accuracy_study_quick(rigid, source_dir):
    exe, source = rigid, source_dir
    with tempfile.TemporaryDirectory() as out:
        p = subprocess.run([exe, "study", "accuracy", "--quick", "--out", out], capture_output=True, text=True,
                           timeout=600)
        print(p.stdout)
        if p.returncode != 0:
            fail(f"exit {p.returncode}\n{p.stderr}")
        with open(os.path.join(out, "accuracy.csv"), newline="") as f:
            reader = csv.DictReader(f)
            if reader.fieldnames != EXPECTED_COLUMNS:
                fail(f"columns {reader.fieldnames}")
            rows = list(reader)
        cases = {(r["scene"], r["motion"]) for r in rows}
        if cases != QUICK_CASES:
            fail(f"cases {sorted(cases)}")
        settings = sorted({r["setting"] for r in rows})
        for c in cases:
            got = sorted(r["setting"] for r in rows if (r["scene"], r["motion"]) == c)
            if len(got) != len(set(got)):
                fail(f"{c}: duplicate settings {got}")
        for name in ("converged reference", "preset fast", "preset balanced", "preset reference"):
            if name not in settings:
                fail(f"no '{name}' rows")
        # the converged reference is the reference: error 0, same outcome
        for r in rows:
            if r["axis"] == "converged":
                if float(r["error"]) != 0.0 or float(r["traj_rel_err"]) != 0.0 or r["outcome_match"] != "1":
                    fail(f"converged reference row of {r['scene']}/{r['motion']} has error {r['error']}")
            if r["wall_s"] == "" or not float(r["wall_s"]) > 0:
                fail(f"row without wall time: {r}")
        # errors fall as the safety factor falls (splitting): strictly, for at least one case
        falling = []
        for c in sorted(cases):
            sweep = sorted((float(r["safety"]), float(r["error"])) for r in rows
                           if (r["scene"], r["motion"]) == c and r["axis"] == "safety" and r["integrator"] == "splitting")
            if len(sweep) < 3:
                fail(f"{c}: safety sweep has {len(sweep)} rows")
            errors = [e for _, e in sweep]
            print(f"{c[0]}/{c[1]}: error by safety {sweep}")
            if all(a < b for a, b in zip(errors, errors[1:])) and errors[0] > 0:
                falling.append(c)
        if not falling:
            fail("no case whose error falls with the safety factor")
        print(f"errors fall with the safety factor for {falling}")
        # oracles where they exist
        for r in rows:
            if r["oracle"] and r["oracle_value"] == "":
                fail(f"{r['scene']}/{r['motion']}: oracle {r['oracle']} without a value")
        png = os.path.join(out, "accuracy_pareto.png")
        with open(png, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                fail("accuracy_pareto.png is not a PNG")
        with open(os.path.join(out, "accuracy_table.md")) as f:
            table = f.read()
        for p in ("fast", "balanced", "reference"):
            if p not in table.splitlines()[0]:
                fail(f"table header lacks {p}")
    # the preset names are checked on the command line
    scene = os.path.join(source, "models", "demo", "block_a02.toml")
    check_refused(exe, ["run", scene, "--accuracy", "precise"], "--accuracy must be fast, balanced or reference")
    check_refused(exe, ["campaign", os.path.join(source, "jobs", "ci_small.toml"), "--dry-run", "--accuracy", "precise"],
                  "--accuracy must be fast, balanced or reference")
    # the preset is part of the cube's identity: a resume with another preset is refused
    job = os.path.join(source, "jobs", "ci_small.toml")
    with tempfile.TemporaryDirectory() as tmp:
        cube = os.path.join(tmp, "ci_small.h5")
        p = subprocess.run([exe, "campaign", job, "--out", cube, "--accuracy", "fast", "--progress", "none"],
                           capture_output=True, text=True, timeout=600)
        if p.returncode != 0:
            fail(f"campaign --accuracy fast: exit {p.returncode}\n{p.stderr}")
        check_refused(exe, ["campaign", job, "--out", cube, "--accuracy", "reference", "--progress", "none"],
                      "accuracy preset")
        p = subprocess.run([exe, "campaign", job, "--out", cube, "--accuracy", "fast", "--progress", "none"],
                           capture_output=True, text=True, timeout=600)
        if p.returncode != 0:
            fail(f"resume with the same preset: exit {p.returncode}\n{p.stderr}")
