"""The convergence study's comparer (`python3 -m rigidpy.outcome_agreement --pair ...`,
docs/accuracy.md "Convergence of the contact solve") on hand-made cubes whose flips, distances
from the failure rule and capped contact solves are planted here, so every count is known by
construction, independently of the engine and of the comparer:

- a reference cube of three objects drawn from a planted probit (a block with its rocking angle
  alpha, a leaning block with a tilt rule and no alpha, a stack with neither), and a default cube
  equal to it but for planted flips (survived -> overturned with a survivor's peak tilt at 0.95
  alpha, overturned -> survived at 0.6 alpha; one flip on the tilt-rule object at 0.3 of its rule;
  one on the stack), not-run, inferred and failed cells that must not count, and planted capped
  solves (unconverged_steps) at the default;
- the fitted median and dispersion against a second method: the scalar probit's likelihood
  maximised here with scipy's Nelder-Mead;
- --check against the issue's targets, and bad input (a missing cube) exits 2.

    /usr/bin/python3 -m pytest tests/python/test_convergence_study.py
"""
import csv
import json
import math
import os
import subprocess
import sys

import pytest

np = pytest.importorskip("numpy")
pytest.importorskip("h5py")
optimize = pytest.importorskip("scipy.optimize")
special = pytest.importorskip("scipy.special")

import synthetic_cube as sc  # noqa: E402

PYTHON_DIR = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src", "python"))
ALPHA = 0.2                  # rad, the block's rocking angle
TILT_RULE = 30.0             # degrees, the leaning block's failure rule
NOT_RUN, SURVIVED, OVERTURNED, INFERRED, FAILED = 0, 1, 2, 3, 4


def compare(*args):
    p = subprocess.run([sys.executable, "-m", "rigidpy.outcome_agreement", *args], capture_output=True, text=True,
                       cwd=PYTHON_DIR)
    return p


def cells_of(outcome, critical_deg, rng):
    """Peak tilts that put every survivor at a margin below 0.9 of the critical tilt (so the planted
    flips alone fill the upper bins), overturned runs past it; no capped solve."""
    tilt = np.where(outcome == OVERTURNED, 95.0, rng.uniform(0.05, 0.85, outcome.shape) * critical_deg)
    tilt[np.isin(outcome, (NOT_RUN, INFERRED))] = np.nan
    steps = np.where(np.isin(outcome, (SURVIVED, OVERTURNED, FAILED)), 0, -1).astype(np.int32)
    return dict(max_tilt_deg=tilt, max_slip_m=np.where(np.isnan(tilt), np.nan, 0.001), unconverged_steps=steps)


@pytest.fixture(scope="module")
def planted(tmp_path_factory):
    tmp = str(tmp_path_factory.mktemp("convergence"))
    rng = np.random.default_rng(33)
    pgv = np.exp(rng.uniform(math.log(0.05), math.log(0.3), 6))
    alpha_deg = math.degrees(ALPHA)
    objects = {"block": alpha_deg, "leaning": TILT_RULE, "stack": math.nan}
    attrs = {"block": {"alpha_rad": ALPHA, "physics_json": json.dumps({"failure_rule": "below"})},
             "leaning": {"physics_json": json.dumps({"failure_rule": "tilt", "failure_tilt_deg": TILT_RULE})},
             "stack": {"physics_json": json.dumps({"failure_rule": "below"})}}
    ref, cand = {}, {}
    for name, critical in objects.items():
        outcome = sc.planted_outcomes(rng, pgv, sc.MU0, sc.MU1, sc.SIGMA, extras=False)
        outcome[0, 0, 0], outcome[0, 1, 0], outcome[1, 19, 3] = NOT_RUN, FAILED, INFERRED
        ref[name] = (outcome, cells_of(outcome, 1.0 if math.isnan(critical) else critical, rng))
        cand[name] = (outcome.copy(), {k: v.copy() for k, v in ref[name][1].items()})
    flips = []   # (object, index, reference outcome, default outcome, margin)
    block_o, block_c = cand["block"]
    survived = [tuple(i) for i in np.argwhere(ref["block"][0] == SURVIVED)]
    overturned = [tuple(i) for i in np.argwhere(ref["block"][0] == OVERTURNED)]
    for i in survived[:4]:         # up: the default overturned, the reference survived at 0.95 alpha
        block_o[i] = OVERTURNED
        block_c["max_tilt_deg"][i] = 95.0
        ref["block"][1]["max_tilt_deg"][i] = 0.95 * alpha_deg
        flips.append(("block", i, "survived", "overturned", 0.95))
    for i in overturned[:3]:       # down: the default survived at 0.6 alpha
        block_o[i] = SURVIVED
        block_c["max_tilt_deg"][i] = 0.6 * alpha_deg
        flips.append(("block", i, "overturned", "survived", 0.6))
    i = tuple(np.argwhere(ref["leaning"][0] == OVERTURNED)[0])
    cand["leaning"][0][i] = SURVIVED
    cand["leaning"][1]["max_tilt_deg"][i] = 0.3 * TILT_RULE
    flips.append(("leaning", i, "overturned", "survived", 0.3))
    i = tuple(np.argwhere(ref["stack"][0] == SURVIVED)[-1])
    cand["stack"][0][i] = OVERTURNED
    flips.append(("stack", i, "survived", "overturned", math.nan))
    # not flips: an inferred cell against an overturned one, a failed one against a survivor
    cand["block"][0][1, 19, 3] = OVERTURNED if ref["block"][0][1, 19, 3] == INFERRED else cand["block"][0][1, 19, 3]
    # capped solves at the default: 5 cells of the block, one of them flipped
    capped = survived[10:14] + [survived[0]]
    for k, i in enumerate(capped):
        block_c["unconverged_steps"][i] = 10 * (k + 1)
    paths = {}
    for label, cubes in (("ref", ref), ("default", cand)):
        paths[label] = os.path.join(tmp, f"job.{label}.h5")
        sc.write_cube(paths[label], pgv, [(n, o, attrs[n], d) for n, (o, d) in cubes.items()])
    return dict(paths=paths, ref=ref, cand=cand, flips=flips, capped=capped, pgv=pgv, tmp=tmp)


def study(planted, *extra):
    p = compare("--pair", planted["paths"]["ref"], planted["paths"]["default"], "--json", *extra)
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout), p


def test_flips_and_their_distances_are_the_planted_ones(planted):
    out, _ = study(planted)
    scale_index = {round(g, 9): s for s, g in enumerate(sc.SCALES)}
    found = {(f["object"], (f["variant"], f["record"], scale_index[round(f["scale_g"], 9)], f["rotation"]),
              f["reference"], f["default"]): f for f in out["flips"]}
    assert len(out["flips"]) == len(found) == len(planted["flips"])
    for name, (r, s, a), ref_outcome, default_outcome, margin in planted["flips"]:
        f = found[(name, (0, r, s, a), ref_outcome, default_outcome)]
        if math.isnan(margin):
            assert f["margin"] is None or math.isnan(f["margin"])
        else:
            assert f["margin"] == pytest.approx(margin, rel=1e-12)
    rows = {r["object"]: r for r in out["rows"]}
    assert (rows["block"]["up"], rows["block"]["down"]) == (4, 3)
    assert (rows["leaning"]["up"], rows["leaning"]["down"]) == (0, 1)
    assert (rows["stack"]["up"], rows["stack"]["down"]) == (1, 0)
    assert out["total"]["flipped"] == 9 and out["total"]["flipped_no_margin"] == 1
    # the margins' bins: 0.95 -> [0.9, 1), 0.6 -> [0.5, 0.75), 0.3 -> [0.25, 0.5)
    assert out["total"]["flipped_by_margin"] == [0, 1, 3, 0, 4, 0]


def test_counts_of_cells_and_capped_solves(planted):
    out, _ = study(planted)
    rows = {r["object"]: r for r in out["rows"]}
    for name, (outcome, _) in planted["ref"].items():
        default = planted["cand"][name][0]
        both = np.isin(outcome, (SURVIVED, OVERTURNED)) & np.isin(default, (SURVIVED, OVERTURNED))
        assert rows[name]["simulated"] == int(both.sum())
        assert rows[name]["ran_default"] == int(np.isin(default, (SURVIVED, OVERTURNED, FAILED)).sum())
    assert rows["block"]["capped_default"] == len(planted["capped"])
    assert rows["block"]["capped_steps_default"] == sum(10 * (k + 1) for k in range(len(planted["capped"])))
    assert out["total"]["capped_reference"] == 0 and out["total"]["capped_steps_reference"] == 0
    # survivors below 0.9 of the critical tilt: every cell with a survivor is binned, none past 1
    assert out["total"]["survived_by_margin"][-1] == 0
    assert sum(out["total"]["survived_by_margin"]) == sum(
        int((np.isin(planted["ref"][n][0], (SURVIVED, OVERTURNED)) & np.isin(planted["cand"][n][0], (SURVIVED, OVERTURNED))
             & ~((planted["ref"][n][0] == OVERTURNED) & (planted["cand"][n][0] == OVERTURNED))).sum())
        for n in ("block", "leaning"))


def mle(outcome):
    """The scalar lognormal fit by a second method: the probit likelihood of the simulated cells
    maximised with Nelder-Mead (the comparer uses rigidpy.fit's Newton method)."""
    u = np.log(sc.SCALES)
    k = (outcome == OVERTURNED).sum(axis=(0, 2)).astype(float)
    n = k + (outcome == SURVIVED).sum(axis=(0, 2))

    def nll(x):
        z = (u - x[0]) / math.exp(x[1])
        return -np.sum(k * special.log_ndtr(z) + (n - k) * special.log_ndtr(-z))

    res = optimize.minimize(nll, [math.log(0.5), math.log(0.4)], method="Nelder-Mead",
                            options=dict(xatol=1e-10, fatol=1e-12, maxiter=20000))
    return math.exp(res.x[0]), math.exp(res.x[1])


def test_fitted_median_and_dispersion_against_a_second_method(planted):
    out, _ = study(planted)
    rows = {r["object"]: r for r in out["rows"]}
    for name in ("block", "stack"):
        theta_r, beta_r = mle(planted["ref"][name][0])
        theta_c, beta_c = mle(planted["cand"][name][0])
        assert rows[name]["theta_reference"] == pytest.approx(theta_r, rel=1e-5)
        assert rows[name]["beta_reference"] == pytest.approx(beta_r, rel=1e-5)
        assert rows[name]["theta_change"] == pytest.approx(theta_c / theta_r - 1, abs=1e-5)
        assert rows[name]["beta_change"] == pytest.approx(beta_c / beta_r - 1, abs=1e-5)
        low, high = rows[name]["theta_change_interval"]
        assert low <= rows[name]["theta_change"] <= high


def test_targets_and_outputs(planted, tmp_path):
    md, table, flips = (str(tmp_path / n) for n in ("study.md", "study.csv", "flips.csv"))
    p = compare("--pair", planted["paths"]["ref"], planted["paths"]["default"], "--markdown", md, "--csv", table,
                "--flips-csv", flips, "--check")
    # 9 flips of about 1,400 simulated cells is under 2 %, but 5 capped cells of the runs at the default
    # is 0.35 %: both within the targets; the fits move by more than 2 % on some object or not at all
    out, _ = study(planted)
    expect_missed = out["missed"]
    assert p.returncode == (1 if expect_missed else 0), p.stderr
    assert all(not line.startswith(("flipped", "capped")) for line in expect_missed)
    with open(table, newline="") as f:
        rows = list(csv.DictReader(f))
    assert [r["object"] for r in rows] == ["block", "leaning", "stack", ""] and rows[-1]["job"] == "all"
    assert int(rows[-1]["flipped"]) == 9 and int(rows[-1]["capped_default"]) == 5
    with open(flips, newline="") as f:
        assert len(list(csv.DictReader(f))) == 9
    text = open(md).read()
    assert "| **all** |" in text and "| 0.9 - 1 | " in text
    # against itself: no flip, no change, every target met
    same = compare("--pair", planted["paths"]["ref"], planted["paths"]["ref"], "--json", "--check")
    assert same.returncode == 0, same.stderr
    same_rows = json.loads(same.stdout)
    assert same_rows["total"]["flipped"] == 0
    for r in same_rows["rows"]:  # the paired bootstrap of a cube against itself changes nothing
        assert r["theta_change"] == 0 and r["theta_change_interval"] == [0, 0] and r["beta_change_interval"] == [0, 0]


def test_the_flip_target_is_checked(planted):
    """A default cube with every survivor of the block overturned misses the 2 % flip target."""
    outcome, cells = planted["cand"]["block"]
    many = outcome.copy()
    many[planted["ref"]["block"][0] == SURVIVED] = OVERTURNED
    path = os.path.join(planted["tmp"], "many.default.h5")
    attrs = {"alpha_rad": ALPHA}
    sc.write_cube(path, planted["pgv"], [("block", many, attrs, cells),
                                         *[(n, o, {}, d) for n, (o, d) in planted["cand"].items() if n != "block"]])
    p = compare("--pair", planted["paths"]["ref"], path, "--check")
    assert p.returncode == 1
    assert "target missed: flipped" in p.stderr


def test_bad_input_exits_2(planted, tmp_path):
    p = compare("--pair", planted["paths"]["ref"], str(tmp_path / "missing.h5"))
    assert p.returncode == 2 and p.stderr.count("\n") == 1 and "missing.h5" in p.stderr
