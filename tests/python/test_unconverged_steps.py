"""The contact solver's capped steps per cell (the cube's `unconverged_steps`, -1 = not recorded)
reach the readers: `rigid export cells` (column unconverged_steps, empty when not recorded) and
rigidpy's cube reader (ObjectData.unconverged_steps, -1 when not recorded).

    /usr/bin/python3 -m pytest tests/python/test_unconverged_steps.py --cube CUBE [--rigid RIGID]

CUBE is a fixture io_cube_test writes (with or without variants). Oracle: values planted into a
copy with h5py (the dataset is outside the cells' checksum, so the copy stays a valid cube) come
back unchanged; a copy without the dataset, as a cube written before it existed, reads as not
recorded everywhere. The export half is skipped without --rigid; all of it without numpy or h5py.
"""
import csv
import io
import os
import shutil
import subprocess

import pytest

h5py = pytest.importorskip("h5py")
np = pytest.importorskip("numpy")

from rigidpy.cube import NOT_RECORDED, Cube  # noqa: E402


def plant(path, seed):
    """Random counts (some -1, some in the thousands) into every object's unconverged_steps; returns
    them by (object, variant), variant None without variants."""
    rng = np.random.default_rng(seed)
    planted = {}
    with h5py.File(path, "r+") as f:
        varied = "variants" in f
        for name, g in f["objects"].items():
            ds = g["unconverged_steps"]
            values = rng.integers(-1, 5000, size=ds.shape, dtype=np.int32)
            values.flat[0] = NOT_RECORDED
            values.flat[1] = 0
            ds[...] = values
            if varied:
                for v in range(values.shape[0]):
                    planted[(name, v)] = values[v]
            else:
                planted[(name, None)] = values
    return planted


def drop(path):
    """The copy as a cube written before the dataset existed: without it."""
    shape = {}
    with h5py.File(path, "r+") as f:
        varied = "variants" in f
        for name, g in f["objects"].items():
            s = g["outcome"].shape
            for v in range(s[0]) if varied else [None]:
                shape[(name, v)] = s[1:] if varied else s
            del g["unconverged_steps"]
    return {key: np.full(s, NOT_RECORDED, np.int32) for key, s in shape.items()}


def exported(rigid, path):
    """The cells table's unconverged_steps as text, per (object, variant) in row order."""
    r = subprocess.run([rigid, "export", "cells", path, "--csv"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    rows = list(csv.DictReader(io.StringIO(r.stdout, newline="")))
    assert rows and list(rows[0])[-1] == "unconverged_steps"
    table = {}
    for row in rows:
        key = (row["object"], int(row["variant"]) if "variant" in row else None)
        table.setdefault(key, []).append(row["unconverged_steps"])
    return table


def as_text(values):
    """The column as the table writes it: the count, an empty field for not recorded."""
    return ["" if v == NOT_RECORDED else str(int(v)) for v in values.ravel()]


@pytest.fixture
def copy(cube_path, tmp):
    path = os.path.join(tmp, "cube.h5")
    shutil.copyfile(cube_path, path)
    return path


def test_planted_counts_reach_the_python_reader(copy):
    planted = plant(copy, 1)
    cube = Cube(copy)
    assert {(o.name, o.variant) for o in cube.objects} == set(planted)
    for o in cube.objects:
        assert o.unconverged_steps.dtype == np.int32
        assert np.array_equal(o.unconverged_steps, planted[(o.name, o.variant)]), o.label


def test_planted_counts_reach_the_cells_table(copy, rigid):
    planted = plant(copy, 2)
    table = exported(rigid, copy)
    assert set(table) == set(planted)
    for key, values in planted.items():
        assert table[key] == as_text(values), key


def test_a_cube_without_the_dataset_reads_as_not_recorded(copy, rigid_or_none):
    expected = drop(copy)
    for o in Cube(copy).objects:
        assert np.array_equal(o.unconverged_steps, expected[(o.name, o.variant)]), o.label
    if rigid_or_none is None:
        pytest.skip("the export half needs --rigid")
    table = exported(rigid_or_none, copy)
    assert set(table) == set(expected)
    for key, values in expected.items():
        assert table[key] == [""] * values.size, key
