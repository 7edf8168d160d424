"""The figures of `rigid plot`: fragility maps with the fit's contours, per-record curves, the
variants' band and the difference of two cubes. matplotlib is imported by the first figure, not at
start: `rigid fragility` and `rigid hazard` read cubes through this package and would otherwise
pay about a second per call for it."""
import math
import os
import re
import sys
import textwrap

import numpy as np

from . import figure_style as style
from . import files as cube_files
from . import fit as fragility_fit
from .figure_style import DOUBLE_COLUMN_IN, FIT_NAME
from .fit import THRESHOLD_SOURCE, fit_sigma
from .map_fit import CONTOUR_LEVELS, contour_pga, fit_probability
from .outcomes import bins_of_records

DPI = style.RASTER_DPI
CONTOUR_STYLE = {1: dict(ls=(0, (1.2, 1.6)), lw=2.0), 50: dict(ls="-", lw=2.2),
                 99: dict(ls=(0, (5, 2.5)), lw=2.0)}

# The cubes the running command reads (filled by its CLI): no figure may be written over one of them.
INPUTS = []

plt = mcolors = mpatches = mlines = pe = mticker = None


def load_matplotlib():
    global plt, mcolors, mpatches, mlines, pe, mticker
    if plt is not None:
        return
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as pyplot
        from matplotlib import colors, lines, patheffects, patches, ticker
    except ImportError as e:  # pragma: no cover
        sys.stderr.write(f"rigid plot: error: {e}; install python3-matplotlib and run with /usr/bin/python3 "
                         f"(this is {sys.executable})\n")
        sys.exit(2)
    plt, mcolors, mpatches, mlines, pe, mticker = pyplot, colors, patches, lines, patheffects, ticker
    style.apply(plt)


def wrapped(text, width_in):
    """text broken into lines that fit width_in inches at the title's 9 pt (about 17 characters an inch)."""
    return "\n".join(textwrap.fill(part, width=max(20, int(17 * width_in))) for part in text.split("\n"))



def safe_name(name):
    return re.sub(r"[^A-Za-z0-9._-]+", "_", name) or "object"


def file_stem(obj):
    """The start of an object's file names: `rock`, or `rock_v3` for variant 3."""
    return safe_name(obj.name) + ("" if obj.variant is None else f"_v{obj.variant}")


def scale_cell_edges(scales):
    s = np.asarray(scales, float)
    if len(s) == 1:
        w = 0.05 * s[0] if s[0] > 0 else 0.05
        return np.array([s[0] - w, s[0] + w])
    mid = 0.5 * (s[1:] + s[:-1])
    return np.concatenate([[s[0] - (mid[0] - s[0])], mid, [s[-1] + (s[-1] - mid[-1])]])


def display_y_edges(edges, pgv_pga):
    """Bin edges for a log axis: open or zero outer edges clipped to the records' range."""
    e = np.array(edges, float)
    finite = pgv_pga[np.isfinite(pgv_pga) & (pgv_pga > 0)]
    lo_data = finite.min() if finite.size else None
    hi_data = finite.max() if finite.size else None
    if not e[0] > 0:
        inner = e[1] if len(e) > 2 else 0.1
        lo = inner / 2.0
        if lo_data is not None:
            lo = min(lo, 0.85 * lo_data)
        e[0] = min(lo, 0.9 * inner)
    if not np.isfinite(e[-1]):
        inner = e[-2]
        hi = inner * 1.6
        if hi_data is not None:
            hi = max(hi, 1.15 * hi_data)
        e[-1] = max(hi, 1.1 * inner)
    return e


def _fmt_edge(v):
    if v == 0:
        return "0"
    if not np.isfinite(v):
        return "\u221e"
    return f"{v:.3g}"


class MapRows:
    """The rows of a map: one per PGV/PGA bin from the lowest to the highest bin that holds records,
    equal heights, one above the other (row k spans y = k..k+1), each labelled with its bin. A bin
    without records between them keeps its row (hatched, 0 records): the y axis stays continuous, so
    a contour crossing it runs on without a jump. Within a row PGV/PGA runs on a log scale between
    the bin's edges (open outer edges clipped to the records' range)."""

    def __init__(self, edges, pgv_pga):
        edges = np.asarray(edges, float)
        pgv_pga = np.asarray(pgv_pga, float)
        B = len(edges) - 1
        bins = bins_of_records(edges, pgv_pga)
        self.records_in_bin = np.bincount(bins[bins >= 0], minlength=B)
        with_records = np.flatnonzero(self.records_in_bin)
        if with_records.size == 0:  # no record in any bin: show every bin (all hatched)
            self.bins = np.arange(B)
        else:
            self.bins = np.arange(with_records[0], with_records[-1] + 1)
        self.edges = edges
        self.log_edges = np.log(display_y_edges(edges, pgv_pga))

    def __len__(self):
        return len(self.bins)

    def y(self, pgv_pga):
        """Row coordinates of PGV/PGA values; NaN for values in no row (matplotlib breaks lines there)."""
        v = np.atleast_1d(np.asarray(pgv_pga, float))
        out = np.full(v.shape, np.nan)
        with np.errstate(divide="ignore", invalid="ignore"):
            lv = np.log(v)
        for k, b in enumerate(self.bins):
            lo, hi = self.log_edges[b], self.log_edges[b + 1]
            inside = (lv >= lo) & (lv <= hi)
            out[inside] = k + (lv[inside] - lo) / (hi - lo)
        return out

    def label(self, k):
        b = self.bins[k]
        return f"{_fmt_edge(self.edges[b])}\u2013{_fmt_edge(self.edges[b + 1])}"


def _setup_map_axes(ax, cube, rows, scale_edges):
    ax.set_ylim(0, len(rows))
    ax.set_xlim(scale_edges[0], scale_edges[-1])
    ax.yaxis.set_major_locator(mticker.FixedLocator([k + 0.5 for k in range(len(rows))]))
    ax.yaxis.set_major_formatter(mticker.FixedFormatter([rows.label(k) for k in range(len(rows))]))
    ax.yaxis.set_minor_locator(mticker.NullLocator())
    ax.tick_params(axis="y", length=0)
    S = len(cube.scales)
    step = 1 if S <= 12 else int(math.ceil(S / 12))
    ax.set_xticks(cube.scales[::step])
    ax.set_xticklabels([f"{v:g}" for v in cube.scales[::step]])
    ax.set_xlabel("PGA = target GMRotI50 PGA (g)")
    ax.set_ylabel("PGV/PGA bin (s)")


def _hatch_background(ax, scale_edges, rows):
    ax.add_patch(mpatches.Rectangle((scale_edges[0], 0), scale_edges[-1] - scale_edges[0], len(rows),
                                    facecolor="white", edgecolor="0.7", hatch="///", lw=0, zorder=0))


def draw_surface(ax, cube, values, count, cmap, norm, counts="none", rows=None):
    """Cells coloured by value over (scale, PGV/PGA bin), one row per bin with records (`rows`,
    default: the cube's); cells without a value show the hatched background.
    counts: "none"; "deviations": print a cell's record count only where it is below its bin's
    number of records (not-run or failed cells); "all": print every cell's count.
    Returns (mesh, rows, scale_edges, whether a hatched cell shows, the number of counts printed)."""
    rows = MapRows(cube.edges, cube.pgv_pga) if rows is None else rows
    scale_edges = scale_cell_edges(cube.scales)
    _hatch_background(ax, scale_edges, rows)
    data = np.ma.masked_invalid(np.asarray(values, float).T[rows.bins])  # [shown bins, S]
    mesh = ax.pcolormesh(scale_edges, np.arange(len(rows) + 1), data, cmap=cmap, norm=norm, edgecolors="0.35",
                         linewidth=0.4, zorder=1)
    _setup_map_axes(ax, cube, rows, scale_edges)
    printed = 0
    if counts != "none" and count is not None:
        bins = cube.bin_of_records()
        in_bin = np.bincount(bins[bins >= 0], minlength=len(cube.edges) - 1)  # this cube's records
        for k, b in enumerate(rows.bins):
            for s in range(data.shape[1]):
                if np.ma.is_masked(data[k, s]):
                    continue
                if counts == "deviations" and count[s, b] >= in_bin[b]:
                    continue
                rgba = cmap(norm(data[k, s]))
                lum = 0.299 * rgba[0] + 0.587 * rgba[1] + 0.114 * rgba[2]
                ax.text(0.5 * (scale_edges[s] + scale_edges[s + 1]), k + 0.5, str(int(count[s, b])),
                        ha="center", va="center", color="black" if lum > 0.5 else "white", zorder=3,
                        gid="cell count")
                printed += 1
    return mesh, rows, scale_edges, bool(np.ma.getmaskarray(data).any()), printed


def add_bin_totals(ax, rows):
    """The number of records of each row's bin, as labels on the right-hand axis."""
    sec = ax.secondary_yaxis("right")
    sec.yaxis.set_major_locator(mticker.FixedLocator([k + 0.5 for k in range(len(rows))]))
    sec.yaxis.set_major_formatter(mticker.FixedFormatter([f"{rows.records_in_bin[b]}" for b in rows.bins]))
    sec.yaxis.set_minor_locator(mticker.NullLocator())
    sec.tick_params(axis="y", length=0)
    sec.set_ylabel("records in bin")
    return sec


def draw_contours(ax, rows, fit, norm_, pgv_range, color="black", label_prefix="", levels=CONTOUR_LEVELS):
    """The fit's k % contours as PGA(PGV/PGA) curves over the records' PGV/PGA range, in the rows'
    coordinates (broken where PGV/PGA lies in a bin without records)."""
    handles = []
    v = np.geomspace(pgv_range[0], pgv_range[1], 200) if pgv_range[1] > pgv_range[0] else np.array(pgv_range)
    y = rows.y(v)
    for lev in levels:
        pga = contour_pga(fit, norm_, v, lev)
        style = CONTOUR_STYLE[lev]
        x0, x1 = ax.get_xlim()
        where = ""
        if not np.any((pga >= x0) & (pga <= x1)):
            where = " (left of the plot)" if np.all(pga < x0) else (" (right of the plot)" if np.all(pga > x1)
                                                                   else " (outside the plot)")
        (line,) = ax.plot(pga, y, color=color, ls=style["ls"], lw=style["lw"], zorder=4,
                          path_effects=[pe.Stroke(linewidth=style["lw"] + 2.2, foreground="white"), pe.Normal()],
                          label=f"{label_prefix}{lev} % contour{where}")
        ax.set_xlim(x0, x1)
        if len(v) == 1:
            line.set_marker("o")
        handles.append(line)
    return handles


HATCH_LABEL = "no simulated cell (no record in the bin, or not run or failed)"


def plot_map(cube, obj, fit, norm_, info, path, counts):
    load_matplotlib()
    fig, ax = plt.subplots(figsize=(DOUBLE_COLUMN_IN, 5.0), dpi=DPI)
    cmap = plt.get_cmap("viridis")
    cnorm = mcolors.Normalize(0.0, 1.0)
    mesh, rows, _, hatched, printed = draw_surface(ax, cube, obj.fragility, obj.count, cmap, cnorm, counts)
    add_bin_totals(ax, rows)
    cb = fig.colorbar(mesh, ax=ax, ticks=[0, 0.25, 0.5, 0.75, 1.0], pad=0.1)
    cb.set_label("P(overturn): mean over the records of the cell")
    handles = [mpatches.Patch(facecolor="white", edgecolor="0.5", hatch="///", label=HATCH_LABEL)] if hatched else []
    if fit is not None:
        handles += draw_contours(ax, rows, fit, norm_, info["pgv_pga_range_s"])
        sig = fit_sigma(fit, np.array(info["x_range"]))
        sig_txt = f"{sig.min():.2g}" if abs(sig[0] - sig[1]) < 1e-9 else f"{sig.min():.2g}\u2013{sig.max():.2g}"
        fit_text = (f"{FIT_NAME} on {info['n_cells']} cells of {info['n_records']} records, "
                    f"\u03c3 = {sig_txt} (ln PGA)")
    else:
        fit_text = f"no fit: {info.get('reason', '')}"
    alpha_txt = f", alpha = {norm_.alpha:.3g} rad" if norm_.alpha else ""
    # the title promises cell numbers only when some are drawn
    note = ("each cell: mean over the bin's records" if printed == 0 else
            "numbers: records averaged in the cell" if counts == "all" else
            "numbers: records averaged where fewer than the bin's (not run or failed)")
    ax.set_title(wrapped(f"{obj.label}{alpha_txt}: binned overturning probability\n"
                         f"cube {os.path.basename(cube.path)}; {note}", DOUBLE_COLUMN_IN - 1.5))
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False,
              title=fit_text)
    fig.tight_layout(rect=(0, 0.04 if fit is not None else 0, 1, 1))
    if fit is not None:
        style.add_fit_note(fig)
    cube_files.save_figure(fig, path, "--out", INPUTS, dpi=DPI)
    plt.close(fig)


RECORDS_LISTED = 6  # panels with at most this many records name them


def record_label(cube, r):
    """A record's name over its PGV/PGA: two short lines fit beside a panel on a page's width."""
    return f"{cube.records[r]}\n{cube.pgv_pga[r]:.3g} s"


def plot_records(cube, obj, fit, norm_, path):
    """One panel per PGV/PGA bin that holds records (bins without are left out, not drawn empty)."""
    load_matplotlib()
    bins = cube.bin_of_records()
    shown = [b for b in range(len(cube.edges) - 1) if np.any(bins == b)] or [0]
    # a panel of up to RECORDS_LISTED records names them in a legend to its right, off the curves:
    # two such panels a row on a page's width, else three
    listed = any(0 < np.sum(bins == b) <= RECORDS_LISTED for b in shown)
    ncol = min(2 if listed else 3, len(shown))
    nrow = int(math.ceil(len(shown) / ncol))
    fig = plt.figure(figsize=(DOUBLE_COLUMN_IN, 2.1 * nrow + 1.5), dpi=DPI)
    legend_share = 0.75 if listed else 0.0  # of an axes' width, for the names
    grid = fig.add_gridspec(nrow, 2 * ncol, width_ratios=[1, legend_share] * ncol, left=0.09, right=0.86,
                            top=1 - 0.75 / (2.1 * nrow + 1.5), bottom=1.05 / (2.1 * nrow + 1.5), wspace=0.08,
                            hspace=0.55)
    axes = np.empty((nrow, ncol), dtype=object)
    for i in range(nrow * ncol):
        share = axes[0][0] if i else None
        axes[i // ncol][i % ncol] = fig.add_subplot(grid[i // ncol, 2 * (i % ncol)], sharex=share, sharey=share)
    finite = cube.pgv_pga[np.isfinite(cube.pgv_pga) & (cube.pgv_pga > 0)]
    lo, hi = (finite.min(), finite.max()) if finite.size else (0.05, 0.5)
    if hi <= lo:
        lo, hi = lo / 1.2, hi * 1.2
    cnorm = mcolors.LogNorm(lo, hi)
    cmap = mcolors.LinearSegmentedColormap.from_list(
        "plasma_trunc", plt.get_cmap("plasma")(np.linspace(0.0, 0.82, 256)))  # no pale yellow on white
    marker = "o" if len(cube.scales) <= 25 else None
    sgrid = np.linspace(max(cube.scales.min() * 0.5, 1e-3), cube.scales.max(), 200)
    for i in range(nrow * ncol):
        ax = axes[i // ncol][i % ncol]
        if i >= len(shown):
            ax.set_visible(False)
            continue
        b = shown[i]
        recs = [r for r in range(len(cube.records)) if bins[r] == b]
        ax.set_title(f"PGV/PGA {_fmt_edge(cube.edges[b])}\u2013{_fmt_edge(cube.edges[b + 1])} s "
                     f"({len(recs)} record{'s' if len(recs) != 1 else ''})")
        ax.grid(True, color="0.88", lw=0.6)
        ax.set_ylim(-0.05, 1.05)
        ax.set_yticks([0, 0.5, 1])
        if i // ncol != nrow - 1 and i + ncol < len(shown):
            ax.tick_params(labelbottom=False)
        if i % ncol:
            ax.tick_params(labelleft=False)
        if not recs:  # only when no bin holds a record: the one panel says so
            ax.text(0.5, 0.5, "no records", transform=ax.transAxes, ha="center", va="center", color="0.5")
            continue
        for r in recs:  # above the bin mean, so a bin of one record still shows its colour
            ax.plot(cube.scales, obj.probability[r], color=cmap(cnorm(cube.pgv_pga[r])), lw=1.1,
                    marker=marker, ms=2.5, alpha=0.85, zorder=7, label=record_label(cube, r))
        if len(recs) <= RECORDS_LISTED:
            ax.legend(loc="upper left", bbox_to_anchor=(1.03, 1.0), borderaxespad=0.0, frameon=False,
                      handlelength=1.0, handletextpad=0.4, labelspacing=0.3)
        ax.plot(cube.scales, obj.fragility[:, b], color="black", lw=2.0, ls="--", zorder=5)
        if fit is not None:
            v = float(np.median(cube.pgv_pga[recs]))
            ax.plot(sgrid, fit_probability(fit, norm_, sgrid, v), color="tab:green", lw=1.6, zorder=6)
        if i + ncol >= len(shown):
            ax.set_xlabel("PGA (g)")
        if i % ncol == 0:
            ax.set_ylabel("P(overturn)")
    handles = [mlines.Line2D([], [], color="0.4", lw=1.1, marker=marker, ms=2.5,
                             label="one record (colour: its PGV/PGA)"),
               mlines.Line2D([], [], color="black", lw=2.0, ls="--", label="bin mean (the map's cells)")]
    if fit is not None:
        handles.append(mlines.Line2D([], [], color="tab:green", lw=1.6, label=f"{FIT_NAME} at the bin's median PGV/PGA"))
    alpha_txt = f" (alpha = {norm_.alpha:.3g} rad)" if norm_.alpha else ""
    fig.suptitle(wrapped(f"{obj.label}{alpha_txt}: P(overturn) per record vs PGA, one panel per PGV/PGA bin; "
                         f"P = fraction of rotations overturned (inferred counted as overturned); "
                         f"cube {os.path.basename(cube.path)}", DOUBLE_COLUMN_IN - 0.4))
    fig.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, 0.2 / (2.1 * nrow + 1.5)), ncol=2,
               frameon=False)
    if fit is not None:
        style.add_fit_note(fig)
    cax = fig.add_axes([0.9, 0.25, 0.018, 0.6])
    sm = plt.cm.ScalarMappable(norm=cnorm, cmap=cmap)
    cb = fig.colorbar(sm, cax=cax)
    cb.set_label("record PGV/PGA (s)")
    ticks = [lo] + [e for e in cube.edges if lo * 1.08 < e < hi / 1.08] + [hi]
    cb.set_ticks(ticks)
    cb.set_ticklabels([f"{t:.3g}" for t in ticks])
    cb.ax.yaxis.set_minor_locator(mticker.NullLocator())
    cube_files.save_figure(fig, path, "--out", INPUTS, dpi=DPI)
    plt.close(fig)


def plot_variant_band(cube, name, curves, pooled, pgv_pga_s, path):
    load_matplotlib()
    fig, ax = plt.subplots(figsize=(DOUBLE_COLUMN_IN, 4.2), dpi=DPI)
    a = pooled["pga_g"]
    for k, (theta, beta, how) in curves:
        ax.plot(a, fragility_fit.lognormal_probability(a, theta, beta), color="0.55", lw=0.7,
                ls=":" if how == THRESHOLD_SOURCE else "-", zorder=2)
    lo, hi = pooled["percentiles"][0], pooled["percentiles"][-1]
    ax.fill_between(a, pooled["band_lower"], pooled["band_upper"], color="tab:blue", alpha=0.25, lw=0, zorder=1,
                    label=f"{lo}-{hi} % of the variants' P(PGA) (epistemic band)")
    ax.plot(a, pooled["mixture_probability"], color="black", lw=2.2, zorder=4,
            label=f"pooled: mean over variants (median {pooled['median_g']:.3g} g)")
    ax.plot([], [], color="0.55", lw=0.7, label="one variant (dotted: empirical threshold, a step)")
    ax.set_xscale("log")
    ax.set_xlim(a[0], a[-1])
    ax.xaxis.set_major_formatter(mticker.FormatStrFormatter("%g"))
    if a[-1] / a[0] < 100:  # a decade or two: label some minor ticks too, else one label shows
        ax.xaxis.set_minor_formatter(mticker.FuncFormatter(
            lambda v, _: f"{v:g}" if round(v / 10 ** math.floor(math.log10(v) + 1e-9)) in (2, 5) else ""))
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("PGA = target GMRotI50 PGA (g)")
    ax.set_ylabel("P(overturn)")
    ax.grid(True, which="both", color="0.9", lw=0.6)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=2, frameon=False)  # off the curves
    ax.set_title(wrapped(f"{name}: fragility of {len(curves)} variants at PGV/PGA {pgv_pga_s:.3g} s; "
                         f"cube {os.path.basename(cube.path)}", DOUBLE_COLUMN_IN - 0.5))
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    style.add_fit_note(fig)
    cube_files.save_figure(fig, path, "--out", INPUTS, dpi=DPI)
    plt.close(fig)


def plot_diff(view_a, view_b, name, fa, ca_, fb, cb_, d, stats, la, lb, fits, path, counts):
    """The two cubes' maps side by side above their difference, on a page's width."""
    load_matplotlib()
    fig = plt.figure(figsize=(DOUBLE_COLUMN_IN, 8.4), dpi=DPI)
    outer = fig.add_gridspec(2, 1, height_ratios=[1, 1], hspace=0.42, left=0.12, right=0.9, bottom=0.17, top=0.9)
    top = outer[0].subgridspec(1, 3, width_ratios=[1, 1, 0.05], wspace=0.08)
    bottom = outer[1].subgridspec(1, 3, width_ratios=[0.5, 1, 0.05], wspace=0.08)
    ax_a, ax_b, cax_p = fig.add_subplot(top[0]), fig.add_subplot(top[1]), fig.add_subplot(top[2])
    ax_d, cax_d = fig.add_subplot(bottom[1]), fig.add_subplot(bottom[2])
    cmap = plt.get_cmap("viridis")
    pn = mcolors.Normalize(0.0, 1.0)
    # the same rows in the three panels: the bins with records in either cube
    rows = MapRows(view_a.edges, np.concatenate([view_a.pgv_pga, view_b.pgv_pga]))
    for ax, v, frag, cnt, lab, fit in ((ax_a, view_a, fa, ca_, la, fits[0]), (ax_b, view_b, fb, cb_, lb, fits[1])):
        mesh = draw_surface(ax, v, frag, cnt, cmap, pn, counts, rows)[0]
        ax.set_title(wrapped(f"{lab}: P(overturn) ({os.path.basename(v.path)})", 2.6))
        if fit is not None:
            draw_contours(ax, rows, fit[0], fit[1], fit[2]["pgv_pga_range_s"])
        thin_ticks(ax)
    fig.colorbar(mesh, cax=cax_p, ticks=[0, 0.25, 0.5, 0.75, 1], label="P(overturn)")
    dmap = plt.get_cmap("RdBu_r")
    dn = mcolors.Normalize(-1.0, 1.0)
    mesh_d = draw_surface(ax_d, view_a, d, None, dmap, dn, "none", rows)[0]
    thin_ticks(ax_d)
    handles = []
    for fit, color, lab in ((fits[0], "black", la), (fits[1], "tab:orange", lb)):
        if fit is not None:
            handles += draw_contours(ax_d, rows, fit[0], fit[1], fit[2]["pgv_pga_range_s"], color=color,
                                     label_prefix=f"{lab} ", levels=(50,))
    ax_d.set_title(f"difference {la} \u2212 {lb} (red: {la} more fragile)\n"
                   f"mean \u00b1 sd = {stats[1]:+.3f} \u00b1 {stats[2]:.3f} over {stats[0]} cells")
    ax_b.set_ylabel("")
    ax_b.tick_params(axis="y", labelleft=False)
    fig.colorbar(mesh_d, cax=cax_d, ticks=[-1, -0.5, 0, 0.5, 1], label=f"P({la}) \u2212 P({lb})")
    leg = [mpatches.Patch(facecolor="white", edgecolor="0.5", hatch="///", label="no cell in both cubes")]
    if fits[0] is not None or fits[1] is not None:
        leg += [mlines.Line2D([], [], color="black", lw=2, ls=CONTOUR_STYLE[k]["ls"], label=f"{k} % contour")
                for k in CONTOUR_LEVELS]
        leg += [mlines.Line2D([], [], color=h.get_color(), lw=2, label=f"{h.get_label()} (bottom)") for h in handles]
    fig.legend(handles=leg, loc="lower center", bbox_to_anchor=(0.5, 0.035), ncol=3, frameon=False,
               title=FIT_NAME if len(leg) > 1 else None)
    if len(leg) > 1:
        style.add_fit_note(fig)
    fig.suptitle(f"{name}: {la} vs {lb}, binned fragility (each cell: mean over the bin's records)")
    cube_files.save_figure(fig, path, "--out", INPUTS, dpi=DPI)
    plt.close(fig)


def thin_ticks(ax, most=6):
    """At most `most` PGA tick labels on a narrow map, so they do not run into each other."""
    ticks = ax.get_xticks()
    if len(ticks) > most:
        step = int(math.ceil(len(ticks) / most))
        ax.set_xticks(ticks[::step])
        ax.set_xticklabels([f"{v:g}" for v in ticks[::step]])
