"""The figure of `rigid hazard reweight`: the logic tree's mean hazard curve with its 5-95 % and
16-84 % fractile bands before and after the rocks' evidence, and each branch's survival with its
prior and posterior weight."""
import os

import numpy as np

from . import figure_style as style
from . import files as cube_files


def draw(path, r, inputs):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    style.apply(plt)

    c = r["curves"]
    a = np.array(c["pga_g"])
    # one panel above the other on a page's width
    fig, (left, right) = plt.subplots(2, 1, figsize=(style.DOUBLE_COLUMN_IN, 8.6))
    for key, colour, label in (("prior", "tab:blue", "prior"), ("posterior", "tab:red", "posterior")):
        s = {k: np.array(v) for k, v in c[key].items()}
        positive = s["mean"] > 0
        left.fill_between(a, masked(s["0.05"]), masked(s["0.95"]), color=colour, alpha=0.12, lw=0,
                          label=f"{label} 5-95 %")
        left.fill_between(a, masked(s["0.16"]), masked(s["0.84"]), color=colour, alpha=0.25, lw=0,
                          label=f"{label} 16-84 %")
        left.loglog(a[positive], s["mean"][positive], color=colour, lw=2, label=f"{label} mean")
        left.loglog(a[positive], s["0.5"][positive], color=colour, lw=1, ls="--", label=f"{label} median")
    for p in r["pga_at_annual_rate"]:
        left.axhline(p["annual_rate"], color="gray", lw=0.7, ls=":")
        change = p["change_percent"]
        if np.isfinite(change):
            left.annotate(f"{p['annual_rate']:g}/yr: {p['prior_mean_pga_g']:.2f} -> {p['posterior_mean_pga_g']:.2f} g "
                          f"({change:+.0f} %)", (a[0], p["annual_rate"]), xytext=(4, 3), textcoords="offset points",
                          color="0.3")
    left.set_xlabel("PGA (g)")
    left.set_ylabel("annual rate of exceedance")
    left.set_title("hazard before and after the rocks' survival")
    left.grid(True, which="both", alpha=0.3)
    left.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=4, frameon=False)  # off the curves

    branches = r["branches"]
    x = np.arange(len(branches))
    right.bar(x, [b["survival"] for b in branches], color="0.6", label="survival of the rock(s)")
    right.set_ylim(0, 1.05)
    right.set_ylabel("P(survival) under the branch")
    right.set_xlabel("branch (rlz_id)")
    step = max(1, len(branches) // 20)
    right.set_xticks(x[::step])
    right.set_xticklabels([str(b["rlz_id"]) for b in branches][::step])
    if r["prune"] is not None:
        right.axhline(r["prune"], color="black", lw=0.8, ls="--", label=f"prune below {r['prune']:g}")
    weights = right.twinx()
    weights.plot(x, [b["prior_weight"] for b in branches], "o", color="tab:blue", ms=4, label="prior weight")
    weights.plot(x, [b["posterior_weight"] for b in branches], "s", color="tab:red", ms=4, mfc="none",
                 label="posterior weight")
    weights.set_ylim(0, 1.05 * max(max(b["prior_weight"], b["posterior_weight"]) for b in branches))
    weights.set_ylabel("branch weight")
    h1, l1 = right.get_legend_handles_labels()
    h2, l2 = weights.get_legend_handles_labels()
    right.legend(h1 + h2, l1 + l2, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2, frameon=False)
    rocks = "; ".join(f"{rock['rock']}, {rock['exposure_age']}" for rock in r["rocks"])
    right.set_title(f"each branch: {rocks}")
    fig.tight_layout(h_pad=1.5)
    fmt = os.path.splitext(path)[1].lower().lstrip(".")
    cube_files.write_output(path, "--plot", inputs, lambda tmp: fig.savefig(tmp, dpi=style.RASTER_DPI, format=fmt))
    plt.close(fig)
    return fig


def masked(v):
    """Rates of 0 (a level never exceeded) left off a log axis."""
    return np.where(v > 0, v, np.nan)
