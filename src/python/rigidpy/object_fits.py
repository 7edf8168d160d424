"""The fits of a cube's objects for `rigid fragility` and `rigid hazard`: per object the
scalar fit per PGV/PGA bin and the vector fit with their bootstrap (fit.py), and per object with
variants the pooled fragility and the sensitivity across variants (VariantAnalysis)."""
import math

import numpy as np

from . import fit as ff
from . import progress
from . import sensitivity
from .errors import InputError
from .fit import SCALAR_SOURCE, THRESHOLD_SOURCE
from .map_fit import Normalisation, block_parameter, parse_per_object


METHOD = ("maximum likelihood (probit) on the simulated cells (overturned 1, survived 0); the stop rule's "
          "inferred cells, not-run and failed cells left out; per PGV/PGA bin P = Phi(ln(PGA/theta)/beta) on "
          "the bin's records; vector fit P = Phi((u - mu(x))/sigma(x)), u = ln(PGA/(g tan alpha)), "
          "x = ln((PGV/PGA) p/alpha), mu linear, sigma constant (this project's form, not Purvance et al. "
          "2008's coefficients); intervals: percentile bootstrap over records (Hesterberg's expanded "
          "percentile), records resampled with replacement")


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
                          else ff.reference_pgv_pga_s(cube.pgv_pga, records))
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
        # a calibrated object's variants are its calibration's members, pooled by their weights
        # (those with a fragility, renormalised); other variants count equally
        self.calibration = cube.calibrations.get(self.name)
        all_weights = cube.variant_weights(self.name)
        weights = None
        if self.calibration is not None:
            weights = [float(all_weights[f.obj.variant]) for f, d in zip(fits, self.lognormals)
                       if math.isfinite(d["theta_g"])]
        self.n_threshold = sum(d["source"] == THRESHOLD_SOURCE for d in self.lognormals)
        self.without = [f.obj.variant for f, d in zip(fits, self.lognormals) if d["source"] == "none"]
        self.pooled = None
        if usable:
            lo_g, hi_g = fits[0].scale_range_g
            spread = max([b for _, b in usable] + [0.1])
            grid = np.geomspace(min([t for t, _ in usable] + [lo_g]) * math.exp(-3 * spread),
                                max([t for t, _ in usable] + [hi_g]) * math.exp(3 * spread), 200)
            self.pooled = ff.pooled_fragility(usable, grid, weights)
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

    def weights_text(self):
        if self.calibration is None:
            return "variants equally weighted"
        return (f"each variant by its weight in the calibration {self.calibration.path} "
                f"({len(self.calibration.weights)} member scenes)")

    def document(self):
        """JSON of the analysis (arrays as lists)."""
        return {"object": self.name, "variants": len(self.fits), "pgv_pga_s": self.pgv_pga_s,
                "variant_fragility": [dict(d, variant=f.obj.variant, label=f.obj.label)
                                      for f, d in zip(self.fits, self.lognormals)],
                "variants_with_empirical_threshold": self.n_threshold,
                "variants_without_fragility": self.without,
                "pooled": None if self.pooled is None else dict(self.pooled, weights=self.weights_text()),
                "calibration": None if self.calibration is None else {
                    "path": self.calibration.path, "sha256": self.calibration.sha256,
                    "members": len(self.calibration.weights),
                    "weights": [float(w) for w in self.calibration.weights],
                    "summary": self.calibration.summary},
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
