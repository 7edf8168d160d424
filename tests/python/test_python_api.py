"""rigidpy's API (docs/python.md) against independent oracles:

a. open_cube on a small campaign (jobs/ci_small.toml, run here): every variable equals the raw
   HDF5 value read with h5py, the PGV/PGA bins' CF bounds are the default bins docs/cube.md states,
   the records' PGA and PGV/PGA coordinates are /records' columns, `sel(scale=0.3)` is the 0.3 g
   column; a calibrated campaign's variants carry the members' weights (0.75, 0.25, by hand).
b. fragility(): the planted probit model of a synthetic cube (synthetic_cube.py) recovered;
   hazard(): the toppling rate of a power-law hazard curve against its closed form
   k0 theta^-k exp(k^2 beta^2 / 2) (Cornell et al. 2002, physics.md §13) for the fitted lognormal.
c. run() through the extension: outcome, overturn time and maximum tilt equal `rigid run --json`'s
   for the same inputs, bit for bit; the table's acceleration, velocity and displacement follow the
   one-sine pulse in closed form; below the uplift acceleration g tan(alpha) the block does not rock
   (Housner 1963, physics.md §2); the history equals the table `rigid run --history` writes; bad
   input raises InputError with one line.
d. `rigid run --plot` writes a pdf, svg and png (their signatures) and `--animate` a gif; a bad
   extension is one line and exit 2.

    /usr/bin/python3 -m pytest tests/python/test_python_api.py --rigid RIGID --engine BUILD/python

--engine: the folder holding the built extension rigidpy/_engine*.so (CMake's
build/python); without it the tests of run() are skipped with a message.
"""
import glob
import json
import math
import os
import shutil
import subprocess

import pytest

h5py = pytest.importorskip("h5py")
np = pytest.importorskip("numpy")
pytest.importorskip("xarray")
pytest.importorskip("scipy")

import rigidpy  # noqa: E402
from rigidpy.errors import InputError  # noqa: E402

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
G = 9.80665
# docs/cube.md, "Default PGV/PGA bins"
DEFAULT_EDGES = [0, 0.06, 0.08, 0.10, 0.12, 0.15, 0.20, 0.25, 0.35, math.inf]
CELL_VARIABLES = ("outcome", "rotation_deg", "failure_time_s", "max_tilt_deg", "max_slip_m", "failure_reason",
                  "unconverged_steps", "wall_s", "probability", "fragility", "fragility_count")


def same(a, b):
    return np.array_equal(np.asarray(a, float), np.asarray(b, float), equal_nan=True)


def run(cmd, cwd=None):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=600)


@pytest.fixture(scope="module")
def ci_cube(rigid, tmp_path_factory):
    cube = str(tmp_path_factory.mktemp("api") / "ci.h5")
    r = run([rigid, "campaign", os.path.join(SOURCE, "jobs", "ci_small.toml"), "--out", cube, "--progress", "none"])
    assert r.returncode == 0, r.stderr
    return cube


def test_open_cube_is_the_raw_hdf5(ci_cube):
    ds = rigidpy.open_cube(ci_cube)
    with h5py.File(ci_cube, "r") as f:
        names = list(f["objects"])
        assert list(ds.object.values) == names
        assert list(ds.record.values) == list(f["axes/record"].asstr()[()])
        assert same(ds.scale.values, f["axes/scale_g"][()])
        for name in names:
            g = f["objects"][name]
            for var in CELL_VARIABLES:
                assert ds[var].dims[0] == "object"
                assert same(ds[var].sel(object=name).values, g[var][()]), var
            # the selection the acceptance command makes: the 0.3 g column of every record and rotation
            col = list(f["axes/scale_g"][()]).index(0.3)
            assert same(ds.outcome.sel(object=name, scale=0.3).values, g["outcome"][:, col, :])
        rec = f["records"]
        assert same(ds.record_pga_g.values, rec["gmroti_pga_g"][()])
        assert same(ds.pgv_pga_s.values, rec["pgv_pga_s"][()])
        assert same(ds.record_pgv_cm_s.values, rec["gmroti_pgv_cm_s"][()])
    assert ds.outcome.attrs["flag_meanings"] == "not_run survived overturned inferred failed"
    # CF bounds: the coordinate names its bounds variable, which holds the documented edges
    assert ds.pgv_pga.attrs["bounds"] == "pgv_pga_bounds"
    bounds = ds[ds.pgv_pga.attrs["bounds"]].values
    assert same(bounds[:, 0], DEFAULT_EDGES[:-1]) and same(bounds[:, 1], DEFAULT_EDGES[1:])
    assert np.all((bounds[:, 0] <= ds.pgv_pga.values) & (ds.pgv_pga.values <= bounds[:, 1]))
    # each record's bin holds its PGV/PGA
    for s, b in zip(ds.pgv_pga_s.values, ds.pgv_pga_bin_of_record.values):
        assert DEFAULT_EDGES[b] <= s < DEFAULT_EDGES[b + 1]


def test_open_cube_refuses_what_is_not_a_cube(tmp_path):
    bad = tmp_path / "x.h5"
    bad.write_text("not hdf5")
    with pytest.raises(InputError, match="x.h5"):
        rigidpy.open_cube(str(bad))
    with pytest.raises(InputError, match="no such file"):
        rigidpy.open_cube(str(tmp_path / "none.h5"))


def test_variants_and_calibration_weights_are_coordinates(rigid, tmp_path):
    from test_calibrated_campaign import calibration_body, calibration_document, write_json
    models, motions = os.path.join(SOURCE, "models", "demo"), os.path.join(SOURCE, "waveforms", "demo")
    for name in os.listdir(models):
        if name.startswith(("block_a02", "block_a03")):
            shutil.copy(os.path.join(models, name), tmp_path)
    shutil.copy(os.path.join(motions, "pulse_sine_0p5s-X.AT2"), tmp_path)
    write_json(str(tmp_path / "rock.calibration.json"), calibration_document(calibration_body((0.5, 0.25, 0.25))))
    (tmp_path / "job.toml").write_text('[campaign]\nseed = 3\nscales = [0.3, 0.6]\nrotations = 1\n'
                                       '[[object]]\nname = "rock"\ncalibration = "rock.calibration.json"\n'
                                       '[[record]]\nmotion = "pulse_sine_0p5s-X.AT2"\n[run]\nfree_time_s = 1.0\n')
    r = run([rigid, "campaign", "job.toml", "--out", "cal.h5", "--progress", "none"], cwd=str(tmp_path))
    assert r.returncode == 0, r.stderr
    ds = rigidpy.open_cube(str(tmp_path / "cal.h5"))
    assert ds.outcome.dims == ("object", "variant", "record", "scale", "rotation")
    # the members' weights by hand: block_a02's two members 0.5 + 0.25, block_a03's 0.25
    assert np.allclose(ds.weight.sel(object="rock").values, [0.75, 0.25], rtol=0, atol=1e-12)
    with h5py.File(str(tmp_path / "cal.h5"), "r") as f:
        scenes = list(f["variants/scene"].asstr()[()])
        assert list(ds.scene.values) == scenes
        assert same(ds.outcome.sel(object="rock").values, f["objects/rock/outcome"][()])


def planted_cube(path):
    """A cube of one rock whose outcomes are drawn from synthetic_cube's planted probit model."""
    import synthetic_cube as sc
    rng = np.random.default_rng(20261206)
    pgv_pga = np.exp(rng.uniform(math.log(0.035), math.log(0.5), sc.R))
    sc.write_cube(path, pgv_pga, [("rock", sc.planted_outcomes(rng, pgv_pga, sc.MU0, sc.MU1, sc.SIGMA), {})])
    return sc


def test_fragility_recovers_the_planted_model(tmp_path):
    cube = str(tmp_path / "planted.h5")
    sc = planted_cube(cube)
    ds = rigidpy.fragility(cube, bootstrap=20)
    s = float(ds.vector_pgv_pga_s[0])
    # planted: ln C ~ N(MU0 + MU1 ln(PGV/PGA), SIGMA) (un-normalised variables)
    theta, beta = math.exp(sc.MU0 + sc.MU1 * math.log(s)), sc.SIGMA
    # within 4 standard errors, each taken from the 90 % bootstrap interval (+-1.645 of them)
    for fitted, planted, stem in ((math.log(float(ds.vector_theta_g[0])), math.log(theta), "theta"),
                                  (float(ds.vector_beta[0]), beta, "beta")):
        lo, hi = (float(ds[f"vector_{stem}_{end}{'_g' if stem == 'theta' else ''}"][0]) for end in ("lower", "upper"))
        if stem == "theta":
            lo, hi = math.log(lo), math.log(hi)
        assert abs(fitted - planted) < 4 * (hi - lo) / 3.29, stem
    assert float(ds.vector_theta_lower_g[0]) <= float(ds.vector_theta_g[0]) <= float(ds.vector_theta_upper_g[0])
    assert same(ds.pgv_pga_bounds[:, 0], DEFAULT_EDGES[:-1])
    with pytest.raises(InputError, match="bootstrap"):
        rigidpy.fragility(cube, bootstrap=2)


def test_hazard_rate_is_the_closed_form(tmp_path):
    cube = str(tmp_path / "planted.h5")
    planted_cube(cube)
    k0, k = 1e-4, 2.5  # H(a) = k0 a^-k, a in g
    curve = tmp_path / "curve.csv"
    pga = np.geomspace(1e-4, 1e3, 400)
    curve.write_text("pga_g,annual_rate\n" + "".join(f"{a!r},{k0 * a ** -k!r}\n" for a in pga))
    r = rigidpy.hazard(cube, str(curve), 10000, bootstrap=20)
    (f,) = r["fragility"]
    expected = k0 * f["theta_g"] ** -k * math.exp(0.5 * (k * f["beta"]) ** 2)
    assert abs(r["annual_toppling_rate"] / expected - 1) < 0.01
    assert abs(r["survival_probability"] - math.exp(-r["annual_toppling_rate"] * 10000)) < 1e-12


# ----------------------------------------------------------------------------------------------
# run() through the extension


@pytest.fixture(scope="module")
def engine(request):
    folder = request.config.getoption("--engine")
    if not folder or not glob.glob(os.path.join(folder, "rigidpy", "_engine*.so")):
        pytest.skip("no built extension (--engine BUILD/python; CMake builds it when pybind11-dev is installed)")
    rigidpy.__path__.append(os.path.join(folder, "rigidpy"))  # the package here, its extension there
    from rigidpy import _engine
    return _engine


SCENE = os.path.join(SOURCE, "models", "demo", "block_a03.toml")
PULSE = os.path.join(SOURCE, "waveforms", "demo", "pulse_sine_0p5s-X.AT2")  # 1 g one-sine pulse, T = 0.5 s
RECORD = os.path.join(SOURCE, "waveforms", "demo", "mp_pulse_1s-X.AT2")


@pytest.mark.parametrize("options", [
    {"motion": RECORD, "target_pga": 0.6, "rotation": 30.0},
    {"motion": RECORD, "target_pga": 0.25, "rotation": 0.0},
    {"motion": RECORD, "target_pga": 0.5, "rotation": 75.0, "contact": "penalty"},
])
def test_run_equals_rigid_run_json(engine, rigid, options):
    cmd = [rigid, "run", SCENE, "--motion", options["motion"], "--target-pga", str(options["target_pga"]),
           "--rotation", str(options["rotation"]), "--json"]
    if "contact" in options:
        cmd += ["--contact", options["contact"]]
    r = run(cmd)
    assert r.returncode == 0, r.stderr
    cli = json.loads(r.stdout)
    ds = rigidpy.run(SCENE, **options)
    assert bool(ds.attrs["overturned"]) == cli["overturned"]
    if cli["failure_time_s"] is None:
        assert math.isnan(ds.attrs["failure_time_s"])
    else:
        assert ds.attrs["failure_time_s"] == cli["failure_time_s"]
    for key in ("max_tilt_deg", "max_slip_m", "steps", "simulated_s"):
        assert ds.attrs[key] == cli[key], key
    # frames sample the run: their largest tilt is at most the run's (to the last bit of the degrees)
    assert float(ds.tilt.max()) <= cli["max_tilt_deg"] * (1 + 1e-12)
    if cli["overturned"]:
        assert float(ds.time[-1]) >= cli["failure_time_s"] - 0.011


def test_one_of_the_runs_overturns(engine):
    assert rigidpy.run(SCENE, motion=RECORD, target_pga=0.6, rotation=30.0).attrs["overturned"] == 1


def test_table_follows_the_pulse_and_the_block_stays_below_uplift(engine):
    amplitude_g, period = 0.25, 0.5  # below g tan(alpha) = 0.31 g for alpha = 0.3 rad
    ds = rigidpy.run(SCENE, motion=PULSE, factor=amplitude_g, interval=0.005, free_time=0.5)
    t = ds.time.values
    w = 2 * math.pi / period
    inside = t <= period
    a = ds.table_acceleration.sel(axis="x").values
    assert np.allclose(a[inside] / G, amplitude_g * np.sin(w * t[inside]), rtol=0, atol=2e-3 * amplitude_g)
    # the pedestal moves by the engine's steps: within one step's change of the closed form
    step = ds.attrs["dt_s"]
    v = amplitude_g * G / w * (1 - np.cos(w * np.minimum(t, period)))  # back to 0 after one sine
    assert np.allclose(ds.table_velocity.sel(axis="x").values, v, rtol=0, atol=amplitude_g * G * step)
    d = amplitude_g * G / w * (np.minimum(t, period) - np.sin(w * np.minimum(t, period)) / w)
    assert np.allclose(ds.table_displacement.sel(axis="x").values, d, rtol=0, atol=v.max() * step)
    assert abs(ds.table_displacement.sel(axis="x").values[-1] / (amplitude_g * G * period / w) - 1) < 1e-3
    assert np.all(ds.table_acceleration.sel(axis=["y", "z"]).values == 0)
    assert float(ds.tilt.max()) < 0.05 and not ds.attrs["overturned"]
    assert np.all(ds.contacts.values[1:] > 0)  # the first frame is before any step (no contacts yet)


def test_history_equals_the_cli_table(engine, rigid, tmp_path):
    csv = str(tmp_path / "h.csv")
    r = run([rigid, "run", SCENE, "--motion", RECORD, "--target-pga", "0.6", "--rotation", "30", "--history", csv])
    assert r.returncode == 0, r.stderr
    table = rigidpy.history_from_csv(csv)
    ds = rigidpy.run(SCENE, motion=RECORD, target_pga=0.6, rotation=30.0)
    for var in ("tilt", "slip", "contacts", "position", "orientation", "contact_force", "table_acceleration"):
        assert np.allclose(table[var].values, ds[var].values, rtol=1e-12, atol=1e-12), var
    assert same(table.time.values, ds.time.values)
    assert np.allclose(table.base_height.values, ds.base_height.values, rtol=1e-12)
    # block_a03: a 1 m high rectangular block, its centre 0.5 m above its base (its model file's comment)
    assert abs(float(ds.base_height[0]) - 0.5) < 1e-6


@pytest.mark.parametrize("kwargs, words", [
    ({"scene": "no_such_scene.toml", "motion": RECORD}, "no_such_scene.toml"),
    ({"scene": SCENE, "motion": "no_such_record-X.AT2"}, "no_such_record"),
    ({"scene": SCENE, "motion": RECORD, "contact": "glue"}, "contact"),
    ({"scene": SCENE, "motion": RECORD, "target_pga": -1}, "target_pga"),
    ({"scene": SCENE, "motion": RECORD, "model": "rocking2d", "dt": 1e-3}, "rocking2d"),
])
def test_bad_input_raises_one_line(engine, kwargs, words):
    with pytest.raises(InputError) as e:
        rigidpy.run(**kwargs)
    assert words in str(e.value) and "\n" not in str(e.value)


# ----------------------------------------------------------------------------------------------
# rigid run --plot / --animate


SIGNATURES = {".pdf": b"%PDF", ".png": b"\x89PNG", ".svg": b"<?xml", ".gif": b"GIF8"}


def test_plot_and_animate(rigid, tmp_path):
    pytest.importorskip("matplotlib")
    figures = [str(tmp_path / f"run{e}") for e in (".pdf", ".svg", ".png")]
    outputs = list(figures)
    for i, path in enumerate(figures):
        cmd = [rigid, "run", SCENE, "--motion", RECORD, "--target-pga", "0.6", "--rotation", "30", "--plot", path]
        if i == 0:
            pytest.importorskip("PIL")
            cmd += ["--animate", str(tmp_path / "run.gif"), "--json"]
            outputs.append(str(tmp_path / "run.gif"))
        r = run(cmd)
        assert r.returncode == 0, r.stderr
        if i == 0:
            assert json.loads(r.stdout)["overturned"]  # --json's standard output stays one JSON object
    for path in outputs:
        with open(path, "rb") as f:
            assert f.read(5).startswith(SIGNATURES[os.path.splitext(path)[1]]), path
    assert not glob.glob(str(tmp_path / ".*tmp")), "a temporary was left behind"


@pytest.mark.parametrize("flags", [["--plot", "x.jpg"], ["--animate", "x.mp4"], ["--plot", "x.png", "--model", "rocking2d"]])
def test_plot_bad_input(rigid, tmp_path, flags):
    r = run([rigid, "run", SCENE, "--motion", RECORD, *flags], cwd=str(tmp_path))
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "rigid: error:" in r.stderr
    assert not os.listdir(tmp_path)
