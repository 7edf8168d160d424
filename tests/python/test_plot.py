"""Checks `rigid plot` (src/python/rigidpy/plot.py, through its launcher src/python/rigid_plot.py)
on synthetic cubes written with h5py in the documented layout (docs/cube.md, synthetic_cube.py),
with outcomes drawn from a KNOWN probit model, so the planted parameters are an independent oracle
for the maximum-likelihood fit.

    /usr/bin/python3 -m pytest tests/python/test_plot.py

Skipped when numpy, h5py or matplotlib is missing.
"""
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys

import pytest

h5py = pytest.importorskip("h5py")
np = pytest.importorskip("numpy")
pytest.importorskip("matplotlib")  # the tool needs it

import figure_checks  # noqa: E402  (measurements of a rendered figure)
from synthetic_cube import (A, ALPHA, EDGES, MU0, MU1, P, R, SCALES, SIGMA, bin_of,  # noqa: E402
                            derived, phi, planted_outcomes, write_cube)
from rigidpy import checksums as cube_checksums  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.normpath(os.path.join(HERE, "..", "..", "src", "python", "rigid_plot.py"))


def run_tool(*args, expect=0):
    p = subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)
    if p.returncode != expect:
        raise AssertionError(f"rigid_plot.py {' '.join(args)}: exit {p.returncode}, expected {expect}\n"
                             f"stdout:\n{p.stdout}\nstderr:\n{p.stderr}")
    return p


def read(path):
    with open(path) as fh:
        return fh.read()


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def is_png(path):
    with open(path, "rb") as fh:
        return fh.read(8) == b"\x89PNG\r\n\x1a\n" and os.path.getsize(path) > 5000


class TestRigidPlot:
    @pytest.fixture(autouse=True, scope="class")
    def _cubes(self, request, tmp_path_factory):
        cls = request.cls
        cls.tmp = str(tmp_path_factory.mktemp("plot"))
        rng = np.random.default_rng(20261122)
        cls.pgv_pga = np.exp(rng.uniform(math.log(0.035), math.log(0.5), R))
        cls.planted = planted_outcomes(rng, cls.pgv_pga, MU0, MU1, SIGMA)
        # more fragile copy for the diff (median PGA lower by a factor e^0.4)
        cls.fragile = planted_outcomes(rng, cls.pgv_pga, MU0 - 0.4, MU1, SIGMA)
        # complete separation: overturns exactly above 0.55 g -> no finite MLE
        sep = np.where(SCALES[None, :, None] > 0.55, 2, 1).astype(np.int8) * np.ones((R, 1, A), np.int8)
        cls.cube = os.path.join(cls.tmp, "planted.h5")
        write_cube(cls.cube, cls.pgv_pga, [
            ("rock_plain", cls.planted, {}),
            ("rock_norm", cls.planted, {"alpha_rad": ALPHA, "p_rad_s": P}),
            ("rock_separated", sep, {}),
        ])
        cls.cube_b = os.path.join(cls.tmp, "fragile.h5")
        write_cube(cls.cube_b, cls.pgv_pga, [("rock_plain", cls.fragile, {})])
        cls.maps_dir = os.path.join(cls.tmp, "maps")
        cls.maps = run_tool("maps", cls.cube, "--out", cls.maps_dir)
        with open(os.path.join(cls.maps_dir, "fit.json")) as fh:
            cls.fit = {o["object"]: o for o in json.load(fh)["objects"]}

    # -- numerics against known values ------------------------------------------------------
    # -- the fit recovers the planted model ---------------------------------------------------
    def test_fit_recovers_planted_parameters(self):
        o = self.fit["rock_plain"]
        f = o["fit"]
        assert f is not None, o.get("reason")
        assert f["converged"]
        assert not f["separated"]
        (m0, m1), (s0,) = f["mu_coefficients"], f["log_sigma_coefficients"]
        (e0, e1), (es,) = f["mu_se"], f["log_sigma_se"]
        # 4 standard errors (statistical tolerance) and loose absolute bounds (in case the SE is wrong)
        assert abs(m0 - MU0) < 4 * e0, (m0, e0)
        assert abs(m1 - MU1) < 4 * e1, (m1, e1)
        assert abs(s0 - math.log(SIGMA)) < 4 * es, (math.exp(s0), es)
        assert abs(m0 - MU0) < 0.25
        assert abs(m1 - MU1) < 0.12
        assert abs(math.exp(s0) - SIGMA) < 0.05
        assert f["log_likelihood"] > f["null_log_likelihood"]
        # the fit's cells: the simulated ones (survived, overturned), not the inferred ones
        assert o["n_cells"] == int(np.isin(self.planted, (1, 2)).sum())
        assert o["n_overturned"] == int((self.planted == 2).sum())
        assert o["alpha_source"] == "unknown"

    def test_fit_is_a_likelihood_maximum(self):
        from rigidpy import fit as fragility_fit
        known = np.isin(self.planted, (1, 2))
        k = (self.planted == 2).sum(axis=2).ravel().astype(float)
        n = known.sum(axis=2).ravel().astype(float)
        u = np.tile(np.log(SCALES), R)
        x = np.repeat(np.log(self.pgv_pga), len(SCALES))
        ok = n > 0
        f = self.fit["rock_plain"]["fit"]
        theta = np.array(f["mu_coefficients"] + f["log_sigma_coefficients"])
        ll = fragility_fit.probit_derivatives(theta, u[ok], x[ok], k[ok], n[ok], 1, 0)[0]
        assert round(abs(f["log_likelihood"] - ll), 6) == 0
        for i in range(3):
            for h in (1e-3, -1e-3):
                t = theta.copy()
                t[i] += h
                assert fragility_fit.probit_derivatives(t, u[ok], x[ok], k[ok], n[ok], 1, 0)[0] < ll

    def test_normalisation_shifts_coefficients_not_contours(self):
        a, b = self.fit["rock_plain"], self.fit["rock_norm"]
        assert b["alpha_rad"] == ALPHA
        assert b["p_rad_s"] == P
        assert "object attribute" in b["alpha_source"]
        # u' = u - ln tan(alpha), x' = x + ln(p/alpha): mu'(x') = mu(x) - ln tan(alpha)
        c = math.log(P / ALPHA)
        m0, m1 = a["fit"]["mu_coefficients"]
        n0, n1 = b["fit"]["mu_coefficients"]
        assert round(abs(m1 - n1), 5) == 0
        assert round(abs(m0 - math.log(math.tan(ALPHA)) - m1 * c - n0), 5) == 0
        for ra, rb in zip(a["contours_at_bin_median_pgv_pga"], b["contours_at_bin_median_pgv_pga"]):
            for lev in (1, 50, 99):
                assert round(abs(rb[f"pga_g_{lev}pct"] - ra[f"pga_g_{lev}pct"]), 6) == 0
        # the 50 % contour is the planted median where the data are
        for row in a["contours_at_bin_median_pgv_pga"]:
            planted = math.exp(MU0 + MU1 * math.log(row["pgv_pga_s"]))
            assert abs(math.log(row["pga_g_50pct"] / planted)) < 0.12, row

    def test_command_line_alpha_overrides(self):
        out = os.path.join(self.tmp, "maps_cli")
        run_tool("maps", self.cube, "--out", out, "--object", "rock_norm", "--alpha", "rock_norm=0.3", "--p", "2.0")
        with open(os.path.join(out, "fit.json")) as fh:
            o = json.load(fh)["objects"]
        assert [x["object"] for x in o] == ["rock_norm"]
        assert (o[0]["alpha_rad"], o[0]["alpha_source"]) == (0.3, "command line")
        assert o[0]["p_rad_s"] == 2.0

    def test_separated_outcomes_give_no_contours(self):
        o = self.fit["rock_separated"]
        assert "separated" in o["reason"]
        assert "contours_at_bin_median_pgv_pga" not in o

    # -- maps -------------------------------------------------------------------------------
    def test_maps_write_pngs(self):
        for name in ("rock_plain", "rock_norm", "rock_separated"):
            for kind in ("map", "records"):
                assert is_png(os.path.join(self.maps_dir, f"{name}_{kind}.png")), (name, kind)
        # the fit said as a median PGA and a dispersion, its coefficients with what they multiply
        assert (re.search((r"rock_plain: \d+ cells \(\d+ overturned\) of 80 records; .*median PGA "
                                           r"[\d.]+ g, dispersion sigma [\d.]+ \(of ln PGA\)\n  fit P = Phi"), self.maps.stdout))
        assert "rock_separated: 6400 cells, no fit: " in self.maps.stdout

    # -- diff -------------------------------------------------------------------------------
    def read_mismatch(self, out):
        return read_csv(os.path.join(out, "mismatch.csv"))

    def test_diff_with_itself_is_zero(self):
        out = os.path.join(self.tmp, "diff_self")
        p = run_tool("diff", self.cube, self.cube, "--out", out)
        rows = self.read_mismatch(out)
        assert [r["object"] for r in rows] == ["rock_plain", "rock_norm", "rock_separated"]
        for r in rows:
            assert int(r["n_cells"]) > 100
            assert float(r["mean_3D_minus_2D"]) == 0.0
            assert float(r["sd"]) == 0.0
            assert is_png(os.path.join(out, f"{r['object']}_diff.png"))
        assert "sign convention: difference = 3D \u2212 2D" in p.stdout
        with open(os.path.join(out, "mismatch.md")) as fh:
            assert "0.000 \u00b1 0.000" in fh.read()

    def test_diff_sign_and_values(self):
        out = os.path.join(self.tmp, "diff_ab")
        run_tool("diff", self.cube_b, self.cube, "--out", out, "--label-a", "fragile", "--label-b", "planted")
        rows = self.read_mismatch(out)
        assert [r["object"] for r in rows] == ["rock_plain"]  # matched by name only
        _, fa, _ = derived(self.fragile, self.pgv_pga)
        _, fb, _ = derived(self.planted, self.pgv_pga)
        d = (fa - fb)[np.isfinite(fa - fb)]
        r = rows[0]
        assert int(r["n_cells"]) == d.size
        assert round(abs(d.mean() - float(r["mean_fragile_minus_planted"])), 5) == 0
        assert round(abs(d.std(ddof=1) - float(r["sd"])), 5) == 0
        assert round(abs((-d.mean()) - float(r["mean_planted_minus_fragile"])), 5) == 0
        assert d.mean() > 0.02  # the more fragile cube is A: positive A - B

    def test_diff_rejects_other_bins(self):
        other = os.path.join(self.tmp, "other_bins.h5")
        shutil.copy(self.cube, other)
        edges = np.array(EDGES, float)
        edges[1] = 0.05
        with h5py.File(other, "r+") as f:
            f["axes/pgv_pga_edges_s"][1] = 0.05
            # a cube written with other edges, not a damaged one: its fragility follows them
            for g in f["objects"].values():
                _, frag, count = derived(g["outcome"][()], self.pgv_pga, edges)
                g["fragility"][...] = frag
                g["fragility_count"][...] = count
            cube_checksums.seal(f)
        p = run_tool("diff", self.cube, other, "--out", os.path.join(self.tmp, "bad"), expect=2)
        assert "different PGV/PGA bin edges" in p.stderr

    # -- table ------------------------------------------------------------------------------
    def test_table(self):
        md = os.path.join(self.tmp, "table", "scenarios.md")
        run_tool("table", self.cube, "--out", md, "--layout", "objects")
        text = read(md)
        assert len(text) > 200
        lines = [l for l in text.splitlines() if l.startswith("| rock_plain |")]
        assert len(lines) == 1
        cells = [c.strip() for c in lines[0].strip("|").split("|")]
        assert len(cells) == 1 + R + 1
        o = self.planted
        over, known = np.isin(o, (2, 3)), np.isin(o, (1, 2, 3))
        for r in (0, 17, R - 1):
            assert cells[1 + r].rstrip("\u2020") == f"{over[r].sum() / known[r].sum():.2f}"
        assert cells[-1].rstrip("\u2020") == f"{over.sum() / known.sum():.2f}"
        # the long CSV beside it, and one scale
        rows = read_csv(os.path.splitext(md)[0] + ".csv")
        assert len(rows) == 3 * (R + 1)
        s = 6  # 0.7 g
        md2 = os.path.join(self.tmp, "table", "at07.md")
        run_tool("table", self.cube, self.cube_b, "--out", md2, "--target-pga", "0.7", "--counts")
        rows = read_csv(os.path.splitext(md2)[0] + ".csv")
        row = [x for x in rows if x["cube"] == "planted" and x["object"] == "rock_plain" and x["record"] == "all"][0]
        assert int(row["known"]) == int(known[:, s].sum())
        assert round(abs(over[:, s].sum() / known[:, s].sum() - float(row["overturn_fraction"])), 5) == 0
        text = read(md2)
        assert "| **all** |" in text  # 80 records: records as rows
        assert "planted: rock_plain" in text
        run_tool("table", self.cube, "--out", md2, "--target-pga", "0.75", expect=2)

    def test_bad_input(self):
        p = run_tool("maps", os.path.join(self.tmp, "missing.h5"), "--out", self.tmp, expect=2)
        assert "no such file" in p.stderr
        p = run_tool("maps", self.cube, "--out", self.tmp, "--object", "nope", expect=2)
        assert "no object 'nope'" in p.stderr


# --------------------------------------------------------------------------------------------
# Figures: which rows and panels a map shows, and legends off the data


def display_paths(artist):
    """The artist's drawn geometry in display coordinates, as (path, filled, pad): lines split at
    NaNs (pad: half the marker size, in pixels), a mesh's cells, a band's or patch's outline."""
    import matplotlib.collections
    import matplotlib.lines
    import matplotlib.path
    out = []
    if isinstance(artist, matplotlib.lines.Line2D):
        xy = artist.get_transform().transform(artist.get_xydata())
        ok = np.all(np.isfinite(xy), axis=1)
        pad = 0.5 * artist.get_markersize() * artist.figure.dpi / 72 if artist.get_marker() not in (None, "", "None") else 0
        start = None
        for i in range(len(ok) + 1):  # each run of finite points is one polyline
            if i < len(ok) and ok[i]:
                start = i if start is None else start
            elif start is not None:
                out.append((matplotlib.path.Path(xy[start:i]), False, pad))
                start = None
        return out
    if isinstance(artist, matplotlib.collections.PathCollection):  # scatter: markers at data offsets
        xy = artist.get_offset_transform().transform(artist.get_offsets())
        size = math.sqrt(max(artist.get_sizes(), default=0.0)) * artist.figure.dpi / 72
        return [(matplotlib.path.Path(p[None, :]), False, 0.5 * size) for p in xy if np.all(np.isfinite(p))]
    trans = artist.get_transform()
    for path in artist.get_paths() if hasattr(artist, "get_paths") else [artist.get_path()]:
        out.append((trans.transform_path(path), True, 0))
    return out


def legend_overlaps(fig):
    """(legend, axes, artist) triples where a legend's window extent touches drawn data: a line or
    marker inside it, a filled mesh cell, band or patch under it. Only the part of the legend inside
    an axes can cover that axes' data (artists are clipped to their axes)."""
    from matplotlib.transforms import Bbox
    fig.canvas.draw()
    legends = list(fig.legends) + [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
    hits = []
    for leg in legends:
        box = leg.get_window_extent()
        for ax in fig.axes:
            region = Bbox.intersection(box, ax.get_window_extent())
            if region is None or region.width <= 0 or region.height <= 0:
                continue
            for artist in list(ax.lines) + list(ax.collections) + list(ax.patches):
                if not artist.get_visible():
                    continue
                for path, filled, pad in display_paths(artist):
                    r = region.padded(pad) if pad else region
                    if path.intersects_bbox(r, filled=filled) or any(r.contains(x, y) for x, y in path.vertices):
                        hits.append((leg, ax, artist))
                        break
    return hits


class TestFigures:
    """A cube whose records fill bins 1, 2, 5 and 7 of EDGES only (3 bins without records between
    them), two of them with few enough records to be named in a legend."""
    HELD = {1: 20, 2: 5, 5: 20, 7: 6}

    @pytest.fixture(autouse=True, scope="class")
    def _figures(self, request, tmp_path_factory):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.figure
        cls = request.cls
        cls.tmp = str(tmp_path_factory.mktemp("figures"))
        rng = np.random.default_rng(20261126)
        pgv = []
        for b, n in cls.HELD.items():
            pgv += list(np.exp(rng.uniform(math.log(EDGES[b]) + 0.01, math.log(EDGES[b + 1]) - 0.01, n)))
        cls.pgv_pga = np.array(pgv)
        cls.cube = os.path.join(cls.tmp, "gapped.h5")
        outcome = planted_outcomes(rng, cls.pgv_pga, MU0, MU1, SIGMA)
        # the 6 records of bin 7 overturn at random (P ~ 0.5 at every scale): their curves zigzag over
        # the whole panel, so no corner inside it is free for a legend
        last = [r for r, v in enumerate(cls.pgv_pga) if bin_of(v) == 7]
        outcome[last] = np.where(rng.random(outcome[last].shape) < 0.5, 2, 1)
        write_cube(cls.cube, cls.pgv_pga, [("rock", outcome, {})])
        other = os.path.join(cls.tmp, "gapped_b.h5")
        write_cube(other, cls.pgv_pga, [("rock", planted_outcomes(rng, cls.pgv_pga, MU0 - 0.3, MU1, SIGMA), {})])
        curve = os.path.join(cls.tmp, "curve.csv")
        a = np.geomspace(1e-3, 10.0, 40)
        with open(curve, "w") as fh:
            fh.write("pga_g,annual_rate\n" + "".join(f"{x!r},{1e-4 * x ** -2.0!r}\n" for x in a))
        accuracy_csv = os.path.join(cls.tmp, "accuracy.csv")
        write_accuracy_rows(accuracy_csv)

        from rigidpy import accuracy as accuracy_plot
        from rigidpy import fit as fragility_fit
        from rigidpy import fragility as rigid_fragility
        from rigidpy import plot as rp
        from rigidpy.cube import Cube
        from rigidpy.figures import plot_variant_band
        cls.figures = {}
        original = matplotlib.figure.Figure.savefig

        def keep(fig, fname, *args, **kwargs):  # the tools write through a private temporary ".NAME.XXXX.tmp"
            name = os.path.basename(str(fname))
            cls.figures[re.sub(r"^\.(.*)\.[^.]+\.tmp$", r"\1", name)] = fig
            return original(fig, fname, *args, **kwargs)

        matplotlib.figure.Figure.savefig = keep
        try:
            cls.assert_zero(rp.main(["maps", cls.cube, "--out", os.path.join(cls.tmp, "maps")]), "maps")
            cls.assert_zero(rp.main(["diff", cls.cube, other, "--out", os.path.join(cls.tmp, "diff")]), "diff")
            grid = np.geomspace(0.05, 5.0, 200)
            lognormals = [(0.4, 0.3), (0.6, 0.4), (0.9, 0.35)]
            pooled = fragility_fit.pooled_fragility(lognormals, grid)
            plot_variant_band(Cube(cls.cube), "rock", [(k, (t, b, "fit")) for k, (t, b) in enumerate(lognormals)],
                              pooled, 0.15, os.path.join(cls.tmp, "rock_variants.png"))
            cls.assert_zero(rigid_fragility.main(["hazard", cls.cube, "--curve", curve, "--age", "1000",
                                                  "--bootstrap", "20", "--plot", os.path.join(cls.tmp, "hazard.png")]),
                            "hazard --plot")
            accuracy_plot.plot(accuracy_plot.read(accuracy_csv), os.path.join(cls.tmp, "accuracy_pareto.png"))
            draw_shaketable_fragility(rng, os.path.join(cls.tmp, "shaketable_fragility.png"))
        finally:
            matplotlib.figure.Figure.savefig = original

    @staticmethod
    def assert_zero(code, what):
        if code not in (0, None):
            raise AssertionError(f"{what}: exit {code}")

    def figure(self, suffix):
        found = [f for name, f in self.figures.items() if name.endswith(suffix)]
        assert len(found) == 1, (suffix, sorted(self.figures))
        return found[0]

    @staticmethod
    def bin_label(b):
        def edge(v):
            return "\u221e" if v == math.inf else f"{v:.3g}"
        return f"{edge(EDGES[b])}\u2013{edge(EDGES[b + 1])}"

    def test_map_rows_are_the_bins_with_records(self):
        """Rows from the lowest to the highest bin with records: the bins without records between
        them keep their rows, hatched (no cell), so the y axis and the contours run on."""
        import matplotlib.collections
        assert sorted({bin_of(v) for v in self.pgv_pga}) == sorted(self.HELD)  # the fixture itself
        held = list(range(min(self.HELD), max(self.HELD) + 1))
        for suffix, panels in (("rock_map.png", 1), ("rock_diff.png", 3)):
            fig = self.figure(suffix)
            fig.canvas.draw()
            # the map panels: a mesh and a title (a colour bar's axes has a mesh, no title)
            maps = [ax for ax in fig.axes if ax.get_title()
                    and any(isinstance(c, matplotlib.collections.QuadMesh) for c in ax.collections)]
            assert len(maps) == panels, suffix
            for ax in maps:
                mesh = [c for c in ax.collections if isinstance(c, matplotlib.collections.QuadMesh)][0]
                rows, cols = np.array(mesh.get_coordinates().shape[:2]) - 1
                assert (rows, cols) == (len(held), len(SCALES)), suffix
                positions = list(ax.get_yticks())  # the labels as the formatter writes them (hidden on shared axes)
                ticks = [ax.yaxis.get_major_formatter()(y, i) for i, y in enumerate(positions)]
                lo, hi = sorted(ax.get_ylim())
                shown = [t for t, y in zip(ticks, positions) if lo <= y <= hi]
                assert shown == [self.bin_label(b) for b in held], suffix
        # the map's cells are the cube's fragility of the bins with records, in order
        fig = self.figure("rock_map.png")
        mesh = [c for c in fig.axes[0].collections if isinstance(c, matplotlib.collections.QuadMesh)][0]
        _, frag, _ = derived(planted_outcomes_of(self.cube), self.pgv_pga)
        shown = np.ma.filled(mesh.get_array().astype(float), np.nan).reshape(len(held), len(SCALES))
        np.testing.assert_allclose(shown, frag.T[held], rtol=0, atol=1e-12)
        empty = [k for k, b in enumerate(held) if b not in self.HELD]
        assert empty and np.all(np.isnan(shown[empty])), "the rows of bins without records have no cell"

    def test_contours_run_on_through_bins_without_records(self):
        """The map's 50 % contour is one unbroken curve in the map's rows over the records'
        PGV/PGA range: its y steps are small (no jump over a missing bin) and none is NaN."""
        fig = self.figure("rock_map.png")
        ax = fig.axes[0]
        line = [ln for ln in ax.lines if ln.get_label().startswith("50 % contour")][0]
        y = np.asarray(line.get_ydata(), float)
        assert np.all(np.isfinite(y)) and np.max(np.abs(np.diff(y))) < 0.1, f"50 % contour: largest step {np.nanmax(np.abs(np.diff(y))):.3f} rows"
        assert y.min() < 1 and y.max() > max(self.HELD) - min(self.HELD), "it spans the rows of every held bin"

    def test_paper_ready(self):
        """Every figure, measured as drawn (figure_checks.py): at most a page wide (7.2 in), no text
        under 8 pt, no text under a legend, no two texts overlapping, no empty axes."""
        for name, fig in sorted(self.figures.items()):
            found = figure_checks.problems(fig)
            assert found == [], f"{name}: {found}"

    def test_titles_promise_only_what_is_drawn(self):
        """A map's title speaks of cell numbers only when numbers are drawn in cells; the fit's
        provenance note is said once per figure, in no legend entry."""
        for name, fig in self.figures.items():
            strings = figure_checks.text_strings(fig)
            notes = [t for t in strings if "Purvance" in t]
            assert len(notes) <= 1, f"{name}: the fit's provenance said {len(notes)} times"
            for lg in figure_checks.legends(fig):
                assert not any("Purvance" in t.get_text() for t in lg.get_texts()), f"{name}: provenance in a legend"
        for name, fig in self.figures.items():
            if not name.endswith("_map.png"):
                continue
            title = fig.axes[0].get_title()
            counts = [t for t in fig.axes[0].texts if t.get_gid() == "cell count"]
            assert ("numbers" in title) == bool(counts), f"{name}: title {title!r} with {len(counts)} cell numbers"

    def test_records_panels_only_for_bins_with_records(self):
        fig = self.figure("rock_records.png")
        panels = [ax for ax in fig.axes if ax.get_visible() and ax.get_title().startswith("PGV/PGA")]
        assert [ax.get_title().split(" (")[0] for ax in panels] == [f"PGV/PGA {self.bin_label(b)} s" for b in sorted(self.HELD)]
        assert "no records" not in [t.get_text() for ax in fig.axes for t in ax.texts]
        named = [ax for ax in panels if ax.get_legend() is not None]
        assert len(named) == 2  # the panels of 5 and 6 records name them

    def test_legends_off_the_data(self):
        expected = ("rock_map.png", "rock_records.png", "rock_diff.png", "rock_variants.png", "hazard.png",
                    "accuracy_pareto.png", "shaketable_fragility.png")
        for suffix in expected:
            fig = self.figure(suffix)
            fig.canvas.draw()
            legends = list(fig.legends) + [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
            assert legends, f"{suffix}: no legend drawn"
            hits = legend_overlaps(fig)
            assert [] == [(suffix, type(a).__name__, a.get_label()) for _, _, a in hits]

    def test_overlap_oracle_finds_a_covered_curve(self):
        """The oracle itself: a legend put on a curve is found, one beside the axes is not."""
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots()
        x = np.linspace(0, 1, 50)
        ax.plot(x, x, label="diagonal")
        ax.legend(loc="center")
        assert len(legend_overlaps(fig)) == 1
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0))
        assert legend_overlaps(fig) == []
        ax.fill_between(x, 0, 1, alpha=0.2)
        ax.legend(loc="center")  # inside a filled band: covered, though no vertex lies in the legend
        assert len(legend_overlaps(fig)) >= 1
        plt.close(fig)
        fig, ax = plt.subplots()
        ax.scatter([0.5], [0.5], label="one point")  # a scatter marker under the legend
        ax.set_xlim(0, 1)
        ax.set_ylim(0, 1)
        ax.legend(loc="center")
        assert len(legend_overlaps(fig)) == 1
        ax.legend(loc="upper left")
        assert legend_overlaps(fig) == []
        plt.close(fig)


def test_figure_checks_find_planted_faults():
    """The figure oracle itself (figure_checks.py): each planted fault is found, the clean figure
    passes."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    def clean():
        fig, ax = plt.subplots(figsize=(3.5, 2.5))
        ax.plot([0, 1], [0, 1], label="a line")
        ax.set_title("title", fontsize=9)
        ax.tick_params(labelsize=8)
        ax.xaxis.label.set_fontsize(8)
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8)
        return fig, ax

    fig, ax = clean()
    assert figure_checks.problems(fig) == [], figure_checks.problems(fig)
    ax.text(0.5, 0.1, "small", fontsize=6)
    assert any("6.0 pt" in p for p in figure_checks.problems(fig)), "a 6 pt text is found"
    fig, ax = clean()
    ax.text(0.2, 0.8, "one label", fontsize=8)
    ax.text(0.21, 0.8, "another label", fontsize=8)
    assert any("overlap" in p for p in figure_checks.problems(fig)), "two texts on each other are found"
    fig, ax = clean()
    ax.legend(loc="center", fontsize=8)
    assert any("under a legend" in p for p in figure_checks.problems(fig)), "a line under a legend is found"
    fig, ax = clean()
    fig.set_size_inches(12, 4)
    assert any("wide" in p for p in figure_checks.problems(fig)), "a figure wider than a page is found"
    fig, (left, right) = plt.subplots(1, 2, figsize=(7, 3))
    left.plot([0, 1], [0, 1], label="a long name that runs on and on")
    right.plot([0, 1], [0, 1])
    left.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8)
    for a in (left, right):
        a.tick_params(labelsize=8, labelleft=False)
    assert any("runs into the axes" in p for p in figure_checks.problems(fig)), "a legend under a neighbouring panel is found"
    fig, ax = clean()
    ax.plot([0.5], [0.5], "o", ms=6)
    ax.annotate("on it", (0.5, 0.5), fontsize=8)
    assert any("on a marker" in p for p in figure_checks.problems(fig)), "a label on a marker is found"
    fig, (ax, empty) = plt.subplots(1, 2, figsize=(7, 3))
    ax.plot([0, 1], [0, 1])
    for a in (ax, empty):
        a.tick_params(labelsize=8)
    assert any("empty axes" in p for p in figure_checks.problems(fig)), "an empty panel is found"
    plt.close("all")


def draw_shaketable_fragility(rng, path):
    """`rigid shaketable fragility`'s figure on planted lab tests: two PGV/PGA bins of 3 motions,
    12 PGAs each, outcomes from a probit of median 0.5 g, the model's share and both fits."""
    from rigidpy import shaketable as sf
    scales = np.linspace(0.1, 1.2, 12)
    p = np.array([phi(math.log(a / 0.5) / 0.3) for a in scales])
    k = (rng.random((6, 12)) < p).astype(float)
    lab = sf.BinnedCells(k, np.ones((6, 12)), scales)
    fit = {"theta_g": 0.5, "beta": 0.3, "theta_interval_g": (0.45, 0.56)}
    rows = [{"motions": np.arange(3 * i, 3 * i + 3), "lab": fit, "model": dict(fit, theta_g=0.55),
             "label": label, "tests": 36} for i, label in enumerate(("0.06-0.1 s", "0.1-0.2 s"))]
    sf.draw(rows, lab, np.tile(p, (6, 1)), np.ones((6, 12), bool), scales, path, [])


def planted_outcomes_of(cube):
    with h5py.File(cube, "r") as f:
        return f["objects/rock/outcome"][()]


def write_accuracy_rows(path):
    """A small `rigid study accuracy` CSV: two cases, a safety sweep per integrator, tolerances, the
    presets, the converged reference and the contact-model rows against an oracle."""
    cols = ["scene", "motion", "setting", "axis", "preset", "integrator", "safety", "wall_s", "error", "traj_rel_err",
            "outcome_match", "oracle", "oracle_value", "oracle_err", "model_quantity", "model_value",
            "search_wall_s", "contact", "stiffness_n_m"]
    rows = []
    for case, scale in (("a", 1.0), ("b", 2.0)):
        def row(setting, axis, **kw):
            r = dict.fromkeys(cols, "")
            r.update(scene=f"scene_{case}", motion="sine", setting=setting, axis=axis, integrator="splitting",
                     safety="0.2", outcome_match="1", oracle="housner_one_sine_threshold_g")
            r.update({k: str(v) for k, v in kw.items()})
            rows.append(r)
        for integ in ("splitting", "rk4"):
            for sf in (0.05, 0.1, 0.2, 0.4, 0.8):
                row(f"safety {sf:g} {integ}", "safety", integrator=integ, safety=sf, wall_s=scale / sf,
                    error=scale * 1e-3 * sf ** 2)
        row("tolerance loose", "tolerance", wall_s=scale * 3, error=scale * 2e-4)
        row("tolerance sleep", "tolerance", wall_s=scale * 0.3, error=scale * 1e-6)  # cheap and accurate: lower left
        for p, sf in (("fast", 0.8), ("balanced", 0.2), ("reference", 0.05)):
            row(f"preset {p}", "preset", preset=p, safety=sf, wall_s=scale / sf, error=scale * 1e-3 * sf ** 2)
        row("converged reference", "converged", safety=0.01, wall_s=scale * 100, error=0, traj_rel_err=0)
        for k in (1e8, 1e9, 1e10):
            row(f"stiffness {k:g}", "stiffness", contact="penalty", stiffness_n_m=k, wall_s=scale * math.log10(k),
                oracle_err=0.1 / math.log10(k), search_wall_s=1)
        for sf in (0.05, 0.2, 0.8):
            row(f"rigid {sf:g}", "rigid", contact="rigid", safety=sf, wall_s=scale / sf, oracle_err=0.01 * sf,
                search_wall_s=1)
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=cols)
        w.writeheader()
        w.writerows(rows)

