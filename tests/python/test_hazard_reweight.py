"""`rigid hazard reweight` (src/python/rigidpy/hazard_reweight.py) against independent oracles:

1. Closed form: power-law branches H_k(a) = k0_k a^-k_k under a lognormal fragility topple at
   nu_k = k0_k theta^-k exp(k^2 beta^2 / 2); rates within 1 %, posterior weights w_k S_k / sum
   within 0.005, S_k = exp(-nu_k T), on a fixed tree and on a planted tree drawn anew each run (its
   seed in the message); with the bootstrap ensemble, S_k is the mean over the members' closed forms.
   PGA at 1e-4/yr of a one-branch power law: (k0 / 1e-4)^(1/k).
2. Age distributions: survival E[exp(-nu T)] against the mean of exp(-nu t) over 1e6 sampled ages
   (normal truncated at 0, lognormal), within 4 Monte Carlo standard errors; once through the CLI.
3. A one-branch tree gives exactly `rigid hazard` on the same curve (rate and survival).
4. OpenQuake's own files (tests/data/openquake/README.md): the prior mean equals the engine's mean
   curve (case 7, weights 0.7/0.3; case 14, ten sites, weights 0.5/0.5) to its printed digits; the
   reweighted export read back gives the posterior as its prior; the engine 3.7 export read as is.
5. Several rocks: survival is the product of each rock's own; --prune: Stirling's rule.
6. Bad input: one stderr line naming the file and line (or the option), exit 2.

    /usr/bin/python3 -m pytest tests/python/test_hazard_reweight.py [--rigid RIGID]
"""
import csv
import json
import math
import os
import shutil

import pytest

np = pytest.importorskip("numpy")
pytest.importorskip("h5py")
pytest.importorskip("scipy")

import openquake_layout as ol  # noqa: E402  (exports written in the documented layout)
import synthetic_cube as tp  # noqa: E402
from rigidpy.exposure_age import ExposureAge  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
FIXTURES = os.path.join(HERE, "..", "data", "openquake")
IMLS = np.geomspace(0.02, 6.0, 40)
FAST = ("--bootstrap", "20")


@pytest.fixture(scope="module")
def cube(tmp_path_factory):
    """A cube of two planted rocks: `rock` (the probit model of synthetic_cube) and `weak` (median
    halved)."""
    folder = tmp_path_factory.mktemp("cube")
    rng = np.random.default_rng(20260301)
    pgv = np.exp(rng.uniform(math.log(0.035), math.log(0.5), 30))
    rock = tp.planted_outcomes(rng, pgv, tp.MU0, tp.MU1, tp.SIGMA)
    weak = tp.planted_outcomes(rng, pgv, tp.MU0 - math.log(2), tp.MU1, tp.SIGMA)
    path = str(folder / "rocks.h5")
    tp.write_cube(path, pgv, [("rock", rock, {"alpha_rad": tp.ALPHA, "p_rad_s": tp.P}), ("weak", weak, {})])
    return path


def power_law_export(folder, branches, t=1.0):
    """branches: [(k0, k, weight)] -> an export of their PoEs over t years."""
    rows = [(f"b{i}~k{k:g}", w, -np.expm1(-k0 * IMLS ** -k * t)) for i, (k0, k, w) in enumerate(branches)]
    return ol.write_export(folder, rows, IMLS, t)


def run_json(tool, *args):
    p = tool("hazard", "reweight", *args, "--json")
    assert p.returncode == 0, f"rigid hazard reweight exit {p.returncode}: {p.stderr.strip()}"
    return json.loads(p.stdout)


def closed_rate(k0, k, theta, beta):
    return k0 * theta ** -k * math.exp(0.5 * k * k * beta * beta)


def lognormal_of(doc, rock=0):
    (f,) = doc["rocks"][rock]["fragility"]
    return f["theta_g"], f["beta"]


# --------------------------------------------------------------------------------------------
# 1. closed form


def check_closed_form(tool, cube, folder, branches, age, label):
    power_law_export(folder, branches)
    doc = run_json(tool, folder, "--rock", f"{cube}:rock", "--age", repr(age), "--fragility-uncertainty", "none", *FAST)
    theta, beta = lognormal_of(doc)
    rates = [closed_rate(k0, k, theta, beta) for k0, k, _ in branches]
    survival = [math.exp(-r * age) for r in rates]
    total = sum(w * s for (_, _, w), s in zip(branches, survival))
    for b, (k0, k, w), r, s in zip(doc["branches"], branches, rates, survival):
        assert abs(b["toppling_rate_per_year"] / r - 1) < 0.01, (
            f"{label}: branch {b['rlz_id']} (k0 {k0:.3g}, k {k:.3g}): rate {b['toppling_rate_per_year']:.5g}, closed "
            f"form {r:.5g}")
        assert abs(b["posterior_weight"] - w * s / total) < 0.005, (
            f"{label}: branch {b['rlz_id']}: posterior {b['posterior_weight']:.4f}, closed form {w * s / total:.4f}")
        assert b["prior_weight"] == pytest.approx(w, abs=1e-7)
    return doc, theta, beta


def test_closed_form_fixed_and_planted_trees(tmp, tool, cube):
    fixed = [(1e-5, 2.0, 0.3), (3e-5, 2.5, 0.2), (1e-4, 2.2, 0.1), (5e-6, 3.0, 0.25), (2e-5, 1.5, 0.15)]
    doc, theta, beta = check_closed_form(tool, cube, os.path.join(tmp, "fixed"), fixed, 4000.0, "fixed tree")
    spread = [b["survival"] for b in doc["branches"]]
    assert min(spread) < 0.2 and max(spread) > 0.7, f"the fixed tree tells branches apart (survivals {spread})"

    seed = int.from_bytes(os.urandom(4), "little")
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 9))
    k = rng.uniform(1.5, 3.0, n)
    # k0, the rate at 1 g; at most 5 per year at the lowest level (a PoE that prints below 1)
    k0 = np.exp(rng.uniform(math.log(2e-6), np.log(np.minimum(5e-5, 5 * IMLS[0] ** k))))
    w = rng.dirichlet(np.ones(n))
    w = np.round(w / w.sum(), 7)
    w[-1] = 1 - w[:-1].sum()
    # an age at which the branches' survivals spread: the median rate's e-folding time
    age = 1.0 / float(np.median([closed_rate(a, b, theta, beta) for a, b in zip(k0, k)]))
    check_closed_form(tool, cube, os.path.join(tmp, "planted"), list(zip(k0, k, w)), age,
                      f"planted tree (seed {seed}, {n} branches)")


def test_bootstrap_members_and_pga(tmp, tool, cube):
    branches = [(1e-5, 2.0, 0.5), (6e-5, 2.6, 0.5)]
    folder = power_law_export(os.path.join(tmp, "tree"), branches)
    doc = run_json(tool, folder, "--rock", f"{cube}:rock", "--age", "5000", *FAST)
    members = doc["rocks"][0]["fragility_members"]
    assert len(members) >= 15, f"bootstrap members carried ({len(members)})"
    survival = []
    for k0, k, _ in branches:
        s = sum(m["weight"] * math.exp(-5000 * sum(l["weight"] * closed_rate(k0, k, l["theta_g"], l["beta"])
                                                   for l in m["lognormals"])) for m in members)
        survival.append(s / sum(m["weight"] for m in members))
    total = sum(w * s for (_, _, w), s in zip(branches, survival))
    for b, (_, _, w), s in zip(doc["branches"], branches, survival):
        assert abs(b["survival"] - s) < 0.005 and abs(b["posterior_weight"] - w * s / total) < 0.005, (
            f"branch {b['rlz_id']}: survival {b['survival']:.4f} and posterior {b['posterior_weight']:.4f}; the members' "
            f"closed forms give {s:.4f} and {w * s / total:.4f}")

    # one power-law branch: PGA exceeded at rate r is (k0 / r)^(1/k), before and after (one branch)
    single = power_law_export(os.path.join(tmp, "single"), [(2e-5, 2.4, 1.0)])
    doc = run_json(tool, single, "--rock", f"{cube}:rock", "--age", "100", "--fragility-uncertainty", "none", *FAST)
    for p in doc["pga_at_annual_rate"]:
        exact = (2e-5 / p["annual_rate"]) ** (1 / 2.4)
        assert abs(p["prior_mean_pga_g"] / exact - 1) < 0.01 and abs(p["change_percent"]) < 1e-9, (
            f"PGA at {p['annual_rate']:g}/yr: {p['prior_mean_pga_g']:.4f} g, closed form {exact:.4f} g; change "
            f"{p['change_percent']:.2g} % with one branch")


# --------------------------------------------------------------------------------------------
# 2. the age's distribution


def monte_carlo_survival(rng, nu, mean, sd, kind, n=1_000_000):
    if kind == "normal":
        t = rng.normal(mean, sd, int(n * 1.2))
        t = t[t > 0][:n]
    else:
        s2 = math.log1p((sd / mean) ** 2)
        t = rng.lognormal(math.log(mean) - s2 / 2, math.sqrt(s2), n)
    v = np.exp(-nu * t)
    return v.mean(), v.std() / math.sqrt(len(v))


def test_age_distribution_against_monte_carlo(tmp, tool, cube):
    rng = np.random.default_rng(7)
    for kind in ("normal", "lognormal"):
        for mean, sd in ((10000.0, 1500.0), (8000.0, 5000.0)):
            age = ExposureAge(mean, sd, kind)
            for nu in (2e-5, 1e-4, 4e-4):
                mc, se = monte_carlo_survival(rng, nu, mean, sd, kind)
                got = float(age.survival(nu))
                assert abs(got - mc) < 4 * se + 1e-12, (f"{kind} age {mean:g} +- {sd:g}, nu {nu:g}: survival {got:.6f}, "
                                                        f"Monte Carlo {mc:.6f} +- {se:.1e}")
    # through the command line: a lognormal age, the fitted fragility alone
    branches = [(1e-5, 2.0, 0.6), (5e-5, 2.5, 0.4)]
    folder = power_law_export(os.path.join(tmp, "tree"), branches)
    doc = run_json(tool, folder, "--rock", f"{cube}:rock", "--age", "9000", "--age-sd", "3000", "--age-dist",
                   "lognormal", "--fragility-uncertainty", "none", *FAST)
    for b in doc["branches"]:
        mc, se = monte_carlo_survival(rng, b["toppling_rate_per_year"], 9000.0, 3000.0, "lognormal")
        assert abs(b["survival"] - mc) < 4 * se, f"CLI: branch {b['rlz_id']}: {b['survival']:.6f}, Monte Carlo {mc:.6f}"


# --------------------------------------------------------------------------------------------
# 3. one branch = rigid hazard


def test_one_branch_is_rigid_hazard(tmp, tool, cube):
    folder = power_law_export(os.path.join(tmp, "one"), [(3e-5, 2.3, 1.0)])
    curve = os.path.join(folder, "hazard_curve-rlz-000-PGA_42.csv")
    p = tool("hazard", cube, "--object", "rock", "--curve", curve, "--age", "6000", "--json", *FAST)
    assert p.returncode == 0, p.stderr
    single = json.loads(p.stdout)
    doc = run_json(tool, folder, "--rock", f"{cube}:rock", "--age", "6000", "--fragility-uncertainty", "none", *FAST)
    (b,) = doc["branches"]
    assert b["toppling_rate_per_year"] == single["annual_toppling_rate"], "the same rate as rigid hazard, exactly"
    assert b["survival"] == single["survival_probability"], "the same survival as rigid hazard, exactly"
    assert b["posterior_weight"] == 1.0


# --------------------------------------------------------------------------------------------
# 4. OpenQuake's own files


def old_layout_rows(path):
    """The engine's older export: `lon lat,poe poe ...` or bare `poe poe ...` per site."""
    rows = []
    for line in open(path).read().splitlines():
        site, _, poes = line.rpartition(",")
        rows.append((tuple(float(v) for v in site.split()) if site else None, [float(v) for v in poes.split()]))
    return rows


def test_openquake_case_7_mean(tmp, tool, cube):
    here = os.path.join(FIXTURES, "classical_case_7")
    b1 = old_layout_rows(os.path.join(here, "hazard_curve-smltp_b1-gsimltp_b1-ltr_0.csv"))[0][1]
    b2 = old_layout_rows(os.path.join(here, "hazard_curve-smltp_b2-gsimltp_b1-ltr_1.csv"))[0][1]
    engine_mean = old_layout_rows(os.path.join(here, "hazard_curve-mean.csv"))[0][1]
    # IMLs and investigation time of the case's job.ini; weights of its source_model_logic_tree.xml
    folder = ol.write_export(os.path.join(tmp, "case7"), [("b1~b1", 0.7, b1), ("b2~b1", 0.3, b2)], [0.1, 0.12, 0.2],
                             1.0, poe_format="{!r}")  # the engine's 10 digits, all kept
    out = os.path.join(tmp, "case7_reweighted")
    doc = run_json(tool, folder, "--rock", f"{cube}:weak", "--age", "20", "--fragility-uncertainty", "none",
                   "--write-curves", out, *FAST)
    mean = -np.expm1(-np.array(doc["curves"]["prior"]["mean"]))
    assert np.max(np.abs(mean - engine_mean)) < 2e-9, f"prior mean {mean} equals the engine's {engine_mean}"
    # the reweighted export read back: its realizations carry the posterior weights
    back = run_json(tool, out, "--rock", f"{cube}:weak", "--age", "20", "--fragility-uncertainty", "none", *FAST)
    assert [b["prior_weight"] for b in back["branches"]] == pytest.approx(
        [b["posterior_weight"] for b in doc["branches"]], abs=1e-7)
    assert back["curves"]["prior"]["mean"] == pytest.approx(doc["curves"]["posterior"]["mean"], rel=1e-6)
    assert "mean" in back["openquake_statistics"] and back["openquake_statistics"]["mean"]["max_abs_poe_difference"] < 1e-6


def test_openquake_case_14(tmp, tool, cube):
    here = os.path.join(FIXTURES, "classical_case_14")
    old = os.path.join(here, "engine_pre_3.7")
    a = old_layout_rows(os.path.join(old, "hazard_curve-smltp_simple_fault-gsimltp_AbrahamsonSilva2008-ltr_0.csv"))
    b = old_layout_rows(os.path.join(old, "hazard_curve-smltp_simple_fault-gsimltp_CampbellBozorgnia2008-ltr_1.csv"))
    engine_mean = old_layout_rows(os.path.join(old, "hazard_curve-mean.csv"))
    # the sites and IMLs of the engine 3.7 export of the same case
    lines = open(os.path.join(here, "hazard_curve-rlz-000_PGA.csv")).read().splitlines()
    imls = [float(c[4:]) for c in lines[1].split(",")[3:]]
    sites = [tuple(float(v) for v in line.split(",")[:2]) for line in lines[2:]]
    folder = os.path.join(tmp, "case14")
    ol.write_realizations(folder, [(0, "simple_fault~AbrahamsonSilva2008", 0.5),
                                   (1, "simple_fault~CampbellBozorgnia2008", 0.5)])
    for i, rows in enumerate((a, b)):
        # the layout's 7 significant digits would hide the engine's 10: written here with all of them
        path = ol.write_curve(folder, f"rlz-{i:03d}", imls, [], 50.0)
        with open(path, "a") as f:
            for site, (_, poes) in zip(sites, rows):
                f.write(f"{site[0]:.5f},{site[1]:.5f},0.00000," + ",".join(repr(max(p, 0.0)) for p in poes) + "\n")
    for s in (0, 4, 9):
        doc = run_json(tool, folder, "--rock", f"{cube}:rock", "--age", "500", "--site", f"{sites[s][0]},{sites[s][1]}",
                       "--fragility-uncertainty", "none", *FAST)
        mean = -np.expm1(-50.0 * np.array(doc["curves"]["prior"]["mean"]))
        assert np.max(np.abs(mean - engine_mean[s][1])) < 2e-9, f"site {sites[s]}: prior mean equals the engine's"

    # the engine 3.7 export as it is (with the realizations file written from the logic tree)
    p = tool("hazard", "reweight", here, "--rock", f"{cube}:rock", "--age", "500", *FAST)
    assert_one_line_error(p, "hazard_curve-rlz-000_PGA.csv", "line 4", "--site")
    doc = run_json(tool, here, "--rock", f"{cube}:rock", "--age", "500", "--site", "-122.39,38.1", *FAST)
    assert doc["site"].startswith("-122.39000,38.10000") and len(doc["branches"]) == 2


# --------------------------------------------------------------------------------------------
# 5. several rocks, pruning, outputs


def test_several_rocks_prune_and_outputs(tmp, tool, cube):
    branches = [(1e-5, 2.0, 0.25), (3e-5, 2.5, 0.25), (1e-4, 2.2, 0.25), (5e-6, 3.0, 0.25)]
    folder = power_law_export(os.path.join(tmp, "tree"), branches)
    common = ("--fragility-uncertainty", "none", *FAST)
    one = run_json(tool, folder, "--rock", f"{cube}:rock", "--age", "3000", *common)
    two = run_json(tool, folder, "--rock", f"{cube}:weak", "--age", "1000", "--age-sd", "200", *common)
    plot, table = os.path.join(tmp, "reweight.png"), os.path.join(tmp, "branches.csv")
    both = run_json(tool, folder, "--rock", f"{cube}:rock", "--age", "3000", "--rock", f"{cube}:weak", "--age", "1000",
                    "--age-sd", "200", "--plot", plot, "--csv", table, *common)
    s = np.array([a["survival"] * b["survival"] for a, b in zip(one["branches"], two["branches"])])
    assert [b["survival"] for b in both["branches"]] == pytest.approx(s, rel=1e-12), "survivals multiply"
    assert [b["posterior_weight"] for b in both["branches"]] == pytest.approx(0.25 * s / (0.25 * s).sum(), abs=1e-12)
    assert os.path.getsize(plot) > 20000, "the figure is written"
    paper_ready_figure(both, os.path.join(tmp, "reweight_again.pdf"))
    with open(table, newline="") as f:
        rows = list(csv.DictReader(f))
    assert [float(r["posterior_weight"]) for r in rows] == pytest.approx([b["posterior_weight"] for b in both["branches"]])
    assert list(rows[0])[:6] == ["rlz_id", "branch_path", "prior_weight", "toppling_rate_per_year", "survival",
                                 "posterior_weight"]

    # Stirling's rule: branches below P dropped, the others' prior weights renormalised
    survival = np.array([b["survival"] for b in one["branches"]])
    cut = float(np.sort(survival)[1]) + 1e-6  # drops the two least likely
    pruned = run_json(tool, folder, "--rock", f"{cube}:rock", "--age", "3000", "--prune", repr(cut), *common)
    keep = survival >= cut
    assert [b["posterior_weight"] for b in pruned["branches"]] == pytest.approx(keep * 0.25 / (0.25 * keep.sum()))
    # every branch pruned: no posterior, exit 2 (after the fit, whose progress line may precede it on a slow machine)
    p = tool("hazard", "reweight", folder, "--rock", f"{cube}:rock", "--age", "3000", "--prune", "0.999", *common)
    last = p.stderr.strip().splitlines()[-1]
    assert p.returncode == 2 and "realizations_42.csv" in last and "--prune 0.999" in last, p.stderr


# --------------------------------------------------------------------------------------------
# 6. bad input


def assert_one_line_error(p, *words):
    lines = p.stderr.strip().splitlines()
    assert p.returncode == 2 and len(lines) == 1, f"exit {p.returncode}, stderr {p.stderr!r}"
    for w in words:
        assert w in lines[0], f"{w!r} named in {lines[0]!r}"


def test_bad_inputs(tmp, tool, cube):
    good = [(1e-5, 2.0, 0.5), (3e-5, 2.5, 0.5)]

    def export(name):
        return power_law_export(os.path.join(tmp, name), good)

    def reweight(folder, *more):
        return tool("hazard", "reweight", folder, "--rock", f"{cube}:rock", "--age", "1000", *more, *FAST)

    def edit(path, old, new, count=1):
        text = open(path).read()
        assert old in text, (path, old)
        open(path, "w").write(text.replace(old, new, count))

    f = export("weights")
    edit(os.path.join(f, "realizations_42.csv"), "5.0000000E-01", "4.0000000E-01")
    assert_one_line_error(reweight(f), "realizations_42.csv", "lines 3-4", "sum to 0.9")

    f = export("no_realizations")
    os.remove(os.path.join(f, "realizations_42.csv"))
    assert_one_line_error(reweight(f), "realizations_*.csv", "no such file")

    f = export("missing_curve")
    os.remove(os.path.join(f, "hazard_curve-rlz-001-PGA_42.csv"))
    assert_one_line_error(reweight(f), "realizations_42.csv", "line 4", "realization 1")

    f = export("imls")
    edit(os.path.join(f, "hazard_curve-rlz-001-PGA_42.csv"), "poe-0.0200000", "poe-0.0210000")
    assert_one_line_error(reweight(f), "hazard_curve-rlz-001-PGA_42.csv", "line 2", "IMLs")

    f = export("imt_header")
    edit(os.path.join(f, "hazard_curve-rlz-000-PGA_42.csv"), "imt='PGA'", "imt='SA(0.2)'")
    assert_one_line_error(reweight(f), "hazard_curve-rlz-000-PGA_42.csv", "line 1", "SA(0.2)")

    f = export("imt_files")
    for i in (0, 1):
        os.rename(os.path.join(f, f"hazard_curve-rlz-00{i}-PGA_42.csv"), os.path.join(f, f"hazard_curve-rlz-00{i}-SA(1.0)_42.csv"))
    assert_one_line_error(reweight(f), "SA(1.0)", "no PGA")

    f = export("poe_one")
    path = os.path.join(f, "hazard_curve-rlz-000-PGA_42.csv")
    lines = open(path).read().splitlines()
    cells = lines[2].split(",")
    cells[3] = "1.000000E+00"
    open(path, "w").write("\n".join(lines[:2] + [",".join(cells)]) + "\n")
    assert_one_line_error(reweight(f), "hazard_curve-rlz-000-PGA_42.csv", "line 3", "outside [0, 1)")

    f = export("poe_rises")
    path = os.path.join(f, "hazard_curve-rlz-000-PGA_42.csv")
    lines = open(path).read().splitlines()
    cells = lines[2].split(",")
    cells[10] = "9.000000E-01"  # above the lower levels' PoEs
    open(path, "w").write("\n".join(lines[:2] + [",".join(cells)]) + "\n")
    assert_one_line_error(reweight(f), "hazard_curve-rlz-000-PGA_42.csv", "line 3", "does not increase")

    f = os.path.join(tmp, "sites")
    ol.write_realizations(f, [(0, "a", 1.0)])
    poe = -np.expm1(-1e-5 * IMLS ** -2.0)
    ol.write_curve(f, "rlz-000", IMLS, [((0.0, 0.0), poe), ((1.0, 1.0), poe)], 1.0)
    assert_one_line_error(reweight(f), "hazard_curve-rlz-000-PGA_42.csv", "line 4", "--site")

    for age in ("0", "-5"):
        p = tool("hazard", "reweight", export("age"), "--rock", f"{cube}:rock", "--age", age)
        assert_one_line_error(p, f"--age {age}", "positive")
    shutil.rmtree(os.path.join(tmp, "age"))


def paper_ready_figure(document, path):
    """The figure drawn again from the command's --json document, measured as drawn
    (figure_checks.py: page width, 8 pt type, nothing under a legend, no overlaps, no empty axes)."""
    import figure_checks
    import matplotlib.pyplot as plt
    from rigidpy import reweight_figure

    def nan_for_none(v):  # the JSON's null is the report's NaN
        if isinstance(v, dict):
            return {k: nan_for_none(x) for k, x in v.items()}
        if isinstance(v, list):
            return [nan_for_none(x) for x in v]
        return math.nan if v is None else v

    fig = reweight_figure.draw(path, nan_for_none(document), [])
    try:
        found = figure_checks.problems(fig)
        assert found == [], f"rigid hazard reweight --plot: {found}"
        assert open(path, "rb").read(4) == b"%PDF", "a .pdf name writes a pdf"
    finally:
        plt.close(fig)
