"""Shared fixtures of the Python tests (pytest). CTest runs each file as

    /usr/bin/python3 -m pytest tests/python/test_X.py [--rigid build/bin/rigid] [--cube CUBE.h5]

Options: --rigid, the built executable (tests that run it are skipped without it; the commands of
the Python package then run through its launchers in src/python); --cube, a cube a CTest fixture
wrote (test_cube.py, test_variant_cube.py); --shared, the read-only reference data (default
../shared beside the checkout; tests that need it are skipped with a message when it is absent).
A run in which every test was skipped exits 77, CTest's SKIP_RETURN_CODE.
"""
import contextlib
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.normpath(os.path.join(HERE, "..", ".."))
PYTHON_DIR = os.path.join(SOURCE_DIR, "src", "python")
# the package under test, and this folder's helpers (synthetic_cube, compare_cubes)
for path in (PYTHON_DIR, HERE):
    if path not in sys.path:
        sys.path.insert(0, path)

LAUNCHERS = {"plot": "rigid_plot.py", "fragility": "rigid_fragility.py", "hazard": "rigid_fragility.py",
             "accuracy": "accuracy_plot.py", "shaketable": "shaketable_fragility.py"}

SKIPPED_ALL = 77


def pytest_addoption(parser):
    parser.addoption("--rigid", default=None, help="the built rigid executable")
    parser.addoption("--cube", default=None, help="a cube written by a CTest fixture")
    parser.addoption("--shared", default=os.path.join(SOURCE_DIR, "..", "shared"),
                     help="the read-only reference data (default ../shared beside the checkout)")
    parser.addoption("--engine", default=None,
                     help="test_python_api.py, test_notebook.py: the folder of the built extension "
                          "(rigidpy/_engine*.so; CMake's BUILD/python)")
    parser.addoption("--all-recordings", action="store_true",
                     help="test_lab_motion.py: compare every real recording, not every fourth")


def pytest_sessionfinish(session, exitstatus):
    """Every test skipped (a missing Debian package, no --rigid): CTest reports a skip, not a pass."""
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if reporter is None or exitstatus != 0:
        return
    stats = reporter.stats
    if stats.get("skipped") and not stats.get("passed") and not stats.get("failed"):
        session.exitstatus = SKIPPED_ALL


@pytest.fixture(scope="session")
def source_dir():
    return SOURCE_DIR


@pytest.fixture(scope="session")
def rigid(request):
    """The built executable (absolute path); the test is skipped without --rigid."""
    path = request.config.getoption("--rigid")
    if not path:
        pytest.skip("needs the built executable (--rigid PATH)")
    return os.path.abspath(path)


@pytest.fixture(scope="session")
def rigid_or_none(request):
    path = request.config.getoption("--rigid")
    return os.path.abspath(path) if path else None


def launcher(command):
    """The launcher in src/python that `rigid COMMAND` runs."""
    return os.path.join(PYTHON_DIR, LAUNCHERS[command])


@pytest.fixture(scope="session")
def tool(rigid_or_none):
    """tool(COMMAND, ARGS...): `rigid COMMAND ARGS...` through the executable when --rigid is given,
    else the package's launcher with this interpreter (`plot`, `fragility`, `hazard`)."""
    def run(command, *args):
        if rigid_or_none:
            cmd = [rigid_or_none, command, *args]
        else:
            script = launcher(command)
            cmd = [sys.executable, script, *([command] if command in ("fragility", "hazard") else []), *args]
        return subprocess.run(cmd, capture_output=True, text=True)
    return run


@pytest.fixture(scope="session")
def shared_dir(request):
    """The read-only reference data; the test is skipped with a message when it is absent."""
    path = os.path.abspath(request.config.getoption("--shared"))
    if not os.path.isdir(path):
        pytest.skip(f"{path}: no reference data (../shared beside the checkout)")
    return path


@pytest.fixture(scope="session")
def cube_path(request):
    """The cube a CTest fixture wrote (--cube); the test is skipped without it."""
    path = request.config.getoption("--cube")
    if not path:
        pytest.skip("needs a cube written by the CTest fixture (--cube PATH)")
    if not os.path.isfile(path):
        pytest.fail(f"{path}: no such cube (its CTest fixture failed?)")
    return path


@pytest.fixture
def tmp(tmp_path):
    """A fresh directory for one test, as a str (removed by pytest's own retention rules)."""
    return str(tmp_path)


@pytest.fixture
def subtest():
    """subtest(**case): names the case (engine, object, ...) in a failing assertion inside it, as
    unittest's subTest did; the test stops at the first failure."""
    @contextlib.contextmanager
    def case(**where):
        try:
            yield
        except AssertionError as e:
            raise AssertionError(f"{where}: {e}") from e
    return case
