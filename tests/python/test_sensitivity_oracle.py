"""Sensitivity oracle of uncertainty campaigns (docs/uncertainty.md), end to end through `rigid campaign` and
`rigid fragility`.

A rectangular block on a pedestal (the library's block_a04, 1 m tall) under a quasi-static record:
the ground acceleration ramps up over 3 s and holds for 5 s, scaled to each campaign scale (the
plateau, in g). Rigid statics says the block goes (topples, or slides off its pedestal) at
a/g = min(mu, tan alpha), tan alpha = (b + d)/h for a centre of mass moved by d along the ground
acceleration's direction. The variants are a grid over friction mu and that offset d (so alpha);
the grid makes mu and d exactly uncorrelated, so any correlation of the threshold with a
parameter is the physics':

1. every variant's threshold (between its highest surviving and lowest failing scale) brackets
   g min(mu, tan alpha) within one scale step: the variants were applied as the statics assumes;
2. with mu > tan alpha for every variant, `rigid fragility`'s sensitivity table ranks alpha first
   (rank correlation and partial rank correlation near 1) and friction near zero;
3. with mu < tan alpha for every variant (sliding), friction first and alpha near zero.

    /usr/bin/python3 -m pytest tests/python/test_sensitivity_oracle.py --rigid RIGID
"""
import json
import math
import os
import subprocess

import pytest

h5py = pytest.importorskip("h5py")
pytest.importorskip("numpy")

B, H = 0.5 * math.tan(0.4), 0.5   # block_a04: half-width b, centroid height h (models/library/README.md)
OFFSETS = [-0.08, -0.0533, -0.0267, 0.0]  # d along +x: the ground accelerates +x, the block leans over its -x edge
SCALE_STEP = 0.01


def write_ramp(path, rise_s=3.0, hold_s=5.0, dt=0.005):
    n = int(round((rise_s + hold_s) / dt)) + 1
    a = [min(i * dt / rise_s, 1.0) for i in range(n)]
    with open(path, "w") as f:
        f.write("RIGID TEST RECORD (PEER NGA AT2 FORMAT)\nquasi-static ramp to 1 g, held\n"
                "ACCELERATION TIME SERIES IN UNITS OF G\n")
        f.write(f"NPTS= {n}, DT= {dt} SEC\n")
        for i in range(0, n, 5):
            f.write("".join(f"{v:15.6E}" for v in a[i:i + 5]) + "\n")


def write_job(source, d, name, frictions):
    scene = os.path.join(source, "models", "library", "block_a04", "block_a04.toml")
    text = f"""[campaign]
seed = 3
output = "{name}.h5"
scales = "0.05:0.55:{SCALE_STEP}"
rotation_angles_deg = [0.0]
stop_after = 2

[[object]]
name = "box"
scene = "{scene}"

[sweep]
method = "grid"
friction = {{ values = {frictions} }}
com_offset_x_m = {{ values = {OFFSETS} }}

[[record]]
motion = "ramp-X.AT2"

[run]
free_time_s = 1.0
"""
    path = os.path.join(d, name + ".toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def run(args, cwd):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run(args, cwd=cwd, env=env, capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stdout[-2000:], p.stderr[-2000:])
    return p


def thresholds(cube_path):
    """Per variant: (friction, offset, highest surviving scale, lowest failing scale)."""
    with h5py.File(cube_path, "r") as f:
        scales = f["axes/scale_g"][()]
        friction = f["variants/friction"][()]
        offset = f["variants/com_offset_x_m"][()]
        outcome = f["objects/box/outcome"][()]  # [variant, record, scale, rotation]
    out = []
    for v in range(outcome.shape[0]):
        o = outcome[v, 0, :, 0]
        failed = (o == 2) | (o == 3)
        survived = o == 1
        low = scales[survived].max() if survived.any() else 0.0
        high = scales[failed].min() if failed.any() else math.inf
        out.append((friction[v], offset[v], low, high))
    return out


def sensitivity_rows(rigid, d, cube):
    p = run([rigid, "fragility", cube, "--json", "--no-store"], d)
    assert p.returncode == 0, f"rigid fragility {cube} exits 0"
    if p.returncode != 0:
        return {}
    rows = json.loads(p.stdout)["variant_analysis"][0]["sensitivity"]
    return {r["parameter"]: r for r in rows}


@pytest.mark.parametrize("name, frictions, first, last", [
    ("rocking", [0.6, 0.8, 1.0], "alpha_rad", "friction"),
    ("sliding", [0.1, 0.15, 0.2], "friction", "alpha_rad")])
def test_sensitivity_ranks_the_governing_parameter_first(name, frictions, first, last, rigid, source_dir, tmp):
    d = tmp
    write_ramp(os.path.join(d, "ramp-X.AT2"))
    job = write_job(source_dir, d, name, frictions)
    p = run(["mpirun", "--oversubscribe", "-np", "2", rigid, "campaign", job, "--progress", "none"], d)
    assert p.returncode == 0, f"{name}: the campaign completes"
    cube = os.path.join(d, name + ".h5")
    worst, outside = 0.0, 0
    for mu, off, low, high in thresholds(cube):
        statics = min(mu, (B + off) / H)
        # the bracket (highest survived, lowest failed] is one scale step and holds statics (1 % slack)
        inside = low <= statics * 1.01 and statics * 0.99 <= high and high - low <= SCALE_STEP + 1e-9
        worst = max(worst, abs(0.5 * (low + high) - statics))
        if not inside:
            outside += 1
            print(f"     mu {mu:.3f}, d {off:+.4f}: threshold in ({low:.2f}, {high:.2f}] g, statics {statics:.4f} g")
    assert outside == 0, (f"{name}: every variant's threshold brackets g min(mu, tan alpha) (midpoints within "
                        f"{worst:.4f} g of statics, scale step {SCALE_STEP} g)")
    rows = sensitivity_rows(rigid, d, cube)
    # alpha is a function of the offset alone, so the two rank together; friction is the other
    same = {"alpha_rad": ("alpha_rad", "com_offset_x_m"), "friction": ("friction",)}
    table = ", ".join(f"{k} {r['rho_theta']:+.2f}" for k, r in rows.items())
    top = max(rows.values(), key=lambda r: abs(r["rho_theta"]))["parameter"]
    assert top in same[first], f"{name}: rank correlation ranks {first} first ({table})"
    assert abs(rows[first]["rho_theta"]) > 0.9, f"{name}: rho(theta) of {first} {rows[first]['rho_theta']:+.2f} > 0.9"
    assert abs(rows[last]["rho_theta"]) < 0.3, f"{name}: rho(theta) of {last} {rows[last]['rho_theta']:+.2f} near zero"
    lo, hi = rows[last]["rho_theta_interval"]
    assert lo <= 0 <= hi, f"{name}: the interval of rho(theta) of {last} [{lo:+.2f}, {hi:+.2f}] covers 0"
