"""The time history of one run as a figure and as an animation: the Dataset of rigidpy.run (or of
the table `rigid run --history` writes) drawn for `rigid run --plot FILE` and `--animate FILE.gif`
and for notebooks (rigidpy.plot_history, rigidpy.animate_history).

    rigid_run_plot.py HISTORY.csv [--plot FILE.pdf|svg|png] [--animate FILE.gif] [--title TEXT]
                      [--overturned-at SECONDS] [--quiet]

Exit status: 0 done, 2 bad input, 1 internal error."""
import math
import os
import sys

import numpy as np

from .command_line import OneLineParser, exit_status
from .errors import InputError
from .files import write_output

G = 9.80665  # standard gravity (m s-2): the table's acceleration is drawn in g
FIGURE_FORMATS = ("pdf", "svg", "png")
MAX_ANIMATION_FRAMES = 120  # a gif of any run stays about a megabyte and takes seconds to draw
ANIMATION_FPS = 20
ANIMATION_DPI = 72


def _pyplot():
    import matplotlib.pyplot as plt  # the caller's backend (a notebook's inline one); main() picks Agg
    return plt


def _overturn_time(ds):
    t = ds.attrs.get("failure_time_s", math.nan)
    return float(t) if t is not None and math.isfinite(float(t)) else None


def plot_history(ds, path=None, title=None):
    """Tilt, slip and table acceleration against time, one line per free block (and per axis of
    the table), the overturn marked; saved to `path` (format from its extension) when given.
    Returns the matplotlib Figure."""
    plt = _pyplot()
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(8, 7.5), constrained_layout=True)
    t = ds["time"].values
    for b in ds["block"].values:
        axes[0].plot(t, ds["tilt"].sel(block=b).values, label=str(b))
        axes[1].plot(t, 1000 * ds["slip"].sel(block=b).values, label=str(b))
    for a, colour in zip(ds["axis"].values, ("tab:blue", "tab:orange", "tab:green")):
        acc = ds["table_acceleration"].sel(axis=a).values / G
        if np.any(acc != 0):
            axes[2].plot(t, acc, lw=0.7, color=colour, label=f"{a}")
    axes[0].set_ylabel("tilt (deg)")
    axes[1].set_ylabel("slip (mm)")
    axes[2].set_ylabel("table acceleration (g)")
    axes[2].set_xlabel("time (s)")
    overturn = _overturn_time(ds)
    for ax in axes:
        if overturn is not None:
            ax.axvline(overturn, color="k", ls="--", lw=0.8)
        ax.grid(alpha=0.3)
    if overturn is not None:
        axes[0].annotate(f"overturned at {overturn:.2f} s", (overturn, 1), xycoords=("data", "axes fraction"),
                         xytext=(-4, -12), textcoords="offset points", fontsize=8, ha="right")
    for ax in axes:
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, frameon=False)
    fig.suptitle(title or ds.attrs.get("scene", "") or "time history")
    if path is not None:
        fig.savefig(path)
    return fig


def animate_history(ds, path, title=None, fps=ANIMATION_FPS):
    """The run as an animated gif (matplotlib's PillowWriter, Debian python3-pil): left, the
    blocks seen from the side (x-z), each drawn as its initially vertical axis through its centre
    of mass, from its base to as far above (`base_height`), on the table moving with the ground;
    right, the tilt as it grows. At most MAX_ANIMATION_FRAMES frames (the history subsampled
    evenly)."""
    plt = _pyplot()
    from matplotlib.animation import FuncAnimation, PillowWriter
    n = ds.sizes["time"]
    frames = np.unique(np.linspace(0, n - 1, min(n, MAX_ANIMATION_FRAMES)).round().astype(int))
    pos = ds["position"].values  # [time, block, axis]
    quat = ds["orientation"].values  # [time, block, (w, x, y, z)]
    table = ds["table_displacement"].values
    half = np.maximum(ds["base_height"].values, 1e-3)  # each block's centre above its base
    base_z = float((pos[0, :, 2] - half).min())  # the table top, under the lowest block
    fig, (side, tilt) = plt.subplots(1, 2, figsize=(9, 4), constrained_layout=True)
    x_lo = min(pos[:, :, 0].min(), table[:, 0].min() + pos[0, :, 0].min()) - half.max()
    x_hi = max(pos[:, :, 0].max(), table[:, 0].max() + pos[0, :, 0].max()) + half.max()
    z_hi = max(pos[:, :, 2].max() + half.max(), base_z + 2 * half.max())
    side.set_xlim(x_lo, x_hi)
    side.set_ylim(min(base_z, pos[:, :, 2].min() - half.max()) - 0.1 * half.max(), z_hi)  # a fall off the pedestal
    side.set_aspect("equal")
    side.set_xlabel("x (m)")
    side.set_ylabel("z (m)")
    table_line, = side.plot([], [], color="0.3", lw=6, solid_capstyle="butt")
    sticks = [side.plot([], [], lw=3, marker="o", markevery=[1])[0] for _ in range(pos.shape[1])]
    clock = side.text(0.02, 0.95, "", transform=side.transAxes, fontsize=9)
    t = ds["time"].values
    for b in ds["block"].values:
        tilt.plot(t, ds["tilt"].sel(block=b).values, lw=0.8, label=str(b))
    cursor = tilt.axvline(t[0], color="k", lw=0.8)
    tilt.set_xlabel("time (s)")
    tilt.set_ylabel("tilt (deg)")
    tilt.grid(alpha=0.3)
    fig.suptitle(title or ds.attrs.get("scene", "") or "run")

    def matrix(q):
        w, x, y, z = q
        return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                         [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                         [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])

    # the world vertical carried with each block from its first pose (body frames are principal axes)
    up_in_body = [matrix(quat[0, b]).T @ np.array([0.0, 0.0, 1.0]) for b in range(pos.shape[1])]

    def up_axis(i, b):
        return matrix(quat[i, b]) @ up_in_body[b]

    def draw(i):
        dx = table[i, 0]
        table_line.set_data([pos[0, :, 0].min() - half.max() + dx, pos[0, :, 0].max() + half.max() + dx],
                            [base_z, base_z])
        for b, stick in enumerate(sticks):
            u = up_axis(i, b)
            c = pos[i, b]
            ends = np.array([c - half[b] * u, c, c + half[b] * u])
            stick.set_data(ends[:, 0], ends[:, 2])
        clock.set_text(f"t = {t[i]:.2f} s")
        cursor.set_xdata([t[i], t[i]])
        return [table_line, clock, cursor, *sticks]

    animation = FuncAnimation(fig, draw, frames=frames, blit=False)
    animation.save(path, writer=PillowWriter(fps=fps), dpi=ANIMATION_DPI)
    plt.close(fig)


def main(argv=None):
    import matplotlib
    matplotlib.use("Agg")
    p = OneLineParser(prog="rigid run", description="Draw a run's time history (rigid run --plot/--animate).")
    p.add_argument("history", help="the table rigid run --history writes (CSV)")
    p.add_argument("--plot", help="figure: .pdf, .svg or .png")
    p.add_argument("--animate", help="animation: .gif")
    p.add_argument("--title", help="title of the figure")
    p.add_argument("--overturned-at", type=float, help="the overturn time to mark (s)")
    p.add_argument("--quiet", action="store_true", help="no `wrote FILE` lines (rigid run --json keeps stdout JSON)")
    args = p.parse_args(sys.argv[1:] if argv is None else argv)
    return exit_status("rigid run", lambda: draw_outputs(args), args)


def draw_outputs(args):
    from .simulation import history_from_csv
    if args.plot and args.plot.rsplit(".", 1)[-1].lower() not in FIGURE_FORMATS:
        raise InputError(f"--plot {args.plot}: the format comes from the extension: .pdf, .svg or .png")
    if args.animate and not args.animate.lower().endswith(".gif"):
        raise InputError(f"--animate {args.animate}: only .gif")
    attrs = {} if args.overturned_at is None else {"failure_time_s": args.overturned_at}
    ds = history_from_csv(args.history, attrs)
    if ds.sizes["time"] == 0 or ds.sizes["block"] == 0:
        raise InputError(f"{args.history}: no frame or no free block to draw")
    if args.plot:
        fig = plot_history(ds, title=args.title)
        fmt = args.plot.rsplit(".", 1)[-1].lower()
        write_output(args.plot, "--plot", [args.history], lambda tmp: fig.savefig(tmp, format=fmt))
        if not args.quiet:
            print(f"wrote {args.plot}")
    if args.animate:
        try:
            import PIL  # noqa: F401  (PillowWriter's)
        except ImportError:
            raise InputError("--animate: needs python3-pil (Debian) for matplotlib's PillowWriter")
        def save_gif(tmp):  # Pillow takes the format from the extension, the temporary has none
            animate_history(ds, tmp + ".gif", title=args.title)
            os.replace(tmp + ".gif", tmp)
        write_output(args.animate, "--animate", [args.history], save_gif)
        if not args.quiet:
            print(f"wrote {args.animate}")
    return 0
