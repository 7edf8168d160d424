"""`rigid fragility` and `rigid hazard`: from a campaign cube to fitted fragilities, exports hazard
codes read, and the probability that a rock survived a hazard model over its exposure age.

    rigid_fragility.py fragility CUBE [--object NAME]... [--variant K] [--pgv-pga S] [--json] [--csv FILE]
                       [--nrml FILE] [--no-store] [--bootstrap N] [--seed N] [--level 0.9]
    rigid_fragility.py hazard CUBE --curve CURVE.csv --age YEARS [--object NAME] [--variant K]
                       [--pgv-pga S | --pgv-pga-dist lognormal:MEDIAN,BETA] [--site ID]
                       [--confidence 0.95] [--plot PNG] [--json]

Fits (fit.py): per PGV/PGA bin a lognormal (theta, beta) on the records of the bin, and
the vector fit P = Phi((u - mu(x)) / sigma(x)) over all records, evaluated at a chosen PGV/PGA;
90 % intervals by bootstrap over records. Hazard (hazard.py): lambda = E[H(C)], survival
exp(-lambda T). Exit status: 0 done, 2 bad input, 1 internal error.

With variants (a cube with a variant axis: epistemic uncertainty, layout at the top of src/io/cube.cpp):
each variant is fitted as an object is; the variants of an object are equally weighted samples of
the epistemic distribution, so the pooled fragility is the mixture P(a) = mean_v P_v(a) of the
lognormals standing for them (the vector fit at the chosen PGV/PGA, or the empirical threshold of a
variant with separated outcomes), reported with its median, the moment-matched lognormal, the
5/50/95 % of theta and beta over variants and the 5-95 % band of P_v(a); the sensitivity of theta
and beta to each varied parameter is sensitivity.py's. `hazard` integrates the pooled fragility
and reports the survival probability's epistemic 5-95 % range over variants beside the aleatory
interval; --variant K uses one variant as if it were an object.
"""
import argparse
import contextlib
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
    from . import files as cube_files
    from . import fit as ff
    from . import hazard as hc
    from . import nrml
    from . import progress
    from . import sensitivity
    from .cube import Cube
    from .errors import InputError
    from .fit import SCALAR_SOURCE, THRESHOLD_SOURCE
    from .map_fit import Normalisation, block_parameter, parse_per_object
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
    """Everything `rigid fragility` reports of one object (or one variant of it).

    A variant is fitted exactly as an object is. Its bootstrap uses the same seeds as the other
    variants of its object (the object's index, not the variant's), so replicate i resamples the
    same records in every variant: the records are shared by the variants, and a pooled replicate
    (the hazard's aleatory interval) mixes the variants' fits of one resample. With
    `require_fragility` False (variants) an object with nothing to fit gets `no_fit` instead of
    the error."""

    def __init__(self, cube, obj, args, points_s=None, require_fragility=True):
        alpha, alpha_src = block_parameter(cube, obj, "alpha_rad", parse_per_object(None, "--alpha"))
        p, p_src = block_parameter(cube, obj, "p_rad_s", parse_per_object(None, "--p"))
        self.norm = Normalisation(alpha, alpha_src, p, p_src)
        self.obj = obj
        self.cells = ff.Cells(obj.outcome, cube.scales, cube.pgv_pga)
        self.no_fit = None
        self.scalar = self.threshold = None
        if self.cells.n.sum() == 0:
            self.no_fit = f"{cube.path}: object {obj.label}: no simulated cell (nothing to fit)"
        elif self.cells.k.sum() == 0:
            self.no_fit = (f"{cube.path}: object {obj.label}: no overturned cell among its {int(self.cells.n.sum())} "
                           f"simulated cells: no fragility to fit (the campaign's scales stay below it)")
        if self.no_fit and require_fragility:
            raise InputError(self.no_fit)
        self.edges = cube.edges
        self.scale_range_g = (float(cube.scales[cube.scales > 0].min()), float(cube.scales.max()))
        if self.no_fit:
            for _ in range(fits_per_object(cube)):  # the progress line's fits this object would have had
                ff._fit_done()
            self.pgv_pga_s = args.pgv_pga if args.pgv_pga is not None else (points_s or [math.nan])[0]
            self.points_s = [self.pgv_pga_s] if points_s is None else list(points_s)
            self.bins = []
            self.vector = {"reason": "no overturned cell" if self.cells.n.sum() else "no simulated cell",
                           "n_records": int(len(self.cells.records_with_cells())), "n_cells": int(self.cells.n.sum()),
                           "n_overturned": 0}
            return
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
        if obj.variant is not None:
            # variants also report the scalar lognormal over all their records, and a variant whose
            # outcomes are separated (a deterministic, quasi-static case) its empirical threshold
            rng = np.random.default_rng([args.seed, index, len(cube.edges)])
            self.scalar = ff.scalar_fragility(self.cells, None, rng, args.bootstrap, args.level)
            if "points" not in self.vector:
                self.threshold = ff.empirical_threshold(self.cells)

    def chosen(self):
        return self.vector["points"][0] if "points" in self.vector else None


def fits_per_object(cube):
    """The fits ObjectFit makes of one object (variant): one per PGV/PGA bin, the vector fit, and
    with variants the scalar fit over all records."""
    return len(cube.edges) - 1 + 1 + (cube.variants is not None)


def start_progress(cube, objs, command):
    """The progress line of the fits to come (shown when they take more than a few seconds)."""
    ff.PROGRESS = progress.FitProgress(len(objs) * fits_per_object(cube), f"rigid {command}")


def end_progress():
    if ff.PROGRESS is not None:
        ff.PROGRESS.finish()
        ff.PROGRESS = None


# --------------------------------------------------------------------------------------------
# rigid fragility


# Bootstrap replicates over variants for the sensitivity intervals: resampling variants costs rank
# statistics only, so this is fixed (not --bootstrap, which counts probit refits).
SENSITIVITY_REPLICATES = 1000


def fragility_source(fit):
    """Which fragility stands for a variant, the one order the pool, the sensitivity and the hazard
    follow: the vector fit; when that has no finite estimate, the scalar fit over all records (with
    few records the PGV/PGA term can separate the outcomes while PGA alone does not, and dropping
    the variant would bias the pool towards the variants that fit); for separated outcomes the
    empirical threshold; else "none"."""
    if "points" in fit.vector:
        return "vector fit"
    s = getattr(fit, "scalar", None)
    if s is not None and math.isfinite(s.get("theta_g", math.nan)):
        return SCALAR_SOURCE
    if fit.threshold is not None:
        return THRESHOLD_SOURCE
    return "none"


def variant_lognormal(fit):
    """The lognormal (theta, beta) standing for one variant in the pooled fragility and the
    sensitivity (fragility_source): the vector fit at the chosen PGV/PGA, the scalar fit, the
    empirical threshold (a step, beta 0, flagged), or none (theta NaN)."""
    source = fragility_source(fit)
    if source == "vector fit":
        c = fit.chosen()
        return {"theta_g": c["theta_g"], "beta": c["beta"], "source": source,
                "theta_interval_g": c["theta_interval_g"], "beta_interval": c["beta_interval"]}
    if source == SCALAR_SOURCE:
        s = fit.scalar
        return {"theta_g": s["theta_g"], "beta": s["beta"], "source": source,
                "theta_interval_g": s.get("theta_interval_g"), "beta_interval": s.get("beta_interval")}
    if source == THRESHOLD_SOURCE:
        return {"theta_g": fit.threshold["theta_g"], "beta": 0.0, "source": source,
                "between_g": fit.threshold["between_g"]}
    return {"theta_g": math.nan, "beta": math.nan, "source": "none", "reason": fit.vector.get("reason", "")}


def common_pgv_pga(cube, objs, args):
    """One PGV/PGA for every variant of an object (their curves are pooled there): --pgv-pga, else
    the median of the records with simulated cells in any variant."""
    if args.pgv_pga is not None:
        return args.pgv_pga
    used = set()
    for o in objs:
        used |= set(ff.Cells(o.outcome, cube.scales, cube.pgv_pga).records_with_cells().tolist())
    if not used:
        raise InputError(f"{cube.path}: object {objs[0].name}: no simulated cell in any variant (nothing to fit)")
    return float(np.median(cube.pgv_pga[sorted(used)]))


class VariantAnalysis:
    """An object's variants together: each variant's lognormal, the pooled (mixture) fragility with
    the epistemic spread, and the sensitivity of theta and beta to the varied parameters."""

    def __init__(self, cube, fits, args):
        self.name = fits[0].obj.name
        self.fits = fits
        self.pgv_pga_s = fits[0].pgv_pga_s
        self.lognormals = [variant_lognormal(f) for f in fits]
        usable = [(d["theta_g"], d["beta"]) for d in self.lognormals if math.isfinite(d["theta_g"])]
        self.n_threshold = sum(d["source"] == THRESHOLD_SOURCE for d in self.lognormals)
        self.without = [f.obj.variant for f, d in zip(fits, self.lognormals) if d["source"] == "none"]
        self.pooled = None
        if usable:
            lo_g, hi_g = fits[0].scale_range_g
            spread = max([b for _, b in usable] + [0.1])
            grid = np.geomspace(min([t for t, _ in usable] + [lo_g]) * math.exp(-3 * spread),
                                max([t for t, _ in usable] + [hi_g]) * math.exp(3 * spread), 200)
            self.pooled = ff.pooled_fragility(usable, grid)
        index = int(fits[0].obj.attrs.get("index", 0))
        rng = np.random.default_rng([args.seed, index, 0, 1])
        theta = np.array([d["theta_g"] for d in self.lognormals])
        # beta of a threshold is 0 by construction, not an estimate: left out of beta's statistics
        beta = np.array([d["beta"] if d["source"] == "vector fit" else math.nan for d in self.lognormals])
        self.parameters = self._parameters(cube)
        self.sensitivity = sensitivity.sensitivity_table(self.parameters, {"theta": theta, "beta": beta}, rng,
                                                         SENSITIVITY_REPLICATES, args.level)

    def _parameters(self, cube):
        out = []
        for name, units, values in cube.variants.parameters:
            if isinstance(values, list):
                codes, order = sensitivity.category_codes(values)
                out.append((name, units, f"text (category order: {', '.join(order)})", codes))
            else:
                out.append((name, units, "varied", np.asarray(values, float)))
        for key, units in (("alpha_rad", "rad"), ("p_rad_s", "rad s-1")):
            values = np.array([float(f.obj.attrs.get(key, math.nan)) for f in self.fits])
            if np.isfinite(values).any():
                out.append((key, units, "derived", values))
        return out

    def document(self):
        """JSON of the analysis (arrays as lists)."""
        return {"object": self.name, "variants": len(self.fits), "pgv_pga_s": self.pgv_pga_s,
                "variant_fragility": [dict(d, variant=f.obj.variant, label=f.obj.label)
                                      for f, d in zip(self.fits, self.lognormals)],
                "variants_with_empirical_threshold": self.n_threshold,
                "variants_without_fragility": self.without,
                "pooled": None if self.pooled is None else dict(self.pooled, weights="variants equally weighted"),
                "sensitivity": self.sensitivity,
                "sensitivity_method": SENSITIVITY_METHOD}


SENSITIVITY_METHOD = ("Spearman rank correlation with theta (and beta) across variants, percentile bootstrap "
                      f"interval over variants ({SENSITIVITY_REPLICATES} resamples, seeded by --seed); PRCC: "
                      "correlation of rank residuals after regressing out the other varied parameters' ranks "
                      "(Marino et al., J. Theor. Biol. 254, 2008); text parameters by their category order; "
                      "theta of separated variants is their empirical threshold, their beta is left out")


def analyse_variants(cube, objs, args):
    """(fits, analyses): the fits of every (object, variant) in cube order, and per object with
    variants its VariantAnalysis (none with --variant: one variant has nothing to pool)."""
    fits, analyses = [], []
    for name in [n for n in cube.base_names() if any(o.name == n for o in objs)]:
        group = [o for o in objs if o.name == name]
        point = common_pgv_pga(cube, group, args)
        group_fits = [ObjectFit(cube, o, args, points_s=[point], require_fragility=False) for o in group]
        if args.variant is not None and group_fits[0].no_fit:
            raise InputError(group_fits[0].no_fit)
        if all(f.no_fit for f in group_fits):
            raise InputError(f"{cube.path}: object {name}: no overturned cell in any of its {len(group)} variants: "
                             f"no fragility to fit (the campaign's scales stay below it)")
        fits += group_fits
        if args.variant is None:
            analyses.append(VariantAnalysis(cube, group_fits, args))
    return fits, analyses


def fmt_param(v):
    return v if isinstance(v, str) else f"{v:.4g}"


def print_variant_tables(cube, fits, analyses, args):
    pct = int(args.level * 100)
    print(f"rigid fragility {cube.path}: {cube.variants.count} variants ({cube.variants.method}, seed "
          f"{cube.variants.seed}); lognormal fragilities P = Phi(ln(PGA/theta)/beta), PGA = GMRotI50 in g")
    print(f"  maximum likelihood on the simulated cells (inferred cells left out); {pct} % intervals from "
          f"{args.bootstrap} bootstrap resamples of records (seed {args.seed}): aleatory/sampling")
    names = [n for n, _, _ in cube.variants.parameters]
    by_object = {}
    for f in fits:
        by_object.setdefault(f.obj.name, []).append(f)
    for name, group in by_object.items():
        print()
        print(f"object {name}: vector fit at PGV/PGA {group[0].pgv_pga_s:.3f} s and the scalar fit over all records, "
              f"per variant (per-bin fits: --json, --csv, the cube)")
        head = ["variant"] + names + ["alpha (rad)", f"theta (g) [{pct} %]", f"beta [{pct} %]",
                                      f"scalar theta (g) [{pct} %]", f"scalar beta [{pct} %]", "note"]
        rows = []
        for f in group:
            k = f.obj.variant
            d = variant_lognormal(f)
            params = [fmt_param(values[k]) for _, _, values in cube.variants.parameters]
            alpha = f"{f.norm.alpha:.4f}" if f.norm.alpha else "-"
            if d["source"] == "vector fit":
                theta = fmt_interval(d["theta_g"], *d["theta_interval_g"], scale_range_g=f.scale_range_g)
                beta = fmt_interval(d["beta"], *d["beta_interval"])
                note = ""
            elif d["source"] == SCALAR_SOURCE:
                theta, beta = f"{d['theta_g']:.3f} +", f"{d['beta']:.3f} +"
                note = "+ the scalar fit over all records (the vector fit's outcomes are separated)"
            elif d["source"] == THRESHOLD_SOURCE:
                theta, beta = f"{d['theta_g']:.3f} *", "0 (step)"
                note = (f"* empirical threshold: between {d['between_g'][0]:g} and {d['between_g'][1]:g} g "
                        f"(outcomes separated: no finite fit)")
            else:
                theta, beta, note = "-", "-", d.get("reason", "")
            sc = f.scalar or {}
            stheta = fmt_interval(sc.get("theta_g"), *sc.get("theta_interval_g", (0, 0)), scale_range_g=f.scale_range_g)
            sbeta = fmt_interval(sc.get("beta"), *sc.get("beta_interval", (0, 0)))
            rows.append([f"{name} [v{k}]"] + params + [alpha, theta, beta, stheta, sbeta, note])
        widths = [max(len(str(r[i])) for r in rows + [head]) for i in range(len(head))]
        print("  " + "  ".join(str(h).ljust(w) for h, w in zip(head, widths)).rstrip())
        for r in rows:
            print("  " + "  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip())
        if any(str(c).endswith(BEYOND_MARK) for r in rows for c in r):
            lo, hi = group[0].scale_range_g
            print(f"  {BEYOND_MARK} the interval reaches beyond the campaign's scales ({lo:g}-{hi:g} g): the records do "
                  f"not bound theta there")
    for a in analyses:
        print()
        if a.pooled is None:
            print(f"object {a.name}: no variant has a fragility: nothing pooled")
            continue
        p = a.pooled
        print(f"object {a.name}, pooled over {p['n_variants']} of {len(a.fits)} variants (equally weighted mixture "
              f"P(a) = mean_v P_v(a), at PGV/PGA {a.pgv_pga_s:.3f} s):")
        print(f"  median of the mixture {p['median_g']:.4f} g; moment-matched lognormal theta "
              f"{p['lognormal_theta_g']:.4f} g, beta {p['lognormal_beta']:.4f}")
        tp, bp = p["theta_percentiles_g"], p["beta_percentiles"]
        print(f"  epistemic spread over variants (5 / 50 / 95 %): theta {tp[0]:.4f} / {tp[1]:.4f} / {tp[2]:.4f} g, "
              f"beta {bp[0]:.4f} / {bp[1]:.4f} / {bp[2]:.4f}")
        i = int(np.argmin(np.abs(np.log(p["pga_g"] / p["median_g"]))))
        print(f"  5-95 % band of P_v(a) over variants at the pooled median: [{p['band_lower'][i]:.3f}, "
              f"{p['band_upper'][i]:.3f}] (the whole band: --json, the cube)")
        if a.n_threshold:
            print(f"  note: {a.n_threshold} variant(s) enter as their empirical threshold (a step at theta, beta 0 "
                  f"in the percentiles above)")
        if a.without:
            print(f"  note: variant(s) {', '.join(map(str, a.without))} have no fragility and are left out of the pool")
        print(f"  sensitivity across variants, sorted by |rho(theta)| ({pct} % intervals: bootstrap over variants):")
        head = ["parameter", "kind", "rho(theta)", "PRCC(theta)", "rho(beta)", "PRCC(beta)", "note"]
        rows = []
        for r in a.sensitivity:
            rows.append([r["parameter"] + (f" ({r['units']})" if r["units"] not in ("", "1") else ""), r["kind"],
                         fmt_interval(r["rho_theta"], *r["rho_theta_interval"], digits=2),
                         fmt_interval(r["prcc_theta"], *r["prcc_theta_interval"], digits=2),
                         fmt_interval(r["rho_beta"], *r["rho_beta_interval"], digits=2),
                         fmt_interval(r["prcc_beta"], *r["prcc_beta_interval"], digits=2), r["note"]])
        widths = [max(len(str(r[i])) for r in rows + [head]) for i in range(len(head))]
        print("    " + "  ".join(str(h).ljust(w) for h, w in zip(head, widths)).rstrip())
        for r in rows:
            print("    " + "  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip())
        if a.n_threshold:
            print(f"    theta of the {a.n_threshold} separated variant(s) is its empirical threshold; their beta "
                  f"(0 by construction) is left out of beta's statistics")


def fmt_probability(p, digits=4):
    """A probability or rate: fixed-point while that keeps two significant digits, else scientific
    (a survival probability of exp(-21) must not print as 0.0000)."""
    if p is None or not math.isfinite(p):
        return "-"
    if p == 0:
        return "0"
    if abs(p) < 10.0 ** (2 - digits):
        return f"{p:.{digits - 1}e}"
    return f"{p:.{digits}f}"


def fmt_factor(f, what):
    """"rates x 0.5": a factor of the ruling-out test; the solver's search ends (0, infinity) in words."""
    if f == 0:
        return f"{what} x less than {math.exp(-6):.3g}"
    if not math.isfinite(f):
        return f"{what} x more than {math.exp(6):.3g}"
    return f"{what} x {f:.3g}"


# An interval end this far beyond the campaign's scales is not bounded by the records (the
# bootstrap's fits run off to what the data cannot tell): flagged with BEYOND_MARK.
BEYOND_MARK = "!"


def interval_beyond(lo, hi, scale_range_g):
    """True when [lo, hi] (g) reaches outside the campaign's scales: the interval hits the edge of
    what the cells can tell (a resample without overturning below the lowest scale, or none above)."""
    if scale_range_g is None or not (math.isfinite(lo) and math.isfinite(hi)):
        return False
    low, top = scale_range_g
    return lo < low or hi > top


def fmt_interval(v, lo, hi, digits=3, scale_range_g=None):
    """v [lo, hi]; with scale_range_g (a PGA interval) flagged BEYOND_MARK when it reaches outside
    the campaign's scales. Values below 10^-digits print in scientific notation, not as 0.000."""
    def num(x):
        return f"{x:.{digits - 1}e}" if x != 0 and abs(x) < 10.0 ** -digits else f"{x:.{digits}f}"

    if v is None or not math.isfinite(v):
        return "-"
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return f"{num(v)} [-]"
    mark = BEYOND_MARK if interval_beyond(lo, hi, scale_range_g) else ""
    return f"{num(v)} [{num(lo)}, {num(hi)}]{mark}"


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
        flagged = False
        for r in f.bins:
            if r["n_records"] == 0:
                continue
            theta = fmt_interval(r.get("theta_g"), *r.get("theta_interval_g", (0, 0)), scale_range_g=f.scale_range_g)
            beta = fmt_interval(r.get("beta"), *r.get("beta_interval", (0, 0)))
            flagged |= theta.endswith(BEYOND_MARK)
            note = f"  ({r['reason']})" if "reason" in r else f"  ({r['interval_note']})" if "interval_note" in r else ""
            print(f"  {bin_label(r['lower_s'], r['upper_s']):<16} {r['n_records']:>7} {r['n_cells']:>6} "
                  f"{r['n_overturned']:>10}  {theta:<24} {beta:<22}{note}")
        c = f.chosen()
        v = f.vector
        if c is not None:
            vtheta = fmt_interval(c['theta_g'], *c['theta_interval_g'], scale_range_g=f.scale_range_g)
            flagged |= vtheta.endswith(BEYOND_MARK)
            print(f"  {'vector fit at':<16} {v['n_records']:>7} {v['n_cells']:>6} {v['n_overturned']:>10}  "
                  f"{vtheta:<24} {fmt_interval(c['beta'], *c['beta_interval']):<22}"
                  f"  (PGV/PGA {c['pgv_pga_s']:.3f} s)")
        else:
            print(f"  vector fit: {v.get('reason')}")
        if flagged:
            print(f"  {BEYOND_MARK} the interval reaches beyond the campaign's scales ({f.scale_range_g[0]:g}-"
                  f"{f.scale_range_g[1]:g} g): the records do not bound theta there (more records, or scales "
                  f"reaching further, would)")
        failed = sum(r.get("bootstrap_failed", 0) for r in f.bins) + v.get("bootstrap_failed", 0)
        if failed:
            total = sum(r.get("bootstrap_replicates", 0) for r in f.bins) + v.get("bootstrap_replicates", 0)
            print(f"  note: {failed} of {total} bootstrap resamples had no finite fit (outcomes separated, or one PGV/PGA "
                  f"only for the vector fit) and were left out"
                  + ("; with so many the intervals may be too narrow (more records or rotations would tell)"
                     if failed > 0.1 * total else ""))


def csv_rows(fits):
    """One row per object (variant) and bin, and the vector fit; with variants a `variant` column,
    each variant's scalar fit over all records (or its empirical threshold); the caller adds the
    pooled lognormal."""
    rows = []
    for f in fits:
        rows += fit_csv_rows(f) if f.obj.variant is None else variant_csv_rows(f)
    return rows


def fit_csv_rows(f):
    """A fit's bins with records and its chosen vector fit."""
    out = [_csv_row(f.obj.name, "bin", r["lower_s"], r["upper_s"], "", r) for r in f.bins if r["n_records"] > 0]
    c = f.chosen()
    if c is not None:
        v = dict(f.vector)
        v.update(c)
        out.append(_csv_row(f.obj.name, "vector", "", "", c["pgv_pga_s"], v))
    return out


def variant_csv_rows(f):
    out = fit_csv_rows(f)
    if f.threshold is not None:
        r = dict(f.vector, theta_g=f.threshold["theta_g"], beta=0.0,
                 reason=f"empirical threshold between {f.threshold['between_g'][0]:g} and "
                        f"{f.threshold['between_g'][1]:g} g (outcomes separated: no finite fit)")
        out.append(_csv_row(f.obj.name, "threshold", "", "", f.pgv_pga_s, r))
    if f.scalar is not None:
        out.append(_csv_row(f.obj.name, "scalar", "", "", "", f.scalar))
    if f.no_fit:
        out.append(_csv_row(f.obj.name, "none", "", "", "", dict(f.vector, reason=f.vector["reason"])))
    return [with_variant(r, f.obj.variant) for r in out]


def with_variant(row, variant):
    """The row with its `variant` column after `object`."""
    return {"object": row["object"], "variant": variant, **{k: v for k, v in row.items() if k != "object"}}


def pooled_csv_row(a):
    p = a.pooled
    r = {"n_records": max(f.vector.get("n_records", 0) for f in a.fits),
         "n_cells": sum(f.vector.get("n_cells", 0) for f in a.fits),
         "n_overturned": sum(f.vector.get("n_overturned", 0) for f in a.fits),
         "theta_g": p["lognormal_theta_g"], "beta": p["lognormal_beta"],
         "reason": f"moment-matched lognormal of the mixture of {p['n_variants']} variants; mixture median "
                   f"{p['median_g']:.6g} g; theta 5-95 % over variants {p['theta_percentiles_g'][0]:.6g}-"
                   f"{p['theta_percentiles_g'][2]:.6g} g"}
    return with_variant(_csv_row(a.name, "pooled", "", "", a.pgv_pga_s, r), "pooled")


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


def no_damage_limit(theta_g, beta):
    """The PGA below which the lognormal gives P < 1e-4: no damage there."""
    return theta_g * math.exp(beta * ff.norm_ppf(1e-4))


def max_iml(theta_g, beta, top_scale_g, probability):
    """The NRML maxIML of a function: OpenQuake holds P at P(maxIML) for every PGA above it, so it is
    carried to where the lognormal reaches `probability` (theta exp(beta Phi^-1(P))), or kept at the
    campaign's top scale when that is higher; `probability` None keeps the top scale (the fit's
    data range, clipping P above it)."""
    if probability is None:
        return top_scale_g
    return max(top_scale_g, theta_g * math.exp(beta * ff.norm_ppf(probability)))


def few_records(n_records, minimum):
    return n_records < minimum


def variant_nrml_functions(fits, analyses, max_probability=0.99):
    """With variants: one function per variant (its lognormal at the chosen PGV/PGA; a variant whose
    fragility is an empirical threshold has none, a step not being a logncdf) and the pooled one."""
    functions, skipped = [], []
    for f in fits:
        d = variant_lognormal(f)
        if d["source"] not in ("vector fit", SCALAR_SOURCE):
            skipped.append(f.obj.label)
            continue
        lo, hi = f.scale_range_g
        functions.append({"id": f"{f.obj.name}_v{f.obj.variant}_pgv_pga_{f.pgv_pga_s:.4g}s", "theta_g": d["theta_g"],
                          "beta": d["beta"], "min_iml": lo, "max_iml": max_iml(d["theta_g"], d["beta"], hi, max_probability),
                          "no_damage_limit": no_damage_limit(d["theta_g"], d["beta"])})
    for a in analyses:
        if a.pooled is None:
            continue
        lo, hi = a.fits[0].scale_range_g
        t, b = a.pooled["lognormal_theta_g"], a.pooled["lognormal_beta"]
        functions.append({"id": f"{a.name}_pooled_pgv_pga_{a.pgv_pga_s:.4g}s", "theta_g": t, "beta": b,
                          "min_iml": lo, "max_iml": max_iml(t, b, hi, max_probability),
                          "no_damage_limit": no_damage_limit(t, b)})
    return functions, skipped


def nrml_functions(fits, max_probability=0.99, min_records=0):
    """One function per object and PGV/PGA bin with a fit; bins fitted on fewer than `min_records`
    records left out (returned as (functions, left out labels))."""
    functions, left_out = [], []
    for f in fits:
        lo, hi = f.scale_range_g
        for r in f.bins:
            if "theta_g" not in r:
                continue
            label = f"{f.obj.name}_pgv_pga_{bin_label(r['lower_s'], r['upper_s']).replace('>= ', 'above_')}s"
            if r["n_records"] < min_records:
                left_out.append(f"{label} ({r['n_records']} record(s))")
                continue
            functions.append({"id": label, "theta_g": r["theta_g"], "beta": r["beta"], "min_iml": lo,
                              "max_iml": max_iml(r["theta_g"], r["beta"], hi, max_probability),
                              "no_damage_limit": no_damage_limit(r["theta_g"], r["beta"])})
    return functions, left_out


def nrml_range_text(max_probability):
    if max_probability is None:
        return ("; maxIML is the campaign's top scale, above which OpenQuake holds each function's P at its value "
                "there")
    return (f"; maxIML is where each lognormal reaches P = {max_probability:g} (or the campaign's top scale when "
            f"higher): the fit is extrapolated beyond the campaign's scales")


def json_clean(v):
    """Plain JSON: no NaN or infinity (null), numpy scalars as numbers, bootstrap replicates left out."""
    if isinstance(v, dict):
        return {k: json_clean(x) for k, x in v.items() if not k.startswith("replicate_") and k != "start"}
    if isinstance(v, (list, tuple)):
        return [json_clean(x) for x in v]
    if isinstance(v, np.ndarray):
        return json_clean(v.tolist())
    if isinstance(v, (np.floating, float)):
        return float(v) if math.isfinite(v) else None
    if isinstance(v, (np.integer, np.bool_)):
        return v.item()
    return v


def json_document(cube, fits, args, analyses=None):
    if cube.variants is not None:
        return json_clean({"cube": cube.path, "method": METHOD, "bootstrap_replicates": args.bootstrap, "seed": args.seed,
                           "interval_level": args.level,
                           "variants": {"count": cube.variants.count, "method": cube.variants.method,
                                        "seed": cube.variants.seed,
                                        "parameters": [{"name": n, "units": u, "values": v}
                                                       for n, u, v in cube.variants.parameters]},
                           "objects": [{"object": f.obj.name, "variant": f.obj.variant, "label": f.obj.label,
                                        "alpha_rad": f.norm.alpha, "p_rad_s": f.norm.p,
                                        "inferred_cells_left_out": f.cells.inferred, "bins": f.bins, "vector": f.vector,
                                        "scalar": f.scalar, "fragility": variant_lognormal(f)}
                                       for f in fits],
                           "variant_analysis": [a.document() for a in analyses or []]})
    return json_clean({"cube": cube.path, "method": METHOD, "bootstrap_replicates": args.bootstrap, "seed": args.seed,
                  "interval_level": args.level,
                  "objects": [{"object": f.obj.name, "alpha_rad": f.norm.alpha, "p_rad_s": f.norm.p,
                               "inferred_cells_left_out": f.cells.inferred, "bins": f.bins, "vector": f.vector}
                              for f in fits]})


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
            pg.attrs["description"] = ("equally weighted mixture of the variants' lognormals, P(a) = mean_v P_v(a), "
                                       "and the epistemic spread over variants")
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


def check_completeness(cube, state, args):
    """A cube whose campaign has not run every cell: refused with --require-complete, else its
    warning kept for warn_incomplete (printed once the fit stands, so bad input stays one line)."""
    problem = cube.incomplete(state)
    if problem is not None and args.require_complete:
        raise InputError(problem + " (--require-complete)")
    args.incomplete = problem


def warn_incomplete(args):
    if getattr(args, "incomplete", None):
        sys.stderr.write(f"rigid {args.command}: warning: {args.incomplete}; the fits use the cells run so far\n")


def check_nrml_options(args):
    if args.nrml_max_probability != 0 and not 0.5 <= args.nrml_max_probability < 1:
        raise InputError(f"--nrml-max-probability {args.nrml_max_probability}: must be 0 (the campaign's top scale) "
                         f"or in [0.5, 1)")
    if args.nrml_min_records < 0:
        raise InputError(f"--nrml-min-records {args.nrml_min_records}: must be 0 or more")
    for option, value in (("--nrml-id", args.nrml_id), ("--nrml-asset-category", args.nrml_asset_category),
                          ("--nrml-loss-category", args.nrml_loss_category)):
        if value is not None and (not value.strip() or any(c in value for c in '<>&"')):
            raise InputError(f"{option} {value!r}: must be a non-empty name without < > & \"")


def cmd_fragility(args):
    check_nrml_options(args)
    outputs = [(o, p) for o, p in (("--csv", args.csv), ("--nrml", args.nrml)) if p]
    for option, path in outputs:
        cube_files.refuse_output_over_inputs(path, option, [args.cube])
    if len(outputs) == 2 and (cube_files.same_file(args.csv, args.nrml) or
                              os.path.abspath(args.csv) == os.path.abspath(args.nrml)):
        raise InputError(f"--csv and --nrml: the same file {args.nrml}")
    if not os.path.isfile(args.cube):
        raise InputError(f"{args.cube}: no such file")
    state = cube_files.campaign_state(args.cube)  # before our own lock, which would look like a campaign's
    # a store holds the cube's lock from the read to the rename: no campaign or second store between
    with contextlib.nullcontext() if args.no_store else cube_files.CubeLock(args.cube):
        return fragility_locked(args, state)


def fragility_locked(args, state):
    cube = Cube(args.cube)
    check_completeness(cube, state, args)
    objs = cube.select(args.object, args.variant)
    analyses = []
    start_progress(cube, objs, "fragility")
    try:
        if cube.variants is None:
            fits = [ObjectFit(cube, o, args) for o in objs]
        else:
            fits, analyses = analyse_variants(cube, objs, args)
    finally:
        end_progress()
    warn_incomplete(args)
    if args.json:
        json.dump(json_document(cube, fits, args, analyses), sys.stdout, indent=1, allow_nan=False)
        print()
    elif cube.variants is None:
        print_table(cube, fits, args)
    else:
        print_variant_tables(cube, fits, analyses, args)
    if args.csv:
        rows = csv_rows(fits) + [pooled_csv_row(a) for a in analyses if a.pooled is not None]

        def write_csv(tmp):
            with open(tmp, "w", newline="") as fh:
                w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
                w.writeheader()
                w.writerows(rows)
        cube_files.write_output(args.csv, "--csv", [args.cube], write_csv)
    if args.nrml:
        skipped, left_out = [], []
        max_p = None if args.nrml_max_probability == 0 else args.nrml_max_probability
        if cube.variants is None:
            functions, left_out = nrml_functions(fits, max_p, args.nrml_min_records)
        else:
            functions, skipped = variant_nrml_functions(fits, analyses, max_p)
        if skipped and not args.json:
            print(f"note: no NRML function for {', '.join(skipped)}: an empirical threshold (a step) or no "
                  f"fragility is not a lognormal")
        if left_out and not args.json:
            print(f"note: no NRML function for {', '.join(left_out)}: fewer than --nrml-min-records "
                  f"{args.nrml_min_records} records")
        if not functions:
            raise InputError(f"{args.cube}: no PGV/PGA bin has a finite fit: no NRML written")
        tree = nrml.fragility_model(args.nrml_id or os.path.splitext(os.path.basename(args.cube))[0],
                                    f"Overturning fragility of precariously balanced rocks from the Rigid cube "
                                    f"{os.path.basename(args.cube)}: " + (
                                        "one lognormal function of GMRotI50 PGA (g) per object and PGV/PGA bin"
                                        if cube.variants is None else
                                        "per object one lognormal function of GMRotI50 PGA (g) per variant (id _vK) "
                                        "at the chosen PGV/PGA, and the pooled one (id _pooled: moment-matched "
                                        "lognormal of the equally weighted mixture of the variants)") + nrml_range_text(max_p),
                                    functions, asset_category=args.nrml_asset_category,
                                    loss_category=args.nrml_loss_category)
        cube_files.write_output(args.nrml, "--nrml", [args.cube], lambda tmp: nrml.write(tmp, tree))
    if not args.no_store:
        store(args.cube, cube, fits, args, analyses)
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
    if args.plot:
        check_plot_path(args)
    try:
        curve = hc.read_curve(args.curve, args.site)
    except hc.CurveError as e:
        raise InputError(str(e))
    state = cube_files.campaign_state(args.cube)
    cube = Cube(args.cube)
    check_completeness(cube, state, args)
    objs = cube.select([args.object] if args.object else None, args.variant)
    names = cube.base_names() if not args.object else [args.object]
    if len(names) > 1:
        raise InputError(f"{args.cube}: {len(names)} objects; choose one with --object "
                         f"({', '.join(names)})")
    if cube.variants is not None and args.variant is None:
        return hazard_pooled(args, cube, curve, objs)
    obj = objs[0]
    cells = ff.Cells(obj.outcome, cube.scales, cube.pgv_pga)
    points = pgv_pga_points(args, cube.pgv_pga[cells.records_with_cells()])
    args.pgv_pga = None
    start_progress(cube, [obj], "hazard")
    try:
        fit = ObjectFit(cube, obj, args, points_s=[s for _, s in points])
    finally:
        end_progress()
    v = fit.vector
    if "points" not in v and fit.threshold is not None:
        # one variant whose outcomes are separated: its empirical threshold, a step, without bootstrap
        t = fit.threshold["theta_g"]
        used_s = cube.pgv_pga[cells.records_with_cells()]
        v = dict(v, points=[{"pgv_pga_s": s, "theta_g": t, "beta": 0.0, "theta_interval_g": ff.NO_INTERVAL,
                             "beta_interval": ff.NO_INTERVAL, "source": THRESHOLD_SOURCE} for _, s in points],
                 replicate_theta_g=np.empty((0, len(points))), replicate_beta=np.empty((0, len(points))),
                 pgv_pga_range_s=[float(used_s.min()), float(used_s.max())])
    if "points" not in v:
        raise InputError(f"{args.cube}: object {obj.label}: no vector fit ({v.get('reason')})")
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
    result = {"cube": args.cube, "object": obj.label, "curve": args.curve, "site": curve.site,
              "curve_pga_range_g": [float(curve.pga_g[0]), float(curve.pga_g[curve.top - 1])],
              **curve_end(curve, mixture),
              "age_years": args.age, "pgv_pga": [{"weight": w, "pgv_pga_s": s} for w, s in points],
              "pgv_pga_weight_outside_records": outside,
              "fragility": [dict({"pgv_pga_s": p["pgv_pga_s"], "theta_g": p["theta_g"], "beta": p["beta"],
                                  "theta_interval_g": p["theta_interval_g"], "beta_interval": p["beta_interval"]},
                                 **({"source": p["source"]} if "source" in p else {}))
                            for p in v["points"]],
              "n_records": v["n_records"], "campaign_scale_range_g": list(fit.scale_range_g),
              "annual_toppling_rate": lam, "annual_toppling_rate_interval": [lam_lo, lam_hi],
              "share_of_rate_beyond_curve": extended,
              "survival_probability": surv,
              "survival_probability_interval": [hc.survival(lam_hi, args.age), hc.survival(lam_lo, args.age)],
              "confidence": args.confidence,
              "ruled_out": surv < 1 - args.confidence,
              "rate_factor_to_rule_out": rate_factor, "pga_factor_to_rule_out": pga_factor,
              "interval_level": args.level, "bootstrap_replicates": args.bootstrap}
    emit_hazard(args, result, lambda: plot_hazard(args.plot, curve, mixture, v, points, result))
    return 0


PLOT_FORMATS = ("png", "pdf", "svg", "eps", "ps", "jpg", "jpeg", "tif", "tiff", "webp")


def check_plot_path(args):
    """--plot: a figure format matplotlib writes, and neither the cube nor the curve."""
    ext = os.path.splitext(args.plot)[1].lower().lstrip(".")
    if ext not in PLOT_FORMATS:
        raise InputError(f"--plot {args.plot}: the file name must end in one of "
                         f"{', '.join('.' + f for f in PLOT_FORMATS)} (the figure's format)")
    cube_files.refuse_output_over_inputs(args.plot, "--plot", [args.cube, args.curve])


def curve_end(curve, mixture):
    """P(topple) of the fragility at the curve's last PGA with a positive rate, and whether the curve
    ends there at rate 0 (nothing counted beyond) or is extended."""
    top = float(curve.pga_g[curve.top - 1])
    p = sum(w * float(hc.fragility_probability(top, t, b)) for w, t, b in mixture)
    return {"fragility_probability_at_curve_end": p, "curve_ends_at_zero": bool(curve.top < len(curve.rate))}


def emit_hazard(args, result, draw):
    """The hazard's report: JSON or the text, then the plot (`draw`) when asked for."""
    warn_incomplete(args)
    if args.json:
        json.dump(json_clean(result), sys.stdout, indent=1, allow_nan=False)
        print()
    else:
        print_hazard(result)
    if args.plot:
        draw()
        if not args.json:
            print(f"wrote {args.plot}")


def hazard_pooled(args, cube, curve, objs):
    """`rigid hazard` on an object with variants: the pooled (mixture) fragility integrated, its
    aleatory interval (bootstrap over records: replicate i of every variant resamples the same
    records, ObjectFit says why, and the pooled replicate mixes them), and the epistemic 5-95 %
    range over variants of the survival probability, each variant's own lognormal integrated."""
    used = set()
    for o in objs:
        used |= set(ff.Cells(o.outcome, cube.scales, cube.pgv_pga).records_with_cells().tolist())
    if not used:
        raise InputError(f"{args.cube}: object {objs[0].name}: no simulated cell in any variant")
    points = pgv_pga_points(args, cube.pgv_pga[sorted(used)])
    args.pgv_pga = None
    start_progress(cube, objs, "hazard")
    try:
        fits = [ObjectFit(cube, o, args, points_s=[s for _, s in points], require_fragility=False) for o in objs]
    finally:
        end_progress()
    per_variant = []  # (variant, source, [(weight, theta, beta)] over the PGV/PGA points)
    for f in fits:
        source = fragility_source(f)
        if source == "vector fit":
            mix = [(w, p["theta_g"], p["beta"]) for (w, _), p in zip(points, f.vector["points"])]
        elif source == SCALAR_SOURCE:  # over all PGV/PGA
            mix = [(1.0, f.scalar["theta_g"], f.scalar["beta"])]
        elif source == THRESHOLD_SOURCE:  # a step does not depend on PGV/PGA
            mix = [(1.0, f.threshold["theta_g"], 0.0)]
        else:
            continue
        per_variant.append((f, source, mix))
    if not per_variant:
        raise InputError(f"{args.cube}: object {objs[0].name}: no variant has a fragility ({fits[0].vector.get('reason')})")
    n = len(per_variant)
    mixture = [(w / n, t, b) for _, _, mix in per_variant for w, t, b in mix]
    lam, extended = hc.mixture_rate(curve, mixture)
    rates = [hc.mixture_rate(curve, mix)[0] for _, _, mix in per_variant]
    survivals = [hc.survival(r, args.age) for r in rates]
    lo_pct, hi_pct = ff.EPISTEMIC_PERCENTILES[0], ff.EPISTEMIC_PERCENTILES[-1]
    # aleatory: replicate i of the pooled fragility; a variant without vector bootstrap (a threshold or
    # the scalar fit) is held fixed, and one whose fit does not exist in resample i (few records:
    # the resample's outcomes are separated) sits that replicate out, the others reweighted; with
    # many variants and few records nearly every resample loses one, and requiring all of them
    # left a handful of replicates and a degenerate interval
    boot = [f.vector["replicate_theta_g"].shape[0] for f, src, _ in per_variant if src == "vector fit"]
    replicates = min(boot) if boot else 0
    reps = []
    for i in range(replicates):
        members = []
        for f, src, mix in per_variant:
            if src == "vector fit":
                t, b = f.vector["replicate_theta_g"][i], f.vector["replicate_beta"][i]
                if np.all(np.isfinite(t)):
                    members.append([(w, t[j], b[j]) for j, (w, _) in enumerate(points)])
            else:
                members.append(mix)
        if members:
            mix_i = [(w / len(members), th, be) for m in members for w, th, be in m]
            reps.append(hc.mixture_rate(curve, mix_i)[0])
    n_records = len(used)
    record_s = cube.pgv_pga[sorted(used)]
    outside = sum(w for w, s in points if not record_s.min() <= s <= record_s.max())
    lam_lo, lam_hi = ff.percentile_interval(reps, args.level, n_records) if reps else ff.NO_INTERVAL
    surv = hc.survival(lam, args.age)
    rate_factor, pga_factor = hc.ruling_factors(curve, mixture, args.age, args.confidence)
    result = {"cube": args.cube, "object": objs[0].name, "pooled": True, "variants": len(fits),
              "variants_pooled": n, "variant": None,
              "variants_without_fragility": [f.obj.variant for f in fits
                                             if all(f is not g for g, _, _ in per_variant)],
              "curve": args.curve, "site": curve.site,
              "curve_pga_range_g": [float(curve.pga_g[0]), float(curve.pga_g[curve.top - 1])],
              **curve_end(curve, mixture),
              "age_years": args.age, "pgv_pga": [{"weight": w, "pgv_pga_s": s} for w, s in points],
              "pgv_pga_weight_outside_records": outside,
              "variant_fragility": [{"variant": f.obj.variant, "source": src,
                                     "lognormals": [{"weight": w, "theta_g": t, "beta": b} for w, t, b in mix],
                                     "annual_toppling_rate": r, "survival_probability": sv}
                                    for (f, src, mix), r, sv in zip(per_variant, rates, survivals)],
              "n_records": n_records,
              "annual_toppling_rate": lam, "annual_toppling_rate_interval": [lam_lo, lam_hi],
              "annual_toppling_rate_epistemic_range": [float(v) for v in np.percentile(rates, [lo_pct, hi_pct])],
              "share_of_rate_beyond_curve": extended,
              "survival_probability": surv,
              "survival_probability_interval": [hc.survival(lam_hi, args.age), hc.survival(lam_lo, args.age)],
              "survival_probability_epistemic_range": [float(v) for v in np.percentile(survivals, [lo_pct, hi_pct])],
              "epistemic_percentiles": [lo_pct, hi_pct],
              "confidence": args.confidence,
              "ruled_out": surv < 1 - args.confidence,
              "rate_factor_to_rule_out": rate_factor, "pga_factor_to_rule_out": pga_factor,
              "interval_level": args.level, "bootstrap_replicates": args.bootstrap}
    no_replicates = {"replicate_theta_g": np.empty((0, len(points))), "replicate_beta": np.empty((0, len(points)))}
    emit_hazard(args, result, lambda: plot_hazard(args.plot, curve, mixture, no_replicates, points,
                                                  dict(result, object=f"{objs[0].name} (pooled)"),
                                                  variant_mixtures=[mix for _, _, mix in per_variant]))
    return 0


def print_hazard(r):
    pct = int(r["interval_level"] * 100)
    site = f" (site {r['site']})" if r["site"] else ""
    lo, hi = r["curve_pga_range_g"]
    print(f"rigid hazard: object {r['object']} of {r['cube']}; hazard curve {r['curve']}{site}, PGA {lo:g}-{hi:g} g; "
          f"exposure age {r['age_years']:g} years")
    if r.get("pooled"):
        thresholds = sum(v["source"] == THRESHOLD_SOURCE for v in r["variant_fragility"])
        scalars = sum(v["source"] == SCALAR_SOURCE for v in r["variant_fragility"])
        print(f"  fragility: pooled over {r['variants_pooled']} of {r['variants']} variants (equally weighted mixture of "
              f"their vector fits" + (f"; {scalars} scalar fit(s) over all records" if scalars else "") +
              (f"; {thresholds} empirical threshold(s), steps" if thresholds else "") + ")")
    elif len(r["fragility"]) == 1:
        f = r["fragility"][0]
        scales = r.get("campaign_scale_range_g")
        theta = fmt_interval(f['theta_g'], *f['theta_interval_g'], scale_range_g=scales)
        print(f"  fragility at PGV/PGA {f['pgv_pga_s']:.3f} s ({f.get('source', 'vector fit')}): theta "
              f"{theta} g, beta {fmt_interval(f['beta'], *f['beta_interval'])}")
        if theta.endswith(BEYOND_MARK):
            print(f"  {BEYOND_MARK} theta's interval reaches beyond the campaign's scales ({scales[0]:g}-{scales[1]:g} g): "
                  f"the records do not bound it there")
    else:
        print(f"  fragility: the vector fit averaged over {len(r['fragility'])} PGV/PGA values of the given distribution")
    if r["pgv_pga_weight_outside_records"] > 0.01:
        print(f"  note: {100 * r['pgv_pga_weight_outside_records']:.0f} % of the PGV/PGA weight lies outside the records' "
              f"range: the vector fit is extrapolated there")
    lam, (a, b) = r["annual_toppling_rate"], r["annual_toppling_rate_interval"]
    have_interval = math.isfinite(a) and math.isfinite(b)
    no_interval = ("[no interval: an empirical threshold]" if r.get("fragility", [{}])[0].get("source") == THRESHOLD_SOURCE
                   else f"[no interval: {r['n_records']} record(s)]")
    print(f"  annual rate of toppling   {lam:.3e} per year  " + (f"[{pct} %: {a:.3e}, {b:.3e}]" if have_interval else no_interval)
          + f"  (mean return period {fmt_years(1 / lam)} years)" if lam > 0 else "  annual rate of toppling 0")
    for line in hazard_warnings(r):
        print(f"  warning: {line}")
    s, (slo, shi) = r["survival_probability"], r["survival_probability_interval"]
    print(f"  P(survives {r['age_years']:g} years) = exp(-lambda T) = {fmt_probability(s)}  "
          + (f"[{pct} %: {fmt_probability(slo)}, {fmt_probability(shi)}]" if have_interval else no_interval)
          + ("  (aleatory: bootstrap over records)" if r.get("pooled") else ""))
    if r.get("pooled"):
        elo, ehi = r["survival_probability_epistemic_range"]
        plo, phi = r["epistemic_percentiles"]
        print(f"  epistemic range over variants ({plo}-{phi} %, each variant's own fragility): P(survives) "
              f"{fmt_probability(elo)} to {fmt_probability(ehi)}")
    c = int(round(r["confidence"] * 100))
    rates, pgas = fmt_factor(r["rate_factor_to_rule_out"], "rates"), fmt_factor(r["pga_factor_to_rule_out"], "PGAs")
    if r["ruled_out"]:
        print(f"  the rock's survival rules this hazard curve out at {c} % confidence (survival below "
              f"{1 - r['confidence']:.2g}); it would be consistent with the curve's {rates} "
              f"or its {pgas}")
    elif not r["annual_toppling_rate"] > 0:
        print(f"  consistent at {c} % confidence: the fragility gives rate 0 under this curve, so no factor on its "
              f"rates rules it out; its {pgas} would")
    else:
        print(f"  consistent at {c} % confidence; the rock would rule the curve out with its {rates} or its {pgas}")


# Below this P(topple) at the hazard curve's last PGA, the fragility reaches past the curve: the
# rate then rests on what the curve is taken to be beyond its end, which no hazard model said.
CURVE_END_PROBABILITY = 0.9


def hazard_warnings(r):
    """What the reader of a rate must know: a curve ending below the fragility's range, a share of
    the rate from the curve's power-law extension."""
    out = []
    p_end, top = r.get("fragility_probability_at_curve_end"), r["curve_pga_range_g"][1]
    if p_end is not None and p_end < CURVE_END_PROBABILITY:
        beyond = ("PGAs above it are counted as never exceeded (the curve ends at rate 0)" if r.get("curve_ends_at_zero")
                  else "the rate rests on the curve's power-law extension beyond it")
        out.append(f"the hazard curve ends at {top:g} g, where P(topple | PGA) is only {fmt_probability(p_end, 3)}: "
                   f"the fragility lies beyond the curve, and {beyond}; a curve reaching higher PGAs would tell")
    share = r["share_of_rate_beyond_curve"]
    if share > 0.01:
        out.append(f"{100 * share:.1f} % of the rate comes from PGAs outside the curve's {r['curve_pga_range_g'][0]:g}-"
                   f"{top:g} g, where it is extended by its end segments' power law (not data)")
    return out


def fmt_years(v):
    """A number of years: grouped digits up to ten million, then three significant digits."""
    return f"{v:,.0f}" if v < 1e7 else f"{v:.3g}"


def plot_hazard(path, curve, mixture, v, points, r, variant_mixtures=()):
    """The hazard curve, the fragility with its bootstrap band (or, pooled over variants, the 5-95 %
    band of the variants' fragilities: `variant_mixtures`, one mixture per variant), the integrand."""
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
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.5, 8.3), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
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
    if len(variant_mixtures):
        curves = np.array([sum(w * hc.fragility_probability(a, t, b) for w, t, b in mix) for mix in variant_mixtures])
        right.fill_between(a, np.percentile(curves, 5, axis=0), np.percentile(curves, 95, axis=0),
                           color="tab:purple", alpha=0.2, label="5-95 % over variants (epistemic)")
    right.set_ylim(0, 1.02)
    right.set_ylabel("P(topple | PGA)")
    lines = top.get_legend_handles_labels()
    lines2 = right.get_legend_handles_labels()
    # below the panels, off the curves (inside, every corner holds the hazard curve or the fragility)
    fig.legend(lines[0] + lines2[0], lines[1] + lines2[1], loc="lower center", ncol=2, fontsize=8, frameon=False)
    top.set_title(f"{r['object']}: toppling rate {r['annual_toppling_rate']:.2e}/yr, "
                  f"P(survive {r['age_years']:g} yr) = {fmt_probability(r['survival_probability'], 3)}", fontsize=10)
    bottom.semilogx(a, dens, color="black")
    bottom.fill_between(a, 0, dens, color="gray", alpha=0.3)
    bottom.set_xlabel("PGA (g, GMRotI50)")
    bottom.set_ylabel("d lambda / d ln PGA (per year)")
    bottom.grid(True, which="both", alpha=0.3)
    fig.tight_layout(rect=(0, 0.09, 1, 1))
    fmt = os.path.splitext(path)[1].lower().lstrip(".")
    cube_files.write_output(path, "--plot", [], lambda tmp: fig.savefig(tmp, dpi=120, format=fmt))
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
        sp.add_argument("--require-complete", action="store_true",
                        help="refuse a cube whose campaign has not run every cell (stopped or still running); "
                             "default: fit the cells run so far, with a warning")
        sp.add_argument("--variant", type=int, metavar="K",
                        help="a cube with variants: only variant K (0-based); default: every variant, and "
                             "their pooled fragility")

    f = sub.add_parser("fragility", help="fit fragilities per object: per PGV/PGA bin and at a chosen PGV/PGA")
    common(f)
    f.add_argument("--object", action="append", help="only this object (repeatable; every variant of it); default: all")
    f.add_argument("--csv", help="write one row per object and bin (and the vector fit) to this CSV")
    f.add_argument("--nrml", help="write an OpenQuake NRML 0.5 fragility model (one function per object and bin)")
    f.add_argument("--nrml-id", help="id of the NRML fragilityModel (default: the cube's file name without .h5)")
    f.add_argument("--nrml-asset-category", default="buildings",
                   help="assetCategory of the NRML fragilityModel (default buildings, what the engine's exposure "
                        "models use; OpenQuake matches it against the exposure)")
    f.add_argument("--nrml-loss-category", default="structural",
                   help="lossCategory of the NRML fragilityModel (default structural)")
    f.add_argument("--nrml-max-probability", type=float, default=0.99, metavar="P",
                   help="each function's maxIML is the PGA where its lognormal reaches P, or the campaign's top "
                        "scale when higher (OpenQuake holds P at P(maxIML) above it); 0: the campaign's top scale "
                        "(default 0.99)")
    f.add_argument("--nrml-min-records", type=int, default=0, metavar="N",
                   help="leave PGV/PGA bins fitted on fewer than N records out of the NRML (default 0: all; the "
                        "table and CSV flag bins with fewer than 3)")
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
        if not 0 <= args.seed < 2 ** 63:
            raise InputError(f"--seed {args.seed}: must be a whole number from 0 to 2^63 - 1")
        if args.bootstrap < 20 or args.bootstrap > 100000:
            raise InputError(f"--bootstrap {args.bootstrap}: must be 20-100000")
        if not 0.5 <= args.level < 1:
            raise InputError(f"--level {args.level}: must be in [0.5, 1)")
        if args.pgv_pga is not None and not (args.pgv_pga > 0 and math.isfinite(args.pgv_pga)):
            raise InputError(f"--pgv-pga {args.pgv_pga}: must be a positive number of seconds")
        if getattr(args, "pgv_pga_dist", None) and args.pgv_pga is not None:
            raise InputError("--pgv-pga and --pgv-pga-dist: give one")
        return args.func(args)
    except (InputError, cube_files.OutputError) as e:
        # a cube that cannot be fitted may be one whose campaign has not run the cells yet: say so
        incomplete = getattr(args, "incomplete", None)
        more = f" ({incomplete})" if incomplete and incomplete not in str(e) else ""
        sys.stderr.write(f"rigid {args.command}: error: {e}{more}\n")
        return 2
    except OSError as e:
        sys.stderr.write(f"rigid {args.command}: error: {e}\n")
        return 2
    except Exception as e:  # a bug of ours, not the input's: one line, exit 1
        sys.stderr.write(f"rigid {args.command}: internal error: {type(e).__name__}: {e}\n")
        return 1


if __name__ == "__main__":
    sys.exit(main())
