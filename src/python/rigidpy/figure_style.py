"""The type and sizes of every figure the commands write, set for a journal page: widths of one
column (3.5 in) or the full page (7.2 in), no text under 8 pt at that size, and the one place
the fit's provenance is said, a footnote of the figure rather than every legend entry."""

SINGLE_COLUMN_IN = 3.5
DOUBLE_COLUMN_IN = 7.2
MIN_FONT_PT = 8.0
FIGURE_FORMATS = ("png", "pdf", "svg")
RASTER_DPI = 300  # a png at print resolution; pdf and svg are vector

# What the legends call the fit, and the footnote that says once what it is.
FIT_NAME = "probit fit"
FIT_NOTE = ("Probit fit: this project's form in the variables of Purvance et al. (2008), "
            "not their coefficients.")

RC = {"font.size": 8, "axes.titlesize": 9, "axes.labelsize": 8, "xtick.labelsize": 8, "ytick.labelsize": 8,
      "legend.fontsize": 8, "legend.title_fontsize": 8, "figure.titlesize": 9, "lines.markersize": 4,
      "pdf.fonttype": 42, "svg.fonttype": "none"}


def apply(plt):
    """Journal type for every figure made afterwards (pdf fonts embedded as TrueType, svg text kept
    as text, so a journal's production can edit the labels)."""
    plt.rcParams.update(RC)


def add_fit_note(fig):
    """The fit's provenance, once, under the figure."""
    fig.text(0.01, 0.005, FIT_NOTE, ha="left", va="bottom", fontsize=MIN_FONT_PT, color="0.3")


# Where a point's label may go, in points from the point: right, left, above, below, then the
# diagonals, then the same farther out.
_OFFSETS = [(6, -4), (-6, -4), (0, 6), (0, -13), (6, 5), (-6, 5), (6, -12), (-6, -12)]
_OFFSETS += [(2 * dx, 2 * dy) for dx, dy in _OFFSETS]


def place_labels(ax, labels):
    """Annotate points without a label covering a marker or another label: each of `labels`
    [(x, y, text, annotate kwargs)] goes to the first offset of _OFFSETS where its box touches no
    marker of the axes' lines (a square of the marker's size) and no label placed before it, else
    to the first offset. Call after the axes' limits and the figure's layout are final."""
    import numpy as np
    fig = ax.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    px_per_pt = fig.dpi / 72.0
    markers = []
    for line in ax.lines:
        if line.get_marker() in (None, "None", "", " ") or not line.get_visible():
            continue
        xy = line.get_transform().transform(np.asarray(line.get_xydata(), float))
        half = 0.5 * line.get_markersize() * px_per_pt + line.get_markeredgewidth() * px_per_pt
        markers += [(x - half, y - half, x + half, y + half) for x, y in xy if np.isfinite(x) and np.isfinite(y)]
    taken = []

    def clear(box):
        return not any(box.x0 < x1 and x0 < box.x1 and box.y0 < y1 and y0 < box.y1 for x0, y0, x1, y1 in markers + taken)

    placed = []
    for x, y, text, kwargs in labels:
        annotation = None
        for dx, dy in _OFFSETS:
            ha = "left" if dx > 0 else "right" if dx < 0 else "center"
            if annotation is not None:
                annotation.remove()
            annotation = ax.annotate(text, (x, y), textcoords="offset points", xytext=(dx, dy), ha=ha, va="bottom",
                                     **kwargs)
            box = annotation.get_window_extent(renderer)
            if clear(box):
                break
        else:
            annotation.remove()
            dx, dy = _OFFSETS[0]
            annotation = ax.annotate(text, (x, y), textcoords="offset points", xytext=(dx, dy), ha="left",
                                     va="bottom", **kwargs)
            box = annotation.get_window_extent(renderer)
        taken.append((box.x0, box.y0, box.x1, box.y1))
        placed.append(annotation)
    return placed
