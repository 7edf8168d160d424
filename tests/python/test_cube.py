#!/usr/bin/python3
"""Checks a Rigid fragility cube from outside C++: h5py reads it as documented in
docs/cube.md, h5dump accepts it, and compare_cubes.py sees exactly the differences it should.

    /usr/bin/python3 tests/python/test_cube.py FIXTURE.h5

FIXTURE.h5 is written by io_cube_test (CubeFixture.WritesThePythonFixture, the CTest fixture
cube_fixture) from the synthetic cube of tests/io/cube_test.cpp, so the values below mirror it.
Exit 77 (CTest: skipped) when numpy or h5py is missing.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

try:
    import h5py
    import numpy as np
except ImportError as e:  # pragma: no cover
    print(f"skipped: {e} (install python3-h5py python3-numpy for {sys.executable})")
    sys.exit(77)

HERE = os.path.dirname(os.path.abspath(__file__))
COMPARE = os.path.join(HERE, "compare_cubes.py")
FIXTURE = None  # set from argv

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


class CubeFile(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.f = h5py.File(FIXTURE, "r")

    @classmethod
    def tearDownClass(cls):
        cls.f.close()

    def test_root_attributes(self):
        a = self.f.attrs
        self.assertEqual(set(a), {"schema_version", "software_version", "job_text", "job_hash",
                                  "physics_json", "seed", "units", "job_inputs_sha256",
                                  "inputs_sha256", "axes_sha256", "axes_sha256_covers"})  # in particular no time stamp
        self.assertEqual(a["inputs_sha256"], "c" * 64)
        self.assertTrue(a["job_inputs_sha256"].endswith("  jobs/demo run.toml\n"))
        self.assertEqual(int(a["schema_version"]), 3)
        self.assertEqual(a["software_version"], "0.1.0 (abc1234)")
        self.assertTrue(a["job_text"].startswith("# job\nname = \"demo run\""))
        self.assertEqual(len(a["job_hash"]), 64)
        self.assertEqual(json.loads(a["physics_json"])["friction"], 0.6)
        self.assertEqual(a["seed"].dtype, np.uint64)
        self.assertEqual(int(a["seed"]), 0xFEDCBA9876543210)
        self.assertEqual(a["units"], "SI unless the name says otherwise")

    def test_axes(self):
        ax = self.f["axes"]
        self.assertEqual(list(ax["record"].asstr()[()]), ["rec one", "rec_two", 'rec "three"'])
        self.assertEqual(ax["scale_g"].dtype, np.float64)
        self.assertEqual(ax["scale_g"].attrs["units"], "g")
        self.assertEqual(list(ax["scale_g"][()]), [0.1, 0.2, 0.30000000000000004, 0.4])
        self.assertEqual(ax["rotation"].dtype, np.int32)
        self.assertEqual(list(ax["rotation"][()]), [0, 1])
        edges = ax["pgv_pga_edges_s"][()]
        self.assertEqual(len(edges), 10)  # nine bins
        self.assertEqual(edges[0], 0.0)
        self.assertTrue(math.isinf(edges[-1]))
        self.assertTrue(np.all(np.diff(edges) > 0))
        self.assertEqual(list(ax["pgv_pga_bin"][()]), list(range(9)))
        for name in ("record", "scale_g", "rotation", "pgv_pga_bin"):
            self.assertEqual(ax[name].attrs["CLASS"], b"DIMENSION_SCALE", name)
            self.assertTrue(h5py.h5ds.is_scale(ax[name].id), name)

    def test_records(self):
        r = self.f["records"]
        self.assertEqual(list(r["earthquake"].asstr()[()]), ["Duzce, Turkey", "", "Chi-Chi, Taiwan"])
        self.assertEqual(r["source"].asstr()[0], "x=a b/one-X.AT2,y=a b/one-Y.AT2")
        self.assertTrue(math.isinf(r["end_s"][1]))
        self.assertEqual(list(r["pgv_pga_s"][()]), [0.068, 0.0693, 0.5])
        units = {"start_s": "s", "end_s": "s", "gmroti_pga_g": "g", "gmroti_pgv_cm_s": "cm/s",
                 "pgv_pga_s": "s", "listed_pga_g": "g", "listed_pgv_cm_s": "cm/s",
                 "name": "none", "source": "none", "earthquake": "none", "inputs_sha256": "none",
                 "alignment": "none", "record": "none"}
        self.assertEqual(set(r), set(units))
        for name, unit in units.items():
            self.assertEqual(r[name].shape, (3,), name)
            self.assertEqual(r[name].attrs["units"], unit, name)
            if name != "record":  # the scale itself
                self.assertEqual(r[name].dims[0].label, "record", name)
                self.assertEqual(r[name].dims[0][0].name, "/records/record", name)

    def test_objects(self):
        objs = self.f["objects"]
        self.assertEqual(sorted(objs), ["rock a", "rock_b"])
        self.assertEqual(objs["rock a"].attrs["scene"], "models/rock a/rock.toml")
        self.assertEqual(int(objs["rock a"].attrs["index"]), 0)
        self.assertEqual(int(objs["rock_b"].attrs["index"]), 1)
        for g in objs.values():
            self.assertEqual(set(g), set(CELL_DATASETS) | set(COORDINATES)
                             | {"failure_message", "probability", "fragility", "fragility_count"})
            for name, unit in COORDINATES.items():
                self.assertEqual(g[name].attrs.get("units"), unit, name)
                self.assertTrue(g[name].attrs["long_name"], name)
            self.assertEqual(list(g["scale"][()]), list(self.f["axes/scale_g"][()]))
            self.assertTrue(np.allclose(g["target_pga"][()], 9.80665 * g["scale"][()], rtol=1e-15))
            self.assertEqual(list(g["record"].asstr()[()]), list(self.f["axes/record"].asstr()[()]))
            self.assertEqual(len(g.attrs["datasets_sha256"]), 64)
            self.assertEqual(g["failure_message"].shape, (3, 4, 2))
            self.assertEqual(list(g["outcome"].attrs["flag_values"]), [0, 1, 2, 3, 4])
            self.assertEqual(g["outcome"].attrs["flag_values"].dtype, np.int8)
            self.assertEqual(g["outcome"].attrs["flag_meanings"], "not_run survived overturned inferred failed")
            self.assertEqual(g["failure_reason"].attrs["flag_meanings"], "none exception non_finite worker_lost")
            for name, (dtype, unit) in CELL_DATASETS.items():
                d = g[name]
                self.assertEqual(d.shape, (3, 4, 2), d.name)
                self.assertEqual(d.dtype, np.dtype(dtype), d.name)
                self.assertEqual(d.attrs["units"], unit, d.name)
                self.assertTrue(d.attrs["description"], d.name)
                self.assertTrue(d.attrs["long_name"], d.name)
                self.assertEqual([d.dims[i].label for i in range(3)], ["record", "scale", "rotation"])
                self.assertEqual([d.dims[i][0].name for i in range(3)],
                                 [f"{g.name}/record", f"{g.name}/scale", f"{g.name}/rotation"])
                self.assertFalse(d.chunks or d.compression, "contiguous, uncompressed")
            self.assertEqual(g["outcome"].attrs["legend"],
                             "0 not run, 1 survived, 2 overturned, 3 inferred, 4 failed")
            self.assertEqual(g["probability"].shape, (3, 4))
            self.assertEqual([g["probability"].dims[i][0].name for i in range(2)], [f"{g.name}/record", f"{g.name}/scale"])
            for name in ("fragility", "fragility_count"):
                self.assertEqual(g[name].shape, (4, 9))
                self.assertEqual([g[name].dims[i].label for i in range(2)], ["scale", "pgv_pga_bin"])
                self.assertEqual([g[name].dims[i][0].name for i in range(2)], [f"{g.name}/scale", f"{g.name}/pgv_pga_bin"])
            self.assertEqual(g["fragility_count"].dtype, np.int32)

        a = objs["rock a"]
        self.assertEqual(sorted(set(a["outcome"][()].ravel())), [0, 1, 2, 3, 4])
        # the payload NaN written by the C++ test keeps its bits
        self.assertEqual(a["max_tilt_deg"][()].view(np.uint64).ravel()[3], 0x7FF800000000BEEF)
        # probabilities of the pattern in cube_test.cpp, recomputed here from the outcomes too
        want = [[0, 0.5, 1, 1], [NAN, 0, 1, NAN], [0, 1, 0.5, 1]]
        self.assertTrue(same(a["probability"][()], want))
        o = a["outcome"][()]
        over = ((o == 2) | (o == 3)).sum(axis=2)
        known = over + (o == 1).sum(axis=2)
        with np.errstate(invalid="ignore", divide="ignore"):
            self.assertTrue(same(np.where(known > 0, over / known, NAN), want))
        frag, count = a["fragility"][()], a["fragility_count"][()]
        want_frag = np.full((4, 9), NAN)
        want_frag[:, 1] = [0, 0.25, 1, 1]
        want_frag[:, 8] = [0, 1, 0.5, 1]
        self.assertTrue(same(frag, want_frag))
        want_count = np.zeros((4, 9), dtype=np.int32)
        want_count[:, 1] = [1, 2, 2, 1]
        want_count[:, 8] = 1
        self.assertTrue(np.array_equal(count, want_count))

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
        self.assertEqual(missing, [])

    def test_h5dump_reads_it(self):
        h5dump = shutil.which("h5dump") or ("/usr/bin/h5dump" if os.path.exists("/usr/bin/h5dump") else None)
        if not h5dump:
            self.skipTest("h5dump not installed (Debian: hdf5-tools)")
        r = subprocess.run([h5dump, FIXTURE], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn('DATASET "outcome"', r.stdout)


class CompareCubes(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="rigid_compare_")

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def copy(self, name, change=None):
        p = os.path.join(self.tmp, name)
        shutil.copyfile(FIXTURE, p)
        if change:
            with h5py.File(p, "r+") as f:
                change(f)
        return p

    def run_compare(self, b):
        return subprocess.run([sys.executable, COMPARE, FIXTURE, b], capture_output=True, text=True)

    def test_identical(self):
        r = self.run_compare(self.copy("same.h5"))
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)

    def test_wall_time_is_ignored(self):
        def change(f):
            f["objects/rock a/wall_s"][0, 0, 0] = 123.0
        r = self.run_compare(self.copy("wall.h5", change))
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)

    def test_a_changed_value_is_reported(self):
        def change(f):
            f["objects/rock_b/max_slip_m"][2, 3, 1] = 0.5
        r = self.run_compare(self.copy("value.h5", change))
        self.assertEqual(r.returncode, 1)
        self.assertIn("objects/rock_b/max_slip_m: [2, 3, 1]", r.stdout)

    def test_nan_bits_matter(self):
        def change(f):  # another NaN in place of the payload NaN
            d = f["objects/rock a/max_tilt_deg"]
            v = d[()]
            v.reshape(-1)[3] = np.nan
            d[()] = v
        r = self.run_compare(self.copy("nan.h5", change))
        self.assertEqual(r.returncode, 1, r.stdout)

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
            self.assertEqual(r.returncode, 1, f"{name}: {r.stdout}")

    def test_unreadable_file(self):
        bad = os.path.join(self.tmp, "bad.h5")
        with open(bad, "w") as f:
            f.write("not hdf5")
        self.assertEqual(self.run_compare(bad).returncode, 2)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        print(__doc__.strip().splitlines()[3].strip(), file=sys.stderr)
        sys.exit(2)
    FIXTURE = sys.argv.pop(1)
    unittest.main(verbosity=2)
