"""`rigid run --trajectory`: the XDMF file is well-formed, every DataItem it references exists in
the HDF5 file with the stated shape, frames advance in time, and the pedestal stays a rigid box
(its vertex distances do not change). With ParaView's pvpython present it also opens the file.
Run: /usr/bin/python3 -m pytest tests/python/test_trajectory.py --rigid RIGID (skipped without h5py)."""
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest

h5py = pytest.importorskip("h5py")
np = pytest.importorskip("numpy")


def test_trajectory_xdmf(rigid, source_dir, tmp):
    src = source_dir
    xdmf = os.path.join(tmp, "run.xdmf")
    subprocess.run([rigid, "run", os.path.join(src, "models/demo/block_a02.toml"),
                    "--motion", os.path.join(src, "waveforms/demo/pulse_sine_0p5s-X.AT2"),
                    "--factor", "0.35", "--trajectory", xdmf, "--json"], check=True,
                   stdout=subprocess.DEVNULL)
    tree = ET.parse(xdmf)
    h5 = h5py.File(os.path.join(tmp, "run.h5"), "r")
    items = 0
    for d in tree.iter("DataItem"):
        name, path = d.text.strip().split(":")
        assert name == "run.h5", name
        dims = tuple(int(x) for x in d.get("Dimensions").split())
        assert h5[path].shape == dims, (path, h5[path].shape, dims)
        items += 1
    times = [float(t.get("Value")) for t in tree.iter("Time")]
    assert len(times) > 10 and all(b > a for a, b in zip(times, times[1:])), "time must increase"
    assert np.allclose(times, h5["time"][()])
    # the pedestal (block0) is rigid: pairwise vertex distances are the same in every frame
    first = h5["block0/xyz/0"][()]
    last = h5["block0/xyz/%d" % (len(times) - 1)][()]
    d0 = np.linalg.norm(first[:, None] - first[None], axis=2)
    d1 = np.linalg.norm(last[:, None] - last[None], axis=2)
    assert np.allclose(d0, d1, atol=1e-12)
    pvpython = shutil.which("pvpython")
    if pvpython:
        script = ("from paraview.simple import *\n"
                  "r = XDMFReader(FileNames=[%r])\n"
                  "r.UpdatePipeline(%r)\n"
                  "print('paraview frames', len(r.TimestepValues))\n") % (xdmf, times[-1])
        out = subprocess.run([pvpython, "--force-offscreen-rendering", "-c", script], capture_output=True, text=True)
        print(out.stdout.strip(), out.stderr.strip()[-500:])
        assert out.returncode == 0 and ("paraview frames %d" % len(times)) in out.stdout
    print("ok: %d data items, %d frames%s" % (items, len(times), ", opened by pvpython" if pvpython else ""))
