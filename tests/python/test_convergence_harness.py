"""The convergence study's harness end to end (tests/bench/convergence_study.py, docs/accuracy.md
"Convergence of the contact solve"):

- `--set quick` runs jobs/convergence/quick.toml at the default and at `--accuracy reference` and
  writes its tables; the cells compared are the job's grid, counted here from the job file (objects
  x records x scales x rotations), every one simulated in both cubes (no stop rule, no failure), and
  the flipped and capped cells of its table are those counted here from the two cubes' datasets
  with h5py (outcome codes 1 and 2, unconverged_steps > 0), without rigidpy;
- `--set hard --check`, the full study (label `long`): the issue's targets, flipped <= 2 % of the
  simulated cells, capped <= 1 % at the default and none at the reference, fitted medians and
  dispersions within 2 % (the comparer's --check; its counts are tested on planted cubes by
  test_convergence_study.py).

    /usr/bin/python3 -m pytest tests/python/test_convergence_harness.py --rigid build/bin/rigid [-k full]
"""
import csv
import os
import subprocess
import sys

import pytest

np = pytest.importorskip("numpy")
h5py = pytest.importorskip("h5py")
tomllib = pytest.importorskip("tomllib") if sys.version_info >= (3, 11) else pytest.importorskip("tomli")

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.normpath(os.path.join(HERE, "..", ".."))
DRIVER = os.path.join(SOURCE_DIR, "tests", "bench", "convergence_study.py")


def grid_cells(job_path):
    """Cells of a job without variants: objects x records x scales x rotations, from its file."""
    with open(job_path, "rb") as f:
        job = tomllib.load(f)
    scales = job["campaign"]["scales"]
    if isinstance(scales, str):
        lo, hi, step = (float(v) for v in scales.split(":"))
        scales = [lo + i * step for i in range(int(round((hi - lo) / step)) + 1)]
    return len(job["object"]) * len(job["record"]) * len(scales) * int(job["campaign"]["rotations"])


def run_driver(rigid, out, *args):
    p = subprocess.run([sys.executable, DRIVER, "--rigid", rigid, "--out", out, *args], capture_output=True, text=True)
    return p


def total_row(out):
    with open(os.path.join(out, "study.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    assert rows[-1]["job"] == "all"
    return rows


def test_quick_set_compares_every_cell(rigid, tmp_path):
    out = str(tmp_path / "quick")
    p = run_driver(rigid, out, "--set", "quick", "--np", "1")
    assert p.returncode == 0, p.stdout + p.stderr
    for name in ("quick.default.h5", "quick.reference.h5", "study.md", "flips.csv", "timings.csv"):
        assert os.path.isfile(os.path.join(out, name)), name
    rows = total_row(out)
    cells = grid_cells(os.path.join(SOURCE_DIR, "jobs", "convergence", "quick.toml"))
    assert int(rows[-1]["simulated"]) == cells == 36
    assert int(rows[-1]["ran_reference"]) == int(rows[-1]["ran_default"]) == cells
    cubes = {s: h5py.File(os.path.join(out, f"quick.{s}.h5"), "r") for s in ("default", "reference")}
    flipped = capped_default = capped_reference = 0
    for name in cubes["reference"]["objects"]:
        ref, default = (cubes[s]["objects"][name] for s in ("reference", "default"))
        a, b = ref["outcome"][()], default["outcome"][()]
        assert np.isin(a, (1, 2)).all() and np.isin(b, (1, 2)).all()  # survived or overturned: all simulated
        flipped += int((a != b).sum())
        capped_default += int((default["unconverged_steps"][()] > 0).sum())
        capped_reference += int((ref["unconverged_steps"][()] > 0).sum())
    assert int(rows[-1]["flipped"]) == flipped
    assert (int(rows[-1]["capped_default"]), int(rows[-1]["capped_reference"])) == (capped_default, capped_reference)
    with open(os.path.join(out, "flips.csv"), newline="") as f:
        assert len(list(csv.DictReader(f))) == flipped


def test_bad_rigid_exits_2(tmp_path):
    p = run_driver(str(tmp_path / "no_rigid"), str(tmp_path / "out"), "--set", "quick")
    assert p.returncode == 2 and "not an executable" in p.stderr


@pytest.mark.skipif(os.environ.get("RIGID_CONVERGENCE_FULL") != "1",
                    reason="the full study (~15 min on 2 cores): CTest convergence_study_full, label long")
def test_full_study_meets_the_targets(rigid, tmp_path):
    out = os.environ.get("RIGID_CONVERGENCE_OUT", str(tmp_path / "full"))
    p = run_driver(rigid, out, "--set", "hard", "--check")
    assert p.returncode == 0, p.stdout[-4000:] + p.stderr
    assert int(total_row(out)[-1]["simulated"]) >= 1000
