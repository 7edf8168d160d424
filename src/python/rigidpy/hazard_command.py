"""`rigid hazard`: the fitted fragility (or the pool of variants) integrated over a hazard curve
(hazard.py): the toppling rate, the survival over the exposure age with its intervals, the
warnings, the report and the plot."""
import json
import math
import os
import sys

import numpy as np
from numpy.polynomial.hermite_e import hermegauss

from . import figure_style
from . import files as cube_files
from . import fit as ff
from . import hazard as hc
from .cube import Cube
from .errors import InputError
from .fit import SCALAR_SOURCE, THRESHOLD_SOURCE
from .command_line import check_completeness, number_in, warn_incomplete
from .fragility_report import BEYOND_MARK, fmt_factor, fmt_interval, fmt_probability, json_clean
from .object_fits import ObjectFit, end_progress, fragility_source, start_progress


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


class RockFragility:
    """A rock's fragility as a hazard integral needs it: `mixture`, the fitted fragility as a
    weighted mixture of lognormals [(weight, theta_g, beta)] (one per PGV/PGA point, or per variant),
    and its uncertainty as an ensemble of `members` [(weight, mixture)], weights summing to 1.
    The members are the bootstrap replicates over records (`replicates`), equally weighted, or the
    fitted mixture alone when there are none. For a calibrated object (variants = a calibration's
    member scenes) the mixture and every replicate already mix the members by the calibration's
    weights (pooled_fragility), so the members stay the replicates: the calibration's physics is
    integrated over, the records resampled. Another ensemble with its own weights fits the same
    slot (pass `members`)."""

    def __init__(self, label, mixture, replicates, source, members=None):
        self.label = label
        self.mixture = mixture
        self.replicates = replicates
        self.source = source  # where the members come from, for the report
        if members is None:
            members = [(1.0 / len(replicates), m) for m in replicates] if replicates else [(1.0, mixture)]
        self.members = members


def select_rock(args):
    """The cube of `args.cube` and the objects (one, or every variant of one) standing for the rock
    `args.object` (None: the cube's only object)."""
    state = cube_files.campaign_state(args.cube)
    cube = Cube(args.cube)
    check_completeness(cube, state, args)
    objs = cube.select([args.object] if args.object else None, args.variant)
    names = cube.base_names() if not args.object else [args.object]
    if len(names) > 1:
        raise InputError(f"{args.cube}: {len(names)} objects; choose one with --object "
                         f"({', '.join(names)})")
    return cube, objs


def is_pooled(cube, args):
    return cube.variants is not None and args.variant is None


def object_fragility(args, cube, obj):
    """One object's (or one variant's) fitted fragility: (RockFragility, its ObjectFit, the vector
    fit's result `v`, the PGV/PGA points [(weight, s)]). A variant whose outcomes are separated
    stands as its empirical threshold, a step without bootstrap."""
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
        t = fit.threshold["theta_g"]
        used_s = cube.pgv_pga[cells.records_with_cells()]
        v = dict(v, points=[{"pgv_pga_s": s, "theta_g": t, "beta": 0.0, "theta_interval_g": ff.NO_INTERVAL,
                             "beta_interval": ff.NO_INTERVAL, "source": THRESHOLD_SOURCE} for _, s in points],
                 replicate_theta_g=np.empty((0, len(points))), replicate_beta=np.empty((0, len(points))),
                 pgv_pga_range_s=[float(used_s.min()), float(used_s.max())])
    if "points" not in v:
        raise InputError(f"{args.cube}: object {obj.label}: no vector fit ({v.get('reason')})")
    mixture = [(w, p["theta_g"], p["beta"]) for (w, _), p in zip(points, v["points"])]
    replicates = []
    for i in range(v["replicate_theta_g"].shape[0]):
        t, b = v["replicate_theta_g"][i], v["replicate_beta"][i]
        if np.all(np.isfinite(t)):
            replicates.append([(w, t[j], b[j]) for j, (w, _) in enumerate(points)])
    source = ("bootstrap over records" if replicates else
              "the fitted fragility alone (" + (THRESHOLD_SOURCE if fit.threshold is not None
                                                else f"no bootstrap replicate: {v['n_records']} record(s)") + ")")
    rock = RockFragility(obj.label, mixture, replicates, source)
    return rock, fit, v, points


def pooled_fragility(args, cube, objs):
    """The pooled (mixture) fragility of an object's variants: (RockFragility, the ObjectFits,
    [(fit, source, mixture)] of the variants that have one, the PGV/PGA points, the records used).
    Its members are the pooled bootstrap replicates: replicate i of every variant resamples the
    same records (ObjectFit says why) and the pooled replicate mixes them."""
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
    # each variant by its weight: equal, or a calibrated object's members' (renormalised over the
    # variants that have a fragility, and in each replicate over those that fit in it)
    weight = cube.variant_weights(objs[0].name)

    def weight_of(f):
        return float(weight[f.obj.variant]) if f.obj.variant is not None else 1.0

    total = sum(weight_of(f) for f, _, _ in per_variant)
    mixture = [(weight_of(f) / total * w, t, b) for f, _, mix in per_variant for w, t, b in mix]
    # replicate i of the pooled fragility; a variant without vector bootstrap (a threshold or the
    # scalar fit) is held fixed, and one whose fit does not exist in resample i (few records: the
    # resample's outcomes are separated) sits that replicate out, the others reweighted; with many
    # variants and few records nearly every resample loses one, and requiring all of them left a
    # handful of replicates and a degenerate interval
    boot = [f.vector["replicate_theta_g"].shape[0] for f, src, _ in per_variant if src == "vector fit"]
    replicates = []
    for i in range(min(boot) if boot else 0):
        members = []
        for f, src, mix in per_variant:
            if src == "vector fit":
                t, b = f.vector["replicate_theta_g"][i], f.vector["replicate_beta"][i]
                if np.all(np.isfinite(t)):
                    members.append((weight_of(f), [(w, t[j], b[j]) for j, (w, _) in enumerate(points)]))
            else:
                members.append((weight_of(f), mix))
        if members:
            in_replicate = sum(wm for wm, _ in members)
            replicates.append([(wm / in_replicate * w, th, be) for wm, m in members for w, th, be in m])
    calibration = cube.calibrations.get(objs[0].name)
    pooled_how = ("variants pooled" if calibration is None else
                  f"the {len(calibration.weights)} member scenes of the calibration {calibration.path} mixed by weight")
    rock = RockFragility(f"{objs[0].name} (pooled)", mixture, replicates,
                         f"bootstrap over records, {pooled_how}" if replicates else
                         f"the pooled fragility alone (no bootstrap replicate; {pooled_how})")
    return rock, fits, per_variant, points, used


def cmd_hazard(args):
    result, draw = hazard_result(args)
    emit_hazard(args, result, draw)
    return 0


def hazard_result(args):
    """(result, draw): what `rigid hazard` reports (the JSON document's content) and the function
    that draws its --plot; rigidpy.hazard returns the result."""
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
    cube, objs = select_rock(args)
    if is_pooled(cube, args):
        return hazard_pooled(args, cube, curve, objs)
    obj = objs[0]
    rock, fit, v, points = object_fragility(args, cube, obj)
    lo_s, hi_s = v["pgv_pga_range_s"]
    outside = sum(w for w, s in points if not lo_s <= s <= hi_s)
    mixture = rock.mixture
    lam, extended = hc.mixture_rate(curve, mixture)
    reps = [hc.mixture_rate(curve, m)[0] for m in rock.replicates]
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
    return result, lambda: plot_hazard(args.plot, curve, mixture, v, points, result)


PLOT_FORMATS = figure_style.FIGURE_FORMATS


def check_plot_path(args):
    """--plot: a figure format matplotlib writes, and neither the cube nor the curve."""
    check_figure_path(args.plot, [args.cube, args.curve])


def check_figure_path(path, inputs):
    """A figure's file: a format matplotlib writes, and none of the command's inputs."""
    ext = os.path.splitext(path)[1].lower().lstrip(".")
    if ext not in PLOT_FORMATS:
        raise InputError(f"--plot {path}: the file name must end in one of "
                         f"{', '.join('.' + f for f in PLOT_FORMATS)} (the figure's format)")
    cube_files.refuse_output_over_inputs(path, "--plot", inputs)


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
    aleatory interval (the pooled bootstrap replicates), and the epistemic 5-95 % range over
    variants of the survival probability, each variant's own lognormal integrated."""
    rock, fits, per_variant, points, used = pooled_fragility(args, cube, objs)
    n = len(per_variant)
    mixture = rock.mixture
    lam, extended = hc.mixture_rate(curve, mixture)
    rates = [hc.mixture_rate(curve, mix)[0] for _, _, mix in per_variant]
    survivals = [hc.survival(r, args.age) for r in rates]
    lo_pct, hi_pct = ff.EPISTEMIC_PERCENTILES[0], ff.EPISTEMIC_PERCENTILES[-1]
    calibration = cube.calibrations.get(objs[0].name)
    if calibration is None:
        def epistemic_range(values):
            return [float(v) for v in np.percentile(values, [lo_pct, hi_pct])]
    else:  # a calibration's members count by their weights here as in the mixture
        member_weights = [float(calibration.weights[f.obj.variant]) for f, _, _ in per_variant]

        def epistemic_range(values):
            return [float(v) for v in ff.weighted_percentile(values, member_weights, [lo_pct, hi_pct])]
    reps = [hc.mixture_rate(curve, m)[0] for m in rock.replicates]
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
              "annual_toppling_rate_epistemic_range": epistemic_range(rates),
              "share_of_rate_beyond_curve": extended,
              "survival_probability": surv,
              "survival_probability_interval": [hc.survival(lam_hi, args.age), hc.survival(lam_lo, args.age)],
              "survival_probability_epistemic_range": epistemic_range(survivals),
              "epistemic_percentiles": [lo_pct, hi_pct],
              "confidence": args.confidence,
              "ruled_out": surv < 1 - args.confidence,
              "rate_factor_to_rule_out": rate_factor, "pga_factor_to_rule_out": pga_factor,
              "interval_level": args.level, "bootstrap_replicates": args.bootstrap,
              "calibration": None if calibration is None else {
                  "path": calibration.path, "sha256": calibration.sha256, "members": len(calibration.weights),
                  "weights": [float(w) for w in calibration.weights]}}
    no_replicates = {"replicate_theta_g": np.empty((0, len(points))), "replicate_beta": np.empty((0, len(points)))}
    return result, lambda: plot_hazard(args.plot, curve, mixture, no_replicates, points,
                                       dict(result, object=f"{objs[0].name} (pooled)"),
                                       variant_mixtures=[mix for _, _, mix in per_variant])


def print_hazard(r):
    pct = int(r["interval_level"] * 100)
    site = f" (site {r['site']})" if r["site"] else ""
    lo, hi = r["curve_pga_range_g"]
    print(f"rigid hazard: object {r['object']} of {r['cube']}; hazard curve {r['curve']}{site}, PGA {lo:g}-{hi:g} g; "
          f"exposure age {r['age_years']:g} years")
    if r.get("pooled"):
        thresholds = sum(v["source"] == THRESHOLD_SOURCE for v in r["variant_fragility"])
        scalars = sum(v["source"] == SCALAR_SOURCE for v in r["variant_fragility"])
        cal = r.get("calibration")
        how = ("equally weighted mixture of" if cal is None else
               f"the member scenes of the calibration {cal['path']} ({cal['members']} members), weights "
               f"{', '.join(f'{w:.3g}' for w in cal['weights'])}, mixing")
        print(f"  fragility: pooled over {r['variants_pooled']} of {r['variants']} variants ({how} "
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
    figure_style.apply(plt)

    lo = min(curve.pga_g[0], min(t for _, t, _ in mixture) * 0.2)
    hi = max(curve.pga_g[curve.top - 1], max(t for _, t, _ in mixture) * 5)
    a = np.exp(np.linspace(math.log(lo), math.log(hi), 400))
    p = sum(w * hc.fragility_probability(a, t, b) for w, t, b in mixture)
    h = curve(a)
    # the integrand per unit ln PGA: dlambda / dln a = P(a) |dH / dln a|
    dh = -np.gradient(h, np.log(a))
    dens = p * np.maximum(dh, 0)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(figure_style.DOUBLE_COLUMN_IN, 7.6), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
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
    fig.legend(lines[0] + lines2[0], lines[1] + lines2[1], loc="lower center", ncol=2, frameon=False)
    top.set_title(f"{r['object']}: toppling rate {r['annual_toppling_rate']:.2e}/yr, "
                  f"P(survive {r['age_years']:g} yr) = {fmt_probability(r['survival_probability'], 3)}")
    bottom.semilogx(a, dens, color="black")
    bottom.fill_between(a, 0, dens, color="gray", alpha=0.3)
    bottom.set_xlabel("PGA (g, GMRotI50)")
    bottom.set_ylabel("d lambda / d ln PGA (per year)")
    bottom.grid(True, which="both", alpha=0.3)
    fig.tight_layout(rect=(0, 0.09, 1, 1), h_pad=2.0)  # the panels' y labels apart
    fmt = os.path.splitext(path)[1].lower().lstrip(".")
    cube_files.write_output(path, "--plot", [], lambda tmp: fig.savefig(tmp, dpi=figure_style.RASTER_DPI, format=fmt))
    plt.close(fig)
    return fig
