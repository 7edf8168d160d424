"""The /fragility group `rigid fragility` stores into the cube (docs/cube.md): each object's fits
with dimension scales netCDF readers understand, written into a private copy of the cube that
replaces it (files.py), so a failure never leaves a half-written cube."""
import math
import os
import shutil

import h5py
import numpy as np

from . import files as cube_files
from .errors import InputError
from .object_fits import METHOD, SENSITIVITY_METHOD, variant_lognormal


def write_fit_group(og, fit):
    """One object's (variant's) fits into the HDF5 group og: attributes, per-bin datasets, the
    vector fit (the layout of a cube without variants)."""
    og.attrs["description"] = f"fragility of object {fit.obj.name}"
    og.attrs["fitted_cells_sha256"] = fit.obj.attrs.get("datasets_sha256", "")
    og.attrs["inferred_cells_left_out"] = np.int64(fit.cells.inferred)
    for key, value in (("alpha_rad", fit.norm.alpha), ("p_rad_s", fit.norm.p)):
        if value:
            og.attrs[key] = float(value)

    def column(key, index=None, dtype=float, missing=math.nan):
        vals = []
        for r in fit.bins:
            v = r.get(key)
            vals.append(missing if v is None else (v[index] if index is not None else v))
        return np.asarray(vals, dtype)

    specs = [("pgv_pga_edges_s", np.asarray(fit.edges, float), "s", "bin i: edges[i] <= PGV/PGA < edges[i+1]"),
             ("theta_g", column("theta_g"), "g", "median PGA of the bin's lognormal fragility (NaN: no fit)"),
             ("theta_lower_g", column("theta_interval_g", 0), "g", "lower end of its interval"),
             ("theta_upper_g", column("theta_interval_g", 1), "g", "upper end of its interval"),
             ("beta", column("beta"), "1", "dispersion (standard deviation of ln PGA)"),
             ("beta_lower", column("beta_interval", 0), "1", "lower end of its interval"),
             ("beta_upper", column("beta_interval", 1), "1", "upper end of its interval"),
             ("n_records", column("n_records", dtype=np.int32, missing=0), "1", "records of the bin with simulated cells"),
             ("n_cells", column("n_cells", dtype=np.int32, missing=0), "1", "simulated cells fitted"),
             ("n_overturned", column("n_overturned", dtype=np.int32, missing=0), "1", "overturned among them")]
    bins = dimension(og, "pgv_pga_bin", np.arange(len(fit.edges) - 1, dtype=np.int32), "1",
                     "PGV/PGA bin index; bin i holds pgv_pga_edges_s[i] <= PGV/PGA < pgv_pga_edges_s[i+1]")
    for name, data, units, text in specs:
        ds = og.create_dataset(name, data=data)
        ds.attrs["units"] = units
        ds.attrs["description"] = text
        if name == "pgv_pga_edges_s":
            ds.make_scale(name)  # E = B + 1 edges: a dimension of its own, its own coordinate
        else:
            ds.dims[0].attach_scale(bins)
    v = fit.vector
    if "fit" in v:
        vg = og.create_group("vector")
        vg.attrs["description"] = "P = Phi((u - mu(x)) / sigma(x)); u, x as the attributes say"
        vg.attrs["u"], vg.attrs["x"] = fit.norm.describe()
        for key in ("mu_coefficients", "log_sigma_coefficients", "mu_se", "log_sigma_se"):
            vg.attrs[key] = np.asarray(v["fit"][key], float)
        c = fit.chosen()
        vg.attrs["pgv_pga_s"] = c["pgv_pga_s"]
        vg.attrs["theta_g"], vg.attrs["beta"] = c["theta_g"], c["beta"]
        vg.attrs["theta_interval_g"] = np.asarray(c["theta_interval_g"], float)
        vg.attrs["beta_interval"] = np.asarray(c["beta_interval"], float)


# netCDF-4 readers (xarray's h5netcdf and netcdf4 engines) see a dimension only through a dimension
# scale in the variable's group or an ancestor: every dataset of a /fragility group has one attached
# to each of its dimensions, else xarray refuses the group without phony_dims.
def dimension(group, name, values, units, text):
    """A coordinate variable: a dataset `name` that is the dimension scale of the dimension `name`."""
    if isinstance(values, list) and values and isinstance(values[0], str):
        ds = group.create_dataset(name, data=np.array(values, dtype=object), dtype=h5py.string_dtype("utf-8"))
    else:
        ds = group.create_dataset(name, data=values)
    if units is not None:
        ds.attrs["units"] = units
    ds.attrs["description"] = text
    ds.make_scale(name)
    return ds


def attach(ds, *scales):
    """Attaches one dimension scale to each dimension of ds; a trailing dimension of 2 (an interval)
    gets the group's `bound` scale (lower, upper), made on first use."""
    group = ds.parent
    for i in range(ds.ndim):
        if i < len(scales):
            ds.dims[i].attach_scale(scales[i])
        elif ds.shape[i] == 2:
            bound = group["bound"] if "bound" in group else dimension(group, "bound", ["lower", "upper"], None,
                                                                      "the two ends of an interval")
            ds.dims[i].attach_scale(bound)
    return ds


def write_string_dataset(group, name, values, text, scale=None):
    ds = group.create_dataset(name, data=np.array(values, dtype=object), dtype=h5py.string_dtype("utf-8"))
    ds.attrs["description"] = text
    return attach(ds, scale) if scale is not None else ds


def write_number_dataset(group, name, values, units, text, scale=None):
    ds = group.create_dataset(name, data=np.asarray(values, float))
    ds.attrs["units"] = units
    ds.attrs["description"] = text
    return attach(ds, scale) if scale is not None else ds


def write_variant_groups(g, cube, fits, analyses):
    """With variants, /fragility/<object> holds: per variant a group v<K> laid out as an object's
    group without variants (plus the scalar fit over all records and the empirical threshold as
    attributes); `variant_fragility` (datasets [variant]: the lognormal standing for each variant
    and where it comes from); `pooled` (the mixture and the epistemic spread); `sensitivity`."""
    by_name = {}
    for f in fits:
        by_name.setdefault(f.obj.name, []).append(f)
    analysis = {a.name: a for a in analyses}
    for name, group in by_name.items():
        og = g.create_group(name)
        og.attrs["description"] = f"fragility of object {name}, per variant and pooled over variants"
        og.attrs["variants"] = np.int32(cube.variants.count)
        og.attrs["fitted_cells_sha256"] = group[0].obj.attrs.get("datasets_sha256", "")
        for f in group:
            vg = og.create_group(f"v{f.obj.variant}")
            write_fit_group(vg, f)
            vg.attrs["description"] = f"fragility of object {name}, variant {f.obj.variant}"
            vg.attrs["variant"] = np.int32(f.obj.variant)
            if f.no_fit:
                vg.attrs["no_fit"] = f.no_fit
            if f.scalar is not None and "theta_g" in f.scalar:
                vg.attrs["scalar_theta_g"], vg.attrs["scalar_beta"] = f.scalar["theta_g"], f.scalar["beta"]
                vg.attrs["scalar_theta_interval_g"] = np.asarray(f.scalar["theta_interval_g"], float)
                vg.attrs["scalar_beta_interval"] = np.asarray(f.scalar["beta_interval"], float)
            if f.threshold is not None:
                vg.attrs["empirical_threshold_g"] = f.threshold["theta_g"]
                vg.attrs["empirical_threshold_between_g"] = np.asarray(f.threshold["between_g"], float)
        d = [variant_lognormal(f) for f in group]
        sg = og.create_group("variant_fragility")
        sg.attrs["description"] = ("the lognormal standing for each variant in the pool and the sensitivity: the "
                                   "vector fit at pgv_pga_s, or the empirical threshold (beta 0) of separated outcomes")
        sg.attrs["pgv_pga_s"] = float(group[0].pgv_pga_s)
        variant = dimension(sg, "variant", np.array([f.obj.variant for f in group], np.int32), "1", "variant index")
        write_number_dataset(sg, "theta_g", [x["theta_g"] for x in d], "g", "median PGA (NaN: no fragility)", variant)
        write_number_dataset(sg, "beta", [x["beta"] for x in d], "1", "dispersion (0: a step)", variant)
        for key, unit in (("theta_interval_g", "g"), ("beta_interval", "1")):
            write_number_dataset(sg, key, [x.get(key, (math.nan, math.nan)) for x in d], unit,
                                 "bootstrap interval over records [variant, 2] (NaN: none)", variant)
        write_string_dataset(sg, "source", [x["source"] for x in d], "vector fit, empirical threshold or none", variant)
        a = analysis.get(name)
        if a is None:
            continue
        if a.pooled is not None:
            p = a.pooled
            pg = og.create_group("pooled")
            pg.attrs["description"] = (("equally weighted mixture of the variants' lognormals, P(a) = mean_v P_v(a), "
                                        if a.calibration is None else
                                        "mixture of the variants' lognormals by their calibration weights, P(a) = "
                                        "sum_v w_v P_v(a) (w_v renormalised over the variants pooled), ")
                                       + "and the epistemic spread over variants")
            pg.attrs["weights"] = a.weights_text()
            pg.attrs["n_variants"] = np.int32(p["n_variants"])
            pg.attrs["median_g"] = p["median_g"]
            pg.attrs["lognormal_theta_g"], pg.attrs["lognormal_beta"] = p["lognormal_theta_g"], p["lognormal_beta"]
            pg.attrs["lognormal_method"] = p["lognormal_method"]
            pg.attrs["percentiles"] = np.asarray(p["percentiles"], np.int32)
            pg.attrs["theta_percentiles_g"] = np.asarray(p["theta_percentiles_g"], float)
            pg.attrs["beta_percentiles"] = np.asarray(p["beta_percentiles"], float)
            pga = dimension(pg, "pga_g", np.asarray(p["pga_g"], float), "g", "PGA grid")
            write_number_dataset(pg, "mixture_probability", p["mixture_probability"], "1", "pooled P(overturn)", pga)
            write_number_dataset(pg, "band_lower", p["band_lower"], "1", "5th percentile of P_v over variants", pga)
            write_number_dataset(pg, "band_upper", p["band_upper"], "1", "95th percentile of P_v over variants", pga)
        rows = a.sensitivity
        if rows:
            tg = og.create_group("sensitivity")
            tg.attrs["description"] = SENSITIVITY_METHOD
            parameter = dimension(tg, "parameter", [r["parameter"] for r in rows], None, "varied or derived parameter")
            write_string_dataset(tg, "kind", [r["kind"] for r in rows], "varied, text (category order) or derived",
                                 parameter)
            write_string_dataset(tg, "note", [r["note"] for r in rows], "why a statistic is missing", parameter)
            for out in ("theta", "beta"):
                attach(tg.create_dataset(f"n_{out}", data=np.array([r[f"n_{out}"] for r in rows], np.int32)), parameter)
                for stat in ("rho", "prcc"):
                    write_number_dataset(tg, f"{stat}_{out}", [r[f"{stat}_{out}"] for r in rows], "1",
                                         f"{stat} of the parameter with {out} across variants", parameter)
                    write_number_dataset(tg, f"{stat}_{out}_interval", [r[f"{stat}_{out}_interval"] for r in rows],
                                         "1", "bootstrap interval over variants [parameter, 2]", parameter)


def store(path, cube, fits, args, analyses=None):
    """Writes the /fragility group into a private copy of the cube (cube_files.private_temporary)
    and renames it over the cube, so a crash or a full disk leaves the cube as it was and no
    temporary behind. The caller holds the cube's lock; the cube must not have changed since it
    was read (a writer that ignores the lock)."""
    before = os.stat(path)
    with cube_files.private_temporary(path, mode=before.st_mode & 0o7777) as tmp:
        shutil.copyfile(path, tmp)
        with h5py.File(tmp, "a") as f:
            if "fragility" in f:
                del f["fragility"]
            g = f.create_group("fragility")
            g.attrs["description"] = "fitted fragility functions (rigid fragility); refitted by each run"
            g.attrs["method"] = METHOD
            g.attrs["bootstrap_replicates"] = np.int32(args.bootstrap)
            g.attrs["seed"] = np.uint64(args.seed)
            g.attrs["interval_level"] = float(args.level)
            if cube.variants is None:
                for fit in fits:
                    write_fit_group(g.create_group(fit.obj.name), fit)
            else:
                write_variant_groups(g, cube, fits, analyses or [])
        now = os.stat(path)
        if (now.st_mtime_ns, now.st_size, now.st_ino) != (before.st_mtime_ns, before.st_size, before.st_ino):
            raise InputError(f"{path}: the cube changed while it was fitted (a campaign writing it?); not stored, "
                             f"run again once it is done")
