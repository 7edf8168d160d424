"""rigidpy installs as a user installs it (docs/python.md): a copy of the checkout's tracked files,
a virtual environment that sees Debian's packages (`/usr/bin/python3 -m venv
--system-site-packages`), `pip install --no-build-isolation --no-index .` (no network: everything
comes from Debian), then `import rigidpy` from another directory finds the installed package, not
the checkout, and the acceptance command of docs/python.md prints a cube's outcomes at 0.3 g and
runs one simulation.

The extension built by CMake is installed as it is (setup.py's RIGID_PREBUILT_ENGINE) rather than
compiled a second time: the build itself is CMake's, which every build exercises.

    /usr/bin/python3 -m pytest tests/python/test_install.py --engine BUILD/python
"""
import glob
import os
import shutil
import subprocess
import sys

import pytest

pytest.importorskip("xarray")
pytest.importorskip("h5py")
np = pytest.importorskip("numpy")

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=300, **kw)


def tracked_copy(destination):
    """The checkout's tracked files (git ls-files; the worktree's own versions) copied."""
    r = run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"], cwd=SOURCE)
    if r.returncode != 0:
        pytest.skip(f"not a git checkout: {r.stderr.strip()}")
    for rel in filter(None, r.stdout.split("\0")):
        src = os.path.join(SOURCE, rel)
        if os.path.isfile(src):
            os.makedirs(os.path.dirname(os.path.join(destination, rel)), exist_ok=True)
            shutil.copy2(src, os.path.join(destination, rel))


def test_pip_install_into_a_venv_and_use_it_elsewhere(request, tmp_path):
    engine_dir = request.config.getoption("--engine")
    built = glob.glob(os.path.join(engine_dir or "", "rigidpy", "_engine*.so"))
    if not built:
        pytest.skip("no built extension (--engine BUILD/python; CMake builds it when pybind11-dev is installed)")
    if run([sys.executable, "-c", "import ensurepip"]).returncode != 0:
        pytest.skip("no venv with pip (Debian: python3-venv)")
    checkout, venv, elsewhere = tmp_path / "checkout", tmp_path / "venv", tmp_path / "elsewhere"
    tracked_copy(str(checkout))
    r = run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", str(venv)])
    assert r.returncode == 0, r.stderr
    env = dict(os.environ, RIGID_PREBUILT_ENGINE=os.path.abspath(built[0]), PIP_NO_INDEX="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
    env.pop("PYTHONPATH", None)
    r = run([str(venv / "bin" / "pip"), "install", "--no-build-isolation", "--no-index", "."], cwd=str(checkout), env=env)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    # a cube to open: synthetic_cube's planted rock (80 records, scales 0.1-2.0 g, 4 rotations)
    elsewhere.mkdir()
    cube = str(elsewhere / "planted.h5")
    import synthetic_cube as sc
    rng = np.random.default_rng(7)
    pgv_pga = np.exp(rng.uniform(-3.3, -0.7, sc.R))
    sc.write_cube(cube, pgv_pga, [("rock", sc.planted_outcomes(rng, pgv_pga, sc.MU0, sc.MU1, sc.SIGMA), {})])
    scene = os.path.join(SOURCE, "models", "demo", "block_a03.toml")
    motion = os.path.join(SOURCE, "waveforms", "demo", "mp_pulse_1s-X.AT2")
    script = (f"import rigidpy, sys; print(rigidpy.__file__); ds = rigidpy.open_cube({cube!r}); "
              f"print(ds.outcome.sel(scale=0.3)); "
              f"h = rigidpy.run({scene!r}, motion={motion!r}, target_pga=0.6, rotation=30.0); "
              f"print('overturned', h.attrs['overturned'], h.sizes['time'])")
    r = run([str(venv / "bin" / "python"), "-c", script], cwd=str(elsewhere), env=env)
    assert r.returncode == 0, r.stderr
    installed = r.stdout.splitlines()[0]
    assert installed.startswith(str(venv)), f"imported {installed}, not the installed package"
    assert "<xarray.DataArray 'outcome' (object: 1, record: 80, rotation: 4)>" in r.stdout
    assert "overturned 1" in r.stdout
