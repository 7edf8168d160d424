#!/usr/bin/python3
"""Checks src/plot/rigid_plot.py (`rigid plot`) on synthetic cubes written here with h5py in the
documented layout (docs/cube.md), with outcomes drawn from a KNOWN probit
model, so the planted parameters are an independent oracle for the maximum-likelihood fit.

    /usr/bin/python3 tests/python/test_plot.py [PATH/rigid_plot.py]

Exit 0 success, 1 failure, 77 (CTest: skipped) when numpy, h5py or matplotlib is missing.
"""
import csv
import importlib.util
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

try:
    import h5py
    import numpy as np
    import matplotlib  # noqa: F401  (the tool needs it)
except ImportError as e:  # pragma: no cover
    print(f"skipped: {e} (install python3-h5py python3-numpy python3-matplotlib for {sys.executable})")
    sys.exit(77)

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.normpath(os.path.join(HERE, "..", "..", "src", "plot", "rigid_plot.py"))
sys.path.insert(0, os.path.dirname(SCRIPT))
import cube_checksums  # noqa: E402  (synthetic cubes carry the checksums of the current schema)

EDGES = [0.0, 0.06, 0.08, 0.10, 0.12, 0.15, 0.20, 0.25, 0.35, math.inf]
SCALES = np.round(np.arange(1, 21) * 0.1, 10)       # 0.1 .. 2.0 g
R, A = 80, 4
# planted model in un-normalised variables: u = ln(PGA/g), x = ln(PGV/PGA / 1 s)
MU0, MU1, SIGMA = -1.8, -0.5, 0.35
ALPHA, P = 0.2, 2.2                                  # attributes of the normalised copy


def phi(z):
    return 0.5 * math.erfc(-z / math.sqrt(2.0))


def bin_of(v, edges=None):
    edges = EDGES if edges is None else edges
    for i in range(len(edges) - 1):
        if edges[i] <= v < edges[i + 1]:
            return i
    return -1


def derived(outcome, pgv_pga, edges=None):
    """Independent re-implementation of the cube's probability and fragility."""
    over = ((outcome == 2) | (outcome == 3)).sum(axis=2)
    known = over + (outcome == 1).sum(axis=2)
    prob = np.full(known.shape, np.nan)
    prob[known > 0] = over[known > 0] / known[known > 0]
    B = len(EDGES) - 1
    frag = np.full((len(SCALES), B), np.nan)
    count = np.zeros((len(SCALES), B), dtype=np.int32)
    for s in range(len(SCALES)):
        for b in range(B):
            vals = [prob[r, s] for r in range(len(pgv_pga)) if bin_of(pgv_pga[r], edges) == b and not np.isnan(prob[r, s])]
            if vals:
                frag[s, b] = sum(vals) / len(vals)
                count[s, b] = len(vals)
    return prob, frag, count


def planted_outcomes(rng, pgv_pga, mu0, mu1, sigma, extras=True):
    out = np.zeros((len(pgv_pga), len(SCALES), A), dtype=np.int8)
    for r, v in enumerate(pgv_pga):
        mu = mu0 + mu1 * math.log(v)
        for s, g in enumerate(SCALES):
            p = phi((math.log(g) - mu) / sigma)
            out[r, s, :] = np.where(rng.random(A) < p, 2, 1)
    if extras:  # relabel some overturned as inferred and lose some cells: neither biases the fit
        out[(out == 2) & (rng.random(out.shape) < 0.2)] = 3
        out[rng.random(out.shape) < 0.03] = 4
        out[rng.random(out.shape) < 0.02] = 0
    return out


def write_cube(path, pgv_pga, objects, root_attrs=None):
    """objects: list of (name, outcome [R,S,A], attrs dict)."""
    str_t = h5py.string_dtype("utf-8")
    names = [f"rec{r:03d}" for r in range(len(pgv_pga))]
    with h5py.File(path, "w") as f:
        f.attrs["schema_version"] = np.int32(1)
        f.attrs["units"] = "SI unless the name says otherwise"
        for k, v in (root_attrs or {}).items():
            f.attrs[k] = v
        ax = f.create_group("axes")
        ax.create_dataset("record", data=np.array(names, dtype=object), dtype=str_t)
        ax.create_dataset("scale_g", data=SCALES.astype(float))
        ax.create_dataset("rotation", data=np.arange(A, dtype=np.int32))
        ax.create_dataset("pgv_pga_bin", data=np.arange(len(EDGES) - 1, dtype=np.int32))
        ax.create_dataset("pgv_pga_edges_s", data=np.array(EDGES, float))
        rec = f.create_group("records")
        rec.create_dataset("name", data=np.array(names, dtype=object), dtype=str_t)
        rec.create_dataset("pgv_pga_s", data=np.asarray(pgv_pga, float))
        rec.create_dataset("gmroti_pga_g", data=np.full(len(pgv_pga), 0.3))
        objs = f.create_group("objects")
        for i, (name, outcome, attrs) in enumerate(objects):
            g = objs.create_group(name)
            g.attrs["index"] = np.int32(i)
            g.attrs["scene"] = f"{name}.toml"
            for k, v in attrs.items():
                g.attrs[k] = v
            prob, frag, count = derived(outcome, pgv_pga)
            g.create_dataset("outcome", data=outcome)
            g.create_dataset("probability", data=prob)
            g.create_dataset("fragility", data=frag)
            g.create_dataset("fragility_count", data=count)
        cube_checksums.seal(f)


def run_tool(*args, expect=0):
    p = subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)
    if p.returncode != expect:
        raise AssertionError(f"rigid_plot.py {' '.join(args)}: exit {p.returncode}, expected {expect}\n"
                             f"stdout:\n{p.stdout}\nstderr:\n{p.stderr}")
    return p


def load_module():
    sys.path.insert(0, os.path.dirname(SCRIPT))  # rigid_plot imports fragility_fit beside it
    spec = importlib.util.spec_from_file_location("rigid_plot", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def read(path):
    with open(path) as fh:
        return fh.read()


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def is_png(path):
    with open(path, "rb") as fh:
        return fh.read(8) == b"\x89PNG\r\n\x1a\n" and os.path.getsize(path) > 5000


class RigidPlot(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="rigid_plot_test_")
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

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    # -- numerics against known values ------------------------------------------------------
    # -- the fit recovers the planted model ---------------------------------------------------
    def test_fit_recovers_planted_parameters(self):
        o = self.fit["rock_plain"]
        f = o["fit"]
        self.assertIsNotNone(f, o.get("reason"))
        self.assertTrue(f["converged"])
        self.assertFalse(f["separated"])
        (m0, m1), (s0,) = f["mu_coefficients"], f["log_sigma_coefficients"]
        (e0, e1), (es,) = f["mu_se"], f["log_sigma_se"]
        # 4 standard errors (statistical tolerance) and loose absolute bounds (in case the SE is wrong)
        self.assertLess(abs(m0 - MU0), 4 * e0, (m0, e0))
        self.assertLess(abs(m1 - MU1), 4 * e1, (m1, e1))
        self.assertLess(abs(s0 - math.log(SIGMA)), 4 * es, (math.exp(s0), es))
        self.assertLess(abs(m0 - MU0), 0.25)
        self.assertLess(abs(m1 - MU1), 0.12)
        self.assertLess(abs(math.exp(s0) - SIGMA), 0.05)
        self.assertGreater(f["log_likelihood"], f["null_log_likelihood"])
        # the fit's cells: the simulated ones (survived, overturned), not the inferred ones
        self.assertEqual(o["n_cells"], int(np.isin(self.planted, (1, 2)).sum()))
        self.assertEqual(o["n_overturned"], int((self.planted == 2).sum()))
        self.assertEqual(o["alpha_source"], "unknown")

    def test_fit_is_a_likelihood_maximum(self):
        load_module()
        import fragility_fit  # beside rigid_plot.py (load_module puts it on the path)
        known = np.isin(self.planted, (1, 2))
        k = (self.planted == 2).sum(axis=2).ravel().astype(float)
        n = known.sum(axis=2).ravel().astype(float)
        u = np.tile(np.log(SCALES), R)
        x = np.repeat(np.log(self.pgv_pga), len(SCALES))
        ok = n > 0
        f = self.fit["rock_plain"]["fit"]
        theta = np.array(f["mu_coefficients"] + f["log_sigma_coefficients"])
        ll = fragility_fit.probit_derivatives(theta, u[ok], x[ok], k[ok], n[ok], 1, 0)[0]
        self.assertAlmostEqual(ll, f["log_likelihood"], places=6)
        for i in range(3):
            for h in (1e-3, -1e-3):
                t = theta.copy()
                t[i] += h
                self.assertLess(fragility_fit.probit_derivatives(t, u[ok], x[ok], k[ok], n[ok], 1, 0)[0], ll)

    def test_normalisation_shifts_coefficients_not_contours(self):
        a, b = self.fit["rock_plain"], self.fit["rock_norm"]
        self.assertEqual(b["alpha_rad"], ALPHA)
        self.assertEqual(b["p_rad_s"], P)
        self.assertIn("object attribute", b["alpha_source"])
        # u' = u - ln tan(alpha), x' = x + ln(p/alpha): mu'(x') = mu(x) - ln tan(alpha)
        c = math.log(P / ALPHA)
        m0, m1 = a["fit"]["mu_coefficients"]
        n0, n1 = b["fit"]["mu_coefficients"]
        self.assertAlmostEqual(n1, m1, places=5)
        self.assertAlmostEqual(n0, m0 - math.log(math.tan(ALPHA)) - m1 * c, places=5)
        for ra, rb in zip(a["contours_at_bin_median_pgv_pga"], b["contours_at_bin_median_pgv_pga"]):
            for lev in (1, 50, 99):
                self.assertAlmostEqual(ra[f"pga_g_{lev}pct"], rb[f"pga_g_{lev}pct"], places=6)
        # the 50 % contour is the planted median where the data are
        for row in a["contours_at_bin_median_pgv_pga"]:
            planted = math.exp(MU0 + MU1 * math.log(row["pgv_pga_s"]))
            self.assertLess(abs(math.log(row["pga_g_50pct"] / planted)), 0.12, row)

    def test_command_line_alpha_overrides(self):
        out = os.path.join(self.tmp, "maps_cli")
        run_tool("maps", self.cube, "--out", out, "--object", "rock_norm", "--alpha", "rock_norm=0.3", "--p", "2.0")
        with open(os.path.join(out, "fit.json")) as fh:
            o = json.load(fh)["objects"]
        self.assertEqual([x["object"] for x in o], ["rock_norm"])
        self.assertEqual((o[0]["alpha_rad"], o[0]["alpha_source"]), (0.3, "command line"))
        self.assertEqual(o[0]["p_rad_s"], 2.0)

    def test_separated_outcomes_give_no_contours(self):
        o = self.fit["rock_separated"]
        self.assertIn("separated", o["reason"])
        self.assertNotIn("contours_at_bin_median_pgv_pga", o)

    # -- maps -------------------------------------------------------------------------------
    def test_maps_write_pngs(self):
        for name in ("rock_plain", "rock_norm", "rock_separated"):
            for kind in ("map", "records"):
                self.assertTrue(is_png(os.path.join(self.maps_dir, f"{name}_{kind}.png")), (name, kind))
        # the fit said as a median PGA and a dispersion, its coefficients with what they multiply
        self.assertRegex(self.maps.stdout, r"rock_plain: \d+ cells \(\d+ overturned\) of 80 records; .*median PGA "
                                           r"[\d.]+ g, dispersion sigma [\d.]+ \(of ln PGA\)\n  fit P = Phi")
        self.assertIn("rock_separated: 6400 cells, no fit: ", self.maps.stdout)

    # -- diff -------------------------------------------------------------------------------
    def read_mismatch(self, out):
        return read_csv(os.path.join(out, "mismatch.csv"))

    def test_diff_with_itself_is_zero(self):
        out = os.path.join(self.tmp, "diff_self")
        p = run_tool("diff", self.cube, self.cube, "--out", out)
        rows = self.read_mismatch(out)
        self.assertEqual([r["object"] for r in rows], ["rock_plain", "rock_norm", "rock_separated"])
        for r in rows:
            self.assertGreater(int(r["n_cells"]), 100)
            self.assertEqual(float(r["mean_3D_minus_2D"]), 0.0)
            self.assertEqual(float(r["sd"]), 0.0)
            self.assertTrue(is_png(os.path.join(out, f"{r['object']}_diff.png")))
        self.assertIn("sign convention: difference = 3D \u2212 2D", p.stdout)
        with open(os.path.join(out, "mismatch.md")) as fh:
            self.assertIn("0.000 \u00b1 0.000", fh.read())

    def test_diff_sign_and_values(self):
        out = os.path.join(self.tmp, "diff_ab")
        run_tool("diff", self.cube_b, self.cube, "--out", out, "--label-a", "fragile", "--label-b", "planted")
        rows = self.read_mismatch(out)
        self.assertEqual([r["object"] for r in rows], ["rock_plain"])  # matched by name only
        _, fa, _ = derived(self.fragile, self.pgv_pga)
        _, fb, _ = derived(self.planted, self.pgv_pga)
        d = (fa - fb)[np.isfinite(fa - fb)]
        r = rows[0]
        self.assertEqual(int(r["n_cells"]), d.size)
        self.assertAlmostEqual(float(r["mean_fragile_minus_planted"]), d.mean(), places=5)
        self.assertAlmostEqual(float(r["sd"]), d.std(ddof=1), places=5)
        self.assertAlmostEqual(float(r["mean_planted_minus_fragile"]), -d.mean(), places=5)
        self.assertGreater(d.mean(), 0.02)  # the more fragile cube is A: positive A - B

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
        self.assertIn("different PGV/PGA bin edges", p.stderr)

    # -- table ------------------------------------------------------------------------------
    def test_table(self):
        md = os.path.join(self.tmp, "table", "scenarios.md")
        run_tool("table", self.cube, "--out", md, "--layout", "objects")
        text = read(md)
        self.assertGreater(len(text), 200)
        lines = [l for l in text.splitlines() if l.startswith("| rock_plain |")]
        self.assertEqual(len(lines), 1)
        cells = [c.strip() for c in lines[0].strip("|").split("|")]
        self.assertEqual(len(cells), 1 + R + 1)
        o = self.planted
        over, known = np.isin(o, (2, 3)), np.isin(o, (1, 2, 3))
        for r in (0, 17, R - 1):
            self.assertEqual(cells[1 + r].rstrip("\u2020"), f"{over[r].sum() / known[r].sum():.2f}")
        self.assertEqual(cells[-1].rstrip("\u2020"), f"{over.sum() / known.sum():.2f}")
        # the long CSV beside it, and one scale
        rows = read_csv(os.path.splitext(md)[0] + ".csv")
        self.assertEqual(len(rows), 3 * (R + 1))
        s = 6  # 0.7 g
        md2 = os.path.join(self.tmp, "table", "at07.md")
        run_tool("table", self.cube, self.cube_b, "--out", md2, "--scale", "0.7", "--counts")
        rows = read_csv(os.path.splitext(md2)[0] + ".csv")
        row = [x for x in rows if x["cube"] == "planted" and x["object"] == "rock_plain" and x["record"] == "all"][0]
        self.assertEqual(int(row["known"]), int(known[:, s].sum()))
        self.assertAlmostEqual(float(row["overturn_fraction"]), over[:, s].sum() / known[:, s].sum(), places=5)
        text = read(md2)
        self.assertIn("| **all** |", text)  # 80 records: records as rows
        self.assertIn("planted: rock_plain", text)
        run_tool("table", self.cube, "--out", md2, "--scale", "0.75", expect=2)

    def test_bad_input(self):
        p = run_tool("maps", os.path.join(self.tmp, "missing.h5"), "--out", self.tmp, expect=2)
        self.assertIn("no such file", p.stderr)
        p = run_tool("maps", self.cube, "--out", self.tmp, "--object", "nope", expect=2)
        self.assertIn("no object 'nope'", p.stderr)


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1].endswith(".py"):
        SCRIPT = os.path.abspath(sys.argv.pop(1))
    result = unittest.main(exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
