"""Checks a Rigid fragility cube from outside C++: h5py reads it as documented in
docs/cube.md, h5dump accepts it, and compare_cubes.py sees exactly the differences it should.

    /usr/bin/python3 -m pytest tests/python/test_cube.py --cube FIXTURE.h5

FIXTURE.h5 is written by io_cube_test (CubeFixture.WritesThePythonFixture, the CTest fixture
cube_fixture) from the synthetic cube of tests/io/cube_test.cpp, so the values below mirror it.
Skipped when numpy or h5py is missing.
"""
import json
import math
import os
import shutil
import subprocess
import sys

import pytest

h5py = pytest.importorskip("h5py")
np = pytest.importorskip("numpy")

HERE = os.path.dirname(os.path.abspath(__file__))
COMPARE = os.path.join(HERE, "compare_cubes.py")

NAN = float("nan")
CELL_DATASETS = {  # name: (dtype, units)
    "outcome": ("int8", "1"),
    "rotation_deg": ("float64", "degree"),
    "failure_time_s": ("float64", "s"),
    "max_tilt_deg": ("float64", "degree"),
    "max_slip_m": ("float64", "m"),
    "wall_s": ("float64", "s"),
    "failure_reason": ("int32", "1"),
    "unconverged_steps": ("int32", "1"),
}
# each object group's own coordinate variables (netCDF-4 dimension scales), name: units
COORDINATES = {"record": None, "scale": "1", "target_pga": "m s-2", "rotation": "1", "pgv_pga_bin": "1"}


def same(a, b):
    """Equal arrays, NaN matching NaN."""
    return np.array_equal(np.asarray(a, dtype=float), np.asarray(b, dtype=float), equal_nan=True)


class TestCubeFile:
    @pytest.fixture(autouse=True, scope="class")
    def _open(self, request, cube_path):
        request.cls.f = h5py.File(cube_path, "r")
        yield
        request.cls.f.close()

    def test_root_attributes(self):
        a = self.f.attrs
        assert (set(a) == ({"schema_version", "software_version", "job_text", "job_hash",
                                  "physics_json", "seed", "units", "job_inputs_sha256",
                                  "inputs_sha256", "axes_sha256", "axes_sha256_covers"}))  # in particular no time stamp
        assert a["inputs_sha256"] == "c" * 64
        assert a["job_inputs_sha256"].endswith("  jobs/demo run.toml\n")
        assert int(a["schema_version"]) == 3
        assert a["software_version"] == "0.1.0 (abc1234)"
        assert a["job_text"].startswith("# job\nname = \"demo run\"")
        assert len(a["job_hash"]) == 64
        assert json.loads(a["physics_json"])["friction"] == 0.6
        assert a["seed"].dtype == np.uint64
        assert int(a["seed"]) == 0xFEDCBA9876543210
        assert a["units"] == "SI unless the name says otherwise"

    def test_axes(self):
        ax = self.f["axes"]
        assert list(ax["record"].asstr()[()]) == ["rec one", "rec_two", 'rec "three"']
        assert ax["scale_g"].dtype == np.float64
        assert ax["scale_g"].attrs["units"] == "g"
        assert list(ax["scale_g"][()]) == [0.1, 0.2, 0.30000000000000004, 0.4]
        assert ax["rotation"].dtype == np.int32
        assert list(ax["rotation"][()]) == [0, 1]
        edges = ax["pgv_pga_edges_s"][()]
        assert len(edges) == 10  # nine bins
        assert edges[0] == 0.0
        assert math.isinf(edges[-1])
        assert np.all(np.diff(edges) > 0)
        assert list(ax["pgv_pga_bin"][()]) == list(range(9))
        for name in ("record", "scale_g", "rotation", "pgv_pga_bin"):
            assert ax[name].attrs["CLASS"] == b"DIMENSION_SCALE", name
            assert h5py.h5ds.is_scale(ax[name].id), name

    def test_records(self):
        r = self.f["records"]
        assert list(r["earthquake"].asstr()[()]) == ["Duzce, Turkey", "", "Chi-Chi, Taiwan"]
        assert r["source"].asstr()[0] == "x=a b/one-X.AT2,y=a b/one-Y.AT2"
        assert math.isinf(r["end_s"][1])
        assert list(r["pgv_pga_s"][()]) == [0.068, 0.0693, 0.5]
        units = {"start_s": "s", "end_s": "s", "gmroti_pga_g": "g", "gmroti_pgv_cm_s": "cm/s",
                 "pgv_pga_s": "s", "listed_pga_g": "g", "listed_pgv_cm_s": "cm/s",
                 "name": "none", "source": "none", "earthquake": "none", "inputs_sha256": "none",
                 "alignment": "none", "record": "none"}
        assert set(r) == set(units)
        for name, unit in units.items():
            assert r[name].shape == (3,), name
            assert r[name].attrs["units"] == unit, name
            if name != "record":  # the scale itself
                assert r[name].dims[0].label == "record", name
                assert r[name].dims[0][0].name == "/records/record", name

    def test_objects(self):
        objs = self.f["objects"]
        assert sorted(objs) == ["rock a", "rock_b"]
        assert objs["rock a"].attrs["scene"] == "models/rock a/rock.toml"
        assert int(objs["rock a"].attrs["index"]) == 0
        assert int(objs["rock_b"].attrs["index"]) == 1
        for g in objs.values():
            assert (set(g) == (set(CELL_DATASETS) | set(COORDINATES)
                             | {"failure_message", "probability", "fragility", "fragility_count"}))
            for name, unit in COORDINATES.items():
                assert g[name].attrs.get("units") == unit, name
                assert g[name].attrs["long_name"], name
            assert list(g["scale"][()]) == list(self.f["axes/scale_g"][()])
            assert np.allclose(g["target_pga"][()], 9.80665 * g["scale"][()], rtol=1e-15)
            assert list(g["record"].asstr()[()]) == list(self.f["axes/record"].asstr()[()])
            assert len(g.attrs["datasets_sha256"]) == 64
            assert g["failure_message"].shape == (3, 4, 2)
            assert list(g["outcome"].attrs["flag_values"]) == [0, 1, 2, 3, 4]
            assert g["outcome"].attrs["flag_values"].dtype == np.int8
            assert g["outcome"].attrs["flag_meanings"] == "not_run survived overturned inferred failed"
            assert g["failure_reason"].attrs["flag_meanings"] == "none exception non_finite worker_lost"
            for name, (dtype, unit) in CELL_DATASETS.items():
                d = g[name]
                assert d.shape == (3, 4, 2), d.name
                assert d.dtype == np.dtype(dtype), d.name
                assert d.attrs["units"] == unit, d.name
                assert d.attrs["description"], d.name
                assert d.attrs["long_name"], d.name
                assert [d.dims[i].label for i in range(3)] == ["record", "scale", "rotation"]
                assert [d.dims[i][0].name for i in range(3)] == [f"{g.name}/record", f"{g.name}/scale", f"{g.name}/rotation"]
                assert not (d.chunks or d.compression), "contiguous, uncompressed"
            assert g["outcome"].attrs["legend"] == "0 not run, 1 survived, 2 overturned, 3 inferred, 4 failed"
            assert g["probability"].shape == (3, 4)
            assert [g["probability"].dims[i][0].name for i in range(2)] == [f"{g.name}/record", f"{g.name}/scale"]
            for name in ("fragility", "fragility_count"):
                assert g[name].shape == (4, 9)
                assert [g[name].dims[i].label for i in range(2)] == ["scale", "pgv_pga_bin"]
                assert [g[name].dims[i][0].name for i in range(2)] == [f"{g.name}/scale", f"{g.name}/pgv_pga_bin"]
            assert g["fragility_count"].dtype == np.int32

        a = objs["rock a"]
        assert sorted(set(a["outcome"][()].ravel())) == [0, 1, 2, 3, 4]
        # the payload NaN written by the C++ test keeps its bits
        assert a["max_tilt_deg"][()].view(np.uint64).ravel()[3] == 0x7FF800000000BEEF
        # probabilities of the pattern in cube_test.cpp, recomputed here from the outcomes too
        want = [[0, 0.5, 1, 1], [NAN, 0, 1, NAN], [0, 1, 0.5, 1]]
        assert same(a["probability"][()], want)
        o = a["outcome"][()]
        over = ((o == 2) | (o == 3)).sum(axis=2)
        known = over + (o == 1).sum(axis=2)
        with np.errstate(invalid="ignore", divide="ignore"):
            assert same(np.where(known > 0, over / known, NAN), want)
        frag, count = a["fragility"][()], a["fragility_count"][()]
        want_frag = np.full((4, 9), NAN)
        want_frag[:, 1] = [0, 0.25, 1, 1]
        want_frag[:, 8] = [0, 1, 0.5, 1]
        assert same(frag, want_frag)
        want_count = np.zeros((4, 9), dtype=np.int32)
        want_count[:, 1] = [1, 2, 2, 1]
        want_count[:, 8] = 1
        assert np.array_equal(count, want_count)

    def test_every_dataset_is_described(self):
        missing = []

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                # text in the object groups has no units (CF); every number has
                text = name.startswith("objects/") and obj.dtype.kind == "O"
                for attr in ("description",) if text else ("units", "description"):
                    if attr not in obj.attrs:
                        missing.append(f"{name}@{attr}")
                if name.startswith("objects/") and "long_name" not in obj.attrs:
                    missing.append(f"{name}@long_name")
        self.f.visititems(visit)
        assert missing == []

    def test_h5dump_reads_it(self, cube_path):
        h5dump = shutil.which("h5dump") or ("/usr/bin/h5dump" if os.path.exists("/usr/bin/h5dump") else None)
        if not h5dump:
            pytest.skip("h5dump not installed (Debian: hdf5-tools)")
        r = subprocess.run([h5dump, cube_path], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        assert 'DATASET "outcome"' in r.stdout


class TestCompareCubes:
    @pytest.fixture(autouse=True)
    def _paths(self, cube_path, tmp):
        self.fixture, self.tmp = cube_path, tmp

    def copy(self, name, change=None):
        p = os.path.join(self.tmp, name)
        shutil.copyfile(self.fixture, p)
        if change:
            with h5py.File(p, "r+") as f:
                change(f)
        return p

    def run_compare(self, b, *options):
        return subprocess.run([sys.executable, COMPARE, *options, self.fixture, b], capture_output=True, text=True)

    def test_identical(self):
        r = self.run_compare(self.copy("same.h5"))
        assert r.returncode == 0, r.stdout + r.stderr

    def test_wall_time_is_ignored(self):
        def change(f):
            f["objects/rock a/wall_s"][0, 0, 0] = 123.0
        r = self.run_compare(self.copy("wall.h5", change))
        assert r.returncode == 0, r.stdout + r.stderr

    def test_a_changed_value_is_reported(self):
        def change(f):
            f["objects/rock_b/max_slip_m"][2, 3, 1] = 0.5
        r = self.run_compare(self.copy("value.h5", change))
        assert r.returncode == 1
        assert "objects/rock_b/max_slip_m: [2, 3, 1]" in r.stdout

    def test_nan_bits_matter(self):
        def change(f):  # another NaN in place of the payload NaN
            d = f["objects/rock a/max_tilt_deg"]
            v = d[()]
            v.reshape(-1)[3] = np.nan
            d[()] = v
        r = self.run_compare(self.copy("nan.h5", change))
        assert r.returncode == 1, r.stdout

    def test_strings_attributes_and_missing_datasets(self):
        def rename(f):
            f["records/earthquake"][1] = "Somewhere"
        def attr(f):
            f.attrs["job_hash"] = "0" * 64
        def dataset_attr(f):
            f["axes/scale_g"].attrs["units"] = "m/s^2"
        def drop(f):
            del f["objects/rock a/fragility_count"]
        for name, change in (("s.h5", rename), ("a.h5", attr), ("d.h5", dataset_attr), ("m.h5", drop)):
            r = self.run_compare(self.copy(name, change))
            assert r.returncode == 1, f"{name}: {r.stdout}"

    def test_another_build_differs_only_in_its_version(self):
        def version(f):
            f.attrs["software_version"] = "another build"
        other = self.copy("v.h5", version)
        assert self.run_compare(other).returncode == 1
        r = self.run_compare(other, "--other-build")
        assert r.returncode == 0, r.stdout + r.stderr
        def version_and_value(f):
            version(f)
            f["objects/rock_b/max_slip_m"][2, 3, 1] = 0.5
        assert self.run_compare(self.copy("vv.h5", version_and_value), "--other-build").returncode == 1

    def test_unreadable_file(self):
        bad = os.path.join(self.tmp, "bad.h5")
        with open(bad, "w") as f:
            f.write("not hdf5")
        assert self.run_compare(bad).returncode == 2

