"""Pareto plot and markdown table of `rigid study accuracy` (docs/accuracy.md).

    accuracy_plot.py DIR/accuracy.csv --figure DIR/accuracy_pareto.png --table DIR/accuracy_table.md

Top panel: each numerical setting of the default contact model (time-step safety factor x
rotation integrator, at-rest stop tolerances, the three presets) as one point: total wall time over the study's cases (sum of the
median wall times) against the median over the cases of its error against the converged
reference run (relative RMS trajectory error, or the relative change of a quasi-static
threshold). The converged reference itself (error 0) is drawn on the floor of the axis. The
Pareto front (no other setting both cheaper and more accurate) is the grey step line.
Bottom panel: the contact model, a model axis (it changes the physics): for each model setting,
the penalty springs at K = 1e8 (the study's), 1e9 and 1e10 N/m (safety 0.2) and rigid contact at
safety 0.05-0.8, the total wall time over the cases with a rigid-block oracle (Housner one-sine
threshold, g tan alpha, rigid statics of the stack, Newmark sliding) against the median and
worst |relative error| against those oracles: both models on one Pareto plot.

Runs with Debian's /usr/bin/python3 (numpy, matplotlib). Exit status: 0 done, 2 bad input.
"""
import argparse
import csv
import math
import os
import sys

from . import figure_style

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as e:  # pragma: no cover
    sys.stderr.write(f"accuracy_plot: error: {e}; run with /usr/bin/python3 (python3-matplotlib)\n")
    sys.exit(2)

FLOOR = 1e-7          # where error 0 is drawn on the log axis
MODEL_AXES = ("stiffness", "rigid")  # settings that change the physics, not the numerics
ORACLES = ("housner_one_sine_threshold_g", "g_tan_alpha_g", "rigid_statics_toppling_g",
           "newmark_sliding_displacement_m")
PRESETS = ("fast", "balanced", "reference")
PRESET_COLOURS = {"fast": "#d62728", "balanced": "#2ca02c", "reference": "#1f77b4"}


def num(s):
    try:
        return float(s) if s != "" else math.nan
    except ValueError:
        return math.nan


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise ValueError(f"{path}: no rows")
    return rows


def case_of(r):
    return f"{r['scene']}/{r['motion']}"


def median(v):
    v = sorted(x for x in v if not math.isnan(x))
    if not v:
        return math.nan
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def aggregate(rows):
    """Per numerical setting: total wall time, median and max error over the cases. A setting
    missing from a case (the at-rest tolerances where there is no at-rest stop: quasi-static tests,
    the geode drop) runs there exactly as the default, safety 0.2 splitting: that row stands in."""
    cases = []
    by = {}
    for r in rows:
        if r["axis"] in MODEL_AXES:
            continue
        c = case_of(r)
        if c not in cases:
            cases.append(c)
        by[(c, r["setting"])] = r
    default = "safety 0.2 splitting"
    out = {}
    for name in dict.fromkeys(r["setting"] for r in rows if r["axis"] not in MODEL_AXES):
        a = None
        for c in cases:
            r = by.get((c, name)) or by.get((c, default))
            if r is None:
                continue
            if a is None:
                first = by.get((c, name)) or r
                a = dict(axis=first["axis"], preset=first["preset"], wall=0.0, errors=[], cases=0,
                         integrator=first["integrator"], safety=num(first["safety"]), mismatches=0)
            a["wall"] += num(r["wall_s"])
            a["errors"].append(num(r["error"]))
            a["cases"] += 1
            if r["outcome_match"] == "0":
                a["mismatches"] += 1
        if a is not None:
            out[name] = a
    for a in out.values():
        a["median"] = median(a["errors"])
        a["max"] = max((e for e in a["errors"] if not math.isnan(e)), default=math.nan)
    return out


def pareto_front(points):
    """Non-dominated (wall, error) points, sorted by wall."""
    front, best = [], math.inf
    for w, e in sorted(points):
        if e < best:
            front.append((w, e))
            best = e
    return front


def plot(rows, path):
    """The two panels one above the other on a page's width; the format from the file name."""
    agg = aggregate(rows)
    figure_style.apply(plt)
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(figure_style.DOUBLE_COLUMN_IN, 9.0))
    labels = {ax: [], bx: []}  # placed once the layout is final, off the markers
    # top: numerical settings
    style = {("safety", "splitting"): dict(marker="o", color="#444444", label="safety sweep, splitting"),
             ("safety", "rk4"): dict(marker="s", color="#9467bd", label="safety sweep, RK4"),
             ("tolerance", None): dict(marker="^", color="#ff7f0e", label="at-rest / sleep tolerances (safety 0.2)"),
             ("effects", None): dict(marker="v", color="#17becf", label="every effect simulated (safety 0.2)")}
    for key, st in style.items():
        axis, integ = key
        pts = sorted((a["safety"], a["wall"], max(a["median"], FLOOR), name) for name, a in agg.items()
                     if a["axis"] == axis and (integ is None or a["integrator"] == integ))
        if not pts:
            continue
        ax.plot([p[1] for p in pts], [p[2] for p in pts], ls="-" if axis == "safety" else "none", lw=1,
                ms=5, mfc="white", mew=1.2, **st)
        if axis == "safety":
            labels[ax] += [(w, e, f"{s:g}", dict(color=st["color"])) for s, w, e, _ in pts]
    for name, a in agg.items():
        if a["axis"] == "converged":
            ax.plot([a["wall"]], [FLOOR], marker="D", ms=5, color="black", ls="none",
                    label="converged reference (error 0, on the floor)")
    for p in PRESETS:
        a = agg.get(f"preset {p}")
        if a is None:
            continue
        e = max(a["median"], FLOOR)
        ax.plot([a["wall"]] * 2, [e, max(a["max"], FLOOR)], color=PRESET_COLOURS[p], lw=2, alpha=0.6)
        ax.plot([a["wall"]], [max(a["max"], FLOOR)], marker="_", ms=10, mew=2, color=PRESET_COLOURS[p])
        ax.plot([a["wall"]], [e], marker="*", ms=12, color=PRESET_COLOURS[p], mec="black", mew=0.8, ls="none",
                label=f"preset {p} (bar: up to the worst case)")
        labels[ax].append((a["wall"], e, p, dict(weight="bold", color=PRESET_COLOURS[p])))
    front = pareto_front([(a["wall"], max(a["median"], FLOOR)) for a in agg.values()])
    if len(front) > 1:
        ax.step([w for w, _ in front], [e for _, e in front], where="post", color="grey", lw=3, alpha=0.3,
                zorder=0, label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time, sum over the cases (s, one core)")
    ax.set_ylabel("error vs converged reference (median over cases)")
    ncases = max((a["cases"] for a in agg.values()), default=0)
    ax.set_title(f"Numerical settings ({ncases} cases; numbers = safety factor)")
    ax.grid(True, which="major", alpha=0.3)

    # bottom: both contact models against the rigid-block oracles, one point per model setting
    models = {}
    for r in rows:
        if r["oracle"] not in ORACLES:
            continue
        if r["axis"] not in MODEL_AXES:
            continue
        err = abs(num(r["oracle_err"]))
        if math.isnan(err):
            continue
        wall = num(r["wall_s"]) + (0 if math.isnan(num(r["search_wall_s"])) else num(r["search_wall_s"]))
        rigid = r.get("contact", "penalty") == "rigid"
        key = ("rigid", num(r["safety"])) if rigid else ("penalty", num(r["stiffness_n_m"]))
        m = models.setdefault(key, dict(wall=0.0, errors=[]))
        m["wall"] += wall
        m["errors"].append(err)
    series = {"penalty": dict(marker="o", color="#7f7f7f", label="penalty springs (numbers: K_N = K_S)"),
              "rigid": dict(marker="s", color="#d62728", label="rigid contact (numbers: safety)")}
    for model, st in series.items():
        pts = sorted((m["wall"], max(median(m["errors"]), FLOOR), max(max(m["errors"]), FLOOR), k)
                     for (mm, k), m in models.items() if mm == model)
        if not pts:
            continue
        bx.plot([p[0] for p in pts], [p[1] for p in pts], ms=5, lw=1.2, mfc="white", mew=1.2, **st)
        for w, e, worst, k in pts:
            bx.plot([w, w], [e, worst], color=st["color"], lw=1.5, alpha=0.4)
            text = f"{k:.0e}".replace("+", "").replace("e0", "e") if model == "penalty" else f"{k:g}"
            labels[bx].append((w, e, text, dict(color=st["color"])))
    bx.set_xscale("log")
    bx.set_yscale("log")
    bx.set_xlabel("wall time, sum over the oracle cases (s; pulse: threshold search + run)")
    bx.set_ylabel("|relative error| vs rigid-block oracles (median; bar: worst)")
    bx.set_title("Contact model (a model axis, not a preset)")
    bx.grid(True, which="major", alpha=0.3)
    # each panel's legend below it: off the points (inside, a corner free of points is not guaranteed)
    for axes in (ax, bx):
        handles, names = axes.get_legend_handles_labels()
        if handles:
            axes.legend(handles, names, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2, frameon=False)
    fig.tight_layout(h_pad=1.0)
    for axes in (ax, bx):
        figure_style.place_labels(axes, labels[axes])
    fmt = os.path.splitext(path)[1].lower().lstrip(".") or "png"
    fig.savefig(path, dpi=figure_style.RASTER_DPI, format=fmt)
    return fig


def fmt(v, spec="{:.2g}"):
    return "-" if math.isnan(v) else spec.format(v)


def table(rows, md):
    """Per case: each preset's error vs the converged reference, oracle error and wall time."""
    by = {}
    order = []
    for r in rows:
        c = case_of(r)
        if c not in order:
            order.append(c)
        by[(c, r["setting"])] = r
    lines = ["| case | quantity | " + " | ".join(PRESETS) + " | converged reference |",
             "|---|---|" + "---|" * (len(PRESETS) + 1)]
    total = {p: 0.0 for p in PRESETS + ("converged",)}
    for c in order:
        cells = {}
        for p in PRESETS + ("converged",):
            r = by.get((c, f"preset {p}" if p != "converged" else "converged reference"))
            cells[p] = r
            if r is not None:
                total[p] += num(r["wall_s"])
        ref = cells["converged"]
        if ref is None:
            continue
        oracle = ref["oracle"]

        def cell(p, what):
            r = cells[p]
            if r is None:
                return "-"
            if what == "error":
                s = fmt(num(r["error"]))
                if r["outcome_match"] == "0":
                    s += " (outcome differs)"
                return s
            if what == "oracle":
                return fmt(num(r["oracle_err"]), "{:+.3f}")
            if what == "value":
                return fmt(num(r["model_value"]), "{:.4g}")
            return fmt(num(r["wall_s"]), "{:.3g}")

        lines.append(f"| {c} | error vs converged | " + " | ".join(cell(p, "error") for p in PRESETS) + " | 0 |")
        if oracle:
            lines.append(f"| | {ref['model_quantity']} (oracle {fmt(num(ref['oracle_value']), '{:.4g}')}) | " +
                         " | ".join(cell(p, "value") for p in PRESETS + ("converged",)) + " |")
        lines.append("| | wall (s) | " + " | ".join(cell(p, "wall") for p in PRESETS + ("converged",)) + " |")
    lines.append("| **all cases** | wall (s) | " + " | ".join(f"**{total[p]:.3g}**" for p in PRESETS + ("converged",)) + " |")
    with open(md, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--figure", help="the Pareto figure; its format (png, pdf, svg) from the name")
    ap.add_argument("--table")
    a = ap.parse_args()
    try:
        rows = read(a.csv)
    except (OSError, ValueError) as e:
        sys.stderr.write(f"accuracy_plot: error: {e}\n")
        return 2
    if a.figure:
        plot(rows, a.figure)
        print(f"wrote {a.figure}")
    if a.table:
        table(rows, a.table)
        print(f"wrote {a.table}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
