"""`rigid fragility` and `rigid hazard` (src/python/rigidpy/fragility.py) against independent oracles:

1. Rate of toppling: a lognormal fragility under a power-law hazard H(a) = k0 a^-k has the closed
   form lambda = k0 theta^-k exp(k^2 beta^2 / 2); the integration matches within 0.5 % over k 1-4
   and beta 0.1-0.8, survival exp(-lambda T) likewise. A curved (log-quadratic) hazard against
   scipy's adaptive quadrature of P(a) |H'(a)|. The PGA factor that rules a power-law curve out is
   the k-th root of the rate factor.
2. Curve layouts: two columns, OpenQuake's poe-IML export (annual rate -ln(1 - poe) / T), the
   nshmp-haz layout with several sites.
3. End to end on a cube written here in the documented layout: each bin's theta, beta equal
   statsmodels' probit GLM on the cube's simulated cells counted here; the hazard command's rate
   equals the closed form of the lognormal it reports; the /fragility group holds what --json
   printed; --no-store leaves the cube's bytes alone.
4. NRML: parsed back, the structure is the OpenQuake documentation's fragility example element for
   element (continuous, logncdf), and its mean/stddev give back theta, beta.
5. Bad input: one stderr line naming the file (and the line), exit 2.

    /usr/bin/python3 -m pytest tests/python/test_hazard.py [--rigid RIGID]

With --rigid (the built executable) the command-line cases go through `rigid fragility|hazard`;
without it, through the package's launcher. Skipped without numpy, scipy, h5py or statsmodels.
"""
import csv
import json
import math
import os
import xml.etree.ElementTree as ET

import pytest

np = pytest.importorskip("numpy")
h5py = pytest.importorskip("h5py")
sm = pytest.importorskip("statsmodels.api", reason="install python3-statsmodels")
from scipy import integrate  # noqa: E402
from scipy.special import ndtr, ndtri  # noqa: E402

import synthetic_cube as tp  # noqa: E402  (the synthetic cube writer of the documented layout)
from rigidpy import hazard as hc  # noqa: E402

NS = "{http://openquake.org/xmlns/nrml/0.5}"


def write_two_column(path, a, h, header=True):
    with open(path, "w") as f:
        if header:
            f.write("pga_g,annual_rate\n")
        for x, y in zip(a, h):
            f.write(f"{x!r},{y!r}\n")


# --------------------------------------------------------------------------------------------
# 1. the rate against closed forms and quadrature


def test_closed_forms(tmp):
    a = np.geomspace(0.005, 5.0, 30)
    worst, worst_s = 0.0, 0.0
    for k in (1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0):
        k0 = 2e-5
        path = os.path.join(tmp, f"power_{k}.csv")
        write_two_column(path, a, k0 * a**-k)
        curve = hc.read_curve(path)
        for beta in (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8):
            for theta in (0.15, 0.6):
                exact = k0 * theta**-k * math.exp(0.5 * k * k * beta * beta)
                lam, _ = hc.toppling_rate(curve, theta, beta)
                worst = max(worst, abs(lam / exact - 1))
                T = 0.2 / exact  # survival exp(-0.2) at the exact rate: a sensitive range
                worst_s = max(worst_s, abs(hc.survival(lam, T) / math.exp(-exact * T) - 1))
    assert worst < 0.005, (f"power-law hazard: lambda = k0 theta^-k exp(k^2 beta^2/2) within 0.5 % over k 1-4, "
                         f"beta 0.1-0.8 (worst {100 * worst:.4f} %)")
    assert worst_s < 0.005, f"survival exp(-lambda T) within 0.5 % of the closed form (worst {100 * worst_s:.4f} %)"

    # a curve that bends in log-log: ln H = c0 + c1 ln a + c2 (ln a)^2, sampled at 40 points, against
    # scipy's quad of P(a) |dH/da| on the exact curve
    # (steepening with PGA as real curves do; decreasing over the sampled 0.02-5 g)
    c0, c1, c2 = math.log(1e-4), -2.2, -0.15
    exact_h = lambda x: math.exp(c0 + c1 * math.log(x) + c2 * math.log(x) ** 2)
    a = np.geomspace(0.02, 5.0, 40)
    path = os.path.join(tmp, "bent.csv")
    write_two_column(path, a, [exact_h(x) for x in a])
    curve = hc.read_curve(path)
    worst = 0.0
    for theta, beta in ((0.2, 0.25), (0.5, 0.4), (1.0, 0.25), (0.35, 0.5)):
        def integrand(ln_x):
            x = math.exp(ln_x)
            dh_dlnx = exact_h(x) * (c1 + 2 * c2 * ln_x)  # dH / d ln a
            return float(ndtr(math.log(x / theta) / beta)) * -dh_dlnx
        ref, _ = integrate.quad(integrand, math.log(0.02), math.log(100.0), limit=400, epsabs=0, epsrel=1e-10)
        lam, ext = hc.toppling_rate(curve, theta, beta)
        worst = max(worst, abs(lam / ref - 1))
    assert worst < 0.005, (f"log-quadratic hazard: rate within 0.5 % of quadrature of P(a)|H'(a)| on the exact curve "
                         f"(worst {100 * worst:.3f} %)")

    # a curve that ends at rate 0 (nothing exceeds a_max): H = k0 a^-k up to a_max, 0 beyond, so
    # lambda = k0 E[C^-k; C <= a_max] = k0 theta^-k exp(k^2 beta^2/2) Phi(ln(a_max/theta)/beta + k beta)
    k, k0, a_max = 2.0, 1e-5, 0.8
    a = np.geomspace(0.01, a_max, 25)
    path = os.path.join(tmp, "ends.csv")
    write_two_column(path, list(a) + [1.0, 2.0], list(k0 * a**-k) + [0.0, 0.0])
    curve = hc.read_curve(path)
    worst = 0.0
    for theta, beta in ((0.4, 0.3), (0.7, 0.5), (1.2, 0.4)):
        exact = k0 * theta**-k * math.exp(0.5 * k * k * beta * beta) * float(ndtr(math.log(a_max / theta) / beta + k * beta))
        worst = max(worst, abs(hc.toppling_rate(curve, theta, beta)[0] / exact - 1))
    rate_factor, pga_factor = hc.ruling_factors(curve, [(1.0, 0.7, 0.5)], 1000.0, 0.95)
    assert worst < 0.005 and math.isfinite(rate_factor) and pga_factor > 0, (f"curve ending at rate 0: lambda = closed form of the truncated power law (worst {100 * worst:.3f} %), "
          f"ruling factors finite")

    # ruling out: PGA x f multiplies a power-law H by f^k, so the PGA factor is the rate factor^(1/k)
    k, k0, theta, beta, years, conf = 2.5, 2e-5, 0.4, 0.45, 12000.0, 0.95
    path = os.path.join(tmp, "rule.csv")
    write_two_column(path, np.geomspace(0.005, 5.0, 30), k0 * np.geomspace(0.005, 5.0, 30) ** -k)
    curve = hc.read_curve(path)
    rate_factor, pga_factor = hc.ruling_factors(curve, [(1.0, theta, beta)], years, conf)
    exact_rate = k0 * theta**-k * math.exp(0.5 * k * k * beta * beta)
    exact_factor = -math.log(1 - conf) / years / exact_rate
    assert abs(rate_factor / exact_factor - 1) < 0.005, f"rate factor to rule out {rate_factor:.4f} = -ln(1 - c)/(T lambda) {exact_factor:.4f}"
    assert abs(pga_factor / exact_factor ** (1 / k) - 1) < 0.005, f"PGA factor to rule out {pga_factor:.4f} = rate factor^(1/k) {exact_factor ** (1 / k):.4f}"


# --------------------------------------------------------------------------------------------
# 2. layouts


def test_layouts(tmp):
    imls = [0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0]
    poes = [0.9, 0.7, 0.45, 0.2, 0.08, 0.025, 0.004, 6e-4, 5e-5]
    oq = os.path.join(tmp, "hazard_curve-mean-PGA_27.csv")
    with open(oq, "w") as f:
        f.write("#,,,,,,,,,,\"generated_by='OpenQuake engine 3.16', start_date='2026-01-01', checksum=1, "
                "kind='mean', investigation_time=50.0, imt='PGA'\"\n")
        f.write("lon,lat,depth," + ",".join(f"poe-{v}" for v in imls) + "\n")
        f.write("-117.1,34.2,0.0," + ",".join(repr(p) for p in poes) + "\n")
    c = hc.read_curve(oq)
    want = [-math.log(1 - p) / 50.0 for p in poes]
    assert np.allclose(c.pga_g, imls) and np.allclose(c.rate, want, rtol=1e-12), "OpenQuake poe-IML export: PGAs read, rates = -ln(1 - poe) / investigation_time"

    nshmp = os.path.join(tmp, "nshmp_curves.csv")
    with open(nshmp, "w") as f:
        f.write("name,lon,lat," + ",".join(str(v) for v in imls) + "\n")
        f.write("Lovejoy Buttes,-117.83,34.59," + ",".join(repr(r * 2) for r in want) + "\n")
        f.write("Granite Dells,-116.45,33.75," + ",".join(repr(r) for r in want) + "\n")
    c = hc.read_curve(nshmp, "Granite Dells")
    c1 = hc.read_curve(nshmp, "1")
    c0 = hc.read_curve(nshmp, "-117.83,34.59")
    assert (np.allclose(c.rate, want) and np.allclose(c1.rate, want) and np.allclose(c0.rate, 2 * np.array(want))
          and c.site.startswith("Granite Dells")), "nshmp-haz layout: a site chosen by name, lon,lat or index"
    try:
        hc.read_curve(nshmp)
        assert False, "several sites without --site refused"
    except hc.CurveError as e:
        assert "2 sites" in str(e) and nshmp in str(e), f"several sites without --site refused ({e})"
    plain = os.path.join(tmp, "plain.txt")
    write_two_column(plain, imls, want, header=False)
    assert np.allclose(hc.read_curve(plain).rate, want), "two columns without a header"


# --------------------------------------------------------------------------------------------
# 3. end to end on a cube


def bin_cells(outcome, pgv_pga, lo, hi):
    """(ln PGA, overturned, simulated) rows of the bin's records, counted from the outcome codes
    (1 survived, 2 overturned; inferred 3, failed 4 and not run 0 are not simulations)."""
    recs = [r for r in range(len(pgv_pga)) if lo <= pgv_pga[r] < hi]
    over = (outcome[recs] == 2).sum(axis=(0, 2)).astype(float)
    sim = over + (outcome[recs] == 1).sum(axis=(0, 2))
    keep = sim > 0
    return np.log(tp.SCALES[keep]), over[keep], sim[keep], len(recs)


def statsmodels_lognormal(u, k, n):
    X = np.column_stack([np.ones_like(u), u])
    res = sm.GLM(np.column_stack([k, n - k]), X, family=sm.families.Binomial(sm.families.links.probit())).fit(
        tol=1e-12, maxiter=200)
    b0, b1 = res.params
    return math.exp(-b0 / b1), 1.0 / b1  # P = Phi(b0 + b1 ln a) = Phi(ln(a / theta) / beta)


def end_to_end(tmp, tool):
    rng = np.random.default_rng(20261125)
    pgv = np.exp(rng.uniform(math.log(0.035), math.log(0.5), tp.R))
    outcome = tp.planted_outcomes(rng, pgv, tp.MU0, tp.MU1, tp.SIGMA)
    never = np.ones_like(outcome)
    cube = os.path.join(tmp, "planted.h5")
    tp.write_cube(cube, pgv, [("rock", outcome, {"alpha_rad": tp.ALPHA, "p_rad_s": tp.P}), ("stout", never, {})])
    out_csv, out_xml = os.path.join(tmp, "fits.csv"), os.path.join(tmp, "fits.xml")
    p = tool("fragility", cube, "--object", "rock", "--bootstrap", "60", "--csv", out_csv, "--nrml", out_xml, "--json")
    assert p.returncode == 0, f"rigid fragility exit {p.returncode} {p.stderr.strip()}"
    if p.returncode != 0:
        return
    doc = json.loads(p.stdout)
    rock = doc["objects"][0]
    worst = 0.0
    fitted = 0
    for b in rock["bins"]:
        if "theta_g" not in b:
            continue
        upper = math.inf if b["upper_s"] is None else b["upper_s"]  # JSON has no infinity: null
        u, k, n, nrec = bin_cells(outcome, pgv, b["lower_s"], upper)
        theta, beta = statsmodels_lognormal(u, k, n)
        worst = max(worst, abs(b["theta_g"] / theta - 1), abs(b["beta"] / beta - 1))
        fitted += 1
        if not (b["theta_interval_g"][0] < b["theta_g"] < b["theta_interval_g"][1]
                and b["beta_interval"][0] < b["beta"] < b["beta_interval"][1]):
            assert False, f"bin {b['bin']}: the estimate inside its interval"
        if b["n_records"] != nrec or b["n_cells"] != int(n.sum()):
            assert False, f"bin {b['bin']}: {b['n_records']} records, {b['n_cells']} cells; counted {nrec}, {int(n.sum())}"
    assert fitted >= 8 and worst < 1e-6, (f"{fitted} bins: theta, beta equal statsmodels' probit GLM on the cube's "
                                        f"simulated cells (largest relative difference {worst:.1e})")
    inferred = int((outcome == 3).sum())
    assert rock["inferred_cells_left_out"] == inferred, f"inferred cells reported left out ({inferred})"

    # the planted model at the chosen PGV/PGA: u = ln PGA, mu = MU0 + MU1 ln s (un-normalised)
    pt = rock["vector"]["points"][0]
    planted_theta = math.exp(tp.MU0 + tp.MU1 * math.log(pt["pgv_pga_s"]))
    assert abs(math.log(pt["theta_g"] / planted_theta)) < 0.08 and abs(pt["beta"] / tp.SIGMA - 1) < 0.15, (f"vector fit at PGV/PGA {pt['pgv_pga_s']:.3f} s: theta {pt['theta_g']:.3f} g (planted {planted_theta:.3f}), "
          f"beta {pt['beta']:.3f} (planted {tp.SIGMA})")

    with open(out_csv, newline="") as fh:
        rows = list(csv.DictReader(fh))
    bins = [b for b in rock["bins"] if b["n_records"] > 0]
    assert (len(rows) == len(bins) + 1 and all(r["object"] == "rock" for r in rows)
          and all(abs(float(r["theta_g"]) - b["theta_g"]) < 1e-12 for r, b in zip(rows, bins) if "theta_g" in b)
          and {"theta_lower_g", "theta_upper_g", "beta_lower", "beta_upper", "n_records", "n_cells"} <= set(rows[0])), f"CSV: one row per bin and the vector fit, with intervals and counts ({len(rows)} rows)"

    nrml_check(out_xml, bins, float(tp.SCALES.min()), float(tp.SCALES.max()))

    with h5py.File(cube, "r") as f:
        g = f["fragility/rock"]
        stored = g["theta_g"][...]
        want = np.array([b.get("theta_g", np.nan) or np.nan for b in rock["bins"]], float)
        assert (np.allclose(stored, want, equal_nan=True) and np.allclose(
            g["beta"][...], [b.get("beta", np.nan) or np.nan for b in rock["bins"]], equal_nan=True)
              and "method" in f["fragility"].attrs and g.attrs["fitted_cells_sha256"] is not None
              and np.array_equal(f["objects/rock/outcome"][...], outcome)), "cube: /fragility/rock holds the printed fits and the method; the cells untouched"
    with open(cube, "rb") as fh:
        before = fh.read()
    p = tool("fragility", cube, "--object", "rock", "--bootstrap", "20", "--no-store")
    with open(cube, "rb") as fh:
        assert p.returncode == 0 and fh.read() == before, "--no-store leaves the cube's bytes as they were"

    # hazard: the reported lognormal under a power-law curve gives the closed-form rate
    k, k0, years = 2.8, 3e-6, 15000.0
    curve = os.path.join(tmp, "power.csv")
    a = np.geomspace(0.01, 5, 25)
    write_two_column(curve, a, k0 * a**-k)
    plot = os.path.join(tmp, "hazard.png")
    p = tool("hazard", cube, "--object", "rock", "--curve", curve, "--age", str(years), "--bootstrap", "60",
             "--json", "--plot", plot)
    assert p.returncode == 0, f"rigid hazard exit {p.returncode} {p.stderr.strip()}"
    if p.returncode == 0:
        r = json.loads(p.stdout)
        f0 = r["fragility"][0]
        exact = k0 * f0["theta_g"] ** -k * math.exp(0.5 * k * k * f0["beta"] ** 2)
        lo, hi = r["annual_toppling_rate_interval"]
        assert abs(r["annual_toppling_rate"] / exact - 1) < 0.005 and lo < r["annual_toppling_rate"] < hi, (f"hazard: rate {r['annual_toppling_rate']:.4e} = closed form {exact:.4e} of the reported lognormal, "
              f"inside its interval [{lo:.3e}, {hi:.3e}]")
        assert (abs(r["survival_probability"] - math.exp(-exact * years)) < 1e-4
              and r["survival_probability_interval"][0] <= r["survival_probability"] <= r["survival_probability_interval"][1]), f"survival {r['survival_probability']:.4f} = exp(-lambda T) {math.exp(-exact * years):.4f}"
        assert r["ruled_out"] == (r["survival_probability"] < 0.05), "ruled out exactly when survival < 1 - confidence"
        with open(plot, "rb") as fh:
            assert fh.read(8) == b"\x89PNG\r\n\x1a\n", "hazard plot written (PNG)"

    # an object that never overturned has no fragility: one line, exit 2
    bad_input_case(tool, "object with no overturned cell", ["hazard", cube, "--object", "stout", "--curve", curve, "--age", "1000"],
                   [cube, "stout", "no overturned cell"])
    bad_input_case(tool, "fragility of an object with no overturned cell", ["fragility", cube, "--object", "stout", "--no-store"],
                   [cube, "no overturned cell"])

    # two records: a fit, but no interval (resampling two records shows nothing of other records)
    few = os.path.join(tmp, "few.h5")
    two = np.array([0.1, 0.11])
    tp.write_cube(few, two, [("rock", tp.planted_outcomes(rng, two, tp.MU0, tp.MU1, tp.SIGMA), {})])
    p = tool("fragility", few, "--json", "--no-store")
    if p.returncode == 0:
        b = [b for b in json.loads(p.stdout)["objects"][0]["bins"] if b["n_records"] > 0][0]
        assert b["theta_g"] > 0 and b["theta_interval_g"] == [None, None] and "interval_note" in b, f"2 records: theta {b['theta_g']:.3f} g, no interval ({b.get('interval_note')})"
    else:
        assert False, f"fragility of a 2-record cube: exit {p.returncode} {p.stderr.strip()}"
    return cube, curve


# --------------------------------------------------------------------------------------------
# 4. NRML


def nrml_check(path, bins, min_iml, max_iml):
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        assert False, f"NRML well formed ({e})"
        return
    assert root.tag == NS + "nrml", "NRML: root <nrml> in the NRML 0.5 namespace"
    models = list(root)
    assert (len(models) == 1 and models[0].tag == NS + "fragilityModel"
          and set(models[0].attrib) == {"id", "assetCategory", "lossCategory"}
          and models[0].get("assetCategory") == "buildings" and models[0].get("lossCategory") == "structural"), "NRML: one <fragilityModel id assetCategory lossCategory>"
    model = models[0]
    children = list(model)
    tags = [c.tag.replace(NS, "") for c in children]
    assert tags[:2] == ["description", "limitStates"] and all(t == "fragilityFunction" for t in tags[2:]), "NRML: <description>, <limitStates>, then the <fragilityFunction>s (the documentation's order)"
    limit_states = children[1].text.split()
    assert limit_states == ["overturned"], f"NRML: limit states {limit_states}"
    functions = children[2:]
    fitted = [b for b in bins if "theta_g" in b]
    assert len(functions) == len(fitted), f"NRML: one function per fitted PGV/PGA bin ({len(functions)})"
    ids = [fn.get("id") for fn in functions]
    assert len(set(ids)) == len(ids), "NRML: function ids unique"
    worst = 0.0
    for fn, b in zip(functions, fitted):
        ok = (fn.attrib == {"id": fn.get("id"), "format": "continuous", "shape": "logncdf"}
              and [c.tag.replace(NS, "") for c in fn] == ["imls", "params"])
        imls, params = fn[0], fn[1]
        ok = ok and set(imls.attrib) == {"imt", "noDamageLimit", "minIML", "maxIML"} and imls.get("imt") == "PGA"
        ok = ok and set(params.attrib) == {"ls", "mean", "stddev"} and params.get("ls") == "overturned"
        # minIML = noDamageLimit = the lower of the lowest scale and the PGA where P = 1e-4 (OpenQuake
        # sets P = 0 at or below the limit and evaluates max(PGA, minIML))
        lower = min(min_iml, b["theta_g"] * math.exp(b["beta"] * float(ndtri(1e-4))))
        ok = ok and abs(float(imls.get("minIML")) / lower - 1) < 1e-9 and abs(float(imls.get("maxIML")) - max_iml) < 1e-12
        ok = ok and float(imls.get("noDamageLimit")) == float(imls.get("minIML"))
        if not ok:
            assert False, f"NRML function {fn.get('id')}: the documentation's continuous-function structure"
            continue
        # linear moments of the lognormal capacity back to its median and dispersion
        mean, sd = float(params.get("mean")), float(params.get("stddev"))
        beta = math.sqrt(math.log(1 + (sd / mean) ** 2))
        theta = mean / math.sqrt(1 + (sd / mean) ** 2)
        worst = max(worst, abs(theta / b["theta_g"] - 1), abs(beta / b["beta"] - 1))
        ndl = float(imls.get("noDamageLimit"))
        p_ndl = float(ndtr(math.log(ndl / b["theta_g"]) / b["beta"]))
        worst = max(worst, max(p_ndl / 1e-4 - 1, 0) * 1e-6)  # P at the limit at most 1e-4
    assert worst < 1e-9, (f"NRML: mean, stddev (linear) give back theta, beta; P <= 1e-4 at noDamageLimit "
                        f"(worst {worst:.1e})")


# --------------------------------------------------------------------------------------------
# 5. bad input


def bad_input_case(tool, name, args, fragments):
    p = tool(*args)
    lines = [ln for ln in p.stderr.splitlines() if ln.strip()]
    ok = p.returncode == 2 and len(lines) == 1 and "error" in lines[0] and all(f in lines[0] for f in fragments)
    assert ok, (f"bad input, {name}: exit {p.returncode}, {len(lines)} stderr line(s): "
              f"{lines[0] if lines else ''}")


def bad_inputs(tool, tmp, cube, good_curve):
    def curve(name, text):
        path = os.path.join(tmp, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def hazard(path):
        return ["hazard", cube, "--object", "rock", "--curve", path, "--age", "1000", "--bootstrap", "20"]

    cases = [
        ("curve not decreasing", curve("up.csv", "pga_g,rate\n0.1,1e-2\n0.2,1e-3\n0.4,2e-3\n"), ["up.csv", "line 4"]),
        ("negative rate", curve("neg.csv", "pga_g,rate\n0.1,1e-2\n0.2,-1e-3\n"), ["neg.csv", "line 3"]),
        ("wrong columns", curve("cols.csv", "pga_g,rate\n0.1,1e-2\n0.2,1e-3,7\n"), ["cols.csv", "line 3"]),
        ("three-column header", curve("three.csv", "site,pga,rate\na,0.1,1e-2\n"), ["three.csv", "line 1"]),
        ("not a number", curve("word.csv", "0.1,1e-2\n0.2,lots\n"), ["word.csv", "line 2"]),
        ("NaN rate", curve("nan.csv", "0.1,1e-2\n0.2,nan\n"), ["nan.csv", "line 2"]),
        ("PGAs not increasing", curve("pga.csv", "0.2,1e-2\n0.1,1e-3\n"), ["pga.csv", "line 2"]),
        ("OpenQuake curve of another IMT", curve("sa.csv", "#,\"investigation_time=50.0, imt='SA(1.0)'\"\n"
                                                 "lon,lat,depth,poe-0.1,poe-0.2\n1,2,0,0.1,0.01\n"), ["sa.csv", "SA(1.0)"]),
        ("OpenQuake poe of 1", curve("poe.csv", "#,\"investigation_time=50.0, imt='PGA'\"\n"
                                     "lon,lat,depth,poe-0.1,poe-0.2\n1,2,0,1.0,0.01\n"), ["poe.csv", "line 3"]),
        ("empty curve", curve("empty.csv", ""), ["empty.csv"]),
        ("missing curve", os.path.join(tmp, "absent.csv"), ["absent.csv", "no such file"]),
    ]
    for name, path, fragments in cases:
        bad_input_case(tool, name, hazard(path), fragments)
    bad_input_case(tool, "negative age", ["hazard", cube, "--object", "rock", "--curve", good_curve, "--age", "-5"], ["--age"])
    bad_input_case(tool, "age NaN", ["hazard", cube, "--object", "rock", "--curve", good_curve, "--age", "nan"], ["--age"])
    bad_input_case(tool, "no --object with two objects", ["hazard", cube, "--curve", good_curve, "--age", "100"], ["--object"])
    bad_input_case(tool, "unknown object", ["fragility", cube, "--object", "nope", "--no-store"], ["nope"])
    bad_input_case(tool, "missing cube", ["fragility", os.path.join(tmp, "none.h5")], ["none.h5"])
    not_hdf5 = curve("text.h5", "not a cube\n")
    bad_input_case(tool, "not an HDF5 file", ["fragility", not_hdf5], ["text.h5"])
    bad_input_case(tool, "unknown option", ["fragility", cube, "--frobnicate"], ["--frobnicate"])
    bad_input_case(tool, "bad PGV/PGA distribution", hazard(good_curve) + ["--pgv-pga-dist", "gamma:1,2"], ["--pgv-pga-dist"])


def test_end_to_end_and_bad_inputs(tmp, tool):
    cube, curve = end_to_end(tmp, tool)
    bad_inputs(tool, tmp, cube, curve)
