"""Which varied parameter moves a rock's fragility: rank statistics across the variants of a campaign
(the epistemic axis, layout at the top of src/io/cube.cpp), for `rigid fragility`.

- Spearman's rank correlation rho between a parameter and an output (theta or beta) across
  variants: the Pearson correlation of their ranks (ties get their average rank). It measures a
  monotone, not only linear, dependence, which is what a fragility's median does with friction,
  slenderness or size.
- The partial rank correlation coefficient (PRCC; Saltelli et al., Sensitivity Analysis in
  Practice, Wiley 2004; Marino, Hogue, Ray and Kirschner, J. Theor. Biol. 254, 178-196, 2008):
  the correlation of the residuals of rank(x_j) and rank(y), each linearly regressed on the ranks of
  the other parameters. With parameters sampled together (LHS rarely makes them exactly
  uncorrelated) it separates a parameter's own effect from what it shares with the others.
- Intervals: percentile bootstrap over variants (variants resampled with replacement, the
  statistic recomputed; resamples where it is undefined are left out), seeded by the caller.

Parameters are numeric values per variant; a text parameter (a contact model, an alternative
mesh) enters by the order of its categories (the caller says which order), which is only meaningful
as far as that order is; the table says so.
"""
import math

import numpy as np
from scipy.stats import rankdata


def pearson(a, b):
    """Pearson correlation; NaN when either side is constant."""
    a, b = a - a.mean(), b - b.mean()
    norm = math.sqrt(float(a @ a) * float(b @ b))
    return float(a @ b) / norm if norm > 1e-12 * max(1.0, len(a)) else float("nan")


def spearman(x, y):
    return pearson(rankdata(x), rankdata(y))


def rank_residual(target_ranks, control_ranks):
    """target minus its least-squares fit (with intercept) on the control ranks."""
    design = np.column_stack([np.ones(len(target_ranks))] + list(control_ranks))
    coef, *_ = np.linalg.lstsq(design, target_ranks, rcond=None)
    return target_ranks - design @ coef


def prcc(x, y, controls):
    """Partial rank correlation of x and y given the parameters `controls` (list of arrays). NaN
    when x's rank is (nearly) determined by the controls' ranks (a derived parameter that is a
    monotone function of a varied one) or there are too few variants for the regression."""
    n = len(x)
    if n < len(controls) + 3:
        return float("nan")
    ranks_c = [rankdata(c) for c in controls]
    rx, ry = rankdata(x), rankdata(y)
    ex, ey = rank_residual(rx, ranks_c), rank_residual(ry, ranks_c)
    # a residual of rounding size only: x carries nothing the controls do not
    if float(ex @ ex) < 1e-9 * float((rx - rx.mean()) @ (rx - rx.mean())):
        return float("nan")
    return pearson(ex, ey)


def category_codes(labels):
    """Text values as numbers in the order their categories first appear over the variants (for a
    grid or list, the job's order)."""
    order = []
    for v in labels:
        if v not in order:
            order.append(v)
    return np.array([order.index(v) for v in labels], float), order


def _interval(values, level):
    v = np.asarray([x for x in values if math.isfinite(x)], float)
    if v.size < 10:  # too few defined resamples to place percentiles
        return (float("nan"), float("nan"))
    tail = 50.0 * (1.0 - level)
    lo, hi = np.percentile(v, [tail, 100.0 - tail])
    return (float(lo), float(hi))


def sensitivity_table(parameters, outputs, rng, replicates=500, level=0.9, controls=None):
    """Rows, one per parameter, sorted by |rho| with the first output.

    parameters: [(name, units, kind, values [V])] (kind: "varied", "text (category order)",
    "derived"); outputs: {name: values [V]} (NaN: the variant has none, left out of that output's
    statistics); controls: names of the parameters the PRCC regresses out (default: every
    "varied" or text parameter; a derived one is controlled by these only, since it is a function
    of them). Each row holds, per output, n (variants used), rho, its interval, prcc, its interval."""
    if controls is None:
        controls = [p[0] for p in parameters if p[2] != "derived"]
    by_name = {p[0]: np.asarray(p[3], float) for p in parameters}
    rows = []
    for name, units, kind, values in parameters:
        x_all = np.asarray(values, float)
        row = {"parameter": name, "units": units, "kind": kind}
        notes = []
        for out_name, y in outputs.items():
            y_all = np.asarray(y, float)
            use = np.isfinite(x_all) & np.isfinite(y_all)
            others = [c for c in controls if c != name and np.ptp(by_name[c][use]) > 0] if use.any() else []
            x, yy = x_all[use], y_all[use]
            cs = [by_name[c][use] for c in others]
            row[f"n_{out_name}"] = int(use.sum())
            if use.sum() < 3 or np.ptp(x) == 0 or np.ptp(yy) == 0:
                row[f"rho_{out_name}"] = row[f"prcc_{out_name}"] = float("nan")
                row[f"rho_{out_name}_interval"] = row[f"prcc_{out_name}_interval"] = (float("nan"), float("nan"))
                notes.append(f"{out_name}: " + ("fewer than 3 variants" if use.sum() < 3 else
                                                "parameter constant" if np.ptp(x) == 0 else "output constant"))
                continue
            row[f"rho_{out_name}"] = spearman(x, yy)
            row[f"prcc_{out_name}"] = prcc(x, yy, cs)
            boot_rho, boot_prcc = [], []
            n = len(x)
            for _ in range(replicates):
                pick = rng.integers(0, n, n)
                boot_rho.append(spearman(x[pick], yy[pick]))
                boot_prcc.append(prcc(x[pick], yy[pick], [c[pick] for c in cs]))
            row[f"rho_{out_name}_interval"] = _interval(boot_rho, level)
            row[f"prcc_{out_name}_interval"] = _interval(boot_prcc, level)
            if not math.isfinite(row[f"prcc_{out_name}"]):
                notes.append(f"{out_name}: no PRCC (" + ("too few variants for the regression" if n < len(cs) + 3
                                                        else "rank determined by the other parameters") + ")")
        row["note"] = "; ".join(notes)
        rows.append(row)
    first = next(iter(outputs))
    rows.sort(key=lambda r: -abs(r[f"rho_{first}"]) if math.isfinite(r[f"rho_{first}"]) else 1.0)
    return rows
