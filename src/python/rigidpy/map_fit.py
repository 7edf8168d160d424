"""The fit a map draws for one object: alpha and p from the command line or the cube's attributes
(the normalisation of u and x), the probit fit of the object's simulated cells (fit.py), its
contours, and the lognormal it gives at one PGV/PGA (a variant's curve in the band figure)."""
import math

import numpy as np

from . import fit as fragility_fit
from .errors import InputError
from .fit import SCALAR_SOURCE, THRESHOLD_SOURCE, fit_mu, fit_probit, fit_sigma, norm_ppf
from .outcomes import simulated_counts

FIT_LABEL = "this project's probit fit in the variables of Purvance et al. (2008), not their coefficients"
CONTOUR_LEVELS = (1, 50, 99)


def parse_per_object(values, option):
    """['0.2', 'rock_a=0.3'] -> (default or None, {name: value})."""
    default, per = None, {}
    for v in values or []:
        if "=" in v:
            name, _, num = v.rpartition("=")
        else:
            name, num = None, v
        try:
            val = float(num)
        except ValueError:
            raise InputError(f"{option} {v!r}: expected a number or NAME=NUMBER")
        if not (val > 0 and math.isfinite(val)):
            raise InputError(f"{option} {v!r}: must be positive")
        if name is None:
            default = val
        else:
            per[name] = val
    return default, per


def block_parameter(cube, obj, attr, cli):
    default, per = cli
    if obj.name in per:
        return per[obj.name], "command line"
    if default is not None:
        return default, "command line"
    for where, attrs in (("object attribute", obj.attrs), ("root attribute", cube.root_attrs)):
        if attr in attrs:
            try:
                v = float(np.asarray(attrs[attr]).reshape(-1)[0])
            except (TypeError, ValueError):
                continue
            if v > 0 and math.isfinite(v):
                return v, f"{where} {attr}"
    return None, "unknown"


class Normalisation:
    def __init__(self, alpha, alpha_src, p, p_src):
        self.alpha, self.alpha_src, self.p, self.p_src = alpha, alpha_src, p, p_src
        self.u_shift = -math.log(math.tan(alpha)) if alpha else 0.0          # u = ln(PGA_g) + u_shift
        self.x_shift = math.log(p / alpha) if (alpha and p) else 0.0          # x = ln(PGV/PGA) + x_shift

    def describe(self):
        u = "ln(PGA / (g tan alpha))" if self.alpha else "ln(PGA / g)  (alpha unknown: not normalised)"
        x = ("ln((PGV/PGA) p / alpha)" if (self.alpha and self.p)
             else "ln(PGV/PGA / 1 s)  (alpha or p unknown: not normalised)")
        return u, x

    def pga_g(self, u):
        return np.exp(np.asarray(u) - self.u_shift)

    def x_of(self, pgv_pga):
        return np.log(np.asarray(pgv_pga, float)) + self.x_shift


def fit_object(cube, obj, norm, mu_degree, sigma_degree):
    """Binomial rows (u, x, k, n) of one object and its fit; None fit if too little data."""
    over, known = simulated_counts(obj.outcome)
    n = known.astype(float)          # [R, S]
    k = over.astype(float)
    R, S = n.shape
    rec_ok = np.isfinite(cube.pgv_pga) & (cube.pgv_pga > 0)
    rows = [(r, s) for r in range(R) for s in range(S) if n[r, s] > 0 and rec_ok[r] and cube.scales[s] > 0]
    info = {"object": obj.label, "label": FIT_LABEL,
            "model": "P = Phi((u - mu(x)) / sigma(x)), mu polynomial in x, ln sigma polynomial in x",
            "u": norm.describe()[0], "x": norm.describe()[1],
            "alpha_rad": norm.alpha, "alpha_source": norm.alpha_src,
            "p_rad_s": norm.p, "p_source": norm.p_src,
            "outcomes": "simulated cells (record, scale, rotation): overturned = 1, survived = 0; inferred cells left out",
            "n_cells": int(sum(n[r, s] for r, s in rows)),
            "n_overturned": int(sum(k[r, s] for r, s in rows)),
            "n_records": int(len({r for r, _ in rows}))}
    if not rows:
        info["fit"] = None
        info["reason"] = "no known cells"
        return info, None
    rr = np.array([r for r, _ in rows])
    ss = np.array([s for _, s in rows])
    u = np.log(cube.scales[ss]) + norm.u_shift
    x = norm.x_of(cube.pgv_pga[rr])
    kk, nn = k[rr, ss], n[rr, ss]
    distinct_x = len(np.unique(np.round(x, 12)))
    md = min(mu_degree, distinct_x - 1)
    sd = min(sigma_degree, distinct_x - 1)
    info["mu_degree"], info["sigma_degree"] = md, sd
    if md < mu_degree or sd < sigma_degree:
        info["degree_note"] = f"reduced to the {distinct_x} distinct PGV/PGA values"
    n_par = md + sd + 2
    if info["n_overturned"] < 2 or info["n_cells"] - info["n_overturned"] < 2 or info["n_cells"] < n_par + 3:
        info["fit"] = None
        info["reason"] = "too little data (needs >= 2 overturned, >= 2 survived, > parameters + 2 cells)"
        return info, None
    if n_par > distinct_x:
        info["warning"] = (f"{n_par} parameters for {distinct_x} distinct PGV/PGA values: the fit interpolates "
                           "between few records; lower --mu-degree/--sigma-degree")
    fit = fit_probit(u, x, kk, nn, md, sd)
    info["fit"] = fit
    if fit["separated"]:
        info["reason"] = ("no finite maximum-likelihood estimate: the outcomes are (quasi-)separated "
                          "(sigma -> 0); contours not drawn")
        return info, None
    info["x_range"] = [float(x.min()), float(x.max())]
    # the lognormal the fit gives at the records' median PGV/PGA, where `rigid fragility` reads its
    # vector fit (the same fit at the default degrees: one median per fit, not two)
    info["reference_pgv_pga_s"] = fragility_fit.reference_pgv_pga_s(cube.pgv_pga, rr)
    info["reference_theta_g"] = float(contour_pga(fit, norm, np.array([info["reference_pgv_pga_s"]]), 50)[0])
    info["reference_beta"] = float(fit_sigma(fit, norm.x_of([info["reference_pgv_pga_s"]]))[0])
    info["pgv_pga_range_s"] = [float(cube.pgv_pga[rr].min()), float(cube.pgv_pga[rr].max())]
    # the contour PGA at each bin's median record PGV/PGA, for tables
    bins = cube.bin_of_records()
    table = []
    for b in range(len(cube.edges) - 1):
        sel = [r for r in set(rr.tolist()) if bins[r] == b]
        if not sel:
            continue
        v = float(np.median(cube.pgv_pga[sel]))
        row = {"bin": b, "pgv_pga_s": v}
        for lev in CONTOUR_LEVELS:
            row[f"pga_g_{lev}pct"] = float(contour_pga(fit, norm, np.array([v]), lev)[0])
        table.append(row)
    info["contours_at_bin_median_pgv_pga"] = table
    return info, fit


def contour_pga(fit, norm, pgv_pga, level_pct):
    x = norm.x_of(pgv_pga)
    q = norm_ppf(level_pct / 100.0)
    return norm.pga_g(fit_mu(fit, x) + fit_sigma(fit, x) * q)


def fit_probability(fit, norm, pga_g, pgv_pga):
    return fragility_fit.fit_probability(fit, np.log(pga_g) + norm.u_shift, norm.x_of(pgv_pga))



def normalisation_for(cube, obj, args):
    alpha, asrc = block_parameter(cube, obj, "alpha_rad", parse_per_object(args.alpha, "--alpha"))
    p, psrc = block_parameter(cube, obj, "p_rad_s", parse_per_object(args.p, "--p"))
    if alpha is not None and not alpha < math.pi / 2:
        raise InputError(f"{obj.label}: alpha = {alpha} rad is not below pi/2")
    return Normalisation(alpha, asrc, p, psrc)



def map_lognormal(cube, obj, args, pgv_pga_s):
    """(theta_g, beta, how) of one variant at PGV/PGA `pgv_pga_s` for the band figure: the map's fit there (median
    and sigma of ln PGA), else the scalar fit over all records, else the empirical threshold of
    separated outcomes (a step), else None."""
    norm_ = normalisation_for(cube, obj, args)
    info, fit = fit_object(cube, obj, norm_, args.mu_degree, args.sigma_degree)
    if fit is not None:
        theta = float(contour_pga(fit, norm_, np.array([pgv_pga_s]), 50)[0])
        return theta, float(fit_sigma(fit, norm_.x_of([pgv_pga_s]))[0]), "fit"
    # the same fallbacks, in the same order, as rigid fragility's pool (fragility.fragility_source)
    cells = fragility_fit.Cells(obj.outcome, cube.scales, cube.pgv_pga)
    scalar = fragility_fit.lognormal_fit(*fragility_fit.scalar_rows(cells, cells.records_with_cells()))
    if scalar is not None:
        return scalar["theta_g"], scalar["beta"], SCALAR_SOURCE
    step = fragility_fit.empirical_threshold(cells)
    if step is not None:
        return step["theta_g"], 0.0, THRESHOLD_SOURCE
    return None, None, info.get("reason", "no fit")

