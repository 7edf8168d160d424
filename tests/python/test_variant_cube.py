"""A cube with variants (schema_version 3, formerly 2) as h5py and xarray see it: the /variants table, one
group per base object with its cells led by the variant dimension, and xarray opening that group
with both netCDF engines (named dimensions, the variant coordinate, per-variant values).

    /usr/bin/python3 -m pytest tests/python/test_variant_cube.py --cube CUBE

CUBE is written by io_cube_test (CubeFixture.WritesTheVariantFixture: variant_synthetic() of
tests/io/cube_test.cpp, 2 objects x 3 variants x 3 records x 4 scales x 2 rotations). Skipped
when h5py, xarray, h5netcdf or netCDF4 is missing.
"""
import pytest

h5py = pytest.importorskip("h5py")
pytest.importorskip("netCDF4")  # the "netcdf4" engine
pytest.importorskip("h5netcdf")  # the "h5netcdf" engine
np = pytest.importorskip("numpy")
xr = pytest.importorskip("xarray")

V, R, S, A = 3, 3, 4, 2
ENGINES = ("h5netcdf", "netcdf4")


class TestVariantCube:
    @pytest.fixture(autouse=True)
    def _cube(self, cube_path):
        self.cube = cube_path

    def test_variant_table(self):
        with h5py.File(self.cube, "r") as f:
            assert int(f.attrs["schema_version"]) == 3
            t = f["variants"]
            assert int(t.attrs["count"]) == V
            assert t.attrs["parameters"] == "friction contact density_kg_m3"
            assert list(t["variant"][()]) == [0, 1, 2]
            assert list(t["friction"][()]) == [0.5, 0.6000000000000001, 0.75]
            assert t["friction"].attrs["units"] == "1"
            assert list(t["contact"].asstr()[()]) == ["rigid", "penalty", "rigid"]
            assert "units" not in t["contact"].attrs

    def test_object_groups_lead_with_the_variant_dimension(self):
        with h5py.File(self.cube, "r") as f:
            assert sorted(f["objects"]) == ["rock a", "rock_b"]
            g = f["objects/rock a"]
            assert int(g.attrs["variants"]) == V
            assert g["outcome"].shape == (V, R, S, A)
            assert g["probability"].shape == (V, R, S)
            assert g["fragility"].shape == (V, S, 9)
            assert g["outcome"].dims[0].label == "variant"
            assert g["outcome"].dims[0][0].name == "/objects/rock a/variant"
            # %.17g: the text reads back as the very doubles written
            corners = [float(x) for x in g["support_polygon_m"].asstr()[0].split()]
            assert corners == [-0.1, -0.2, 0.1, -0.2, 0.1, 0.2, -1.0 / 7.0, 0.2]
            assert list(f["objects/rock_b/support_polygon_m"].asstr()[()]) == ["", "", ""]

    def test_xarray_opens_a_variant_group_with_both_engines(self, subtest):
        with h5py.File(self.cube, "r") as f:
            raw = {name: f[f"objects/{name}/outcome"][()] for name in f["objects"]}
            records = list(f["axes/record"].asstr()[()])
        for engine in ENGINES:
            for name, outcome in raw.items():
                with subtest(engine=engine, object=name), \
                        xr.open_dataset(self.cube, group=f"objects/{name}", engine=engine) as ds:
                    assert ds["outcome"].dims == ("variant", "record", "scale", "rotation")
                    assert ds["probability"].dims == ("variant", "record", "scale")
                    assert ds["fragility"].dims == ("variant", "scale", "pgv_pga_bin")
                    assert ds["alpha_rad"].dims == ("variant",)
                    assert list(ds["variant"].values) == [0, 1, 2]
                    assert list(ds["record"].values) == records
                    assert np.array_equal(ds["outcome"].values, outcome)
                    # one variant's slice is that variant's [record, scale, rotation] block
                    assert np.array_equal(ds["outcome"].sel(variant=1).values, outcome[1])
                    for var in ds.variables:
                        assert ds[var].attrs.get("long_name"), var

