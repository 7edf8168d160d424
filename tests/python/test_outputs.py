"""What `rigid fragility`, `rigid hazard` and `rigid plot` print and draw says what it means, checked
against independent oracles on synthetic cubes with planted probit outcomes (test_plot.py's writer):

1. Tiny probabilities in scientific notation with the exponent scipy.stats.norm.logsf gives; a
   survival probability of exp(-21) (a power-law hazard set by the closed form
   lambda = k0 theta^-k exp(k^2 beta^2 / 2) so that lambda T = 21) printed as 7.58e-10, not 0.0000.
2. A hazard curve ending below the fragility's range warned about, with P(topple) at its end equal
   to the lognormal's CDF there; no "inf" or "x 0" factors.
3. The NRML's maxIML where the lognormal CDF reaches 0.99 (closed form theta exp(beta Phi^-1(0.99))
   from the exported mean and stddev), or the campaign's top scale when higher, or (option) the top
   scale; noDamageLimit = minIML, the lower of the lowest scale and the PGA where P = 1e-4 (OpenQuake
   would zero the curve between a higher limit and minIML); id, assetCategory and lossCategory from
   the options (test_openquake_nrml.py reads the exports with OpenQuake itself).
4. Bins fitted on fewer than 3 records flagged in the table and the CSV; left out of the NRML by
   --nrml-min-records.
5. Bootstrap intervals reaching beyond the campaign's scales flagged.
6. The bootstrap progress line: silent for the first 5 s, then one line per 5 s with a fixed
   denominator (a clock under the test's control).
7. `rigid plot maps`: one panel per bin with records (no empty panel), alpha to 3 significant
   digits, --format pdf and svg files; the hazard plot's legend off both panels.

    /usr/bin/python3 -m pytest tests/python/test_outputs.py

Skipped without numpy, scipy, h5py or matplotlib.
"""
import csv
import io
import json
import math
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest

np = pytest.importorskip("numpy")
matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.figure  # noqa: E402
from scipy import stats  # noqa: E402

import synthetic_cube as tp  # noqa: E402  (the synthetic cube writer of the documented layout)
from rigidpy import fragility as rf  # noqa: E402
from rigidpy import fragility_report as report  # noqa: E402
from rigidpy import plot as rp  # noqa: E402
from rigidpy import progress  # noqa: E402

PYTHON_DIR = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src", "python"))
FRAGILITY = os.path.join(PYTHON_DIR, "rigid_fragility.py")
PLOT = os.path.join(PYTHON_DIR, "rigid_plot.py")
NS = "{http://openquake.org/xmlns/nrml/0.5}"


def run(script, *args):
    return subprocess.run([sys.executable, script, *args], capture_output=True, text=True)


def write_curve(path, a, h):
    with open(path, "w") as f:
        f.write("pga_g,annual_rate\n")
        for x, y in zip(a, h):
            f.write(f"{x!r},{y!r}\n")


# --------------------------------------------------------------------------------------------
# 1. scientific notation against scipy's log survival function


def test_scientific_notation():
    for z in (4.0, 6.0, 8.0, 12.0, 20.0, 30.0):
        p = float(stats.norm.sf(z))
        log10 = float(stats.norm.logsf(z)) / math.log(10)
        text = report.fmt_probability(p)
        m = re.fullmatch(r"(\d\.\d+)e([+-]\d+)", text)
        assert (m is not None and int(m.group(2)) == math.floor(log10)
              and abs(float(m.group(1)) - 10 ** (log10 - math.floor(log10))) < 1e-3), f"P = Phi(-{z:g}) prints as {text}: exponent {math.floor(log10)} from norm.logsf"
    assert report.fmt_probability(0.4321) == "0.4321" and report.fmt_probability(0.0) == "0", "ordinary probabilities stay fixed-point (0.4321), zero prints as 0"
    assert report.fmt_probability(0.0049) == "4.900e-03", "0.0049 keeps its two significant digits (4.900e-03)"


def planted_cube(path, rng, mu0, two_record_bin=True):
    """40 records: PGV/PGA log-uniform over 0.1-0.34 s, and (two_record_bin) 2 records at 0.07 s
    (bin 0.06-0.08 s); alpha an awkward 0.123456789 rad for the title test."""
    pgv = list(np.exp(rng.uniform(math.log(0.1), math.log(0.34), 38))) + ([0.07, 0.07] if two_record_bin else [0.2, 0.2])
    pgv = np.array(pgv)
    tp.write_cube(path, pgv, [("rock", tp.planted_outcomes(rng, pgv, mu0, tp.MU1, tp.SIGMA, extras=False),
                               {"alpha_rad": 0.123456789, "p_rad_s": 2.2})])
    return pgv


# --------------------------------------------------------------------------------------------
# 2., 1. (end to end) the hazard report


@pytest.fixture(scope="module")
def planted(tmp_path_factory):
    """(directory, cube, records' PGV/PGA) shared by the tests below."""
    tmp = str(tmp_path_factory.mktemp("outputs"))
    rng = np.random.default_rng(20261126)
    cube = os.path.join(tmp, "planted.h5")
    # mu0 -1.2: theta 0.95 g at PGV/PGA 0.1 s, whose P = 0.99 lies beyond the top scale of 2 g
    pgv = planted_cube(cube, rng, -1.2)
    return tmp, cube, pgv


def test_hazard_report(planted):
    tmp, cube, _ = planted
    flat = os.path.join(tmp, "flat.csv")
    write_curve(flat, [0.001, 100.0], [1e-2, 1e-12])  # any curve: the fit is what --json reports
    r = run(FRAGILITY, "hazard", cube, "--curve", flat, "--age", "1000", "--json", "--bootstrap", "20")
    assert r.returncode == 0, f"hazard --json runs ({r.stderr.strip()[:200]})"
    if r.returncode:
        return
    fit = json.loads(r.stdout)["fragility"][0]
    theta, beta = fit["theta_g"], fit["beta"]
    # a power-law curve H = k0 a^-k over 1e-4..1e3 g whose closed-form rate gives lambda T = 21
    k, years = 2.0, 1000.0
    k0 = 21.0 / years * theta ** k / math.exp(k * k * beta * beta / 2)
    a = np.geomspace(1e-4, 1e3, 60)
    steep = os.path.join(tmp, "steep.csv")
    write_curve(steep, a, k0 * a ** -k)
    r = run(FRAGILITY, "hazard", cube, "--curve", steep, "--age", f"{years:g}", "--bootstrap", "20")
    m = re.search(r"P\(survives 1000 years\) = exp\(-lambda T\) = (\S+)", r.stdout)
    printed = m.group(1) if m else ""
    assert (r.returncode == 0 and re.fullmatch(r"\d\.\d{3}e-10", printed) is not None
          and abs(float(printed) / math.exp(-21) - 1) < 0.01), f"survival exp(-21) = {math.exp(-21):.4g} prints as {printed!r} (scientific, exponent -10)"
    assert "0.0000 [" not in r.stdout and " inf" not in r.stdout, "no 0.0000 interval, no inf in the report"

    # a curve that ends (rate 0) at 0.03 g, far below a fragility of ~0.5 g
    short = os.path.join(tmp, "short.csv")
    write_curve(short, [0.005, 0.01, 0.025, 0.03], [1e-1, 1e-2, 1e-3, 0.0])
    r = run(FRAGILITY, "hazard", cube, "--curve", short, "--age", "1000", "--bootstrap", "20")
    p_end = stats.norm.cdf(math.log(0.025 / theta) / beta)
    m = re.search(r"warning: the hazard curve ends at 0\.025 g, where P\(topple \| PGA\) is only (\S+):", r.stdout)
    assert r.returncode == 0 and m is not None and abs(float(m.group(1)) / p_end - 1) < 0.01, (f"a curve ending at 0.025 g warns, P(topple) there {m.group(1) if m else None} = Phi(ln(0.025/theta)/beta) "
          f"= {p_end:.3e}")
    assert not re.search(r"\binf\b|x 0(\.0+)?\b|\bx nan\b", r.stdout), "no 'inf', 'x 0' or 'x nan' factor when the rate is 0"
    assert "no factor on its rates rules it out" in r.stdout, "rate 0 said in words"

    # the same curve extended by its power law: the share of the rate from beyond is warned about
    open_end = os.path.join(tmp, "open.csv")
    write_curve(open_end, [0.005, 0.01, 0.025], [1e-1, 1e-2, 1e-3])
    r = run(FRAGILITY, "hazard", cube, "--curve", open_end, "--age", "1000", "--bootstrap", "20")
    assert ("warning: the hazard curve ends at 0.025 g" in r.stdout and "power-law extension" in r.stdout
          and re.search(r"warning: 100\.0 % of the rate comes from PGAs outside", r.stdout) is not None), "an extended curve: both warnings (ends below the fragility, 100 % of the rate extrapolated)"
    # a curve covering the fragility: no warning
    r = run(FRAGILITY, "hazard", cube, "--curve", steep, "--age", "1000", "--bootstrap", "20")
    assert "warning" not in r.stdout, "a curve covering the fragility: no warning"


# --------------------------------------------------------------------------------------------
# 3., 4. NRML and the few-record bin


def lognormal_of(mean, stddev):
    beta = math.sqrt(math.log1p((stddev / mean) ** 2))
    return mean * math.exp(-beta * beta / 2), beta


def test_nrml_and_flags(planted):
    tmp, cube, _ = planted
    top = float(tp.SCALES.max())
    xml = os.path.join(tmp, "f.xml")
    out_csv = os.path.join(tmp, "f.csv")
    r = run(FRAGILITY, "fragility", cube, "--nrml", xml, "--csv", out_csv, "--no-store", "--bootstrap", "20",
            "--nrml-id", "sp1_overturning", "--nrml-asset-category", "pbr", "--nrml-loss-category", "rock")
    assert r.returncode == 0, f"fragility --nrml runs ({r.stderr.strip()[:200]})"
    if r.returncode:
        return
    model = ET.parse(xml).getroot().find(f"{NS}fragilityModel")
    assert (model.get("id"), model.get("assetCategory"), model.get("lossCategory")) == ("sp1_overturning", "pbr", "rock"), "NRML id, assetCategory, lossCategory from the options"
    beyond = 0
    ok = True
    functions = model.findall(f"{NS}fragilityFunction")
    for fn in functions:
        imls, params = fn.find(f"{NS}imls"), fn.find(f"{NS}params")
        theta, beta = lognormal_of(float(params.get("mean")), float(params.get("stddev")))
        q99 = theta * math.exp(beta * stats.norm.ppf(0.99))
        want = max(q99, top)
        got = float(imls.get("maxIML"))
        ok &= abs(got / want - 1) < 1e-9 and stats.norm.cdf(math.log(got / theta) / beta) >= 0.99 - 1e-9
        beyond += got > top * (1 + 1e-9)
    assert ok and functions, f"maxIML of all {len(functions)} functions = max(theta exp(beta Phi^-1(0.99)), top scale)"
    low = float(tp.SCALES[tp.SCALES > 0].min())
    for fn in functions:
        imls, params = fn.find(f"{NS}imls"), fn.find(f"{NS}params")
        theta, beta = lognormal_of(float(params.get("mean")), float(params.get("stddev")))
        limit, lower = float(imls.get("noDamageLimit")), float(imls.get("minIML"))
        p_low = stats.norm.cdf(math.log(lower / theta) / beta)
        # OpenQuake sets P = 0 at or below noDamageLimit and evaluates max(PGA, minIML) above it
        assert 0 < limit <= lower <= low and p_low <= 1e-4 * (1 + 1e-9) and (
            lower == low or abs(p_low / 1e-4 - 1) < 1e-6), (f"{fn.get('id')}: noDamageLimit {limit:g} <= minIML "
                                                            f"{lower:g}, the lower of the lowest scale {low:g} g and "
                                                            f"the PGA where P = 1e-4 (P there {p_low:.3g})")
    assert beyond > 0, f"{beyond} function(s) carried beyond the campaign's top scale {top:g} g to P = 0.99"
    r = run(FRAGILITY, "fragility", cube, "--nrml", xml, "--no-store", "--bootstrap", "20", "--nrml-max-probability", "0")
    tops = {float(fn.find(f"{NS}imls").get("maxIML")) for fn in ET.parse(xml).getroot().iter(f"{NS}fragilityFunction")}
    assert r.returncode == 0 and tops == {top}, "--nrml-max-probability 0: maxIML is the campaign's top scale"

    # the 0.06-0.08 s bin holds 2 records: flagged in the table and the CSV, left out by --nrml-min-records 3
    few = [line for line in r.stdout.splitlines() if line.strip().startswith("0.06-0.08")]
    assert len(few) == 1 and "fewer than 3" in few[0], f"table flags the 2-record bin: {few[0].strip() if few else None}"
    with open(out_csv) as fh:
        rows = [row for row in csv.DictReader(fh) if row["fit"] == "bin"]
    flagged = {row["pgv_pga_lower_s"] for row in rows if "fewer than 3" in row["note"]}
    assert flagged == {"0.06"}, f"CSV note flags exactly the bins with < 3 records ({sorted(flagged)})"
    r = run(FRAGILITY, "fragility", cube, "--nrml", xml, "--no-store", "--bootstrap", "20", "--nrml-min-records", "3")
    ids = [fn.get("id") for fn in ET.parse(xml).getroot().iter(f"{NS}fragilityFunction")]
    assert (r.returncode == 0 and not any("0.06-0.08" in i for i in ids) and len(ids) == len(functions) - 1
          and "rock_pgv_pga_0.06-0.08s (2 record(s))" in r.stdout), "--nrml-min-records 3 leaves the 2-record bin out of the NRML, and says so"
    # --nrml-rotd50-ratio R: the same functions with PGA in RotD50 = R x GMRotI50 (theta, IMLs x R, beta kept)
    plain = os.path.join(tmp, "plain.xml")
    rotd = os.path.join(tmp, "rotd50.xml")
    run(FRAGILITY, "fragility", cube, "--nrml", plain, "--no-store", "--bootstrap", "20")
    r = run(FRAGILITY, "fragility", cube, "--nrml", rotd, "--no-store", "--bootstrap", "20", "--nrml-rotd50-ratio", "1.1")
    ok = r.returncode == 0
    for a, b in zip(ET.parse(plain).getroot().iter(f"{NS}fragilityFunction"),
                    ET.parse(rotd).getroot().iter(f"{NS}fragilityFunction")):
        ta, ba = lognormal_of(float(a.find(f"{NS}params").get("mean")), float(a.find(f"{NS}params").get("stddev")))
        tb, bb = lognormal_of(float(b.find(f"{NS}params").get("mean")), float(b.find(f"{NS}params").get("stddev")))
        ok &= abs(tb / ta - 1.1) < 1e-9 and abs(bb / ba - 1) < 1e-9 and all(
            abs(float(b.find(f"{NS}imls").get(k)) / float(a.find(f"{NS}imls").get(k)) - 1.1) < 1e-9
            for k in ("minIML", "maxIML", "noDamageLimit"))
    assert ok and "RotD50" in ET.parse(rotd).getroot().find(f"{NS}fragilityModel").find(f"{NS}description").text, "--nrml-rotd50-ratio 1.1: theta and the IMLs x 1.1, beta kept, said in the description"
    for bad in (["--nrml-id", ""], ["--nrml-asset-category", "a<b"], ["--nrml-max-probability", "0.3"],
                ["--nrml-min-records", "-1"], ["--nrml-rotd50-ratio", "3"], ["--nrml-at-pgv-pga", "-1"]):
        r = run(FRAGILITY, "fragility", cube, "--no-store", *bad)
        assert r.returncode == 2 and len(r.stderr.splitlines()) == 1 and bad[0] in r.stderr, f"{' '.join(bad) or repr('')}: one line naming the option, exit 2"


# --------------------------------------------------------------------------------------------
# 5., 6. interval flags and the progress line


def test_interval_flag_and_progress():
    scales = (0.1, 2.0)
    assert report.fmt_interval(0.3, 0.05, 0.56, scale_range_g=scales).endswith(report.BEYOND_MARK), "theta interval [0.05, 0.56] with scales from 0.1 g: flagged"
    assert report.fmt_interval(0.3, 0.2, 2.5, scale_range_g=scales).endswith(report.BEYOND_MARK), "theta interval reaching 2.5 g over scales up to 2.0 g: flagged"
    assert not report.fmt_interval(0.3, 0.2, 0.5, scale_range_g=scales).endswith(report.BEYOND_MARK), "an interval inside the scales: not flagged"
    assert report.fmt_interval(0.3, 0.0001, 0.5) == "0.300 [1.00e-04, 0.500]", "a lower end of 1e-4 is not 0.000"

    now = [0.0]
    out = io.StringIO()
    p = progress.FitProgress(12, "rigid fragility", stream=out, clock=lambda: now[0])
    lines = []
    for fit in range(12):
        for _ in range(100):
            now[0] += 0.01  # 1 s per fit
            p.resample(100)
        p.fit_done()
    p.finish()
    lines = out.getvalue().splitlines()
    denominators = {re.search(r"/(\d+) fits", ln).group(1) for ln in lines}
    times = [float(re.search(r"(\d+):(\d+) elapsed", ln).group(2)) for ln in lines[:-1]]
    assert denominators == {"12"} and len(lines) >= 3, f"{len(lines)} progress lines, every one out of 12 fits"
    assert times and times[0] >= 5 and all(b - a >= 5 - 1e-9 for a, b in zip(times, times[1:])), f"first line after 5 s, then every 5 s ({times})"
    m = re.search(r"ETA (\d+):(\d+)", lines[0])
    done = float(re.search(r"([\d.]+)/12 fits", lines[0]).group(1))
    assert m is not None and abs(int(m.group(1)) * 60 + int(m.group(2)) - (12 - done)) <= 1, f"ETA at 1 s per fit: {12 - done:.0f} s left ({lines[0]})"
    assert "done in" in lines[-1], f"a closing line: {lines[-1]}"
    quiet = io.StringIO()
    q = progress.FitProgress(3, "x", stream=quiet, clock=lambda: 0.0)
    q.fit_done(), q.finish()
    assert quiet.getvalue() == "", "work under 5 s prints nothing"


# --------------------------------------------------------------------------------------------
# 7. figures


def test_figures(planted):
    tmp, cube, pgv = planted  # steep.csv: written by test_hazard_report, which runs first
    captured = []
    original = matplotlib.figure.Figure.savefig

    def keep(fig, *args, **kwargs):
        captured.append(fig)
        return original(fig, *args, **kwargs)

    matplotlib.figure.Figure.savefig = keep
    try:
        out = os.path.join(tmp, "maps")
        rp.main(["maps", cube, "--out", out])
        rf.main(["hazard", cube, "--curve", os.path.join(tmp, "steep.csv"), "--age", "1000", "--bootstrap", "20",
                 "--plot", os.path.join(tmp, "hazard.svg")])
    finally:
        matplotlib.figure.Figure.savefig = original
    assert len(captured) == 3, f"maps drew 2 figures and hazard 1 ({len(captured)})"
    if len(captured) != 3:
        return
    mapfig, records, hazard = captured
    with_records = {tp.bin_of(v) for v in pgv}
    panels = [ax for ax in records.axes if ax.get_visible() and ax.get_title().startswith("PGV/PGA")]
    texts = [t.get_text() for ax in records.axes for t in ax.texts if ax.get_visible()]
    assert len(panels) == len(with_records) and "no records" not in texts, f"records figure: {len(panels)} panels for the {len(with_records)} bins with records, none empty"
    title = mapfig.axes[0].get_title()
    assert "alpha = 0.123 rad" in title, f"alpha to 3 digits in the map's title ({title.splitlines()[0]})"
    records.canvas.draw()
    hazard.canvas.draw()
    legend = hazard.legends[0].get_window_extent() if hazard.legends else None
    clear = legend is not None and all(not legend.overlaps(ax.get_window_extent()) for ax in hazard.axes)
    assert clear, "hazard plot: the legend is off both panels"
    assert os.path.getsize(os.path.join(tmp, "hazard.svg")) > 0, "hazard --plot x.svg writes SVG"
    for fmt, magic in (("pdf", b"%PDF"), ("svg", b"<?xml")):
        d = os.path.join(tmp, fmt)
        r = run(PLOT, "maps", cube, "--out", d, "--format", fmt)
        files = sorted(os.listdir(d)) if os.path.isdir(d) else []
        heads = [open(os.path.join(d, f), "rb").read(5) for f in files if f.endswith("." + fmt)]
        assert r.returncode == 0 and len(heads) == 2 and all(h.startswith(magic) for h in heads), f"maps --format {fmt}: {[f for f in files if f.endswith(fmt)]}"
    r = run(PLOT, "maps", cube, "--out", os.path.join(tmp, "x"), "--format", "gif")
    assert r.returncode == 2 and len(r.stderr.splitlines()) == 1, "--format gif: one line, exit 2"


# --------------------------------------------------------------------------------------------
# 8. one median per fit


def test_one_median_per_fit(planted):
    """`rigid plot maps` and `rigid fragility` read the same vector fit at the same PGV/PGA (the
    records' median, computed here from the planted records) and report the same median and
    dispersion: one estimate, not two."""
    tmp, cube, pgv = planted
    out = os.path.join(tmp, "median_maps")
    r = run(PLOT, "maps", cube, "--out", out)
    assert r.returncode == 0, r.stderr
    with open(os.path.join(out, "fit.json")) as fh:
        maps = json.load(fh)["objects"][0]
    r = run(FRAGILITY, "fragility", cube, "--json", "--no-store", "--bootstrap", "20")
    point = json.loads(r.stdout)["objects"][0]["vector"]["points"][0]
    median_s = float(np.median(pgv))
    assert abs(maps["reference_pgv_pga_s"] / median_s - 1) < 1e-12 and abs(point["pgv_pga_s"] / median_s - 1) < 1e-12, f"both at the records' median PGV/PGA {median_s:.4g} s"
    assert abs(maps["reference_theta_g"] / point["theta_g"] - 1) < 1e-6 and abs(maps["reference_beta"] / point["beta"] - 1) < 1e-6, f"maps {maps['reference_theta_g']:.6g} g, {maps['reference_beta']:.6g}; fragility {point['theta_g']:.6g} g, {point['beta']:.6g}"
    printed = re.search(r"median PGA (\S+) g", subprocess.run([sys.executable, PLOT, "maps", cube, "--out", out],
                                                              capture_output=True, text=True).stdout)
    assert printed and abs(float(printed.group(1)) / point["theta_g"] - 1) < 1e-3, "the printed median is that one"
