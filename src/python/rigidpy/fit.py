"""Maximum-likelihood fragility fits of a cube's cells and their bootstrap over records: the one
owner of the fit that `rigid plot` draws and `rigid fragility` / `rigid hazard` report.

The model (this project's, not Purvance et al. 2008, whose coefficients are not available:
physics.md section 1) is a probit with a scale that may depend on x:

    P(overturn) = Phi((u - mu(x)) / sigma(x)),   mu polynomial in x, ln sigma polynomial in x,

u = ln PGA (normalised by g tan alpha when alpha is known), x = ln PGV/PGA (normalised by alpha/p).
With mu and sigma constant it is the scalar lognormal fragility P = Phi(ln(PGA/theta) / beta).

Cells: the simulated ones (overturned = 1, survived = 0). The stop rule's inferred cells are
left out: they are the rule's assumption (a record that overturned the block at `stop_after`
scales running would at every higher one), not simulations. Which cells were simulated depends on earlier outcomes only, so leaving the
others out keeps the likelihood exact (a data-dependent design does not enter it). Counting them as
overturned trials shrinks beta (3 % on the planted layout of tests/python/test_fragility_fit.py).

Normal distribution functions are scipy.special's; the optimiser is scipy.optimize's trust-region
Newton-CG method on the exact gradient and Hessian below. statsmodels' GLM fits the constant-scale probit
too (tests/python/test_fragility_fit.py checks both agree) but not a scale that varies with x.
"""
import math

import numpy as np
from scipy import optimize, stats
from scipy.special import log_ndtr, ndtr, ndtri

from .outcomes import INFERRED, simulated_counts

# What stands for an object (a variant) when its vector fit has no finite estimate, in this order
# (fragility.fragility_source; map_fit.map_lognormal follows the same order).
SCALAR_SOURCE = "scalar fit (all records)"
THRESHOLD_SOURCE = "empirical threshold"

# Told of each bootstrap resample and each finished fit when set (progress.FitProgress: the
# command's progress line); this module itself writes nothing.
PROGRESS = None
_LOG_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)


def norm_ppf(p):
    """Phi^-1(p) for 0 < p < 1."""
    if not 0.0 < p < 1.0:
        raise ValueError("norm_ppf needs 0 < p < 1")
    return float(ndtri(p))


def _mills(z):
    """phi(z) / Phi(z), stable for very negative z."""
    with np.errstate(over="ignore"):
        logphi = -0.5 * z * z - _LOG_SQRT_2PI
    return np.exp(logphi - log_ndtr(z))


def design(x, degree):
    return np.vstack([x**j for j in range(degree + 1)]).T  # [n, degree+1]


def probit_derivatives(theta, u, x, k, n, mu_degree, sigma_degree):
    """Log-likelihood, gradient and Hessian of the binomial probit in theta = (m..., s...)."""
    dm = mu_degree + 1
    Xm = design(x, mu_degree)
    Xs = design(x, sigma_degree)
    inv_sigma = np.exp(-(Xs @ theta[dm:]))
    z = (u - Xm @ theta[:dm]) * inv_sigma
    ll = float(np.sum(k * log_ndtr(z) + (n - k) * log_ndtr(-z)))
    lp, lm = _mills(z), _mills(-z)
    g1 = k * lp - (n - k) * lm                                   # d ll / dz
    g2 = -k * lp * (z + lp) - (n - k) * lm * (-z + lm)           # d2 ll / dz2 (< 0)
    J = np.hstack([-Xm * inv_sigma[:, None], -Xs * z[:, None]])  # dz / dtheta
    grad = J.T @ g1
    H = (J * g2[:, None]).T @ J
    # second derivatives of z: d2z/dm ds = x^j x^l / sigma, d2z/ds ds = z x^j x^l
    cross = (Xm * (g1 * inv_sigma)[:, None]).T @ Xs
    H[:dm, dm:] += cross
    H[dm:, :dm] += cross.T
    H[dm:, dm:] += (Xs * (g1 * z)[:, None]).T @ Xs
    return ll, grad, H


def fit_probit(u, x, k, n, mu_degree=1, sigma_degree=0, start=None):
    """Maximum-likelihood fit of P = Phi((u - mu(x)) / sigma(x)) to k overturned out of n cells at
    (u, x), rows weighted by n (bootstrap counts enter as weights). Returns a dict: coefficients,
    standard errors (inverse observed information), log-likelihoods, `separated` when the outcomes
    have no finite maximum-likelihood estimate (sigma -> 0)."""
    u, x, k, n = (np.asarray(a, dtype=float) for a in (u, x, k, n))
    keep = n > 0
    u, x, k, n = u[keep], x[keep], k[keep], n[keep]
    dm, ds = mu_degree + 1, sigma_degree + 1
    if start is None:
        w = n / n.sum()
        u0 = float(np.sum(w * u))
        start = np.zeros(dm + ds)
        start[0] = u0
        start[dm] = math.log(max(float(np.sqrt(np.sum(w * (u - u0) ** 2))), 0.05))
    cache = {}

    def evaluate(theta):
        key = theta.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = probit_derivatives(theta, u, x, k, n, mu_degree, sigma_degree)
        return cache[key]

    # trust-ncg, not trust-exact: a singular Hessian (a coefficient the data cannot identify, as in
    # a bootstrap resample of one record) sends trust-exact's subproblem solver into an endless loop
    res = optimize.minimize(lambda t: -evaluate(t)[0], np.asarray(start, float), method="trust-ncg",
                            jac=lambda t: -evaluate(t)[1], hess=lambda t: -evaluate(t)[2],
                            options={"gtol": 1e-9, "maxiter": 200})
    theta = res.x
    ll, grad, H = evaluate(theta)
    sigma_data = np.exp(design(x, sigma_degree) @ theta[dm:])
    se = [float("nan")] * len(theta)
    try:
        d = np.diag(np.linalg.inv(-H))
        if np.all(d > 0):
            se = [float(v) for v in np.sqrt(d)]
    except np.linalg.LinAlgError:
        pass
    # (quasi-)separated outcomes have no finite estimate: the optimiser stops where the likelihood
    # no longer changes, with sigma tending to 0, the cells classified perfectly (ll -> 0), or
    # coefficients without curvature (standard errors of thousands)
    separated = (bool(np.min(sigma_data) < 1e-4) or not bool(np.all(np.isfinite(theta))) or abs(ll) < 1e-6
                 or not all(math.isfinite(v) and v < 1e3 for v in se))
    # the trust region stops on rounding ("bad approximation") once steps are at the noise of the
    # log-likelihood; a gradient that small is the optimum all the same
    converged = (bool(res.success) or float(np.max(np.abs(grad))) <= 1e-6 * max(1.0, abs(ll))) and not separated
    pbar = float(k.sum() / n.sum())
    ll0 = float(np.sum(k * math.log(pbar) + (n - k) * math.log(1 - pbar))) if 0 < pbar < 1 else 0.0
    return {
        "mu_coefficients": [float(v) for v in theta[:dm]],
        "log_sigma_coefficients": [float(v) for v in theta[dm:]],
        "mu_se": se[:dm],
        "log_sigma_se": se[dm:],
        "log_likelihood": ll,
        "null_log_likelihood": ll0,
        "iterations": int(res.nit),
        "converged": converged,
        "separated": separated,
        "gradient_norm": float(np.max(np.abs(grad))),
    }


def fit_mu(fit, x):
    return np.polyval(fit["mu_coefficients"][::-1], x)


def fit_sigma(fit, x):
    return np.exp(np.polyval(fit["log_sigma_coefficients"][::-1], x))


def fit_probability(fit, u, x):
    return ndtr((np.asarray(u, float) - fit_mu(fit, x)) / fit_sigma(fit, x))


# --------------------------------------------------------------------------------------------
# Cells of one object


class Cells:
    """One object's simulated cells as binomial rows per (record, scale)."""

    def __init__(self, outcome, scales_g, pgv_pga_s):
        over, sim = simulated_counts(outcome)
        self.k = over.astype(float)  # [R, S]
        self.n = sim.astype(float)
        self.scales_g = np.asarray(scales_g, float)
        self.pgv_pga_s = np.asarray(pgv_pga_s, float)
        self.inferred = int(np.sum(outcome == INFERRED))
        usable = np.isfinite(self.pgv_pga_s) & (self.pgv_pga_s > 0)
        self.n[~usable, :] = 0
        self.k[~usable, :] = 0
        self.n[:, ~(self.scales_g > 0)] = 0
        self.k[:, ~(self.scales_g > 0)] = 0

    def records_with_cells(self, records=None):
        idx = np.arange(self.n.shape[0]) if records is None else np.asarray(records, int)
        return idx[self.n[idx].sum(axis=1) > 0]


def reference_pgv_pga_s(pgv_pga_s, records):
    """The PGV/PGA (s) at which a vector fit is read as one lognormal unless told otherwise: the
    median over the fitted records (each once). `rigid fragility`, `rigid hazard` and `rigid plot
    maps` all read it here, so one cube gives one median per fit."""
    return float(np.median(np.asarray(pgv_pga_s, float)[np.unique(np.asarray(records, int))]))


def scalar_rows(cells, records, weights=None):
    """Rows (ln PGA_g, k, n) of a scalar fit over `records`, records weighted by `weights`
    (bootstrap counts). PGA is the only regressor, so rows aggregate over records per scale."""
    w = np.ones(len(records)) if weights is None else np.asarray(weights, float)
    k = w @ cells.k[records]
    n = w @ cells.n[records]
    return np.log(np.where(cells.scales_g > 0, cells.scales_g, 1.0)), k, n


def lognormal_fit(u, k, n, start=None):
    """Scalar fit: median theta (g) and dispersion beta, from rows (ln PGA_g, k, n). None when
    there is no finite estimate (no overturned or no surviving cell, or separated outcomes)."""
    if not (np.sum(k) > 0 and np.sum(n - k) > 0):
        return None
    fit = fit_probit(u, np.zeros_like(u), k, n, 0, 0, start=start)
    if fit["separated"] or not fit["converged"]:
        return None
    return {"theta_g": math.exp(fit["mu_coefficients"][0]), "beta": math.exp(fit["log_sigma_coefficients"][0]),
            "log_likelihood": fit["log_likelihood"], "start": np.array(fit["mu_coefficients"] + fit["log_sigma_coefficients"])}


def bootstrap_counts(rng, n_records, replicates):
    """Records drawn with replacement: [replicates, n_records] counts (records, not cells, are the
    independent samples: cells of one record share its waveform)."""
    return rng.multinomial(n_records, np.full(n_records, 1.0 / n_records), size=replicates)


def percentile_interval(values, level, n_samples):
    """Hesterberg's expanded percentile interval (The American Statistician 69(4), 2015): the
    plain percentile interval is too narrow by about sqrt((n-1)/n) with few records, which left
    the 90 % interval covering the truth in 84.5 % of planted replicates on 20 records; the tail
    probability is widened to Phi(-sqrt(n/(n-1)) t_{n-1}(1 - tail))."""
    v = np.asarray([x for x in values if x is not None and np.isfinite(x)], float)
    if v.size == 0:
        return (float("nan"), float("nan"))
    tail = 0.5 * (1 - level)
    if n_samples > 2:
        tail = float(ndtr(-math.sqrt(n_samples / (n_samples - 1)) * stats.t.ppf(1 - tail, n_samples - 1)))
    lo, hi = np.percentile(v, [100 * tail, 100 * (1 - tail)])
    return (float(lo), float(hi))


# Fewer records than this give no interval: resampling one or two records cannot show how the
# fit would vary over other records (every resample of one record is that record).
MIN_RECORDS_FOR_INTERVAL = 3
# Bootstrap replicates of an interval unless --bootstrap says otherwise, for every command: a 90 %
# percentile interval reads the 5th and 95th percentiles, which 1000 replicates place on 50
# replicates each, 200 on only 10 (Efron & Tibshirani 1993, ch. 19: 1000 or more for percentile
# intervals, 200 suffices only for standard errors).
DEFAULT_BOOTSTRAP = 1000
NO_INTERVAL = (float("nan"), float("nan"))


def few_records_note(n):
    """The flag of a fit on fewer than MIN_RECORDS_FOR_INTERVAL records."""
    return (f"only {n} record(s), fewer than {MIN_RECORDS_FOR_INTERVAL}: no bootstrap interval, and the fit says "
            f"little beyond these records")


def _resample_done(replicates):
    if PROGRESS is not None:
        PROGRESS.resample(replicates)


def _fit_done():
    if PROGRESS is not None:
        PROGRESS.fit_done()


def scalar_fragility(cells, records, rng, replicates, level=0.9):
    """theta, beta of `records` with percentile-bootstrap intervals (records resampled)."""
    try:
        return _scalar_fragility(cells, records, rng, replicates, level)
    finally:
        _fit_done()


def _scalar_fragility(cells, records, rng, replicates, level):
    records = cells.records_with_cells(records)
    out = {"n_records": int(len(records)), "n_cells": int(cells.n[records].sum()),
           "n_overturned": int(cells.k[records].sum())}
    if len(records) == 0:
        out["reason"] = "no simulated cell"
        return out
    u, k, n = scalar_rows(cells, records)
    fit = lognormal_fit(u, k, n)
    if fit is None:
        out["reason"] = ("no overturned cell" if out["n_overturned"] == 0 else
                         "no surviving cell" if out["n_overturned"] == out["n_cells"] else
                         "outcomes separated by PGA (no finite estimate)")
        return out
    if len(records) < MIN_RECORDS_FOR_INTERVAL:
        out.update(theta_g=fit["theta_g"], beta=fit["beta"], log_likelihood=fit["log_likelihood"],
                   theta_interval_g=NO_INTERVAL, beta_interval=NO_INTERVAL, bootstrap_replicates=0, bootstrap_failed=0,
                   interval_note=few_records_note(len(records)))
        return out
    thetas, betas, failed = [], [], 0
    for counts in bootstrap_counts(rng, len(records), replicates):
        _resample_done(replicates)
        b = lognormal_fit(*scalar_rows(cells, records, counts), start=fit["start"])
        if b is None:
            failed += 1
            continue
        thetas.append(b["theta_g"])
        betas.append(b["beta"])
    out.update(theta_g=fit["theta_g"], beta=fit["beta"], log_likelihood=fit["log_likelihood"],
               theta_interval_g=percentile_interval(thetas, level, len(records)),
               beta_interval=percentile_interval(betas, level, len(records)),
               bootstrap_replicates=int(replicates), bootstrap_failed=int(failed))
    return out


def vector_rows(cells, records, u_shift, x_shift, weights=None):
    """Rows (u, x, k, n) of the vector fit, one per (record, scale) of `records` with cells; u =
    ln PGA_g + u_shift, x = ln PGV/PGA + x_shift; records weighted by `weights`."""
    records = np.asarray(records, int)
    w = np.ones(len(records)) if weights is None else np.asarray(weights, float)
    S = len(cells.scales_g)
    u = np.tile(np.log(np.where(cells.scales_g > 0, cells.scales_g, 1.0)) + u_shift, len(records))
    x = np.repeat(np.log(cells.pgv_pga_s[records]) + x_shift, S)
    k = (cells.k[records] * w[:, None]).ravel()
    n = (cells.n[records] * w[:, None]).ravel()
    return u, x, k, n


def lognormal_at(fit, u_shift, x):
    """Median PGA (g) and dispersion of the vector fit at normalised PGV/PGA x."""
    return float(np.exp(fit_mu(fit, x) - u_shift)), float(fit_sigma(fit, x))


def vector_fragility(cells, records, u_shift, x_shift, points_s, rng, replicates, level=0.9, mu_degree=1,
                     sigma_degree=0):
    """The vector fit on `records`, and theta, beta at each PGV/PGA of `points_s` with bootstrap
    intervals (records resampled). `replicate_theta_g`/`replicate_beta` [replicate, point] keep the
    bootstrap's lognormals for what is computed from them (the hazard's interval)."""
    try:
        return _vector_fragility(cells, records, u_shift, x_shift, points_s, rng, replicates, level, mu_degree,
                                 sigma_degree)
    finally:
        _fit_done()


def _vector_fragility(cells, records, u_shift, x_shift, points_s, rng, replicates, level, mu_degree, sigma_degree):
    records = cells.records_with_cells(records)
    out = {"n_records": int(len(records)), "n_cells": int(cells.n[records].sum()),
           "n_overturned": int(cells.k[records].sum())}
    distinct = len(np.unique(np.round(cells.pgv_pga_s[records], 12)))
    md, sd = min(mu_degree, max(distinct - 1, 0)), min(sigma_degree, max(distinct - 1, 0))
    out.update(mu_degree=md, sigma_degree=sd)
    if out["n_overturned"] == 0 or out["n_overturned"] == out["n_cells"]:
        out["reason"] = "no overturned cell" if out["n_overturned"] == 0 else "no surviving cell"
        return out
    fit = fit_probit(*vector_rows(cells, records, u_shift, x_shift), md, sd)
    if fit["separated"] or not fit["converged"]:
        out["reason"] = "outcomes separated (no finite estimate)"
        return out
    start = np.array(fit["mu_coefficients"] + fit["log_sigma_coefficients"])
    xs = np.log(np.asarray(points_s, float)) + x_shift
    if len(records) < MIN_RECORDS_FOR_INTERVAL:
        replicates = 0
        out["interval_note"] = few_records_note(len(records))
    theta = np.empty((replicates, len(xs)))
    beta = np.empty((replicates, len(xs)))
    failed = 0
    x_of_record = np.round(cells.pgv_pga_s[records], 12)
    for i, counts in enumerate(bootstrap_counts(rng, len(records), replicates)):
        _resample_done(replicates)
        # a resample with fewer distinct PGV/PGA values than mu(x) has coefficients cannot say how
        # the fragility moves with PGV/PGA: no estimate, like a separated resample
        if len(np.unique(x_of_record[counts > 0])) <= max(md, sd):
            theta[i], beta[i] = np.nan, np.nan
            failed += 1
            continue
        b = fit_probit(*vector_rows(cells, records, u_shift, x_shift, counts), md, sd, start=start)
        if b["separated"] or not b["converged"]:
            theta[i], beta[i] = np.nan, np.nan
            failed += 1
            continue
        for j, x in enumerate(xs):
            theta[i, j], beta[i, j] = lognormal_at(b, u_shift, x)
    points = []
    for j, (s, x) in enumerate(zip(points_s, xs)):
        t, bt = lognormal_at(fit, u_shift, x)
        points.append({"pgv_pga_s": float(s), "theta_g": t, "beta": bt,
                       "theta_interval_g": percentile_interval(theta[:, j], level, len(records)),
                       "beta_interval": percentile_interval(beta[:, j], level, len(records))})
    out.update(fit=fit, points=points, bootstrap_replicates=int(replicates), bootstrap_failed=int(failed),
               replicate_theta_g=theta, replicate_beta=beta,
               pgv_pga_range_s=[float(cells.pgv_pga_s[records].min()), float(cells.pgv_pga_s[records].max())])
    return out


# --------------------------------------------------------------------------------------------
# Deterministic outcomes, and the variants of a campaign pooled (epistemic uncertainty)


def empirical_threshold(cells, records=None):
    """The toppling PGA of outcomes with complete or quasi-complete separation, where maximum
    likelihood has no finite estimate (the probit's slope runs off to infinity): every simulated
    scale all survived or all overturned, survived below overturned, except at most one mixed scale
    between them. Complete: the geometric mean of the highest all-survived and the lowest
    all-overturned scale (the midpoint on the log axis the fits work on); quasi-complete: the mixed
    scale itself. A step fragility (beta 0). None when more than one scale is mixed (the probit fit
    applies) or one side is missing (no threshold inside the campaign's scales)."""
    records = cells.records_with_cells(records)
    k, n = cells.k[records].sum(axis=0), cells.n[records].sum(axis=0)
    ran = n > 0
    all_over, all_survived = ran & (k == n), ran & (k == 0)
    mixed = ran & ~all_over & ~all_survived
    if mixed.sum() > 1 or not all_over.any() or not all_survived.any():
        return None
    highest_survived = float(cells.scales_g[all_survived].max())
    lowest_overturned = float(cells.scales_g[all_over].min())
    if not highest_survived < lowest_overturned:
        return None  # overturned below a survived scale: not a threshold
    if mixed.any():
        at = float(cells.scales_g[mixed][0])
        if not highest_survived < at < lowest_overturned:
            return None
        return {"theta_g": at, "beta": 0.0, "between_g": [highest_survived, lowest_overturned]}
    return {"theta_g": math.sqrt(highest_survived * lowest_overturned), "beta": 0.0,
            "between_g": [highest_survived, lowest_overturned]}


def lognormal_probability(pga_g, theta_g, beta):
    """P = Phi(ln(PGA/theta)/beta); beta 0 is the step at theta (a deterministic threshold)."""
    a = np.asarray(pga_g, float)
    if beta == 0:
        return (a >= theta_g).astype(float)
    return ndtr(np.log(a / theta_g) / beta)


def mixture_probability(pga_g, lognormals, weights=None):
    """The mixture sum_v w_v P_v(a) of lognormals [(theta_g, beta)]: the fragility of a rock whose
    parameters are one of the variants, each as likely (variants are samples of the epistemic
    distribution: equal weights, the default), or as likely as a calibration says (its members'
    weights), i.e. the pooled fragility."""
    return np.average([lognormal_probability(pga_g, t, b) for t, b in lognormals], axis=0, weights=weights)


def weighted_percentile(values, weights, q):
    """Percentiles q (0-100) of values drawn with probabilities `weights`: the inverse of the
    piecewise-linear CDF through the midpoints of each value's weight (equal weights give
    the Hazen plotting positions)."""
    order = np.argsort(values)
    v, w = np.asarray(values, float)[order], np.asarray(weights, float)[order]
    cdf = (np.cumsum(w) - 0.5 * w) / w.sum()
    return np.interp(np.asarray(q, float) / 100.0, cdf, v)


def mixture_median(lognormals, weights=None):
    """The PGA where the mixture is 1/2 (bisection on ln PGA: the mixture is monotone)."""
    lo = math.log(min(t for t, _ in lognormals)) - 9 * max(b for _, b in lognormals) - 1e-9
    hi = math.log(max(t for t, _ in lognormals)) + 9 * max(b for _, b in lognormals) + 1e-9
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mixture_probability(math.exp(mid), lognormals, weights) < 0.5:
            lo = mid
        else:
            hi = mid
    return math.exp(0.5 * (lo + hi))


def moment_matched_lognormal(lognormals, weights=None):
    """The lognormal with the mixture's mean and variance of ln C (C the toppling PGA): mean_v ln
    theta_v and, by the law of total variance, mean_v beta_v^2 + var_v ln theta_v (population
    variance: the variants are the whole equally weighted mixture). It is the composite fragility
    of the SRSS rule beta_c = sqrt(beta_aleatory^2 + beta_epistemic^2) (Kennedy and Ravindra, Nucl.
    Eng. Des. 79, 1984). Chosen over least squares in probit space because it is closed form, has
    no grid or clipping to choose, and takes steps (beta 0) as they are."""
    ln_theta = np.log([t for t, _ in lognormals])
    beta2 = np.array([b for _, b in lognormals]) ** 2
    if weights is not None:  # a calibration's members: the same moments under their weights
        w = np.asarray(weights, float) / np.sum(weights)
        mean = float(w @ ln_theta)
        return float(math.exp(mean)), float(math.sqrt(w @ beta2 + w @ (ln_theta - mean) ** 2))
    return float(np.exp(ln_theta.mean())), float(math.sqrt(beta2.mean() + ln_theta.var()))


EPISTEMIC_PERCENTILES = (5, 50, 95)


def pooled_fragility(lognormals, pga_g, weights=None):
    """The pooled (mixture) fragility of variants [(theta_g, beta)] and the epistemic spread: its
    median, the moment-matched lognormal, the 5/50/95th percentiles over variants of theta and
    beta, and on the grid `pga_g` the mixture and the 5-95 % band of P_v(a) over variants. With
    `weights` (a calibration's members) each variant counts by its weight in all of them."""
    thetas = np.array([t for t, _ in lognormals])
    betas = np.array([b for _, b in lognormals])
    theta_m, beta_m = moment_matched_lognormal(lognormals, weights)
    curves = np.array([lognormal_probability(pga_g, t, b) for t, b in lognormals])  # [V, N]
    if weights is None:
        def percentiles(x, axis=None):
            return np.percentile(x, EPISTEMIC_PERCENTILES, axis=axis)
    else:
        def percentiles(x, axis=None):
            if axis is None:
                return weighted_percentile(x, weights, EPISTEMIC_PERCENTILES)
            return np.array([weighted_percentile(col, weights, EPISTEMIC_PERCENTILES) for col in x.T]).T
    lo, mid, hi = percentiles(curves, axis=0)
    return {"n_variants": int(len(lognormals)), "median_g": mixture_median(lognormals, weights),
            "lognormal_theta_g": theta_m, "lognormal_beta": beta_m,
            "lognormal_method": "moment-matched: ln C mean and variance of the mixture (law of total variance)",
            "theta_percentiles_g": [float(v) for v in percentiles(thetas)],
            "beta_percentiles": [float(v) for v in percentiles(betas)],
            "percentiles": list(EPISTEMIC_PERCENTILES),
            "pga_g": np.asarray(pga_g, float),
            "mixture_probability": np.average(curves, axis=0, weights=weights),
            "band_lower": lo, "band_median": mid, "band_upper": hi}
