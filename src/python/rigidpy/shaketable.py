"""`rigid shaketable fragility`'s fits: the shake-table rock's fragility from the lab's outcomes
beside the calibrated model's, per PGV/PGA bin, with one table of medians and one figure.

    shaketable_fragility.py CUBE --lab LAB.csv --motions MOTIONS.csv --model MODEL.csv --out OUT
                            [--bins E0,E1,...] [--bootstrap N] [--seed N] [--level 0.9] [--format png]
                            [--physics TEXT]

The command writes LAB.csv (each test's measured PGA, PGV/PGA and outcome), MOTIONS.csv (which
recording each of the cube's records is) and MODEL.csv (the calibrated ensemble's P(overturn) per
motion and PGA, by the ensemble rule of the C++ calibration module: Python holds no copy of it)
beside the cube of its designed campaign, then runs this script.

Both fits are the project's scalar probit P = Phi(ln(PGA/theta)/beta) (fit.py) with
motions as the resampled unit of the bootstrap: the tests of one motion share its waveform, as
the cells of one record do in a campaign. Lab: each test is one Bernoulli outcome at its measured
PGA. Model: at each PGA of the grid, the ensemble's probability of overturning (the lapse rate is
the lab's, not the rock's, and is left out) with the weight of the mean number of headings a
member sees. The fit reads the (motion, PGA)s simulated throughout (MODEL.csv's `simulated`);
the figure's model points also count the stop rule's inferred cells, as overturned, as the rule
says (leaving them out would average only the motions that never overturned at the top PGAs).
A motion's bin is
that of its PGV/PGA (the recording the model scales): lab and model fits in a bin are over the
same motions. Exit status: 0 done, 2 bad input, 1 internal error.
"""
import argparse
import csv
import math
import sys

try:
    import numpy as np
    from . import figure_style
    from . import files as cube_files
    from . import fit as ff
    from .cube import Cube
    from .errors import InputError
    from .fit import DEFAULT_BOOTSTRAP
    from .outcomes import simulated_counts
except ImportError as e:  # pragma: no cover
    sys.stderr.write(f"rigid: error: {e}; install python3-numpy python3-h5py python3-scipy python3-matplotlib "
                     f"and run with /usr/bin/python3 (this is {sys.executable})\n")
    sys.exit(2)


class BinnedCells:
    """Binomial rows per (motion, column) in the shape fragility_fit's scalar fit reads: k and n
    [motions, columns], each column at its own PGA (g)."""

    def __init__(self, k, n, scales_g):
        self.k = np.asarray(k, float)
        self.n = np.asarray(n, float)
        self.scales_g = np.asarray(scales_g, float)

    def records_with_cells(self, records=None):
        idx = np.arange(self.n.shape[0]) if records is None else np.asarray(records, int)
        return idx[self.n[idx].sum(axis=1) > 0]


def read_csv(path, columns):
    try:
        with open(path, newline="") as fh:
            rows = list(csv.DictReader(fh))
    except OSError as e:
        raise InputError(f"{path}: cannot read it ({e.strerror})")
    for i, row in enumerate(rows, start=2):
        missing = [c for c in columns if not row.get(c)]
        if missing:
            raise InputError(f"{path}:{i}: no {', '.join(missing)}")
    return rows


def lab_cells(lab_rows, motion_index):
    """One column per test: its outcome at its measured PGA, in its motion's row."""
    T = len(lab_rows)
    k = np.zeros((len(motion_index), T))
    n = np.zeros((len(motion_index), T))
    pga = np.zeros(T)
    for t, row in enumerate(lab_rows):
        m = motion_index[row["record"]]
        n[m, t] = 1
        k[m, t] = float(row["overturned"])
        pga[t] = float(row["measured_pga_g"])
    return BinnedCells(k, n, pga)


def model_cells(cube, model_rows):
    """Per (motion, scale): the ensemble's P(overturn) as the command computed it (MODEL.csv:
    p_overturn over `cells` cells, inferred cells counted as overturned; 0 cells where some
    member's cell is unknown). Returns the fit's cells (simulated throughout only), P and the mask
    of known (motion, scale)s the figure's points average."""
    R, S = len(cube.records), len(cube.scales)
    return model_cells_on_grid(R, cube.scales, model_rows)


def model_cells_on_grid(R, scales_g, model_rows):
    """model_cells on R motions by the PGA grid `scales_g` (g)."""
    S = len(scales_g)
    p = np.zeros((R, S))
    n = np.zeros((R, S))
    ran = np.zeros((R, S), bool)
    column = {float(v): s for s, v in enumerate(scales_g)}
    for i, row in enumerate(model_rows, start=2):
        r, scale = int(row["record_index"]), float(row["scale_g"])
        if not 0 <= r < R or scale not in column:
            raise InputError(f"model.csv:{i}: record {r} at {scale} g is not a cell of the cube")
        p[r, column[scale]] = float(row["p_overturn"])
        n[r, column[scale]] = float(row["cells"])
        ran[r, column[scale]] = row.get("simulated", "1") == "1"
    return BinnedCells(p * n * ran, n * ran, scales_g), p, n > 0


def model_points(model_p, known, motions):
    """The figure's model point per PGA: the mean P over the motions whose cells are known there
    (simulated or inferred), NaN where none is."""
    return np.array([np.mean(model_p[motions, s][known[motions, s]]) if known[motions, s].any() else np.nan
                     for s in range(model_p.shape[1])])


LAB_OVERTURNED = "lab test: overturned (P = 1)"
LAB_STOOD = "lab test: stood (P = 0)"
MODEL_POINTS = "model: mean P over the bin's motions (inferred cells as overturned)"


def bin_edges(text, pgv_pga):
    """--bins, or three bins of a third of the motions each (edges halfway, geometrically, between
    the neighbouring motions; the outer ones 5 % beyond the extremes)."""
    if text:
        try:
            edges = [float(v) for v in text.split(",")]
        except ValueError:
            raise InputError(f"--bins {text!r}: expected comma-separated numbers (s)")
        if len(edges) < 2 or any(not (e > 0 and math.isfinite(e)) for e in edges) or any(
                b <= a for a, b in zip(edges, edges[1:])):
            raise InputError(f"--bins {text!r}: at least two positive, strictly increasing edges (s)")
        return np.array(edges)
    v = np.sort(pgv_pga)
    groups = np.array_split(v, min(3, len(v)))
    inner = [math.sqrt(a[-1] * b[0]) for a, b in zip(groups, groups[1:])]
    return np.array([v[0] / 1.05] + inner + [v[-1] * 1.05])


def fit_row(source, cells, records, rng, args):
    r = ff.scalar_fragility(cells, records, rng, args.bootstrap, args.level)
    r["source"] = source
    return r


def fmt_g(v):
    return "-" if v is None or not math.isfinite(v) else f"{v:.3f}"


def beyond_note(r, low_g, high_g):
    """A note when theta's interval reaches past the PGAs the fit saw (the fit extrapolates)."""
    lo, hi = r.get("theta_interval_g", (math.nan, math.nan))
    if math.isfinite(hi) and hi > high_g:
        return f"theta's interval reaches past the largest PGA of the data ({high_g:.3g} g): extrapolated"
    if math.isfinite(lo) and lo < low_g:
        return f"theta's interval reaches below the smallest PGA of the data ({low_g:.3g} g): extrapolated"
    return ""


def describe(r):
    if "theta_g" not in r:
        return f"no fit: {r.get('reason', '')}"
    lo, hi = r["theta_interval_g"]
    blo, bhi = r["beta_interval"]
    text = f"theta {fmt_g(r['theta_g'])} g [{fmt_g(lo)}, {fmt_g(hi)}]  beta {r['beta']:.2f} [{fmt_g(blo)}, {fmt_g(bhi)}]"
    notes = [n for n in (r.get("interval_note"), r.get("beyond_note")) if n]
    return text + "".join(f"\n          ({n})" for n in notes)


def fragility_command(argv=None):
    ap = argparse.ArgumentParser(prog="rigid shaketable fragility")
    ap.add_argument("cube")
    ap.add_argument("--lab", required=True)
    ap.add_argument("--motions", required=True)
    ap.add_argument("--model", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--bins", default="")
    ap.add_argument("--bootstrap", type=int, default=DEFAULT_BOOTSTRAP)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--level", type=float, default=0.9)
    ap.add_argument("--format", default="png", choices=["png", "pdf", "svg"])
    ap.add_argument("--physics", default="", help="the model's physics in one line, for the title")
    args = ap.parse_args(argv)

    cube = Cube(args.cube)
    lab_rows = read_csv(args.lab, ["test_no", "record", "measured_pga_g", "overturned"])
    motion_rows = read_csv(args.motions, ["record", "measured_pgv_over_pga_s"])
    if len(motion_rows) != len(cube.records):
        raise InputError(f"{args.motions}: {len(motion_rows)} motions, the cube has {len(cube.records)} records")
    model_rows = read_csv(args.model, ["record_index", "scale_g", "p_overturn", "cells"])
    if len(model_rows) != len(cube.records) * len(cube.scales):
        raise InputError(f"{args.model}: {len(model_rows)} rows, the cube has {len(cube.records)} x {len(cube.scales)} cells")

    motion_index = {row["record"]: i for i, row in enumerate(motion_rows)}
    unknown = sorted({row["record"] for row in lab_rows} - set(motion_index))
    if unknown:
        raise InputError(f"{args.lab}: tests of motions the campaign did not run: {', '.join(unknown)}")
    pgv_pga = np.array([float(row["measured_pgv_over_pga_s"]) for row in motion_rows])
    edges = bin_edges(args.bins, pgv_pga)
    lab = lab_cells(lab_rows, motion_index)
    model, model_p, simulated = model_cells(cube, model_rows)

    groups = []  # (label, lower, upper, motion indices)
    for b in range(len(edges) - 1):
        last = b == len(edges) - 2
        inside = (pgv_pga >= edges[b]) & ((pgv_pga <= edges[b + 1]) if last else (pgv_pga < edges[b + 1]))
        groups.append((f"{edges[b]:.3f}-{edges[b + 1]:.3f} s", float(edges[b]), float(edges[b + 1]), np.flatnonzero(inside)))
    groups.append(("all motions", float(edges[0]), float(edges[-1]), np.arange(len(motion_rows))))

    rows = []
    for g, (label, lo, hi, motions) in enumerate(groups):
        if len(motions) == 0:
            continue
        lab_fit = fit_row("lab", lab, motions, np.random.default_rng([args.seed, g, 0]), args)
        model_fit = fit_row("model", model, motions, np.random.default_rng([args.seed, g, 1]), args)
        tested = lab.scales_g[lab.n[motions].sum(axis=0) > 0]
        lab_fit["beyond_note"] = beyond_note(lab_fit, float(tested.min()), float(tested.max()))
        model_fit["beyond_note"] = beyond_note(model_fit, float(np.min(cube.scales)), float(np.max(cube.scales)))
        tests = int(lab.n[motions].sum())
        over = int(lab.k[motions].sum())
        rows.append(dict(label=label, lower_s=lo, upper_s=hi, motions=motions, tests=tests, overturned=over,
                         lab=lab_fit, model=model_fit))

    print(f"Fragility of the shake-table rock, lab beside model ({args.level:.0%} bootstrap intervals over motions, "
          f"{args.bootstrap} resamples):")
    for r in rows:
        print(f"  {'PGV/PGA ' if r['label'][0].isdigit() else ''}{r['label']}: {len(r['motions'])} motions, {r['tests']} tests ({r['overturned']} overturned)")
        print(f"    lab   {describe(r['lab'])}")
        print(f"    model {describe(r['model'])}")
        if "theta_g" in r["lab"] and "theta_g" in r["model"]:
            print(f"    model/lab median {r['model']['theta_g'] / r['lab']['theta_g']:.2f}")

    table = args.out + ".fragility.csv"
    figure = args.out + ".fragility." + args.format
    inputs = [args.cube, args.lab, args.motions, args.model]
    with cube_files.output_text(table, "--out", inputs, newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["pgv_pga_bin", "pgv_pga_lower_s", "pgv_pga_upper_s", "motions", "tests", "tests_overturned", "source",
                    "theta_g", "theta_low_g", "theta_high_g", "beta", "beta_low", "beta_high", "note"])
        for r in rows:
            for source in ("lab", "model"):
                f = r[source]
                t_lo, t_hi = f.get("theta_interval_g", (math.nan, math.nan))
                b_lo, b_hi = f.get("beta_interval", (math.nan, math.nan))
                w.writerow([r["label"], f"{r['lower_s']:.4f}", f"{r['upper_s']:.4f}", len(r["motions"]), r["tests"],
                            r["overturned"], source] +
                           [f"{v:.4f}" if v is not None and math.isfinite(v) else "" for v in
                            (f.get("theta_g"), t_lo, t_hi, f.get("beta"), b_lo, b_hi)] +
                           ["; ".join(n for n in (f.get("interval_note"), f.get("reason"), f.get("beyond_note")) if n)])
    draw(rows, lab, model_p, simulated, cube.scales, figure, inputs, args.physics)
    print(f"wrote {table} (the table) and {figure} (the figure)")
    return 0


def probit_curve(x, fit, theta=None):
    from scipy.special import ndtr
    theta = fit["theta_g"] if theta is None else theta
    return ndtr(np.log(x / theta) / fit["beta"])


def draw(rows, lab, model_p, known, scales_g, path, inputs, physics=""):
    import matplotlib.pyplot as plt
    fig = fragility_figure(rows, lab, model_p, known, scales_g, physics)
    cube_files.save_figure(fig, path, "--out", inputs, dpi=figure_style.RASTER_DPI)
    plt.close(fig)


def fragility_figure(rows, lab, model_p, known, scales_g, physics=""):
    """The figure: one panel per PGV/PGA bin and one of all motions, three a row on a page's width;
    the title names the model's physics (`physics`, one line)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure_style.apply(plt)
    n = len(rows)
    width = figure_style.DOUBLE_COLUMN_IN
    ncol = min(3, n)
    nrow = -(-n // ncol)
    fig, grid = plt.subplots(nrow, ncol, figsize=(width, 2.4 * nrow + 1.9), sharey=True, squeeze=False)
    for ax in grid.ravel()[n:]:
        ax.set_visible(False)
    axes = [list(grid.ravel()[:n])]
    # PGA on a log axis: the lognormal's own scale, and the lab's tests span two decades
    low = 0.8 * min(float(np.min(scales_g)), float(np.min(lab.scales_g[lab.scales_g > 0])))
    top = 1.25 * max(float(np.max(scales_g)), float(np.max(lab.scales_g)))
    x = np.geomspace(low, top, 400)
    handles = {}
    for ax, r in zip(axes[0], rows):
        motions = r["motions"]
        cols = np.flatnonzero(lab.n[motions].sum(axis=0) > 0)
        outcome = lab.k[motions][:, cols].sum(axis=0)
        jitter = np.random.default_rng(0).uniform(-0.03, 0.03, len(cols))
        # one marker each: a lone "|" at 0 and 1 read like counts of tests
        for value, marker, name in ((1, "^", LAB_OVERTURNED), (0, "v", LAB_STOOD)):
            at = outcome == value
            if at.any():
                handles[name] = ax.scatter(lab.scales_g[cols][at], outcome[at] + jitter[at], s=12, marker=marker,
                                           color="C0" if value else "C2", alpha=0.7)
        h = ax.plot(scales_g, model_points(model_p, known, motions), "o", ms=3, color="C3", alpha=0.6)[0]
        handles[MODEL_POINTS] = h
        for source, color, style, name in (("lab", "C0", "-", "lab probit fit"), ("model", "C3", "--", "model probit fit")):
            f = r[source]
            if "theta_g" not in f:
                continue
            h = ax.plot(x, probit_curve(x, f), style, color=color, lw=1.8)[0]
            handles[name + " (median theta)"] = h
            lo, hi = f["theta_interval_g"]
            if math.isfinite(lo) and math.isfinite(hi):
                h = ax.fill_between(x, probit_curve(x, f, hi), probit_curve(x, f, lo), color=color, alpha=0.15, lw=0)
                handles[name + ": theta's interval"] = h
        ax.set_title(f"{'PGV/PGA ' if r['label'][0].isdigit() else ''}{r['label']}\n{len(motions)} motions, {r['tests']} tests")
        ax.set_xlabel("PGA (g)")
        ax.set_xscale("log")
        ax.set_xlim(low, top)
        ax.set_ylim(-0.08, 1.08)
        ax.grid(alpha=0.3)
    for row in grid:
        row[0].set_ylabel("P(overturn)")
    import textwrap
    title = "Shake-table fragility, lab beside model; model: " + (physics or "physics not stated")
    fig.suptitle(textwrap.fill(title, width=int(15 * width)))  # about 15 characters an inch at 9 pt
    # one legend below the panels: it cannot cover data
    columns = 2
    fig.legend(list(handles.values()), list(handles.keys()), loc="lower center", ncol=columns, frameon=False)
    legend_in = 0.17 * -(-len(handles) // columns) + 0.1
    height = fig.get_size_inches()[1]
    title_in = 0.17 * (textwrap.fill(title, width=int(15 * width)).count("\n") + 1) + 0.1
    fig.tight_layout(rect=(0, legend_in / height, 1, 1 - title_in / height))
    return fig


def main(argv=None):
    try:
        return fragility_command(argv)
    except (InputError, cube_files.OutputError) as e:
        sys.stderr.write(f"rigid: error: {e}\n")
        return 2


# --- `rigid shaketable calibrate`'s diagnostic figure -------------------------------------------
#
#     shaketable_calibration.py NAME.calibration.json --likelihood LIKELIHOOD.csv --out FIGURE
#                               [--format png]
#
# Draws what the calibration wrote, computes nothing: the profile log-likelihood of each variant
# over its headings (LIKELIHOOD.csv, final stage), the held-out scores of each recorded motion and
# the reliability tables (the JSON's cross_validated.by_motion and reliability).

LIKELIHOOD_COLUMNS = ["stage", "variant", "label", "heading_deg", "log_likelihood"]


def read_calibration_json(path):
    """The calibration document as a dict; InputError for a file that is not one."""
    import json
    try:
        with open(path) as fh:
            doc = json.load(fh)
    except OSError as e:
        raise InputError(f"{path}: cannot read it ({e.strerror})")
    except ValueError as e:
        raise InputError(f"{path}: not JSON ({e})")
    if not isinstance(doc, dict) or doc.get("format") != "rigid calibration":
        raise InputError(f"{path}: not a rigid calibration file")
    return doc


def final_stage_likelihood(rows):
    """{label: (headings, log-likelihoods)} of the fitted design's variants, headings ascending:
    the last stage's, and with edge extension (stages after 2, on stage 2's headings) stage 2's
    and every later one's."""
    last = max(int(r["stage"]) for r in rows)
    first = min(last, 2)
    lines = {}
    for r in rows:
        if int(r["stage"]) >= first:
            lines.setdefault(r["label"], []).append((float(r["heading_deg"]), float(r["log_likelihood"])))
    which = f"stage {last}" if first == last else f"stages {first}-{last}"
    return which, {k: tuple(np.array(v) for v in zip(*sorted(pts))) for k, pts in lines.items()}


def reliability_points(table):
    """(mean P, frequency, lower error, upper error, tests) of a reliability table's non-empty bins."""
    full = [b for b in table if b["tests"] > 0]
    mean = np.array([b["mean_p"] for b in full])
    freq = np.array([b["frequency"] for b in full])
    lo = np.array([b["frequency_interval"][0] for b in full])
    hi = np.array([b["frequency_interval"][1] for b in full])
    return mean, freq, freq - lo, hi - freq, [b["tests"] for b in full]


def calibration_title(doc):
    heading = doc.get("parameters", {}).get("heading_deg", {}).get("value")
    import os
    scan = os.path.basename(str(doc.get("scan", "?")))
    text = "Calibration of " + scan + ": " + str(doc.get("physics", "physics not stated"))
    if heading is not None:
        text += f", heading {heading:.1f} deg"
    return text


def calibration_figure(doc, likelihood_rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure_style.apply(plt)
    cv = doc.get("cross_validated", {})
    by = cv.get("by_motion", []) if isinstance(cv, dict) else []
    # likelihood and reliability side by side, the motions' held-out scores below on the page's
    # width; without cross-validation no empty panel, a line under the title says why
    fig = plt.figure(figsize=(figure_style.DOUBLE_COLUMN_IN, 8.4 if by else 4.6))
    grid = fig.add_gridspec(2 if by else 1, 2, height_ratios=[1, 0.9] if by else [1])
    a_lik = fig.add_subplot(grid[0, 0])
    a_motion = fig.add_subplot(grid[1, :]) if by else None
    a_rel = fig.add_subplot(grid[0, 1])
    # (a) likelihood over heading, one line per physics variant of the final stage
    stage, lines = final_stage_likelihood(likelihood_rows)
    best = max(ll.max() for _, ll in lines.values())
    for k, (label, (h, ll)) in enumerate(sorted(lines.items())):
        a_lik.plot(h, ll, "o-", ms=3, lw=1.2, color=f"C{k % 10}", label=label)
    a_lik.axhline(best - 1.92, color="0.4", ls=":", lw=1, label="95 % region: best - 1.92")
    a_lik.set_xlabel("heading of the table's axis in the scan's frame (deg)")
    a_lik.set_ylabel("log-likelihood (best spread and lapse)")
    a_lik.set_title(f"{stage}: likelihood by variant and heading")
    a_lik.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), frameon=False)  # below: it cannot cover a line
    a_lik.grid(alpha=0.3)
    # (b) held-out scores of each recorded motion
    if by:
        x = np.arange(len(by))
        a_motion.bar(x, [m["brier"] for m in by], color="C1", alpha=0.7, label="Brier score (0 best)")
        a_motion.plot(x, [m["accuracy"] for m in by], "ko", ms=4, label="accuracy")
        a_motion.set_xticks(x)
        a_motion.set_xticklabels([f"{m['record']} ({m['overturned']}/{m['tests']})" for m in by], rotation=75)
        a_motion.set_ylim(0, 1.05)
        a_motion.legend(loc="lower left", bbox_to_anchor=(1.0, 0.0), frameon=False)  # right of the bars
        a_motion.set_title(f"left-out motion's own tests: Brier {cv['brier']:.3f}, log loss {cv['log_loss']:.3f} "
                           f"overall")
        a_motion.grid(alpha=0.3, axis="y")
    # (c) reliability: predicted P against the observed share, 95 % Wilson intervals
    a_rel.plot([0, 1], [0, 1], color="0.5", lw=1, ls="--", label="perfectly reliable")
    for key, color, marker, name in (("in_sample", "C0", "s", "in sample"),
                                     ("cross_validated", "C3", "o", "cross-validated")):
        part = doc.get(key, {})
        if not isinstance(part, dict) or "reliability" not in part:
            continue
        mean, freq, elo, ehi, n = reliability_points(part["reliability"])
        a_rel.errorbar(mean, freq, yerr=[elo, ehi], fmt=marker, color=color, ms=4, capsize=2, lw=1,
                       label=f"{name} (Brier {part['brier']:.3f}, log loss {part['log_loss']:.3f})")
        if key == "cross_validated":
            for xm, ym, count in zip(mean, freq, n):
                a_rel.annotate(str(count), (xm, ym), textcoords="offset points", xytext=(4, -8))
    a_rel.set_xlim(-0.02, 1.02)
    a_rel.set_ylim(-0.02, 1.02)
    a_rel.set_xlabel("predicted P(overturn) (bin mean)")
    a_rel.set_ylabel("observed share overturned")
    a_rel.set_title("reliability (numbers: tests per bin)")
    a_rel.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), frameon=False)
    a_rel.grid(alpha=0.3)
    title = calibration_title(doc)
    if not by:
        title += "\ncross-validation by recorded motion: not available (fewer than 3 recorded motions)"
    fig.suptitle(title)
    fig.tight_layout(rect=(0, 0, 1, 0.95 if by else 0.9))
    return fig


def calibration_figure_command(argv=None):
    ap = argparse.ArgumentParser(prog="rigid shaketable calibrate (figure)")
    ap.add_argument("calibration")
    ap.add_argument("--likelihood", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--format", default="png", choices=["png", "pdf", "svg"])
    args = ap.parse_args(argv)
    doc = read_calibration_json(args.calibration)
    rows = read_csv(args.likelihood, LIKELIHOOD_COLUMNS)
    if not rows:
        raise InputError(f"{args.likelihood}: no rows")
    import matplotlib.pyplot as plt
    fig = calibration_figure(doc, rows)
    cube_files.save_figure(fig, args.out, "--out", [args.calibration, args.likelihood], dpi=figure_style.RASTER_DPI)
    plt.close(fig)
    print(f"wrote {args.out} (the calibration's figure)")
    return 0


def calibration_main(argv=None):
    try:
        return calibration_figure_command(argv)
    except (InputError, cube_files.OutputError) as e:
        sys.stderr.write(f"rigid: error: {e}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main())
