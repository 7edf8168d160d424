"""The example notebook docs/notebooks/first_steps.ipynb runs from top to bottom without an error
(nbclient, an ipykernel kernel), on the cube of jobs/ci_small.toml and with the package laid out
as an install lays it (rigidpy beside its built extension). Skipped with a message when
nbformat, nbclient or ipykernel is missing (Debian: python3-nbformat python3-nbclient
python3-ipykernel) or the extension is not built.

    /usr/bin/python3 -m pytest tests/python/test_notebook.py --rigid RIGID --engine BUILD/python
"""
import glob
import os
import shutil
import subprocess

import pytest

nbformat = pytest.importorskip("nbformat", reason="python3-nbformat is not installed")
nbclient = pytest.importorskip("nbclient", reason="python3-nbclient is not installed")
pytest.importorskip("ipykernel", reason="python3-ipykernel is not installed")
pytest.importorskip("xarray")

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
NOTEBOOK = os.path.join(SOURCE, "docs", "notebooks", "first_steps.ipynb")


def test_first_steps_notebook_runs(rigid, request, tmp_path):
    built = glob.glob(os.path.join(request.config.getoption("--engine") or "", "rigidpy", "_engine*.so"))
    if not built:
        pytest.skip("no built extension (--engine BUILD/python; CMake builds it when pybind11-dev is installed)")
    package = tmp_path / "site"
    shutil.copytree(os.path.join(SOURCE, "src", "python", "rigidpy"), package / "rigidpy",
                    ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(built[0], package / "rigidpy")
    cube = str(tmp_path / "ci.h5")
    r = subprocess.run([rigid, "campaign", os.path.join(SOURCE, "jobs", "ci_small.toml"), "--out", cube,
                        "--progress", "none"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    os.environ.update(PYTHONPATH=str(package), RIGID_CUBE=cube, MPLBACKEND="Agg")
    nb = nbformat.read(NOTEBOOK, as_version=4)
    client = nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                                     resources={"metadata": {"path": os.path.dirname(NOTEBOOK)}})
    client.execute()
    outputs = [o for cell in nb.cells if cell.cell_type == "code" for o in cell.get("outputs", [])]
    assert not [o for o in outputs if o.output_type == "error"]
    text = "".join(o.get("text", "") for o in outputs)
    assert str(package) in text, "the notebook imported another rigidpy than the one laid out here"
    assert "survival over 10,000 years" in text and "'overturned': 1" in text
