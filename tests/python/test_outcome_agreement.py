"""`python3 -m rigidpy.outcome_agreement` (docs/accuracy.md) on synthetic cubes (synthetic_cube.py):
a cube against itself agrees on every known cell; against a copy with planted changes the
disagreements are exactly the cells changed here, and the agreement is counted here from the
outcome codes (overturned and inferred one class, survived the other; not-run and failed unknown).

    /usr/bin/python3 -m pytest tests/python/test_outcome_agreement.py
"""
import json
import os
import subprocess
import sys

import pytest

np = pytest.importorskip("numpy")
pytest.importorskip("h5py")

import synthetic_cube as sc  # noqa: E402

PYTHON_DIR = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src", "python"))


def agreement(*cubes):
    p = subprocess.run([sys.executable, "-m", "rigidpy.outcome_agreement", *cubes, "--json"], capture_output=True,
                       text=True, cwd=PYTHON_DIR)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


@pytest.fixture(scope="module")
def planted(tmp_path_factory):
    tmp = str(tmp_path_factory.mktemp("agreement"))
    rng = np.random.default_rng(5)
    pgv = np.exp(rng.uniform(np.log(0.035), np.log(0.5), sc.R))
    outcome = sc.planted_outcomes(rng, pgv, sc.MU0, sc.MU1, sc.SIGMA)  # with inferred, failed, not-run cells
    return tmp, pgv, outcome


def write(tmp, name, pgv, outcome):
    path = os.path.join(tmp, name)
    sc.write_cube(path, pgv, [("rock", outcome, {})], wall_s=0.5)
    return path


def test_a_cube_agrees_with_itself(planted):
    tmp, pgv, outcome = planted
    ref = write(tmp, "ref.h5", pgv, outcome)
    row = agreement(ref, ref)[ref]["rock"]
    known = int(np.isin(outcome, (1, 2, 3)).sum())
    assert row["known"] == known and row["agree"] == known and row["agreement"] == 1.0
    assert row["unknown"] == outcome.size - known and row["differ"] == []
    ran = int(np.isin(outcome, (1, 2, 4)).sum())  # survived, overturned, failed: a simulation ran
    assert row["simulated"] == ran and row["wall"] == pytest.approx(0.5 * ran, rel=1e-12)


def test_planted_changes_are_the_disagreements(planted):
    tmp, pgv, outcome = planted
    ref = write(tmp, "ref.h5", pgv, outcome)
    changed = outcome.copy()
    survived = np.argwhere(outcome == 1)[:5]
    inferred = np.argwhere(outcome == 3)[:3]
    for r, s, a in survived:
        changed[r, s, a] = 2  # survived -> overturned: a disagreement
    for r, s, a in inferred:
        changed[r, s, a] = 2  # inferred -> overturned: the same class, no disagreement
    cand = write(tmp, "cand.h5", pgv, changed)
    row = agreement(ref, cand)[cand]["rock"]
    known = int((np.isin(outcome, (1, 2, 3)) & np.isin(changed, (1, 2, 3))).sum())
    assert row["known"] == known
    assert row["agree"] == known - len(survived)
    assert sorted(row["differ"]) == sorted([list(map(int, c)) for c in survived])
