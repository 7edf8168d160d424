"""Fragility maps, per-record curves, a probit fit, 3D-vs-2D difference maps and scenario tables
from Rigid's HDF5 fragility cubes (docs/cube.md; physics.md sections 1, 11).

    rigid_plot.py maps  CUBE --out DIR [--object NAME]... [--variant K] [--pgv-pga S] [--alpha [NAME=]RAD]...
                        [--p [NAME=]RAD_S]...
    rigid_plot.py diff  CUBE_A CUBE_B --out DIR [--label-a 3D] [--label-b 2D] [--object NAME]... [--variant K]
    rigid_plot.py table CUBE [CUBE...] --out FILE.md [--scale G] [--layout auto|objects|records] [--variant K]

A cube with a variant axis (epistemic variants of every object, layout at the top of src/io/cube.cpp) is
read as one object per (object, variant), named `rock [v3]` in tables and titles (files `rock_v3_...`);
--object NAME selects every variant of NAME, --variant K only variant K. `maps` draws by default,
per object, the variants' fragility curves with their 5-95 % band and the pooled (mixture) curve
(NAME_variants.png) and the map of the pooled cells (NAME_pooled_map.png); --variant K that
variant's map and records figures.

`rigid plot ARGS...` runs this module (its launcher rigid_plot.py) with Debian's /usr/bin/python3 (python3-numpy, python3-h5py,
python3-matplotlib, python3-scipy). The fit is fit.py's (shared with `rigid fragility`).

The fit ("this project's fit", NOT the coefficients of Purvance et al. 2008, which we do not have):

    P(overturn) = Phi((u - mu(x)) / sigma(x)),   u = ln(PGA / (g tan alpha)),
                                                 x = ln((PGV/PGA) p / alpha),
    mu(x) = m0 + m1 x (+ m2 x^2 ...),  ln sigma(x) = s0 (+ s1 x ...)   (--mu-degree, --sigma-degree)

fitted by maximum likelihood to the binomial outcomes of every simulated cell (record, scale,
rotation): overturned and survived; the stop rule's inferred cells, not-run and failed cells are
left out (fit.py says why). PGA is the cell's scale (target
GMRotI50 PGA, g), PGV/PGA the record's `pgv_pga_s` (scaling does not change it).
alpha (rad) and p (rad/s) come from the command line (--alpha, --p; one value for all objects or
NAME=VALUE per object), else from the attributes `alpha_rad` / `p_rad_s` of the object group, else
of the root group; without alpha u = ln(PGA / g) and without alpha or p x = ln(PGV/PGA / 1 s).
The normalisation only shifts the coefficients (u and x move by constants, and mu is a polynomial),
so the fitted probabilities and the 1/50/99 % contours are the same either way; it matters only
when comparing coefficients between blocks. The k % contour is the curve P = k/100, i.e.
PGA = g tan(alpha) exp(mu(x) + sigma(x) Phi^-1(k/100)); it is drawn only over the records'
PGV/PGA range (polynomials are not extrapolated).

Exit status: 0 done, 2 bad input (missing file, no such object, incompatible cubes), 1 internal.
"""
import csv
import json
import math
import os
import sys

try:
    import numpy as np
    from . import files as cube_files
    from . import fit as fragility_fit
    from .cube import Cube, ObjectData
    from .command_line import OneLineParser, add_old_spelling
    from .errors import InputError
    from .figure_style import FIGURE_FORMATS
    from .figures import INPUTS, file_stem, plot_diff, plot_map, plot_records, plot_variant_band, safe_name
    from .fit import fit_sigma
    from .map_fit import (CONTOUR_LEVELS, FIT_LABEL, Normalisation, fit_object, map_lognormal,
                          normalisation_for)
    from .outcomes import bins_of_records, outcome_counts as count_outcomes, overturn_fraction
except ImportError as e:  # pragma: no cover
    sys.stderr.write(f"rigid_plot: error: {e}; install python3-numpy python3-h5py python3-matplotlib "
                     f"python3-scipy and run with /usr/bin/python3 (this is {sys.executable})\n")
    sys.exit(2)

# The study's reported mismatch (2D model minus Rigid 3D, mean and sd over cells; physics.md 11).
STUDY_MISMATCH_2D_MINUS_3D = {0.1: (0.03, 0.12), 0.2: (0.02, 0.08), 0.3: (0.02, 0.10), 0.4: (0.03, 0.14)}


def counts_mode(cube, option):
    """--counts on: every cell; off: none; auto: cells whose count is below their bin's records."""
    return {"on": "all", "off": "none"}.get(option, "deviations")



def variant_maps(cube, variants, args, counts):
    """The band figure and the pooled map of one object's variants; returns its fit.json entry."""
    name = variants[0].name
    pgv_pga_s = args.pgv_pga if args.pgv_pga is not None else float(np.median(
        cube.pgv_pga[np.isfinite(cube.pgv_pga) & (cube.pgv_pga > 0)]))
    curves, missing = [], []
    for o in variants:
        theta, beta, how = map_lognormal(cube, o, args, pgv_pga_s)
        (curves.append((o.variant, (theta, beta, how))) if theta is not None else missing.append((o.variant, how)))
    base = os.path.join(args.out, safe_name(name))
    entry = {"object": name, "variants": len(variants), "pgv_pga_s": pgv_pga_s,
             "variant_fragility": [{"variant": k, "theta_g": t, "beta": b, "source": how} for k, (t, b, how) in curves],
             "variants_without_fragility": [{"variant": k, "reason": why} for k, why in missing], "files": []}
    if curves:
        lognormals = [(t, b) for _, (t, b, _) in curves]
        spread = max([b for _, b in lognormals] + [0.1])
        grid = np.geomspace(min(t for t, _ in lognormals) * math.exp(-3 * spread),
                            max(t for t, _ in lognormals) * math.exp(3 * spread), 400)
        # a calibrated object's members by the calibration's weights, other variants equally
        weights = ([float(cube.variant_weights(name)[k]) for k, _ in curves] if name in cube.calibrations else None)
        pooled = fragility_fit.pooled_fragility(lognormals, grid, weights)
        plot_variant_band(cube, name, curves, pooled, pgv_pga_s, base + "_variants." + args.format)
        entry["pooled"] = {k: pooled[k] for k in ("n_variants", "median_g", "lognormal_theta_g", "lognormal_beta",
                                                  "lognormal_method", "theta_percentiles_g", "beta_percentiles")}
        entry["files"].append(base + "_variants." + args.format)
        print(f"{name}: {len(curves)} of {len(variants)} variants with a fragility at PGV/PGA {pgv_pga_s:.3g} s; "
              f"pooled median {pooled['median_g']:.4g} g, theta 5/50/95 % over variants "
              f"{', '.join(f'{v:.3g}' for v in pooled['theta_percentiles_g'])} g")
    else:
        print(f"{name}: no variant has a fragility ({missing[0][1]})")
    # the pooled cells: a cell's mean over variants (the mixture's binned fragility); the count is
    # the fewest records any variant has there, so "auto" still marks cells some variant lacks
    stack = np.array([o.fragility for o in variants])
    defined = np.isfinite(stack).sum(axis=0)
    frag = np.where(defined > 0, np.nansum(stack, axis=0) / np.maximum(defined, 1), np.nan)
    if name in cube.calibrations:  # the members' weighted mean, over the members with a value there
        w = np.array([float(cube.variant_weights(name)[o.variant]) for o in variants])
        w = np.where(np.isfinite(stack), w.reshape((-1,) + (1,) * (stack.ndim - 1)), 0.0)
        total = w.sum(axis=0)
        frag = np.where(total > 0, np.nansum(stack * w, axis=0) / np.where(total > 0, total, 1), np.nan)
    pooled_obj = ObjectData(f"{name} (pooled over {len(variants)} variants)", {}, None, None, frag,
                            np.min([o.count for o in variants], axis=0))
    plot_map(cube, pooled_obj, None, Normalisation(None, "", None, ""),
             {"reason": f"each cell the {'calibration-weighted ' if name in cube.calibrations else ''}mean over "
                       f"variants of its records' mean; the variants' fits are in "
                       f"{os.path.basename(base)}_variants.{args.format}"},
             base + "_pooled_map." + args.format, counts)
    entry["files"].append(base + "_pooled_map." + args.format)
    print(f"  wrote {', '.join(entry['files'])}")
    return entry



# --------------------------------------------------------------------------------------------
# Subcommands


def _json_clean(v):
    """Strict JSON: non-finite numbers become null."""
    if isinstance(v, dict):
        return {k: _json_clean(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_json_clean(x) for x in v]
    if isinstance(v, (float, np.floating)):
        return float(v) if math.isfinite(v) else None
    if isinstance(v, np.integer):
        return int(v)
    return v


def fit_summary(obj, info, f, norm_):
    """The fit in words a reader can use: its median PGA and dispersion at the records' median
    PGV/PGA (fit.reference_pgv_pga_s, where `rigid fragility` reads its vector fit: the same
    median), and the coefficients with what they multiply."""
    s, theta, sig = info["reference_pgv_pga_s"], info["reference_theta_g"], info["reference_beta"]
    same = info["mu_degree"] == 1 and info["sigma_degree"] == 0
    mu = f["mu_coefficients"]
    u, x = norm_.describe()
    terms = " + ".join([f"{mu[0]:.4g}"] + [f"({c:.4g}) x" + (f"^{k}" if k > 1 else "") for k, c in enumerate(mu) if k])
    return (f"{obj.label}: {info['n_cells']} cells ({info['n_overturned']} overturned) of {info['n_records']} records; "
            f"at the records' median PGV/PGA {s:.3g} s ({'the fit and point of' if same else 'other degrees than'} "
            f"rigid fragility's vector fit): median PGA {theta:.4g} g, "
            f"dispersion sigma {sig:.3g} (of ln PGA)\n"
            f"  fit P = Phi((u - mu(x)) / sigma(x)), u = {u}, x = {x}: mu(x) = {terms}, "
            f"ln sigma = {', '.join(f'{c:.4g}' for c in f['log_sigma_coefficients'])} (fit.json has them all)")


def cmd_maps(args):
    state = cube_files.campaign_state(args.cube)
    cube = Cube(args.cube)
    if problem := cube.incomplete(state):
        sys.stderr.write(f"rigid plot: warning: {problem}; the maps show the cells run so far\n")
    objs = cube.select(args.object, args.variant)
    os.makedirs(args.out, exist_ok=True)
    summary = {"cube": os.path.abspath(cube.path), "label": FIT_LABEL,
               "contour_levels_pct": list(CONTOUR_LEVELS), "objects": []}
    show = counts_mode(cube, args.counts)
    if cube.variants is not None and args.variant is None:
        # With variants the default is, per object, ONE figure of every variant's fragility curve
        # with the epistemic band and the pooled curve, and ONE map: the pooled cells (the mean over
        # variants of each cell's binned probability, which is the mixture's binned fragility).
        # A map and a records figure per variant would be 2 V figures of near-identical surfaces
        # that nobody compares by eye; --variant K draws them for the one variant wanted.
        for name in [n for n in cube.base_names() if any(o.name == n for o in objs)]:
            summary["objects"].append(variant_maps(cube, [o for o in objs if o.name == name], args, show))
        objs = []
    for obj in objs:
        norm_ = normalisation_for(cube, obj, args)
        info, fit = fit_object(cube, obj, norm_, args.mu_degree, args.sigma_degree)
        base = os.path.join(args.out, file_stem(obj))
        info["files"] = [f"{base}_map.{args.format}", f"{base}_records.{args.format}"]
        plot_map(cube, obj, fit, norm_, info, info["files"][0], show)
        plot_records(cube, obj, fit, norm_, info["files"][1])
        summary["objects"].append(info)
        f = info.get("fit")
        if f is not None and fit is not None:
            print(fit_summary(obj, info, f, norm_))
        else:
            print(f"{obj.label}: {info['n_cells']} cells, no fit: {info.get('reason')}")
        if "warning" in info:
            print(f"  warning: {info['warning']}")
        print(f"  wrote {', '.join(info['files'])}")
    jpath = os.path.join(args.out, "fit.json")
    with cube_files.output_text(jpath, "--out", INPUTS) as fh:
        json.dump(_json_clean(summary), fh, indent=2, allow_nan=False)
        fh.write("\n")
    print(f"wrote {jpath}")
    return 0


def _fmt(v, digits=3):
    return "" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.{digits}f}"


def _sfmt(v, digits=3):
    """Signed: +0.050, -0.042, 0.000."""
    if v is None or not math.isfinite(v):
        return ""
    return f"{v:+.{digits}f}" if round(v, digits) != 0 else f"{0:.{digits}f}"


def mismatch(a, b):
    """Per-cell A - B where both are defined: (diff [S,B] with NaN elsewhere, n, mean, sd)."""
    d = a - b
    ok = np.isfinite(d)
    vals = d[ok]
    n = int(vals.size)
    mean = float(vals.mean()) if n else float("nan")
    sd = float(vals.std(ddof=1)) if n > 1 else (0.0 if n == 1 else float("nan"))
    return np.where(ok, d, np.nan), n, mean, sd


def _common_scales(ca, cb):
    ia, ib = [], []
    for i, s in enumerate(ca.scales):
        j = np.where(np.abs(cb.scales - s) <= 1e-9 * max(1.0, abs(s)))[0]
        if j.size:
            ia.append(i)
            ib.append(int(j[0]))
    return np.array(ia, int), np.array(ib, int)


class _View:
    """A cube restricted to some scales (for side-by-side drawing of two cubes)."""

    def __init__(self, cube, idx):
        self.path, self.records, self.edges, self.pgv_pga = cube.path, cube.records, cube.edges, cube.pgv_pga
        self.scales = cube.scales[idx]

    def bin_of_records(self):
        return bins_of_records(self.edges, self.pgv_pga)


def cmd_diff(args):
    ca, cb = Cube(args.cube_a), Cube(args.cube_b)
    if len(ca.edges) != len(cb.edges) or not np.array_equal(ca.edges, cb.edges):
        raise InputError(f"the cubes have different PGV/PGA bin edges ({ca.edges.tolist()} vs {cb.edges.tolist()})")
    ia, ib = _common_scales(ca, cb)
    if ia.size == 0:
        raise InputError("the cubes share no scale")
    # objects are matched by name and variant (a variant cube against its own kind)
    labels_b = {o.label for o in cb.objects}
    objs = ca.select(args.object, args.variant)
    common = [o for o in objs if o.label in labels_b]
    if not common:
        raise InputError(f"no object name in both cubes ({[o.label for o in ca.objects]} vs {sorted(labels_b)})")
    os.makedirs(args.out, exist_ok=True)
    la, lb = args.label_a, args.label_b
    va, vb = _View(ca, ia), _View(cb, ib)
    show = counts_mode(ca, args.counts)
    print(f"sign convention: difference = {la} \u2212 {lb} (A \u2212 B: {ca.path} minus {cb.path}); "
          f"positive = {la} more fragile. The study (report section 3.5) reported 2D model minus Rigid 3D.")
    rows = []
    for oa in common:
        ob = cb.object(oa.name, oa.variant)
        fa, fb = oa.fragility[ia], ob.fragility[ib]
        d, n, mean, sd = mismatch(fa, fb)
        mad = float(np.nanmean(np.abs(d))) if n else float("nan")
        norm_a = normalisation_for(ca, oa, args)
        fits = []
        for cube, o, nrm in ((ca, oa, norm_a), (cb, ob, normalisation_for(cb, ob, args))):
            info, fit = fit_object(cube, o, nrm, args.mu_degree, args.sigma_degree)
            fits.append((fit, nrm, info) if fit is not None else None)
        png = os.path.join(args.out, file_stem(oa) + "_diff." + args.format)
        plot_diff(va, vb, oa.label, fa, oa.count[ia], fb, ob.count[ib], d, (n, mean, sd), la, lb, fits, png, show)
        ref = None
        if norm_a.alpha is not None:
            for key, val in STUDY_MISMATCH_2D_MINUS_3D.items():
                if abs(norm_a.alpha - key) < 1e-6:
                    ref = val
        rows.append({"object": oa.label, "alpha_rad": norm_a.alpha, "n_cells": n, "mean_a_minus_b": mean,
                     "sd": sd, "mean_b_minus_a": -mean if n else float("nan"), "mean_abs": mad,
                     "study_2d_minus_3d": ref, "png": png})
        print(f"{oa.label}: {la} \u2212 {lb} = {mean:+.4f} \u00b1 {sd:.4f} (mean \u00b1 sd over {n} cells; "
              f"{lb} \u2212 {la} = {-mean:+.4f}; mean |diff| {mad:.4f})  -> {png}")
    skipped = [o.label for o in objs if o.label not in labels_b]
    if skipped:
        print(f"not in {cb.path}: {', '.join(skipped)}")
    csv_path = os.path.join(args.out, "mismatch.csv")
    with cube_files.output_text(csv_path, "--out", INPUTS, newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["object", "alpha_rad", "n_cells", f"mean_{la}_minus_{lb}", "sd", f"mean_{lb}_minus_{la}",
                    "mean_abs_diff", "study_2D_minus_3D_mean", "study_2D_minus_3D_sd"])
        for r in rows:
            w.writerow([r["object"], "" if r["alpha_rad"] is None else f"{r['alpha_rad']:g}", r["n_cells"],
                        _fmt(r["mean_a_minus_b"], 6), _fmt(r["sd"], 6), _fmt(r["mean_b_minus_a"], 6),
                        _fmt(r["mean_abs"], 6), "" if r["study_2d_minus_3d"] is None else r["study_2d_minus_3d"][0],
                        "" if r["study_2d_minus_3d"] is None else r["study_2d_minus_3d"][1]])
    md_path = os.path.join(args.out, "mismatch.md")
    with cube_files.output_text(md_path, "--out", INPUTS) as fh:
        fh.write(f"# Binned fragility mismatch: {la} \u2212 {lb}\n\n")
        fh.write(f"- A ({la}): `{ca.path}`\n- B ({lb}): `{cb.path}`\n")
        fh.write(f"- Sign: **{la} \u2212 {lb}** per cell (positive: {la} more fragile); the column "
                 f"{lb} \u2212 {la} is its negative. The study reported 2D model minus Rigid 3D.\n")
        fh.write("- Cells: (scale, PGV/PGA bin) defined in both cubes (scales common to both); "
                 "mean and sample sd (n \u2212 1) over cells, unweighted.\n\n")
        fh.write(f"| object | alpha (rad) | cells | {la} \u2212 {lb} mean \u00b1 sd | {lb} \u2212 {la} mean | "
                 f"mean \\|diff\\| | study 2D \u2212 3D |\n|---|---|---|---|---|---|---|\n")
        for r in rows:
            ref = "" if r["study_2d_minus_3d"] is None else f"{r['study_2d_minus_3d'][0]:.2f} \u00b1 {r['study_2d_minus_3d'][1]:.2f}"
            alpha = "" if r["alpha_rad"] is None else f"{r['alpha_rad']:g}"
            fh.write(f"| {r['object']} | {alpha} | {r['n_cells']} | {_sfmt(r['mean_a_minus_b'])} \u00b1 {_fmt(r['sd'])} | "
                     f"{_sfmt(r['mean_b_minus_a'])} | {_fmt(r['mean_abs'])} | {ref} |\n")
    print(f"wrote {csv_path}, {md_path}")
    return 0


def outcome_counts(outcome, scale_index=None):
    """Cells per outcome code, over every scale or only scale_index."""
    return count_outcomes(outcome if scale_index is None else outcome[:, scale_index:scale_index + 1, :])


def cmd_table(args):
    cubes = [Cube(p) for p in args.cubes]
    multi = len(cubes) > 1
    records = []
    seen = {}
    differing = []
    for c in cubes:
        for r, w in zip(c.records, c.windows):
            if r not in records:
                records.append(r)
                seen[r] = w
            elif (os.path.basename(seen[r][0]), float(seen[r][1]), float(seen[r][2])) != \
                    (os.path.basename(w[0]), float(w[1]), float(w[2])) and r not in differing:
                differing.append(r)
    if differing:
        sys.stderr.write("rigid plot: warning: records matched by name differ in source or time window "
                         f"between cubes: {', '.join(differing)}\n")
    rows = []  # (row label, {record: counts}, all counts, cube, object)
    long_rows = []
    for c in cubes:
        si = None
        if args.target_pga is not None:
            j = np.where(np.abs(c.scales - args.target_pga) <= 1e-9 * max(1.0, abs(args.target_pga)))[0]
            if j.size == 0:
                raise InputError(f"{c.path}: no scale {args.target_pga:g} g (scales: {', '.join(f'{v:g}' for v in c.scales)})")
            si = int(j[0])
        for o in c.select(args.object, args.variant):
            per = {}
            for r, name in enumerate(c.records):
                cnt = outcome_counts(c.counted_outcome(o)[r:r + 1], si)
                per[name] = cnt
                frac, known = overturn_fraction(cnt)
                long_rows.append([c.label, o.label, name, "all" if si is None else f"{c.scales[si]:g}",
                                  cnt["survived"], cnt["overturned"], cnt["inferred"], cnt["not_run"],
                                  cnt["failed"], known, _fmt(frac, 6)])
            allc = outcome_counts(c.counted_outcome(o), si)
            frac, known = overturn_fraction(allc)
            long_rows.append([c.label, o.label, "all", "all" if si is None else f"{c.scales[si]:g}",
                              allc["survived"], allc["overturned"], allc["inferred"], allc["not_run"],
                              allc["failed"], known, _fmt(frac, 6)])
            rows.append((f"{c.label}: {o.label}" if multi else o.label, per, allc))

    def cell(cnt):
        if cnt is None:
            return "\u2013"
        frac, known = overturn_fraction(cnt)
        if known == 0:
            return "n/a"
        txt = f"{frac:.2f}"
        if args.counts:
            txt += f" ({cnt['overturned'] + cnt['inferred']}/{known})"
        if cnt["failed"]:
            txt += "\u2020"
        return txt

    layout = args.layout
    if layout == "auto":
        layout = "records" if len(records) > 10 and len(records) > len(rows) else "objects"
    where = "all scales" if args.target_pga is None else f"scale {args.target_pga:g} g"
    lines = [f"# Scenario table: overturn fraction ({where})", "",
             "Overturn fraction = (overturned + inferred) / (overturned + inferred + survived) over the "
             f"cells (scale, rotation) at {where}; not-run and failed cells are left out "
             "(\u2020: some failed; \u2013: record not in that cube; n/a: no known cell)."
             + (" Parentheses: overturned/known cells." if args.counts else ""),
             "", "Cubes: " + ", ".join(f"`{c.path}`" for c in cubes), ""]
    if differing:
        lines[-1:-1] = ["", "Records are matched by name; these differ in source file or time window between "
                        "the cubes: " + ", ".join(differing) + "."]
    if layout == "objects":
        head = ["object"] + records + ["all"]
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "---|" * len(head))
        for label, per, allc in rows:
            lines.append("| " + " | ".join([label] + [cell(per.get(r)) for r in records] + [cell(allc)]) + " |")
    else:
        head = ["record"] + [label for label, _, _ in rows]
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "---|" * len(head))
        for r in records:
            lines.append("| " + " | ".join([r] + [cell(per.get(r)) for _, per, _ in rows]) + " |")
        lines.append("| **all** | " + " | ".join(cell(allc) for _, _, allc in rows) + " |")
    out = args.out
    d = os.path.dirname(os.path.abspath(out))
    os.makedirs(d, exist_ok=True)
    with cube_files.output_text(out, "--out", INPUTS) as fh:
        fh.write("\n".join(lines) + "\n")
    csv_path = os.path.splitext(out)[0] + ".csv"
    with cube_files.output_text(csv_path, "--out", INPUTS, newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["cube", "object", "record", "scale_g", "survived", "overturned", "inferred", "not_run",
                    "failed", "known", "overturn_fraction"])
        w.writerows(long_rows)
    print("\n".join(lines))
    print(f"wrote {out}, {csv_path}")
    return 0


def build_parser():
    p = OneLineParser(
        prog="rigid plot",
        description="Fragility maps, per-record curves, a probit fit (this project's, not Purvance's), "
                    "difference maps and scenario tables from Rigid fragility cubes (HDF5).",
        epilog="Run with Debian's /usr/bin/python3 (python3-numpy, python3-h5py, python3-matplotlib). "
               "Exit status: 0 done, 2 bad input, 1 internal error.")
    sub = p.add_subparsers(dest="command", required=True, metavar="{maps,diff,table}")

    def variant_option(sp):
        sp.add_argument("--variant", type=int, metavar="K",
                        help="a cube with variants: only variant K (0-based); default: all variants")

    def fit_options(sp):
        sp.add_argument("--alpha", action="append", metavar="[NAME=]RAD",
                        help="block slenderness alpha (rad) for the fit's normalisation, for all objects or "
                             "NAME=RAD per object (repeatable); default: attribute alpha_rad of the object or root "
                             "group, else none (PGA not normalised)")
        sp.add_argument("--p", action="append", metavar="[NAME=]RAD_S",
                        help="block frequency parameter p (rad/s), like --alpha; default: attribute p_rad_s, "
                             "else none (PGV/PGA not normalised)")
        sp.add_argument("--mu-degree", type=int, default=1, choices=range(0, 4), metavar="D",
                        help="degree of the polynomial mu(x) (default 1)")
        sp.add_argument("--sigma-degree", type=int, default=0, choices=range(0, 3), metavar="D",
                        help="degree of the polynomial ln sigma(x) (default 0: constant sigma)")
        sp.add_argument("--counts", choices=("auto", "on", "off"), default="auto",
                        help="print the number of records in each map cell (auto: when there are <= 25 scales)")
        sp.add_argument("--figure-format", dest="format", choices=FIGURE_FORMATS,
                        help="figure file format: png (default; raster at 300 dpi), pdf or svg (vector, for a paper)")
        add_old_spelling(sp, "--format", "--figure-format", choices=FIGURE_FORMATS)

    m = sub.add_parser("maps", help="per object: fragility map PNG with the fit's 1/50/99 %% contours, "
                                    "per-record curves PNG, fit.json")
    m.add_argument("cube", help="campaign cube (HDF5)")
    m.add_argument("--out", required=True, help="output directory")
    m.add_argument("--object", action="append", help="only this object (repeatable; every variant of it); default: all")
    variant_option(m)
    m.add_argument("--pgv-pga", type=float, metavar="S",
                   help="with variants: the PGV/PGA (s) of the variants' fragility curves (default: the records' median)")
    fit_options(m)
    m.set_defaults(func=cmd_maps)

    d = sub.add_parser("diff", help="difference map A - B per object present in both, mismatch mean +- sd "
                                    "(CSV, markdown)")
    d.add_argument("cube_a", metavar="CUBE_A")
    d.add_argument("cube_b", metavar="CUBE_B")
    d.add_argument("--out", required=True, help="output directory")
    d.add_argument("--label-a", default="3D", help="name of cube A in plots and tables (default 3D)")
    d.add_argument("--label-b", default="2D", help="name of cube B (default 2D)")
    d.add_argument("--object", action="append", help="only this object (repeatable; every variant of it)")
    variant_option(d)
    fit_options(d)
    d.set_defaults(func=cmd_diff)

    t = sub.add_parser("table", help="scenario table: objects x records, overturn fraction (markdown + CSV)")
    t.add_argument("cubes", nargs="+", metavar="CUBE")
    t.add_argument("--out", required=True, help="markdown file; the CSV (long format, with counts) goes beside it")
    t.add_argument("--target-pga", type=float, metavar="G", help="only this scale: target PGA (g); default: all scales")
    add_old_spelling(t, "--scale", "--target-pga", type=float)
    t.add_argument("--object", action="append", help="only this object (repeatable; every variant of it)")
    variant_option(t)
    t.add_argument("--layout", choices=("auto", "objects", "records"), default="auto",
                   help="rows are objects (records as columns, plus 'all') or records (plus an 'all' row); "
                        "auto: records as rows when there are more than 10")
    t.add_argument("--counts", action="store_true", help="add overturned/known cell counts to each entry")
    t.set_defaults(func=cmd_table)
    return p


def main(argv=None):
    args = build_parser().parse_args(argv)
    if hasattr(args, "format") and args.format is None:  # None until parsed: the old spelling may set it
        args.format = "png"
    INPUTS[:] = [p for key in ("cube", "cube_a", "cube_b") for p in [getattr(args, key, None)] if p]
    INPUTS.extend(getattr(args, "cubes", None) or [])
    try:
        return args.func(args)
    except (InputError, cube_files.OutputError) as e:
        sys.stderr.write(f"rigid plot: error: {e}\n")
        return 2
    except OSError as e:
        sys.stderr.write(f"rigid plot: error: {e}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main())
