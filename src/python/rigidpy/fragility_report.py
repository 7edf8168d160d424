"""What `rigid fragility` prints and exports: the tables, the CSV rows, the NRML functions and
the JSON document of the fits (object_fits.py)."""
import math

import numpy as np

from . import fit as ff
from .fit import SCALAR_SOURCE, THRESHOLD_SOURCE
from .object_fits import METHOD, variant_lognormal


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
        if a.calibration is None:
            print(f"object {a.name}, pooled over {p['n_variants']} of {len(a.fits)} variants (equally weighted mixture "
                  f"P(a) = mean_v P_v(a), at PGV/PGA {a.pgv_pga_s:.3f} s):")
        else:
            print(f"object {a.name}: calibrated physics from {a.calibration.path} ({len(a.calibration.weights)} member "
                  f"scenes, weights {', '.join(f'{w:.3g}' for w in a.calibration.weights)}); pooled over "
                  f"{p['n_variants']} of them (mixture P(a) = sum_v w_v P_v(a), at PGV/PGA {a.pgv_pga_s:.3f} s):")
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


# Below the PGA where the lognormal gives this P, a function is taken as no damage.
NO_DAMAGE_PROBABILITY = 1e-4


def no_damage_limit(theta_g, beta):
    """The PGA (g) below which the lognormal gives P < NO_DAMAGE_PROBABILITY."""
    return theta_g * math.exp(beta * ff.norm_ppf(NO_DAMAGE_PROBABILITY))


def lower_imls(theta_g, beta, lowest_scale_g):
    """(minIML, noDamageLimit) of a function, one value for both: OpenQuake evaluates a continuous
    function at max(PGA, minIML) and sets P = 0 at or below noDamageLimit, so a limit above minIML
    would zero the fitted curve between them, and one below it would hold P at P(minIML) down to it.
    Both are the lower of the campaign's lowest scale and the PGA where P = 1e-4: below that the
    function is 0 (P < 1e-4 there), above it the lognormal (extrapolated below the lowest scale,
    as maxIML extrapolates above the top one)."""
    low = min(lowest_scale_g, no_damage_limit(theta_g, beta))
    return low, low


def nrml_function(function_id, theta_g, beta, scale_range_g, max_probability):
    """One NRML function of the lognormal (theta_g, beta) fitted over the scales scale_range_g."""
    lo, hi = scale_range_g
    min_iml, limit = lower_imls(theta_g, beta, lo)
    return {"id": function_id, "theta_g": theta_g, "beta": beta, "min_iml": min_iml,
            "max_iml": max_iml(theta_g, beta, hi, max_probability), "no_damage_limit": limit}


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
        functions.append(nrml_function(f"{f.obj.name}_v{f.obj.variant}_pgv_pga_{f.pgv_pga_s:.4g}s", d["theta_g"],
                                       d["beta"], f.scale_range_g, max_probability))
    for a in analyses:
        if a.pooled is None:
            continue
        functions.append(nrml_function(f"{a.name}_pooled_pgv_pga_{a.pgv_pga_s:.4g}s", a.pooled["lognormal_theta_g"],
                                       a.pooled["lognormal_beta"], a.fits[0].scale_range_g, max_probability))
    return functions, skipped


def nrml_functions(fits, max_probability=0.99, min_records=0):
    """One function per object and PGV/PGA bin with a fit; bins fitted on fewer than `min_records`
    records left out (returned as (functions, left out labels))."""
    functions, left_out = [], []
    for f in fits:
        for r in f.bins:
            if "theta_g" not in r:
                continue
            label = f"{f.obj.name}_pgv_pga_{bin_label(r['lower_s'], r['upper_s']).replace('>= ', 'above_')}s"
            if r["n_records"] < min_records:
                left_out.append(f"{label} ({r['n_records']} record(s))")
                continue
            functions.append(nrml_function(label, r["theta_g"], r["beta"], f.scale_range_g, max_probability))
    return functions, left_out


def vector_nrml_functions(fits, pgv_pga_s, max_probability=0.99):
    """One function per object: its vector fit read as a lognormal at the site's PGV/PGA (s), the
    function a site uses instead of choosing a bin. Returns (functions, notes): objects without a
    vector fit are named in the notes, as are PGV/PGAs outside an object's records (extrapolated)."""
    functions, notes = [], []
    for f in fits:
        if "fit" not in f.vector:
            notes.append(f"{f.obj.label}: no vector fit ({f.vector.get('reason', 'no fit')}): no function")
            continue
        theta, beta = ff.lognormal_at(f.vector["fit"], f.norm.u_shift, math.log(pgv_pga_s) + f.norm.x_shift)
        functions.append(nrml_function(f"{f.obj.name}_vector_pgv_pga_{pgv_pga_s:.4g}s", theta, beta, f.scale_range_g,
                                       max_probability))
        lo, hi = f.vector["pgv_pga_range_s"]
        if not lo <= pgv_pga_s <= hi:
            notes.append(f"{f.obj.label}: PGV/PGA {pgv_pga_s:g} s is outside its records' {lo:.3g}-{hi:.3g} s: the "
                         f"vector fit is extrapolated there")
    return functions, notes


def vector_coefficients(f):
    """The vector fit of one object in physical units, for a hazard code that evaluates it at each
    site: ln theta(s) = a + b ln(s / 1 s) (theta in g, s the site's GMRotI50 PGV/PGA), ln beta(s) =
    c + d ln(s / 1 s) (d 0 with the default constant sigma). From mu(x) = sum m_k x^k in x = ln s +
    x_shift and u = ln PGA + u_shift: a = m0 + m1 x_shift - u_shift, b = m1 (mu linear, the
    default); None when the fit has no finite estimate or mu/sigma are of higher degree."""
    v = f.vector
    if "fit" not in v:
        return None
    mu, log_sigma = list(v["fit"]["mu_coefficients"]), list(v["fit"]["log_sigma_coefficients"])
    if len(mu) > 2 or len(log_sigma) > 2:
        return None
    mu += [0.0] * (2 - len(mu))
    log_sigma += [0.0] * (2 - len(log_sigma))
    xs, us = f.norm.x_shift, f.norm.u_shift
    lo, hi = v["pgv_pga_range_s"]
    return {"object": f.obj.label, "ln_theta_intercept": mu[0] + mu[1] * xs - us, "ln_theta_slope": mu[1],
            "ln_beta_intercept": log_sigma[0] + log_sigma[1] * xs, "ln_beta_slope": log_sigma[1],
            "pgv_pga_min_s": lo, "pgv_pga_max_s": hi, "pga_min_g": f.scale_range_g[0],
            "pga_max_g": f.scale_range_g[1], "n_records": v["n_records"], "n_cells": v["n_cells"],
            "n_overturned": v["n_overturned"]}


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
