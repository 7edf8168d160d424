#!/usr/bin/python3
"""A cube with variants (schema_version 3, formerly 2) as h5py and xarray see it: the /variants table, one
group per base object with its cells led by the variant dimension, and xarray opening that group
with both netCDF engines (named dimensions, the variant coordinate, per-variant values).

    /usr/bin/python3 tests/python/test_variant_cube.py CUBE

CUBE is written by io_cube_test (CubeFixture.WritesTheVariantFixture: variant_synthetic() of
tests/io/cube_test.cpp, 2 objects x 3 variants x 3 records x 4 scales x 2 rotations). Exit 77
(CTest: skipped) when h5py, xarray, h5netcdf or netCDF4 is missing.
"""
import sys
import unittest

try:
    import h5py
    import netCDF4  # noqa: F401  (the "netcdf4" engine)
    import h5netcdf  # noqa: F401  (the "h5netcdf" engine)
    import numpy as np
    import xarray as xr
except ImportError as e:  # pragma: no cover
    print(f"skipped: {e} (install python3-h5py python3-xarray python3-h5netcdf python3-netcdf4)")
    sys.exit(77)

CUBE = None  # set from argv
V, R, S, A = 3, 3, 4, 2
ENGINES = ("h5netcdf", "netcdf4")


class VariantCube(unittest.TestCase):
    def test_variant_table(self):
        with h5py.File(CUBE, "r") as f:
            self.assertEqual(int(f.attrs["schema_version"]), 3)
            t = f["variants"]
            self.assertEqual(int(t.attrs["count"]), V)
            self.assertEqual(t.attrs["parameters"], "friction contact density_kg_m3")
            self.assertEqual(list(t["variant"][()]), [0, 1, 2])
            self.assertEqual(list(t["friction"][()]), [0.5, 0.6000000000000001, 0.75])
            self.assertEqual(t["friction"].attrs["units"], "1")
            self.assertEqual(list(t["contact"].asstr()[()]), ["rigid", "penalty", "rigid"])
            self.assertNotIn("units", t["contact"].attrs)

    def test_object_groups_lead_with_the_variant_dimension(self):
        with h5py.File(CUBE, "r") as f:
            self.assertEqual(sorted(f["objects"]), ["rock a", "rock_b"])
            g = f["objects/rock a"]
            self.assertEqual(int(g.attrs["variants"]), V)
            self.assertEqual(g["outcome"].shape, (V, R, S, A))
            self.assertEqual(g["probability"].shape, (V, R, S))
            self.assertEqual(g["fragility"].shape, (V, S, 9))
            self.assertEqual(g["outcome"].dims[0].label, "variant")
            self.assertEqual(g["outcome"].dims[0][0].name, "/objects/rock a/variant")
            # %.17g: the text reads back as the very doubles written
            corners = [float(x) for x in g["support_polygon_m"].asstr()[0].split()]
            self.assertEqual(corners, [-0.1, -0.2, 0.1, -0.2, 0.1, 0.2, -1.0 / 7.0, 0.2])
            self.assertEqual(list(f["objects/rock_b/support_polygon_m"].asstr()[()]), ["", "", ""])

    def test_xarray_opens_a_variant_group_with_both_engines(self):
        with h5py.File(CUBE, "r") as f:
            raw = {name: f[f"objects/{name}/outcome"][()] for name in f["objects"]}
            records = list(f["axes/record"].asstr()[()])
        for engine in ENGINES:
            for name, outcome in raw.items():
                with self.subTest(engine=engine, object=name), \
                        xr.open_dataset(CUBE, group=f"objects/{name}", engine=engine) as ds:
                    self.assertEqual(ds["outcome"].dims, ("variant", "record", "scale", "rotation"))
                    self.assertEqual(ds["probability"].dims, ("variant", "record", "scale"))
                    self.assertEqual(ds["fragility"].dims, ("variant", "scale", "pgv_pga_bin"))
                    self.assertEqual(ds["alpha_rad"].dims, ("variant",))
                    self.assertEqual(list(ds["variant"].values), [0, 1, 2])
                    self.assertEqual(list(ds["record"].values), records)
                    self.assertTrue(np.array_equal(ds["outcome"].values, outcome))
                    # one variant's slice is that variant's [record, scale, rotation] block
                    self.assertTrue(np.array_equal(ds["outcome"].sel(variant=1).values, outcome[1]))
                    for var in ds.variables:
                        self.assertTrue(ds[var].attrs.get("long_name"), var)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    CUBE = sys.argv[1]
    unittest.main(argv=sys.argv[:1], verbosity=2)
