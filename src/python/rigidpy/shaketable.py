"""`rigid shaketable fragility`'s fits: the shake-table rock's fragility from the lab's outcomes
beside the calibrated model's, per PGV/PGA bin, with one table of medians and one figure.

    shaketable_fragility.py CUBE --lab LAB.csv --motions MOTIONS.csv --model MODEL.csv --out OUT
                            [--bins E0,E1,...] [--bootstrap N] [--seed N] [--level 0.9] [--format png]

The command writes LAB.csv (each test's measured PGA, PGV/PGA and outcome), MOTIONS.csv (which
recording each of the cube's records is) and MODEL.csv (the calibrated ensemble's P(overturn) per
motion and PGA, by the ensemble rule of the C++ calibration module: Python holds no copy of it)
beside the cube of its designed campaign, then runs this script.

Both fits are the project's scalar probit P = Phi(ln(PGA/theta)/beta) (fit.py) with
motions as the resampled unit of the bootstrap: the tests of one motion share its waveform, as
the cells of one record do in a campaign. Lab: each test is one Bernoulli outcome at its measured
PGA. Model: at each PGA of the grid, the ensemble's probability of overturning (the lapse rate is
the lab's, not the rock's, and is left out) with the weight of the mean number of headings a
member sees. A motion's bin is
that of its PGV/PGA (the recording the model scales): lab and model fits in a bin are over the
same motions. Exit status: 0 done, 2 bad input, 1 internal error.
"""
import argparse
import csv
import math
import sys

try:
    import numpy as np
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
        pga[t] = float(row["pga_g"])
    return BinnedCells(k, n, pga)


def model_cells(cube, model_rows):
    """Per (motion, scale): the ensemble's P(overturn) as the command computed it (MODEL.csv:
    p_overturn over `cells` cells, 0 cells where not every member's headings were run)."""
    R, S = len(cube.records), len(cube.scales)
    p = np.zeros((R, S))
    n = np.zeros((R, S))
    column = {float(v): s for s, v in enumerate(cube.scales)}
    for i, row in enumerate(model_rows, start=2):
        r, scale = int(row["record_index"]), float(row["scale_g"])
        if not 0 <= r < R or scale not in column:
            raise InputError(f"model.csv:{i}: record {r} at {scale} g is not a cell of the cube")
        p[r, column[scale]] = float(row["p_overturn"])
        n[r, column[scale]] = float(row["cells"])
    return BinnedCells(p * n, n, cube.scales), p, n > 0


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
    args = ap.parse_args(argv)

    cube = Cube(args.cube)
    lab_rows = read_csv(args.lab, ["test_no", "record", "pga_g", "overturned"])
    motion_rows = read_csv(args.motions, ["record", "pgv_over_pga_s"])
    if len(motion_rows) != len(cube.records):
        raise InputError(f"{args.motions}: {len(motion_rows)} motions, the cube has {len(cube.records)} records")
    model_rows = read_csv(args.model, ["record_index", "scale_g", "p_overturn", "cells"])
    if len(model_rows) != len(cube.records) * len(cube.scales):
        raise InputError(f"{args.model}: {len(model_rows)} rows, the cube has {len(cube.records)} x {len(cube.scales)} cells")

    motion_index = {row["record"]: i for i, row in enumerate(motion_rows)}
    unknown = sorted({row["record"] for row in lab_rows} - set(motion_index))
    if unknown:
        raise InputError(f"{args.lab}: tests of motions the campaign did not run: {', '.join(unknown)}")
    pgv_pga = np.array([float(row["pgv_over_pga_s"]) for row in motion_rows])
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
    draw(rows, lab, model_p, simulated, cube.scales, figure, inputs)
    print(f"wrote {table} (the table) and {figure} (the figure)")
    return 0


def probit_curve(x, fit, theta=None):
    from scipy.special import ndtr
    theta = fit["theta_g"] if theta is None else theta
    return ndtr(np.log(x / theta) / fit["beta"])


def draw(rows, lab, model_p, simulated, scales_g, path, inputs):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = len(rows)
    fig, axes = plt.subplots(1, n, figsize=(3.6 * n, 3.6), sharey=True, squeeze=False)
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
        h = ax.scatter(lab.scales_g[cols], outcome + jitter, s=10, marker="|", color="C0", alpha=0.7)
        handles["lab tests (1 overturned, 0 stood)"] = h
        shares = [np.mean(model_p[motions, s][simulated[motions, s]]) if simulated[motions, s].any() else np.nan
                  for s in range(len(scales_g))]
        h = ax.plot(scales_g, shares, "o", ms=3, color="C3", alpha=0.6)[0]
        handles["model: mean P over the bin's motions"] = h
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
        ax.set_title(f"{'PGV/PGA ' if r['label'][0].isdigit() else ''}{r['label']}\n{len(motions)} motions, {r['tests']} tests", fontsize=9)
        ax.set_xlabel("PGA (g)")
        ax.set_xscale("log")
        ax.set_xlim(low, top)
        ax.set_ylim(-0.08, 1.08)
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("P(overturn)")
    # one legend below the panels: it cannot cover data
    fig.legend(list(handles.values()), list(handles.keys()), loc="lower center", ncol=3, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.14, 1, 1))
    cube_files.save_figure(fig, path, "--out", inputs, dpi=150)
    plt.close(fig)


def main(argv=None):
    try:
        return fragility_command(argv)
    except (InputError, cube_files.OutputError) as e:
        sys.stderr.write(f"rigid: error: {e}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main())
