#!/usr/bin/python3
"""`rigid fragility` and `rigid hazard`: from a campaign cube to fitted fragilities, exports hazard
codes read, and the probability that a rock survived a hazard model over its exposure age.

    rigid_fragility.py fragility CUBE [--object NAME]... [--pgv-pga S] [--json] [--csv FILE]
                       [--nrml FILE] [--no-store] [--bootstrap N] [--seed N] [--level 0.9]
    rigid_fragility.py hazard CUBE --curve CURVE.csv --age YEARS [--object NAME]
                       [--pgv-pga S | --pgv-pga-dist lognormal:MEDIAN,BETA] [--site ID]
                       [--confidence 0.95] [--plot PNG] [--json]

Fits (fragility_fit.py): per PGV/PGA bin a lognormal (theta, beta) on the records of the bin, and
the vector fit P = Phi((u - mu(x)) / sigma(x)) over all records, evaluated at a chosen PGV/PGA;
90 % intervals by bootstrap over records. Hazard (hazard_curve.py): lambda = E[H(C)], survival
exp(-lambda T). Exit status: 0 done, 2 bad input, 1 internal error.
"""
import argparse
import csv
import json
import math
import os
import shutil
import sys

try:
    import h5py
    import numpy as np
    from numpy.polynomial.hermite_e import hermegauss
    import fragility_fit as ff
    import hazard_curve as hc
    import nrml
    from rigid_plot import Cube, InputError, Normalisation, block_parameter, parse_per_object
except ImportError as e:  # pragma: no cover
    sys.stderr.write(f"rigid: error: {e}; install python3-numpy python3-h5py python3-scipy python3-matplotlib "
                     f"and run with /usr/bin/python3 (this is {sys.executable})\n")
    sys.exit(2)

METHOD = ("maximum likelihood (probit) on the simulated cells (overturned 1, survived 0); the stop rule's "
          "inferred cells, not-run and failed cells left out; per PGV/PGA bin P = Phi(ln(PGA/theta)/beta) on "
          "the bin's records; vector fit P = Phi((u - mu(x))/sigma(x)), u = ln(PGA/(g tan alpha)), "
          "x = ln((PGV/PGA) p/alpha), mu linear, sigma constant (this project's form, not Purvance et al. "
          "2008's coefficients); intervals: percentile bootstrap over records (Hesterberg's expanded "
          "percentile), records resampled with replacement")


def number_in(text, option, low=None, high=None):
    try:
        v = float(text)
    except ValueError:
        raise InputError(f"{option} {text!r}: expected a number")
    if not math.isfinite(v) or (low is not None and v < low) or (high is not None and v > high):
        raise InputError(f"{option} {text!r}: must be in [{low}, {high}]")
    return v


class ObjectFit:
    """Everything `rigid fragility` reports of one object."""

    def __init__(self, cube, obj, args, points_s=None):
        alpha, alpha_src = block_parameter(cube, obj, "alpha_rad", parse_per_object(None, "--alpha"))
        p, p_src = block_parameter(cube, obj, "p_rad_s", parse_per_object(None, "--p"))
        self.norm = Normalisation(alpha, alpha_src, p, p_src)
        self.obj = obj
        self.cells = ff.Cells(obj.outcome, cube.scales, cube.pgv_pga)
        if self.cells.n.sum() == 0:
            raise InputError(f"{cube.path}: object {obj.name}: no simulated cell (nothing to fit)")
        if self.cells.k.sum() == 0:
            raise InputError(f"{cube.path}: object {obj.name}: no overturned cell among its {int(self.cells.n.sum())} "
                             f"simulated cells: no fragility to fit (the campaign's scales stay below it)")
        index = int(obj.attrs.get("index", 0))
        records = self.cells.records_with_cells()
        self.pgv_pga_s = (args.pgv_pga if args.pgv_pga is not None
                          else float(np.median(cube.pgv_pga[records])))
        self.points_s = [self.pgv_pga_s] if points_s is None else list(points_s)
        bins = cube.bin_of_records()
        self.edges = cube.edges
        self.bins = []
        for b in range(len(cube.edges) - 1):
            rng = np.random.default_rng([args.seed, index, 1 + b])
            r = ff.scalar_fragility(self.cells, np.flatnonzero(bins == b), rng, args.bootstrap, args.level)
            r.update(bin=b, lower_s=float(cube.edges[b]), upper_s=float(cube.edges[b + 1]))
            self.bins.append(r)
        rng = np.random.default_rng([args.seed, index, 0])
        self.vector = ff.vector_fragility(self.cells, records, self.norm.u_shift, self.norm.x_shift, self.points_s, rng,
                                          args.bootstrap, args.level)
        self.scale_range_g = (float(cube.scales[cube.scales > 0].min()), float(cube.scales.max()))

    def chosen(self):
        return self.vector["points"][0] if "points" in self.vector else None


# --------------------------------------------------------------------------------------------
# rigid fragility


def fmt_interval(v, lo, hi, digits=3):
    if v is None or not math.isfinite(v):
        return "-"
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return f"{v:.{digits}f} [-]"
    return f"{v:.{digits}f} [{lo:.{digits}f}, {hi:.{digits}f}]"


def bin_label(lo, hi):
    return f"{lo:g}-{hi:g}" if math.isfinite(hi) else f">= {lo:g}"


def print_table(cube, fits, args):
    print(f"rigid fragility {cube.path}: lognormal fragilities P = Phi(ln(PGA/theta)/beta), PGA = GMRotI50 in g")
    print(f"  maximum likelihood on the simulated cells (inferred cells left out); {int(args.level * 100)} % intervals "
          f"from {args.bootstrap} bootstrap resamples of records (seed {args.seed})")
    for f in fits:
        n = f.norm
        print()
        print(f"object {f.obj.name}: alpha {n.alpha:.4f} rad, p {n.p:.3f} rad/s; {f.cells.inferred} inferred cells left out"
              if n.alpha and n.p else f"object {f.obj.name}: {f.cells.inferred} inferred cells left out")
        print(f"  {'PGV/PGA bin (s)':<16} {'records':>7} {'cells':>6} {'overturned':>10}  {'theta (g) [90 %]':<24} "
              f"{'beta [90 %]':<22}")
        for r in f.bins:
            if r["n_records"] == 0:
                continue
            theta = fmt_interval(r.get("theta_g"), *r.get("theta_interval_g", (0, 0)))
            beta = fmt_interval(r.get("beta"), *r.get("beta_interval", (0, 0)))
            note = f"  ({r['reason']})" if "reason" in r else f"  ({r['interval_note']})" if "interval_note" in r else ""
            print(f"  {bin_label(r['lower_s'], r['upper_s']):<16} {r['n_records']:>7} {r['n_cells']:>6} "
                  f"{r['n_overturned']:>10}  {theta:<24} {beta:<22}{note}")
        c = f.chosen()
        v = f.vector
        if c is not None:
            print(f"  {'vector fit at':<16} {v['n_records']:>7} {v['n_cells']:>6} {v['n_overturned']:>10}  "
                  f"{fmt_interval(c['theta_g'], *c['theta_interval_g']):<24} {fmt_interval(c['beta'], *c['beta_interval']):<22}"
                  f"  (PGV/PGA {c['pgv_pga_s']:.3f} s)")
        else:
            print(f"  vector fit: {v.get('reason')}")
        failed = sum(r.get("bootstrap_failed", 0) for r in f.bins) + v.get("bootstrap_failed", 0)
        if failed:
            total = sum(r.get("bootstrap_replicates", 0) for r in f.bins) + v.get("bootstrap_replicates", 0)
            print(f"  note: {failed} of {total} bootstrap resamples had no finite fit (outcomes separated, or one PGV/PGA "
                  f"only for the vector fit) and were left out"
                  + ("; with so many the intervals may be too narrow (more records or rotations would tell)"
                     if failed > 0.1 * total else ""))


def csv_rows(fits):
    rows = []
    for f in fits:
        for r in f.bins:
            if r["n_records"] == 0:
                continue
            rows.append(_csv_row(f.obj.name, "bin", r["lower_s"], r["upper_s"], "", r))
        c = f.chosen()
        if c is not None:
            v = dict(f.vector)
            v.update(c)
            rows.append(_csv_row(f.obj.name, "vector", "", "", c["pgv_pga_s"], v))
    return rows


def _csv_row(name, kind, lo, hi, at, r):
    def cell(v):  # an empty field where there is no value (no fit, no interval)
        return "" if v is None or (isinstance(v, float) and math.isnan(v)) else v

    ti = [cell(v) for v in r.get("theta_interval_g", ("", ""))]
    bi = [cell(v) for v in r.get("beta_interval", ("", ""))]
    return {"object": name, "fit": kind, "pgv_pga_lower_s": lo, "pgv_pga_upper_s": hi, "pgv_pga_s": at,
            "theta_g": r.get("theta_g", ""), "theta_lower_g": ti[0], "theta_upper_g": ti[1],
            "beta": r.get("beta", ""), "beta_lower": bi[0], "beta_upper": bi[1],
            "n_records": r["n_records"], "n_cells": r["n_cells"], "n_overturned": r["n_overturned"],
            "note": r.get("reason", r.get("interval_note", ""))}


def nrml_functions(fits):
    functions = []
    for f in fits:
        lo, hi = f.scale_range_g
        for r in f.bins:
            if "theta_g" not in r:
                continue
            functions.append({"id": f"{f.obj.name}_pgv_pga_{bin_label(r['lower_s'], r['upper_s']).replace('>= ', 'above_')}s",
                              "theta_g": r["theta_g"], "beta": r["beta"], "min_iml": lo, "max_iml": hi,
                              # the PGA below which the fit gives P < 1e-4: no damage there
                              "no_damage_limit": r["theta_g"] * math.exp(r["beta"] * ff.norm_ppf(1e-4))})
    return functions


def json_clean(v):
    """Plain JSON: no NaN or infinity (null), numpy scalars as numbers, bootstrap replicates left out."""
    if isinstance(v, dict):
        return {k: json_clean(x) for k, x in v.items() if not k.startswith("replicate_") and k != "start"}
    if isinstance(v, (list, tuple)):
        return [json_clean(x) for x in v]
    if isinstance(v, (np.floating, float)):
        return float(v) if math.isfinite(v) else None
    if isinstance(v, (np.integer, np.bool_)):
        return v.item()
    return v


def json_document(cube, fits, args):
    return json_clean({"cube": cube.path, "method": METHOD, "bootstrap_replicates": args.bootstrap, "seed": args.seed,
                  "interval_level": args.level,
                  "objects": [{"object": f.obj.name, "alpha_rad": f.norm.alpha, "p_rad_s": f.norm.p,
                               "inferred_cells_left_out": f.cells.inferred, "bins": f.bins, "vector": f.vector}
                              for f in fits]})


def store(path, cube, fits, args):
    """Writes the /fragility group into a copy of the cube and renames it over the cube, so a
    crash leaves the cube as it was; refuses if the cube changed meanwhile (a running campaign)."""
    before = os.stat(path)
    tmp = path + ".fragility.tmp"
    shutil.copyfile(path, tmp)
    try:
        with h5py.File(tmp, "a") as f:
            if "fragility" in f:
                del f["fragility"]
            g = f.create_group("fragility")
            g.attrs["description"] = "fitted fragility functions (rigid fragility); refitted by each run"
            g.attrs["method"] = METHOD
            g.attrs["bootstrap_replicates"] = np.int32(args.bootstrap)
            g.attrs["seed"] = np.uint64(args.seed)
            g.attrs["interval_level"] = float(args.level)
            for fit in fits:
                og = g.create_group(fit.obj.name)
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
                for name, data, units, text in specs:
                    ds = og.create_dataset(name, data=data)
                    ds.attrs["units"] = units
                    ds.attrs["description"] = text
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
        with open(tmp, "rb") as fh:
            os.fsync(fh.fileno())
        now = os.stat(path)
        if (now.st_mtime_ns, now.st_size, now.st_ino) != (before.st_mtime_ns, before.st_size, before.st_ino):
            raise InputError(f"{path}: the cube changed while it was fitted (a campaign writing it?); not stored, "
                             f"run again once it is done")
        os.replace(tmp, path)
        dfd = os.open(os.path.dirname(os.path.abspath(path)), os.O_RDONLY)
        try:
            os.fsync(dfd)
        finally:
            os.close(dfd)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def cmd_fragility(args):
    cube = Cube(args.cube)
    fits = [ObjectFit(cube, o, args) for o in cube.select(args.object)]
    if args.json:
        json.dump(json_document(cube, fits, args), sys.stdout, indent=1, allow_nan=False)
        print()
    else:
        print_table(cube, fits, args)
    if args.csv:
        rows = csv_rows(fits)
        with open(args.csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows(rows)
    if args.nrml:
        functions = nrml_functions(fits)
        if not functions:
            raise InputError(f"{args.cube}: no PGV/PGA bin has a finite fit: no NRML written")
        tree = nrml.fragility_model(os.path.splitext(os.path.basename(args.cube))[0],
                                    f"Overturning fragility of precariously balanced rocks from the Rigid cube "
                                    f"{os.path.basename(args.cube)}: one lognormal function of GMRotI50 PGA (g) per "
                                    f"object and PGV/PGA bin", functions)
        nrml.write(args.nrml, tree)
    if not args.no_store:
        store(args.cube, cube, fits, args)
    if not args.json:
        wrote = [p for p in (args.csv, args.nrml) if p] + ([] if args.no_store else [f"{args.cube} (/fragility)"])
        if wrote:
            print(f"\nwrote {', '.join(wrote)}")
    return 0


# --------------------------------------------------------------------------------------------
# rigid hazard


def pgv_pga_points(args, fit_records_s):
    """[(weight, PGV/PGA s)]: one value, or 15 Gauss-Hermite nodes of a lognormal."""
    if args.pgv_pga_dist:
        kind, _, rest = args.pgv_pga_dist.partition(":")
        parts = rest.split(",")
        if kind != "lognormal" or len(parts) != 2:
            raise InputError(f"--pgv-pga-dist {args.pgv_pga_dist!r}: expected lognormal:MEDIAN_S,BETA")
        median = number_in(parts[0], "--pgv-pga-dist median", 1e-6, 100)
        beta = number_in(parts[1], "--pgv-pga-dist beta", 0, 5)
        nodes, weights = hermegauss(15)
        weights = weights / weights.sum()
        return [(float(w), float(median * math.exp(beta * z))) for z, w in zip(nodes, weights)]
    s = args.pgv_pga if args.pgv_pga is not None else float(np.median(fit_records_s))
    return [(1.0, s)]


def cmd_hazard(args):
    if not (args.age > 0 and math.isfinite(args.age)):
        raise InputError(f"--age {args.age}: must be a positive number of years")
    if not 0 < args.confidence < 1:
        raise InputError(f"--confidence {args.confidence}: must be between 0 and 1")
    try:
        curve = hc.read_curve(args.curve, args.site)
    except hc.CurveError as e:
        raise InputError(str(e))
    cube = Cube(args.cube)
    objs = cube.select([args.object] if args.object else None)
    if len(objs) > 1:
        raise InputError(f"{args.cube}: {len(objs)} objects; choose one with --object "
                         f"({', '.join(o.name for o in objs)})")
    obj = objs[0]
    cells = ff.Cells(obj.outcome, cube.scales, cube.pgv_pga)
    points = pgv_pga_points(args, cube.pgv_pga[cells.records_with_cells()])
    args.pgv_pga = None
    fit = ObjectFit(cube, obj, args, points_s=[s for _, s in points])
    v = fit.vector
    if "points" not in v:
        raise InputError(f"{args.cube}: object {obj.name}: no vector fit ({v.get('reason')})")
    lo_s, hi_s = v["pgv_pga_range_s"]
    outside = sum(w for w, s in points if not lo_s <= s <= hi_s)
    mixture = [(w, p["theta_g"], p["beta"]) for (w, _), p in zip(points, v["points"])]
    lam, extended = hc.mixture_rate(curve, mixture)
    reps = []
    for i in range(v["replicate_theta_g"].shape[0]):
        t, b = v["replicate_theta_g"][i], v["replicate_beta"][i]
        if np.all(np.isfinite(t)):
            reps.append(hc.mixture_rate(curve, [(w, t[j], b[j]) for j, (w, _) in enumerate(points)])[0])
    lam_lo, lam_hi = ff.percentile_interval(reps, args.level, v["n_records"])
    surv = hc.survival(lam, args.age)
    rate_factor, pga_factor = hc.ruling_factors(curve, mixture, args.age, args.confidence)
    result = {"cube": args.cube, "object": obj.name, "curve": args.curve, "site": curve.site,
              "curve_pga_range_g": [float(curve.pga_g[0]), float(curve.pga_g[curve.top - 1])],
              "age_years": args.age, "pgv_pga": [{"weight": w, "pgv_pga_s": s} for w, s in points],
              "pgv_pga_weight_outside_records": outside,
              "fragility": [{"pgv_pga_s": p["pgv_pga_s"], "theta_g": p["theta_g"], "beta": p["beta"],
                             "theta_interval_g": p["theta_interval_g"], "beta_interval": p["beta_interval"]}
                            for p in v["points"]],
              "n_records": v["n_records"],
              "annual_toppling_rate": lam, "annual_toppling_rate_interval": [lam_lo, lam_hi],
              "share_of_rate_beyond_curve": extended,
              "survival_probability": surv,
              "survival_probability_interval": [hc.survival(lam_hi, args.age), hc.survival(lam_lo, args.age)],
              "confidence": args.confidence,
              "ruled_out": surv < 1 - args.confidence,
              "rate_factor_to_rule_out": rate_factor, "pga_factor_to_rule_out": pga_factor,
              "interval_level": args.level, "bootstrap_replicates": args.bootstrap}
    if args.json:
        json.dump(json_clean(result), sys.stdout, indent=1, allow_nan=False)
        print()
    else:
        print_hazard(result)
    if args.plot:
        plot_hazard(args.plot, curve, mixture, v, points, result)
        if not args.json:
            print(f"wrote {args.plot}")
    return 0


def print_hazard(r):
    pct = int(r["interval_level"] * 100)
    site = f" (site {r['site']})" if r["site"] else ""
    lo, hi = r["curve_pga_range_g"]
    print(f"rigid hazard: object {r['object']} of {r['cube']}; hazard curve {r['curve']}{site}, PGA {lo:g}-{hi:g} g; "
          f"exposure age {r['age_years']:g} years")
    if len(r["fragility"]) == 1:
        f = r["fragility"][0]
        print(f"  fragility at PGV/PGA {f['pgv_pga_s']:.3f} s (vector fit): theta "
              f"{fmt_interval(f['theta_g'], *f['theta_interval_g'])} g, beta {fmt_interval(f['beta'], *f['beta_interval'])}")
    else:
        print(f"  fragility: the vector fit averaged over {len(r['fragility'])} PGV/PGA values of the given distribution")
    if r["pgv_pga_weight_outside_records"] > 0.01:
        print(f"  note: {100 * r['pgv_pga_weight_outside_records']:.0f} % of the PGV/PGA weight lies outside the records' "
              f"range: the vector fit is extrapolated there")
    lam, (a, b) = r["annual_toppling_rate"], r["annual_toppling_rate_interval"]
    have_interval = math.isfinite(a) and math.isfinite(b)
    no_interval = f"[no interval: {r['n_records']} record(s)]"
    print(f"  annual rate of toppling   {lam:.3e} per year  " + (f"[{pct} %: {a:.3e}, {b:.3e}]" if have_interval else no_interval)
          + f"  (mean return period {1 / lam:,.0f} years)" if lam > 0 else "  annual rate of toppling 0")
    if r["share_of_rate_beyond_curve"] > 0.01:
        print(f"  note: {100 * r['share_of_rate_beyond_curve']:.1f} % of the rate comes from PGAs beyond the curve, "
              f"where it is extended by its end segments' power law")
    s, (slo, shi) = r["survival_probability"], r["survival_probability_interval"]
    print(f"  P(survives {r['age_years']:g} years) = exp(-lambda T) = {s:.4f}  "
          + (f"[{pct} %: {slo:.4f}, {shi:.4f}]" if have_interval else no_interval))
    c = int(round(r["confidence"] * 100))
    if r["ruled_out"]:
        print(f"  the rock's survival rules this hazard curve out at {c} % confidence (survival below "
              f"{1 - r['confidence']:.2f}); it would be consistent with the curve's rates x {r['rate_factor_to_rule_out']:.3g} "
              f"or its PGAs x {r['pga_factor_to_rule_out']:.3g}")
    else:
        print(f"  consistent at {c} % confidence; the rock would rule the curve out with its rates x "
              f"{r['rate_factor_to_rule_out']:.3g} or its PGAs x {r['pga_factor_to_rule_out']:.3g}")


def plot_hazard(path, curve, mixture, v, points, r):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lo = min(curve.pga_g[0], min(t for _, t, _ in mixture) * 0.2)
    hi = max(curve.pga_g[curve.top - 1], max(t for _, t, _ in mixture) * 5)
    a = np.exp(np.linspace(math.log(lo), math.log(hi), 400))
    p = sum(w * hc.fragility_probability(a, t, b) for w, t, b in mixture)
    h = curve(a)
    # the integrand per unit ln PGA: dlambda / dln a = P(a) |dH / dln a|
    dh = -np.gradient(h, np.log(a))
    dens = p * np.maximum(dh, 0)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.5, 7.5), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    top.loglog(curve.pga_g[: curve.top], curve.rate[: curve.top], "o", color="tab:blue", ms=4, label="hazard curve (points)")
    top.loglog(a, h, "-", color="tab:blue", lw=1.2, label="H(PGA): annual rate of exceedance")
    top.set_ylabel("annual rate of exceedance")
    top.grid(True, which="both", alpha=0.3)
    right = top.twinx()
    right.plot(a, p, color="tab:red", lw=2, label="P(topple | PGA)")
    reps = [(v["replicate_theta_g"][i], v["replicate_beta"][i]) for i in range(v["replicate_theta_g"].shape[0])
            if np.all(np.isfinite(v["replicate_theta_g"][i]))]
    if reps:
        curves = np.array([sum(w * hc.fragility_probability(a, t[j], b[j]) for j, (w, _) in enumerate(points))
                           for t, b in reps])
        q = 50 * (1 - r["interval_level"])
        right.fill_between(a, np.percentile(curves, q, axis=0), np.percentile(curves, 100 - q, axis=0),
                           color="tab:red", alpha=0.2, label=f"{int(r['interval_level'] * 100)} % band (bootstrap)")
    right.set_ylim(0, 1.02)
    right.set_ylabel("P(topple | PGA)")
    lines = top.get_legend_handles_labels()
    lines2 = right.get_legend_handles_labels()
    top.legend(lines[0] + lines2[0], lines[1] + lines2[1], loc="lower left", fontsize=8)
    top.set_title(f"{r['object']}: toppling rate {r['annual_toppling_rate']:.2e}/yr, "
                  f"P(survive {r['age_years']:g} yr) = {r['survival_probability']:.3f}", fontsize=10)
    bottom.semilogx(a, dens, color="black")
    bottom.fill_between(a, 0, dens, color="gray", alpha=0.3)
    bottom.set_xlabel("PGA (g, GMRotI50)")
    bottom.set_ylabel("d lambda / d ln PGA (per year)")
    bottom.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


# --------------------------------------------------------------------------------------------


class OneLineParser(argparse.ArgumentParser):
    """A bad command line is bad input like any other: one line naming the problem, exit 2."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (--help for the options)\n")


def build_parser():
    p = OneLineParser(prog="rigid", description="Fitted fragilities and the survival test of a rock.",
                      epilog="Exit status: 0 done, 2 bad input, 1 internal error.")
    sub = p.add_subparsers(dest="command", required=True, metavar="{fragility,hazard}")

    def common(sp):
        sp.add_argument("cube", help="campaign cube (HDF5)")
        sp.add_argument("--pgv-pga", type=float, help="PGV/PGA (s) at which the vector fit gives a lognormal "
                                                      "(default: the median of the object's records)")
        sp.add_argument("--bootstrap", type=int, default=200, help="bootstrap resamples of records (default 200)")
        sp.add_argument("--seed", type=int, default=1, help="seed of the bootstrap (default 1)")
        sp.add_argument("--level", type=float, default=0.9, help="interval level (default 0.9)")
        sp.add_argument("--json", action="store_true", help="JSON on standard output instead of the table")

    f = sub.add_parser("fragility", help="fit fragilities per object: per PGV/PGA bin and at a chosen PGV/PGA")
    common(f)
    f.add_argument("--object", action="append", help="only this object (repeatable); default: all")
    f.add_argument("--csv", help="write one row per object and bin (and the vector fit) to this CSV")
    f.add_argument("--nrml", help="write an OpenQuake NRML 0.5 fragility model (one function per object and bin)")
    f.add_argument("--no-store", action="store_true", help="do not store the fits in the cube's /fragility group")
    f.set_defaults(func=cmd_fragility)

    h = sub.add_parser("hazard", help="toppling rate and survival probability under a PGA hazard curve")
    common(h)
    h.add_argument("--object", help="the object (needed when the cube has several)")
    h.add_argument("--curve", required=True, help="hazard curve CSV (PGA g, annual rate; OpenQuake or nshmp-haz layouts)")
    h.add_argument("--site", help="row of a multi-site curve file: its name, lon,lat or 0-based index")
    h.add_argument("--age", type=float, required=True, help="exposure age of the rock (years)")
    h.add_argument("--pgv-pga-dist", help="lognormal:MEDIAN_S,BETA: PGV/PGA distributed (independently of PGA)")
    h.add_argument("--confidence", type=float, default=0.95, help="confidence of the ruling-out test (default 0.95)")
    h.add_argument("--plot", help="PNG of the hazard curve, the fragility and the integrand")
    h.set_defaults(func=cmd_hazard)
    return p


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.bootstrap < 20 or args.bootstrap > 100000:
            raise InputError(f"--bootstrap {args.bootstrap}: must be 20-100000")
        if not 0.5 <= args.level < 1:
            raise InputError(f"--level {args.level}: must be in [0.5, 1)")
        if args.pgv_pga is not None and not (args.pgv_pga > 0 and math.isfinite(args.pgv_pga)):
            raise InputError(f"--pgv-pga {args.pgv_pga}: must be a positive number of seconds")
        if getattr(args, "pgv_pga_dist", None) and args.pgv_pga is not None:
            raise InputError("--pgv-pga and --pgv-pga-dist: give one")
        return args.func(args)
    except InputError as e:
        sys.stderr.write(f"rigid {args.command}: error: {e}\n")
        return 2
    except OSError as e:
        sys.stderr.write(f"rigid {args.command}: error: {e}\n")
        return 2
    except Exception as e:  # a bug of ours, not the input's: one line, exit 1
        sys.stderr.write(f"rigid {args.command}: internal error: {type(e).__name__}: {e}\n")
        return 1


if __name__ == "__main__":
    sys.exit(main())
