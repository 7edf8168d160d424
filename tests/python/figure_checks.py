"""Measurements of a rendered matplotlib figure (Agg), for the figure tests: what a journal's
reader would see at the figure's printed size, taken from the drawn artists, not from the code
that drew them.

problems(fig) lists, in words:
- a visible text (titles, labels, tick labels, legend entries, annotations) under 8 pt;
- a figure wider than a journal's page (7.2 in);
- a visible text, or a line's drawn vertices, inside a legend's box that are not the legend's own;
- two visible texts whose boxes overlap (tick labels of one axis with each other included);
- a label inside an axes (an annotation) on a marker of one of its lines;
- a visible axes with nothing drawn in it (no line, collection, patch or image with data).
"""
import numpy as np

MIN_PT = 8.0
PAGE_WIDTH_IN = 7.2
# boxes may touch: overlaps smaller than this (pixels at the figure's dpi) are rounding
SLACK_PX = 1.0


def render(fig):
    fig.canvas.draw()
    return fig.canvas.get_renderer()


def _visible(artist):
    a = artist
    while a is not None:
        if not a.get_visible():
            return False
        a = getattr(a, "axes", None) if a is not getattr(a, "axes", None) else None
    return True


def _undrawn_tick_labels(fig):
    """Tick labels matplotlib keeps but does not draw: ticks outside the view, labels switched off."""
    undrawn = set()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            ticks = axis.get_major_ticks() + axis.get_minor_ticks()
            # the ticks matplotlib draws in view; none of an axis switched off (a twin's shared x)
            drawn = set(id(t) for t in axis._update_ticks()) if axis.get_visible() else set()
            for t in ticks:
                for label in (t.label1, t.label2):
                    if id(t) not in drawn or not label.get_visible():
                        undrawn.add(id(label))
    return undrawn


def texts(fig):
    """Every text drawn: visible, not empty, in a visible axes (or the figure), tick labels only
    of ticks in view."""
    undrawn = _undrawn_tick_labels(fig)
    out = []
    for t in fig.findobj(lambda a: hasattr(a, "get_text") and hasattr(a, "get_fontsize")):
        if (t.get_text().strip() and t.get_visible() and (t.axes is None or t.axes.get_visible())
                and id(t) not in undrawn):
            out.append(t)
    return out


def _bbox(artist, renderer):
    return artist.get_window_extent(renderer)


def _overlap(a, b):
    w = min(a.x1, b.x1) - max(a.x0, b.x0)
    h = min(a.y1, b.y1) - max(a.y0, b.y0)
    return w > SLACK_PX and h > SLACK_PX


def legends(fig):
    out = list(fig.legends)
    for ax in fig.axes:
        if ax.get_visible() and ax.get_legend() is not None:
            out.append(ax.get_legend())
    return [lg for lg in out if lg.get_visible()]


def empty_axes(fig):
    """Visible axes (not colorbars or secondary axes) with no data drawn."""
    out = []
    for ax in fig.axes:
        if not ax.get_visible() or ax.get_label() == "<colorbar>" or type(ax).__name__ == "SecondaryAxis":
            continue
        drawn = [ln for ln in ax.lines if len(np.atleast_1d(ln.get_xdata())) > 0 and ln.get_visible()]
        drawn += [c for c in ax.collections if c.get_visible()]
        drawn += [p for p in ax.patches if p.get_visible()]
        drawn += [i for i in ax.images if i.get_visible()]
        if not drawn:
            out.append(ax.get_title() or ax.get_label() or "an axes")
    return out


def problems(fig):
    renderer = render(fig)
    found = []
    width_in = fig.get_size_inches()[0]
    if width_in > PAGE_WIDTH_IN + 1e-9:
        found.append(f"figure {width_in:.2f} in wide, more than a page's {PAGE_WIDTH_IN} in")
    ts = texts(fig)
    for t in ts:
        if t.get_fontsize() < MIN_PT - 1e-9:
            found.append(f"text {t.get_text()[:40]!r} at {t.get_fontsize():.1f} pt")
    boxes = [(t, _bbox(t, renderer)) for t in ts]
    for lg in legends(fig):
        box = lg.get_window_extent(renderer)
        own = set(id(t) for t in lg.get_texts()) | {id(lg.get_title())}
        for ax in fig.axes:  # a legend running into another panel is hidden under it
            if ax.get_visible() and ax is not lg.axes and ax.get_label() != "<colorbar>" and _overlap(
                    ax.get_window_extent(renderer), box):
                found.append(f"legend {[x.get_text() for x in lg.get_texts()][:1]} runs into the axes {ax.get_title()[:30]!r}")
        for t, b in boxes:
            if id(t) not in own and _overlap(b, box):
                found.append(f"text {t.get_text()[:40]!r} under the legend {[x.get_text() for x in lg.get_texts()][:2]}")
        for ax in fig.axes:
            if not ax.get_visible():
                continue
            for ln in ax.lines:
                if not ln.get_visible() or len(np.atleast_1d(ln.get_xdata())) == 0:
                    continue
                xy = ln.get_transform().transform(np.column_stack([ln.get_xdata(), ln.get_ydata()]).astype(float))
                if ln.get_linestyle() not in ("None", "", " ") and len(xy) > 1:  # the segments too, not only vertices
                    t = np.linspace(0, 1, 24)[:, None, None]
                    xy = (xy[:-1][None] * (1 - t) + xy[1:][None] * t).reshape(-1, 2)
                xy = xy[np.all(np.isfinite(xy), axis=1)]
                clip = ax.bbox  # only what the axes show
                xy = xy[(xy[:, 0] >= clip.x0) & (xy[:, 0] <= clip.x1) & (xy[:, 1] >= clip.y0) & (xy[:, 1] <= clip.y1)]
                inside = ((xy[:, 0] > box.x0 + SLACK_PX) & (xy[:, 0] < box.x1 - SLACK_PX)
                          & (xy[:, 1] > box.y0 + SLACK_PX) & (xy[:, 1] < box.y1 - SLACK_PX))
                if inside.any():
                    found.append(f"line {ln.get_label()[:40]!r} drawn under a legend")
    for ax in fig.axes:  # a label in the axes (an annotation) on a marker
        if not ax.get_visible():
            continue
        labels = [(t, _bbox(t, renderer)) for t in ax.texts if t.get_visible() and t.get_text().strip()]
        for ln in ax.lines if labels else []:
            if ln.get_marker() in (None, "None", "", " ") or not ln.get_visible():
                continue
            xy = ln.get_transform().transform(np.column_stack([ln.get_xdata(), ln.get_ydata()]).astype(float))
            half = 0.5 * ln.get_markersize() * fig.dpi / 72.0
            for t, b in labels:
                if any(b.x0 < x + half - SLACK_PX and x - half + SLACK_PX < b.x1 and b.y0 < y + half - SLACK_PX
                       and y - half + SLACK_PX < b.y1 for x, y in xy if np.isfinite(x) and np.isfinite(y)):
                    found.append(f"label {t.get_text()[:30]!r} on a marker of {ln.get_label()[:30]!r}")
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            (a, ba), (b, bb) = boxes[i], boxes[j]
            if _overlap(ba, bb):
                found.append(f"texts {a.get_text()[:30]!r} and {b.get_text()[:30]!r} overlap")
    found += [f"empty axes {name!r}" for name in empty_axes(fig)]
    return found


def text_strings(fig):
    return [t.get_text() for t in texts(fig)]
