"""`rigidpy.run(scene, motion=..., target_pga=..., ...)`: one simulation through the C++ engine
(the extension rigidpy._engine, src/pyengine/engine.cpp, over the path `rigid run` takes), returned
as an xarray Dataset with a time coordinate: each free block's tilt, slip, pose and contact state
and the table's motion, with the outcome in its attrs (docs/python.md). `history_from_csv` reads
the table `rigid run --history` writes (io/history_csv.hpp) into the same Dataset, so the figure
of `rigid run --plot` (history_figure.py) is drawn from the same thing a notebook gets."""
import math
import os

import numpy as np

from .cube_dataset import _xarray
from .errors import InputError

AXES = ("x", "y", "z")
QUATERNION = ("w", "x", "y", "z")
# variable -> (dimensions after time, long name, units)
VARIABLES = {
    "tilt": (("block",), "tilt from the block's initial orientation", "degree"),
    "slip": (("block",), "accumulated frictional slip", "m"),
    "contacts": (("block",), "loaded subcontacts touching the block", "1"),
    "position": (("block", "axis"), "centre of mass, world frame", "m"),
    "orientation": (("block", "quaternion"), "body-to-world unit quaternion (w, x, y, z)", "1"),
    "contact_force": (("block", "axis"), "total contact force on the block", "N"),
    "table_displacement": (("axis",), "table (first fixed block) displacement from its start", "m"),
    "table_velocity": (("axis",), "table velocity", "m s-1"),
    "table_acceleration": (("axis",), "ground acceleration driving the table, linear between the record's "
                                      "samples", "m s-2"),
}
OUTCOME_KEYS = ("overturned", "failure_time_s", "failed_block", "steps", "dt_s", "simulated_s", "max_tilt_deg",
                "max_slip_m", "max_overlap_m", "ended_at_rest", "unconverged_steps", "max_solver_sweeps")


def _engine():
    try:
        from . import _engine as engine
    except ImportError as e:
        raise ImportError(
            "rigidpy.run needs the compiled engine rigidpy._engine: install the package from the checkout "
            "(python3 -m venv --system-site-packages venv && venv/bin/pip install --no-build-isolation .; "
            f"docs/python.md) ({e})") from e
    return engine


def _path(p, what):
    if p is None:
        return ""
    p = os.fspath(p)
    if not isinstance(p, str) or not p:
        raise InputError(f"{what}: expected a file path")
    return p


def run(scene, motion=None, target_pga=None, rotation=0.0, contact=None, *, factor=1.0, start=0.0, end=None,
        model=None, accuracy=None, effects=None, integrator=None, state=None, duration=None, free_time=None,
        dt=None, safety=None, interval=0.01):
    """Shakes `scene` (a .toml scene or a Rigid model file) with `motion` (PEER AT2: NAME-X.AT2,
    whose -Y and -Z siblings join, or "H1.AT2,H2.AT2[,V.AT2]"), windowed to [start, end] s,
    scaled to `target_pga` g (GMRotI50) times `factor`, its horizontals rotated by `rotation`
    degrees; the settings are `rigid run`'s flags of the same names (contact "rigid" or "penalty",
    model "dem3d" or "rocking2d", accuracy, effects, integrator, state, duration, free_time, dt,
    safety; None: `rigid run`'s default). Frames every `interval` s of simulated time.

    Returns an xarray Dataset: coordinate `time` (s), variables tilt, slip, contacts, position,
    orientation, contact_force [time, block(, axis)] and table_displacement, table_velocity,
    table_acceleration [time, axis]; attrs: the outcome as `rigid run --json` gives it
    (overturned, failure_time_s (NaN when it did not), max_tilt_deg, ...), the engine, the
    motion's name. With model "rocking2d" the Dataset has the outcome only (the 2D model has no
    blocks to record). Bad input raises rigidpy.errors.InputError with the one-line message."""
    engine = _engine()
    request = engine.RunRequest()
    request.scene = _path(scene, "scene")
    request.motion = _path(motion, "motion")
    numbers = {"target_pga_g": (target_pga, 0.0), "factor": (factor, 1.0), "start_s": (start, 0.0),
               "end_s": (end, math.inf), "rotation_deg": (rotation, 0.0), "interval_s": (interval, 0.01)}
    for attr, (value, default) in numbers.items():
        try:
            setattr(request, attr, default if value is None else float(value))
        except (TypeError, ValueError):
            raise InputError(f"{attr.rsplit('_', 1)[0] if attr != 'factor' else attr}: {value!r} is not a number")
    texts = {"contact": contact, "model": model, "accuracy": accuracy, "effects": effects, "integrator": integrator}
    for attr, value in texts.items():
        if value is not None:
            if not isinstance(value, str):
                raise InputError(f"{attr}: {value!r}: expected text")
            setattr(request, attr, value)
    if state is not None:
        request.state = _path(state, "state")
    for attr, value in (("duration_s", duration), ("free_time_s", free_time), ("dt_s", dt), ("safety", safety)):
        if value is not None:
            try:
                setattr(request, attr, float(value))
            except (TypeError, ValueError):
                raise InputError(f"{attr.replace('_s', '')}: {value!r} is not a number")
    result = engine.run(request)
    outcome = dict(result["outcome"])
    attrs = {k: (math.nan if outcome[k] is None else outcome[k]) for k in OUTCOME_KEYS}
    attrs.update(engine=result["engine"], motion=result["motion"]["name"], scene=request.scene)
    attrs = {k: (int(v) if isinstance(v, bool) else v) for k, v in attrs.items()}
    if "history" not in result:
        return _xarray().Dataset(attrs=attrs)
    h = result["history"]
    arrays = {"tilt": np.degrees(h["tilt_rad"]), "slip": h["slip_m"], "contacts": h["contacts"],
              "position": h["position_m"], "orientation": h["orientation"], "contact_force": h["contact_force_n"],
              "table_displacement": h["table_displacement_m"], "table_velocity": h["table_velocity_m_s"],
              "table_acceleration": h["table_acceleration_m_s2"]}
    return history_dataset(h["time_s"], list(h["block"]), arrays, attrs, h["base_height_m"])


def history_dataset(time_s, blocks, arrays, attrs, base_height_m):
    """The Dataset of a time history: `arrays` (variable -> array [time, ...] in VARIABLES' units);
    `base_height_m` per block, its centre of mass above its lowest point at the start."""
    xr = _xarray()
    data = {}
    for name, (dims, long_name, units) in VARIABLES.items():
        data[name] = xr.Variable(("time",) + dims, np.asarray(arrays[name]), {"long_name": long_name, "units": units})
    coords = {"time": ("time", np.asarray(time_s, float), {"long_name": "simulated time", "units": "s"}),
              "block": ("block", np.array(blocks, dtype=object)),
              "base_height": ("block", np.asarray(base_height_m, float),
                              {"long_name": "centre of mass above the block's lowest point at the start", "units": "m"}),
              "axis": ("axis", list(AXES)),
              "quaternion": ("quaternion", list(QUATERNION))}
    return xr.Dataset(data, coords=coords, attrs=dict(attrs))


def history_from_csv(path, attrs=None):
    """The table `rigid run --history` writes (io/history_csv.hpp) as history_dataset's Dataset."""
    import csv
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})")
    if len(rows) < 2 or not rows[0] or rows[0][0] != "time_s":
        raise InputError(f"{path}: not a history table of `rigid run --history` (no time_s column or no rows)")
    header = rows[0]
    try:
        values = np.array([[float(v) if v else math.nan for v in r] for r in rows[1:]])
    except ValueError as e:
        raise InputError(f"{path}: a field is not a number ({e})")
    if values.shape[1] != len(header):
        raise InputError(f"{path}: rows of {values.shape[1]} fields under a header of {len(header)}")
    column = {name: i for i, name in enumerate(header)}
    blocks = [name.split(":", 1)[1] for name in header if name.startswith("tilt_deg:")]

    def table(stem):
        return values[:, [column[f"{stem}:{a}"] for a in AXES]]

    def per_block(stem, parts=None):
        if parts is None:
            return values[:, [column[f"{stem}:{b}"] for b in blocks]]
        return values[:, [[column[f"{stem}:{p}:{b}"] for p in parts] for b in blocks]]

    try:
        arrays = {"tilt": per_block("tilt_deg"), "slip": per_block("slip_m"),
                  "contacts": per_block("contacts").astype(np.int64), "position": per_block("position_m", AXES),
                  "orientation": per_block("orientation", QUATERNION),
                  "contact_force": per_block("contact_force_n", AXES),
                  "table_displacement": table("table_displacement_m"), "table_velocity": table("table_velocity_m_s"),
                  "table_acceleration": table("table_acceleration_m_s2")}
    except KeyError as e:
        raise InputError(f"{path}: column {e} is missing")
    base = values[0, [column[f"base_height_m:{b}"] for b in blocks]] if len(values) else []
    return history_dataset(values[:, 0], blocks, arrays, attrs or {}, base)
