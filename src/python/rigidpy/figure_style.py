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
