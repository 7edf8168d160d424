"""`rigidpy.open_cube(path)`: a whole fragility cube as one xarray Dataset (docs/python.md).

The cube (docs/cube.md) keeps one HDF5 group per object, each opened by xarray on its own; here
the objects are one dimension, so `ds.outcome.sel(object="block_a03", scale=0.3)` or
`ds.probability.mean("record")` work across the cube. The cube is read through rigidpy's one
reader (cube.Cube: checksums verified, derived datasets recomputed from the cells), and the cell
datasets it does not keep are read beside it with h5py. What the group-by-group view lacks is
added: the PGV/PGA bins as a coordinate with CF bounds, each record's PGA, PGV and PGV/PGA as
coordinates on `record`, the variants' parameters and the calibration's weights as coordinates on
`variant`.

An as-recorded cube (one scale, 0.0: each record at its own amplitude) is laid on the records'
measured PGAs, as every rigid command reads it (cube.Cube._lay_on_record_pgas): the padding
cells are `not_run` (NaN for the numbers, -1 for the codes) and `padding` marks them.
"""
import math

import h5py
import numpy as np

from .cube import Cube, NOT_RECORDED
from .outcomes import CODES, bins_of_records

# the cell datasets beside `outcome` ([R, S, A] or [V, R, S, A]): name -> (fill of a padding cell)
CELL_NUMBERS = {"rotation_deg": np.nan, "failure_time_s": np.nan, "max_tilt_deg": np.nan, "max_slip_m": np.nan,
                "wall_s": np.nan, "failure_reason": 0}
REASONS = "none exception non_finite worker_lost"
RECORD_COLUMNS = {  # /records column -> (coordinate name, units, long name)
    "gmroti_pga_g": ("record_pga_g", "1", "GMRotI50 PGA of the windowed record, in units of g"),
    "gmroti_pgv_cm_s": ("record_pgv_cm_s", "cm s-1", "GMRotI50 PGV of the windowed record"),
    "pgv_pga_s": ("pgv_pga_s", "s", "PGV/PGA of the record (it bins the fragility)"),
    "listed_pga_g": ("listed_pga_g", "1", "PGA given by the record list, 0 if none, in units of g"),
    "start_s": ("start_s", "s", "start of the record's time window"),
    "end_s": ("end_s", "s", "end of the record's time window (inf: to its end)"),
}


def _xarray():
    try:
        import xarray as xr
    except ImportError as e:  # pragma: no cover
        raise ImportError(f"rigidpy.open_cube needs xarray (Debian: python3-xarray): {e}") from e
    return xr


def bin_coordinates(edges):
    """The PGV/PGA bins as CF wants a binned axis: a representative value per bin (its midpoint; an
    open last bin [e, inf) its lower edge e) and the [B, 2] bounds, edges[i] <= s < edges[i + 1]."""
    edges = np.asarray(edges, float)
    lower, upper = edges[:-1], edges[1:]
    middle = np.where(np.isfinite(upper), 0.5 * (lower + upper), lower)
    return middle, np.stack([lower, upper], axis=1)


def _spread(cells, rows, cols, width, fill):
    """Cells [..., R, 1, A] of an as-recorded cube laid on the PGA axis: record r's at column cols[r]."""
    out = np.full(cells.shape[:-2] + (width,) + cells.shape[-1:], fill, dtype=np.asarray(cells).dtype
                  if not (isinstance(fill, float) and math.isnan(fill)) else float)
    out[..., rows, cols, :] = cells[..., rows, 0, :]
    return out


def open_cube(path):
    """The cube at `path` as one xarray Dataset: dimensions object, (variant,) record, scale,
    rotation and pgv_pga (the bins, with `pgv_pga_bounds`). Raises rigidpy.errors.InputError
    (one line naming the file) for a file that is not a readable, intact Rigid cube."""
    xr = _xarray()
    cube = Cube(path)
    names = cube.base_names()
    V = cube.variants.count if cube.variants is not None else None
    R, S = len(cube.records), len(cube.scales)
    lead = ("object",) if V is None else ("object", "variant")
    cells_dims = lead + ("record", "scale", "rotation")
    data = {}

    def per_object(values_of):
        """Stack per (object, variant) arrays into [object, (variant), ...]."""
        rows = []
        for name in names:
            objs = [o for o in cube.objects if o.name == name]
            arrays = [values_of(o) for o in objs]
            rows.append(arrays[0] if V is None else np.stack(arrays))
        return np.stack(rows)

    outcome = per_object(lambda o: o.outcome)
    flags = {"flag_values": np.array([c for _, c in CODES], np.int8),
             "flag_meanings": " ".join(n for n, _ in CODES), "long_name": "outcome of the simulation"}
    data["outcome"] = (cells_dims, outcome, flags)
    data["unconverged_steps"] = (cells_dims, per_object(lambda o: o.unconverged_steps),
                                 {"long_name": "steps whose rigid contact solve stopped at its sweep cap",
                                  "units": "1", "missing_value": NOT_RECORDED})
    raw = _raw_cells(cube, names, V)
    if cube.as_recorded:
        rows, cols = np.arange(R), np.searchsorted(cube.scales, cube.record_pga_g)
        raw = {k: (_spread(v, rows, cols, S, CELL_NUMBERS[k]), a) for k, (v, a) in raw.items()}
        data["padding"] = (cells_dims[:-1], per_object(lambda o: o.padding[..., 0]),
                           {"long_name": "cell added to lay the as-recorded cube on a PGA axis (never run)"})
    for key, (values, attrs) in raw.items():
        data[key] = (cells_dims, values, attrs)
    data["probability"] = (lead + ("record", "scale"), per_object(lambda o: o.probability),
                           {"long_name": "overturning probability over the rotations (overturned + inferred "
                                         "over the known cells)", "units": "1"})
    data["fragility"] = (lead + ("scale", "pgv_pga"), per_object(lambda o: o.fragility),
                         {"long_name": "P(overturn | PGA, PGV/PGA): mean probability of the bin's records",
                          "units": "1"})
    data["fragility_count"] = (lead + ("scale", "pgv_pga"), per_object(lambda o: o.count),
                               {"long_name": "records averaged in fragility", "units": "1"})
    middle, bounds = bin_coordinates(cube.edges)
    data["pgv_pga_bounds"] = (("pgv_pga", "bounds"), bounds, {"long_name": "PGV/PGA bin edges", "units": "s"})
    coords = {
        "object": ("object", np.array(names, dtype=object)),
        "record": ("record", np.array(cube.records, dtype=object)),
        "scale": ("scale", cube.scales, {"long_name": "target GMRotI50 PGA in units of g (standard gravity)",
                                         "units": "1"}),
        "target_pga": ("scale", cube.scales * 9.80665, {"long_name": "target GMRotI50 PGA", "units": "m s-2"}),
        "rotation": ("rotation", np.arange(outcome.shape[-1])),
        "pgv_pga": ("pgv_pga", middle, {"long_name": "PGV/PGA bin (midpoint; an open last bin at its lower edge)",
                                        "units": "s", "bounds": "pgv_pga_bounds"}),
        "pgv_pga_bin": ("pgv_pga", np.arange(len(middle)), {"long_name": "PGV/PGA bin index (the cube's)"}),
    }
    coords.update(_record_coords(cube))
    coords.update(_object_coords(cube, names, V))
    if V is not None:
        coords.update(_variant_coords(cube, names, V))
    ds = xr.Dataset({k: xr.Variable(*v) for k, v in data.items()},
                    coords={k: xr.Variable(*v) for k, v in coords.items()})
    ds.attrs.update(_root_attrs(cube))
    return ds


def _raw_cells(cube, names, V):
    """The cell datasets Cube does not keep, as stored, [object, (variant), R, S, A]; one that not
    every object has is left out."""
    out = {}
    with h5py.File(cube.path, "r") as f:
        for key in CELL_NUMBERS:
            arrays, attrs = [], {}
            groups = [f["objects"][name] for name in names]
            if not all(key in g for g in groups):  # a cube written without it (synthetic, older)
                continue
            for g in groups:
                arrays.append(g[key][()])
                attrs = {a: _plain(g[key].attrs[a]) for a in ("long_name", "units") if a in g[key].attrs}
            if key == "failure_reason":
                attrs.update(flag_values=np.arange(4, dtype=np.int32), flag_meanings=REASONS)
            out[key] = (np.stack(arrays), attrs)
    return out


def _record_coords(cube):
    coords = {"pgv_pga_bin_of_record": ("record", bins_of_records(cube.edges, cube.pgv_pga),
                                        {"long_name": "PGV/PGA bin of the record (index on pgv_pga)"})}
    with h5py.File(cube.path, "r") as f:
        rec = f["records"]
        for column, (name, units, long_name) in RECORD_COLUMNS.items():
            if column in rec:
                coords[name] = ("record", rec[column][()].astype(float), {"units": units, "long_name": long_name})
        for column in ("earthquake", "source"):
            if column in rec:
                coords[column] = ("record", np.array(rec[column].asstr()[()], dtype=object))
    return coords


def _object_coords(cube, names, V):
    """alpha and p of each object (each variant): what normalises the fits (map_fit.block_parameter)."""
    coords = {}
    for key, long_name, units in (("alpha_rad", "slenderness angle alpha", "rad"),
                                  ("p_rad_s", "frequency parameter p", "rad s-1")):
        rows = []
        for name in names:
            values = [float(o.attrs.get(key, cube.root_attrs.get(key, math.nan))) for o in cube.objects
                      if o.name == name]
            rows.append(values[0] if V is None else values)
        coords[key] = (("object",) if V is None else ("object", "variant"), np.array(rows, float),
                       {"long_name": long_name, "units": units})
    return coords


def _variant_coords(cube, names, V):
    coords = {"variant": ("variant", np.arange(V))}
    for name, units, values in cube.variants.parameters:
        attrs = {"long_name": cube.variants.descriptions.get(name, "") or name}
        if units:
            attrs["units"] = units
        values = np.array(values, dtype=object) if values and isinstance(values[0], str) else np.asarray(values, float)
        coords[name if name not in ("object", "record", "scale") else f"variant_{name}"] = ("variant", values, attrs)
    coords["weight"] = (("object", "variant"), np.stack([cube.variant_weights(n) for n in names]),
                        {"long_name": "weight of the variant in the object's pooled fragility (a calibration's "
                                      "member weights, else equal)", "units": "1"})
    return coords


def _plain(v):
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray) and v.dtype.kind == "O":
        return [_plain(x) for x in v]
    return v.item() if isinstance(v, np.generic) else v


def _root_attrs(cube):
    keep = ("schema_version", "software_version", "job_hash", "seed", "units", "inputs_sha256", "job_text")
    attrs = {k: _plain(cube.root_attrs[k]) for k in keep if k in cube.root_attrs}
    attrs["source"] = cube.path
    if cube.variants is not None:
        attrs["variant_method"] = cube.variants.method
    if cube.as_recorded:
        attrs["as_recorded"] = 1
    return attrs
