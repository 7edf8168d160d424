"""`rigidpy.fragility(...)` and `rigidpy.hazard(...)`: the fits of `rigid fragility` and the
survival test of `rigid hazard` as data (docs/python.md). No second fit: the settings go through
the commands' own parser and checks (fragility.build_parser, check_arguments) and the fits are
theirs (fragility.fit_cube, hazard_command.hazard_result); nothing is printed, stored or drawn."""
import math

import numpy as np

from . import files as cube_files
from .cube_dataset import _xarray, bin_coordinates
from .errors import InputError
from .fragility import build_parser, check_arguments, fit_cube
from .fragility_report import json_clean
from .hazard_command import hazard_result

BIN_FIELDS = (("theta_g", "median toppling PGA of the bin's lognormal fit", "1"),
              ("beta", "dispersion (log standard deviation) of the bin's fit", "1"))


def _args(command, cube, options):
    """The command's parsed settings: `options` (keyword -> value; None or False: not given) as the
    flags `rigid COMMAND` takes, so every default and check is the command's."""
    argv = [command, str(cube)]
    for key, value in options.items():
        if value is None or value is False:
            continue
        flag = "--" + key.replace("_", "-")
        if value is True:
            argv.append(flag)
        elif isinstance(value, (list, tuple)):
            for v in value:
                argv += [flag, str(v)]
        else:
            argv += [flag, repr(value) if isinstance(value, float) else str(value)]
    parser = build_parser()

    def error(message):  # a Python caller gets the exception, not an exit
        raise InputError(f"rigidpy.{command}: {message}")
    for p in [parser] + [a for action in parser._subparsers._group_actions for a in action.choices.values()]:
        p.error = error
    args = parser.parse_args(argv)
    check_arguments(args)
    return args


def _interval(d, key):
    lo, hi = d.get(key) or (math.nan, math.nan)
    return (math.nan if lo is None else float(lo)), (math.nan if hi is None else float(hi))


def fragility(cube, objects=None, variant=None, pgv_pga=None, bootstrap=None, seed=None, level=None):
    """The fitted fragilities of a cube, as `rigid fragility` fits them, as an xarray Dataset:
    per object (per variant: `rock [v3]`) and PGV/PGA bin (`pgv_pga`, with CF bounds) the lognormal
    theta_g, beta and their bootstrap intervals (`*_lower`, `*_upper`) and what the fit used
    (n_records, n_cells, n_overturned); the vector fit's lognormal at its PGV/PGA (`vector_*`). The
    pooled fragility of an object's variants is in `attrs["pooled"]` ({object: dict}). Raises
    rigidpy.errors.InputError as the command exits 2. `objects`: a name or a list (default all)."""
    xr = _xarray()
    if isinstance(objects, str):
        objects = [objects]
    args = _args("fragility", cube, {"object": objects, "variant": variant, "pgv_pga": pgv_pga,
                                     "bootstrap": bootstrap, "seed": seed, "level": level, "no_store": True})
    cube_data, fits, analyses = fit_cube(args, cube_files.campaign_state(args.cube))
    middle, bounds = bin_coordinates(cube_data.edges)
    B = len(middle)
    per_bin = {}
    for name, long_name, units in BIN_FIELDS:
        values = np.full((len(fits), B), math.nan)
        lower, upper = values.copy(), values.copy()
        interval_key = "theta_interval_g" if name == "theta_g" else "beta_interval"
        for i, f in enumerate(fits):
            for b, r in enumerate(f.bins):
                values[i, b] = r.get(name, math.nan)
                lower[i, b], upper[i, b] = _interval(r, interval_key)
        stem = name[:-2] if name.endswith("_g") else name
        suffix = "_g" if name.endswith("_g") else ""
        per_bin[name] = (("object", "pgv_pga"), values, {"long_name": long_name, "units": units})
        per_bin[f"{stem}_lower{suffix}"] = (("object", "pgv_pga"), lower, {"long_name": f"lower end of {name}'s interval"})
        per_bin[f"{stem}_upper{suffix}"] = (("object", "pgv_pga"), upper, {"long_name": f"upper end of {name}'s interval"})
    for key in ("n_records", "n_cells", "n_overturned"):
        counts = np.zeros((len(fits), B), np.int64)
        for i, f in enumerate(fits):
            for b, r in enumerate(f.bins):
                counts[i, b] = r.get(key, 0)
        per_bin[key] = (("object", "pgv_pga"), counts, {"long_name": f"{key.replace('_', ' ')} of the bin's fit"})
    vector = {k: np.full(len(fits), math.nan) for k in ("vector_pgv_pga_s", "vector_theta_g", "vector_theta_lower_g",
                                                        "vector_theta_upper_g", "vector_beta", "vector_beta_lower",
                                                        "vector_beta_upper")}
    for i, f in enumerate(fits):
        c = f.chosen()
        vector["vector_pgv_pga_s"][i] = f.pgv_pga_s
        if c is not None:
            vector["vector_theta_g"][i], vector["vector_beta"][i] = c["theta_g"], c["beta"]
            vector["vector_theta_lower_g"][i], vector["vector_theta_upper_g"][i] = _interval(c, "theta_interval_g")
            vector["vector_beta_lower"][i], vector["vector_beta_upper"][i] = _interval(c, "beta_interval")
    data = dict(per_bin)
    data.update({k: (("object",), v, {"long_name": "vector fit: " + k[len("vector_"):].replace("_", " ")})
                 for k, v in vector.items()})
    data["pgv_pga_bounds"] = (("pgv_pga", "bounds"), bounds, {"units": "s"})
    coords = {"object": ("object", np.array([f.obj.label for f in fits], dtype=object)),
              "object_name": ("object", np.array([f.obj.name for f in fits], dtype=object)),
              "alpha_rad": ("object", np.array([f.norm.alpha if f.norm.alpha is not None else math.nan
                                                for f in fits], float)),
              "p_rad_s": ("object", np.array([f.norm.p if f.norm.p is not None else math.nan for f in fits], float)),
              "pgv_pga": ("pgv_pga", middle, {"units": "s", "bounds": "pgv_pga_bounds",
                                              "long_name": "PGV/PGA bin (midpoint; an open last bin at its lower edge)"}),
              "pgv_pga_bin": ("pgv_pga", np.arange(B))}
    if cube_data.variants is not None:
        coords["variant"] = ("object", np.array([f.obj.variant for f in fits], np.int64))
    ds = xr.Dataset({k: xr.Variable(*v) for k, v in data.items()},
                    coords={k: xr.Variable(*v) for k, v in coords.items()})
    ds.attrs.update(source=args.cube, bootstrap_replicates=args.bootstrap, seed=args.seed, interval_level=args.level)
    from .object_fits import METHOD
    ds.attrs["method"] = METHOD
    if analyses:
        ds.attrs["pooled"] = {a.name: json_clean(a.document()) for a in analyses}
    return ds


def hazard(cube, curve, age, object=None, variant=None, pgv_pga=None, pgv_pga_dist=None, site=None,
           confidence=None, bootstrap=None, seed=None, level=None):
    """`rigid hazard` as data: the rock's annual toppling rate under the hazard curve (a CSV path,
    any layout `rigid hazard` reads), its survival probability over `age` years, their intervals,
    whether the curve is ruled out and by what factors; the same dict `rigid hazard --json`
    prints (None for a number that is not finite). Raises rigidpy.errors.InputError as the command
    exits 2."""
    args = _args("hazard", cube, {"curve": curve, "age": float(age), "object": object, "variant": variant,
                                  "pgv_pga": pgv_pga, "pgv_pga_dist": pgv_pga_dist, "site": site,
                                  "confidence": confidence, "bootstrap": bootstrap, "seed": seed, "level": level})
    result, _ = hazard_result(args)
    return json_clean(result)
