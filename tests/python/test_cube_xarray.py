"""The cube as analysis tools see it: xarray opens every group (objects, /fragility after `rigid
fragility`, axes, records) with both netCDF engines without phony dimensions (named dimensions,
coordinate values, CF flags); the demo job's scales select by the decimals the job states;
`rigid export cells --csv` round-trips through pandas with the cube's own values; the campaign's
progress lines count cells out of a fixed total, and dispatch internals come only with --verbose.

    /usr/bin/python3 -m pytest tests/python/test_cube_xarray.py --rigid RIGID

Runs jobs/ci_small.toml on one process (a few seconds). Skipped when xarray,
h5netcdf, netCDF4 or pandas is missing (Debian: python3-xarray python3-h5netcdf python3-netcdf4
python3-pandas).
"""
import os
import re
import shutil
import subprocess
from decimal import Decimal

import pytest

h5py = pytest.importorskip("h5py")
pytest.importorskip("netCDF4")  # the "netcdf4" engine
pytest.importorskip("h5netcdf")  # the "h5netcdf" engine
np = pytest.importorskip("numpy")
pd = pytest.importorskip("pandas")
xr = pytest.importorskip("xarray")

ENGINES = ("h5netcdf", "netcdf4")
OUTCOMES = ["not_run", "survived", "overturned", "inferred", "failed"]
REASONS = ["none", "exception", "non_finite", "worker_lost"]


def same(a, b):
    """Equal arrays, NaN matching NaN."""
    return np.array_equal(np.asarray(a, dtype=float), np.asarray(b, dtype=float), equal_nan=True)


class TestAnalysisReadyCube:
    @pytest.fixture(autouse=True, scope="class")
    def _campaign(self, request, rigid, source_dir, tmp_path_factory):
        """jobs/ci_small.toml run once for the class, and its fragilities stored."""
        cls = request.cls
        cls.rigid, cls.repo = rigid, source_dir
        cls.tmp = str(tmp_path_factory.mktemp("xarray"))
        cls.cube = os.path.join(cls.tmp, "ci.h5")
        job = os.path.join(cls.repo, "jobs", "ci_small.toml")
        r = subprocess.run([cls.rigid, "campaign", job, "--out", cls.cube, "--progress", "log", "--log-interval", "0.05"],
                           capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"rigid campaign failed ({r.returncode}): {r.stderr}")
        cls.campaign_log = r.stderr
        # the fitted fragilities in the cube (/fragility/NAME), as `rigid fragility` stores them
        r = subprocess.run([cls.rigid, "fragility", cls.cube, "--bootstrap", "20"], capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"rigid fragility failed ({r.returncode}): {r.stderr}")
        cls.f = h5py.File(cls.cube, "r")
        cls.objects = list(cls.f["objects"])
        yield
        cls.f.close()

    def test_xarray_opens_every_object_group_with_both_engines(self, subtest):
        records = list(self.f["axes/record"].asstr()[()])
        scales = self.f["axes/scale_g"][()]
        rotations = len(self.f["axes/rotation"])
        assert self.objects
        for engine in ENGINES:
            for name in self.objects:
                with subtest(engine=engine, object=name), \
                        xr.open_dataset(self.cube, group=f"objects/{name}", engine=engine) as ds:
                    assert ds["outcome"].dims == ("record", "scale", "rotation")
                    assert list(ds["record"].values) == records
                    assert same(ds["scale"].values, scales)
                    assert list(ds["rotation"].values) == list(range(rotations))
                    assert np.allclose(ds["target_pga"].values, 9.80665 * scales, rtol=1e-15)
                    assert ds["target_pga"].attrs["units"] == "m s-2"
                    assert "target_pga" in ds.coords
                    g = self.f[f"objects/{name}"]
                    for var in ("outcome", "failure_time_s", "max_tilt_deg", "max_slip_m", "failure_reason"):
                        assert same(ds[var].values, g[var][()]), var
                    for var in ds.variables:
                        assert ds[var].attrs.get("long_name"), var
                    assert list(ds["outcome"].attrs["flag_values"]) == list(range(5))
                    assert ds["outcome"].attrs["flag_meanings"].split() == OUTCOMES
                    assert list(ds["failure_reason"].attrs["flag_values"]) == list(range(4))
                    assert ds["failure_reason"].attrs["flag_meanings"].split() == REASONS
                    # label-based selection works in g
                    p = ds["probability"].sel(scale=scales[-1], record=records[0]).item()
                    assert same(p, g["probability"][0, -1])

    def test_every_group_opens_without_phony_dimensions(self, subtest):
        # netCDF-4 names a dimension without a dimension scale "phony_dim_N" and xarray refuses
        # the group unless asked for phony_dims; every group the cube has must open as is
        groups = []
        self.f.visititems(lambda name, obj: groups.append(name) if isinstance(obj, h5py.Group) else None)
        assert "axes" in groups
        assert any(g.startswith("fragility/") for g in groups), groups
        for engine in ENGINES:
            for group in groups:
                if not any(isinstance(v, h5py.Dataset) for v in self.f[group].values()):
                    continue  # attributes and subgroups only
                with subtest(engine=engine, group=group), \
                        xr.open_dataset(self.cube, group=group, engine=engine) as ds:
                    phony = [d for d in ds.dims if str(d).startswith("phony_dim")]
                    assert phony == [], f"{group}: {dict(ds.sizes)}"
                    assert (ds.data_vars or ds.coords)
        with xr.open_dataset(self.cube, group=f"fragility/{self.objects[0]}", engine="h5netcdf") as ds:
            assert ds["theta_g"].dims == ("pgv_pga_bin",)
            assert ds.sizes["pgv_pga_edges_s"] == ds.sizes["pgv_pga_bin"] + 1

    def test_progress_counts_cells_out_of_a_fixed_total(self):
        # "N/T cells settled": T is the campaign's cell count on every line (inferred cells are
        # settled, not taken out of the total), N never decreases and ends at T
        lines = re.findall(r"(\d+)/(\d+) cells settled \((\d+) %", self.campaign_log)
        assert len(lines) >= 2, self.campaign_log
        cells = sum(self.f[f"objects/{n}/outcome"].size for n in self.objects)
        assert {int(t) for _, t, _ in lines} == {cells}
        settled = [int(n) for n, _, _ in lines]
        assert settled == sorted(settled)
        assert settled[-1] == cells
        assert "ETA" in self.campaign_log
        assert "messages" not in self.campaign_log

    def test_demo_scales_select_by_the_decimals_the_job_states(self, subtest):
        # jobs/demo.toml's scales "0.1:1.0:0.1", read here as decimals (the oracle: Python's
        # Decimal, not the tool's parser); --noop runs no physics, the axes are the demo's own
        job = os.path.join(self.repo, "jobs", "demo.toml")
        text = open(job).read()
        start, stop, step = (Decimal(v) for v in re.search(r'^scales = "([^"]+)"', text, re.M).group(1).split(":"))
        stated = [float(start + i * step) for i in range(int((stop - start) / step) + 1)]
        assert len(stated) == 10
        cube = os.path.join(self.tmp, "demo_noop.h5")
        r = subprocess.run([self.rigid, "campaign", job, "--out", cube, "--noop", "--progress", "none"],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        with h5py.File(cube, "r") as f:
            objects = list(f["objects"])
            assert list(f["axes/scale_g"][()]) == stated
        for engine in ENGINES:
            for name in objects:
                with subtest(engine=engine, object=name), \
                        xr.open_dataset(cube, group=f"objects/{name}", engine=engine) as ds:
                    for v in stated:
                        assert ds.outcome.sel(scale=v).sizes == {"record": 9, "rotation": 2}, v
                        assert float(ds.target_pga.sel(scale=v)) == v * 9.80665

    def test_verbose_alone_logs_the_dispatch_internals(self):
        if shutil.which("mpirun") is None:
            pytest.skip("no mpirun")
        job = os.path.join(self.repo, "jobs", "ci_small.toml")
        env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
        logs = {}
        for extra in ([], ["--verbose"]):
            out = os.path.join(self.tmp, f"noop{len(extra)}.h5")
            r = subprocess.run(["mpirun", "--oversubscribe", "-np", "2", self.rigid, "campaign", job, "--out", out, "--noop",
                                "--progress", "none"] + extra, capture_output=True, text=True, env=env, timeout=120)
            assert r.returncode == 0, r.stderr
            logs[bool(extra)] = r.stderr
        assert "messages" not in logs[False]
        assert "journal syncs" not in logs[False]
        assert "tasks sent to 1 worker ranks in" in logs[True]
        assert "journal syncs" in logs[True]

    def test_rocking_parameters_travel_with_each_single_block_object(self, subtest):
        # rectangular blocks: the weakest of the 16 directions is across the width, where the
        # per-azimuth alpha equals alpha itself; the support polygon is the base's four corners
        for name in self.objects:
            with subtest(object=name), xr.open_dataset(self.cube, group=f"objects/{name}", engine="h5netcdf") as ds:
                if "alpha_rad" not in ds.attrs:
                    continue
                alphas = np.asarray(ds.attrs["alpha_by_azimuth_rad"])
                assert len(alphas) == 16
                assert round(abs(ds.attrs["alpha_rad"] - alphas.min()), 12) == 0
                assert len(ds.attrs["support_polygon_m"]) == 8
                assert ds.attrs["rocking_radius_m"] > 0

    def test_export_cells_round_trips_through_pandas(self):
        r = subprocess.run([self.rigid, "export", "cells", self.cube, "--csv"], capture_output=True)
        assert r.returncode == 0, r.stderr
        csv = os.path.join(self.tmp, "cells.csv")
        with open(csv, "wb") as out:
            out.write(r.stdout)
        # round_trip: pandas' default parser may miss the last bit of a 17-digit number
        t = pd.read_csv(csv, keep_default_na=False, dtype={"failure_message": str, "unconverged_steps": str},
                        float_precision="round_trip",
                        na_values={c: [""] for c in ("rotation_deg", "failure_time_s", "max_tilt_deg", "max_slip_m")})
        cells = sum(self.f[f"objects/{n}/outcome"].size for n in self.objects)
        assert len(t) == cells
        assert (list(t.columns) == (["object", "record", "scale_g", "rotation", "rotation_deg", "outcome",
                                           "failure_time_s", "max_tilt_deg", "max_slip_m", "failure_reason",
                                           "failure_message", "unconverged_steps"]))
        records = list(self.f["axes/record"].asstr()[()])
        scales = self.f["axes/scale_g"][()]
        for name in self.objects:
            g = self.f[f"objects/{name}"]
            rows = t[t["object"] == name]
            shape = g["outcome"].shape
            assert list(rows["record"]) == [records[i] for i in np.indices(shape)[0].ravel()]
            assert same(rows["scale_g"], scales[np.indices(shape)[1].ravel()])
            assert list(rows["rotation"]) == list(np.indices(shape)[2].ravel())
            assert list(rows["outcome"]) == [OUTCOMES[v] for v in g["outcome"][()].ravel()]
            assert list(rows["failure_reason"]) == [REASONS[v] for v in g["failure_reason"][()].ravel()]
            for var in ("rotation_deg", "failure_time_s", "max_tilt_deg", "max_slip_m"):
                assert same(rows[var], g[var][()].ravel()), var
            assert list(rows["failure_message"]) == list(g["failure_message"].asstr()[()].ravel())
            # the contact solver's capped steps; -1 (not recorded) is an empty field
            steps = g["unconverged_steps"][()].ravel()
            assert list(rows["unconverged_steps"]) == ["" if v < 0 else str(v) for v in steps]

    def test_export_of_a_non_cube_is_one_line_exit_2(self):
        for path in (os.path.join(self.tmp, "missing.h5"), os.path.join(self.repo, "jobs", "ci_small.toml")):
            r = subprocess.run([self.rigid, "export", "cells", path, "--csv"], capture_output=True, text=True)
            assert r.returncode == 2, path
            assert r.stdout == ""
            assert len(r.stderr.splitlines()) == 1, r.stderr
            assert r.stderr.startswith("rigid: error: "), r.stderr

    def test_a_flipped_outcome_byte_is_refused(self):
        damaged = os.path.join(self.tmp, "damaged.h5")
        shutil.copyfile(self.cube, damaged)
        name = self.objects[0]
        with h5py.File(damaged, "r+") as f:
            d = f[f"objects/{name}/outcome"]
            d[0, 0, 0] = d[0, 0, 0] ^ 1
        job = os.path.join(self.repo, "jobs", "ci_small.toml")
        for command in (["export", "cells", damaged, "--csv"], ["campaign", job, "--out", damaged]):  # a resume
            r = subprocess.run([self.rigid] + command, capture_output=True, text=True)
            assert r.returncode == 2, command
            assert f"/objects/{name}: datasets changed since written (checksum mismatch)" in r.stderr

