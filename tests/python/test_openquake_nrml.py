"""Every NRML `rigid fragility` writes is read by OpenQuake's own reader and gives, as the engine
evaluates it, the fitted lognormal:

1. per PGV/PGA bin (the default export), the vector fit at a site's PGV/PGA (--nrml-at-pgv-pga),
   and a cube with variants (one function per variant and the pooled one) are parsed by
   openquake.hazardlib.nrml.to_python (its validating XML parser and the risklib fragility
   conversion), one function per id written;
2. each function, built as a damage calculation builds it (FragilityFunctionList.build) and
   evaluated by the engine at PGAs from 0.01 g to twice maxIML, equals Phi(ln(PGA/theta)/beta) of
   the fit's theta and beta as the CSV and --json report them (not the NRML's mean and stddev),
   to 1e-9, above noDamageLimit and up to maxIML; above maxIML the engine holds P(maxIML); at or
   below noDamageLimit it gives 0, where the lognormal is below 1e-4 (the export's no-damage
   level): no step bigger than that anywhere;
3. the vector export at S equals the vector fit --pgv-pga S reports, and the --vector-csv
   coefficients (ln theta = a + b ln S, ln beta = c + d ln S) give the same theta and beta.

OpenQuake is not a Debian package: give a source tree of the engine (a checkout of
github.com/gem/oq-engine, whose dependencies python3-numpy, -scipy, -pandas, -h5py, -shapely,
-pyproj, -toml, -decorator, -psutil, -numba and -xgboost are Debian packages) as

    RIGID_OQ_ENGINE=/path/to/oq-engine /usr/bin/python3 -m pytest tests/python/test_openquake_nrml.py

Without it the OpenQuake checks are skipped with a message; the NRML's structure is checked
everywhere by test_outputs.py.
"""
import csv
import json
import math
import os
import subprocess
import sys

import pytest

np = pytest.importorskip("numpy")
pytest.importorskip("h5py")
from scipy import stats  # noqa: E402

import synthetic_cube as tp  # noqa: E402
import test_variants as tv  # noqa: E402  (its writer of a cube with variants)

PYTHON_DIR = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src", "python"))
FRAGILITY = os.path.join(PYTHON_DIR, "rigid_fragility.py")
SITE_PGV_PGA_S = 0.15
NO_DAMAGE_P = 1e-4


def openquake():
    """(nrml, read_nrml) of the engine named by RIGID_OQ_ENGINE, or a skip saying how to give one."""
    tree = os.environ.get("RIGID_OQ_ENGINE")
    if not tree:
        pytest.skip("RIGID_OQ_ENGINE is not set: give an OpenQuake engine source tree to read the NRML with "
                    "OpenQuake's own reader")
    if not os.path.isfile(os.path.join(tree, "openquake", "hazardlib", "nrml.py")):
        pytest.fail(f"RIGID_OQ_ENGINE={tree}: no openquake/hazardlib/nrml.py there")
    if tree not in sys.path:
        sys.path.insert(0, tree)
    try:
        from openquake.hazardlib import nrml
        from openquake.risklib import read_nrml  # noqa: F401  (registers the fragilityModel conversion)
    except ImportError as e:
        pytest.fail(f"RIGID_OQ_ENGINE={tree}: the engine does not import here ({e}); install its dependencies "
                    f"from Debian")
    return nrml


def run(*args):
    r = subprocess.run([sys.executable, FRAGILITY, "fragility", *args, "--no-store", "--bootstrap", "20"],
                       capture_output=True, text=True)
    assert r.returncode == 0, f"rigid fragility {' '.join(args)}: exit {r.returncode}: {r.stderr.strip()[:300]}"
    return r


@pytest.fixture(scope="module")
def exports(tmp_path_factory):
    """{name: (nrml path, {function id: (theta_g, beta)})} of the three kinds of export."""
    tmp = str(tmp_path_factory.mktemp("oq"))
    rng = np.random.default_rng(20261206)
    pgv = np.exp(rng.uniform(math.log(0.06), math.log(0.34), 40))
    cube = os.path.join(tmp, "planted.h5")
    tp.write_cube(cube, pgv, [("rock", tp.planted_outcomes(rng, pgv, -1.2, tp.MU1, tp.SIGMA, extras=False),
                               {"alpha_rad": 0.2, "p_rad_s": 2.2})])
    out = {}

    bins_xml, bins_csv = os.path.join(tmp, "bins.xml"), os.path.join(tmp, "bins.csv")
    run(cube, "--nrml", bins_xml, "--csv", bins_csv)
    with open(bins_csv) as fh:
        rows = [r for r in csv.DictReader(fh) if r["fit"] == "bin" and r["theta_g"]]
    label = lambda r: f"{float(r['pgv_pga_lower_s']):g}-{float(r['pgv_pga_upper_s']):g}"  # noqa: E731
    out["bins"] = (bins_xml, {f"rock_pgv_pga_{label(r)}s": (float(r["theta_g"]), float(r["beta"])) for r in rows})

    vector_xml, coefficients = os.path.join(tmp, "vector.xml"), os.path.join(tmp, "vector.csv")
    run(cube, "--nrml", vector_xml, "--nrml-at-pgv-pga", f"{SITE_PGV_PGA_S}", "--vector-csv", coefficients)
    point = json.loads(run(cube, "--json", "--pgv-pga", f"{SITE_PGV_PGA_S}").stdout)["objects"][0]["vector"]["points"][0]
    out["vector"] = (vector_xml, {f"rock_vector_pgv_pga_{SITE_PGV_PGA_S:g}s": (point["theta_g"], point["beta"])})
    with open(coefficients) as fh:
        out["coefficients"] = list(csv.DictReader(fh))

    # a cube with variants: 6 planted lognormals, one of them entirely below the lowest scale's 1e-4
    V = 6
    theta, beta = np.linspace(0.25, 1.2, V), np.linspace(0.15, 0.5, V)
    outcome = np.array([tv.lognormal_outcome(rng, t, b) for t, b in zip(theta, beta)])
    variant_cube = os.path.join(tmp, "variants.h5")
    tv.write_variant_cube(variant_cube, [("rock", outcome, {"alpha_rad": np.full(V, 0.2), "p_rad_s": np.full(V, 2.0)})],
                          [("friction", "1", np.linspace(0.4, 0.9, V))])
    variants_xml = os.path.join(tmp, "variants.xml")
    run(variant_cube, "--nrml", variants_xml)
    doc = json.loads(run(variant_cube, "--json").stdout)
    s = f"{doc['variant_analysis'][0]['pgv_pga_s']:.4g}"
    fits = {f"rock_v{o['variant']}_pgv_pga_{s}s": (o["fragility"]["theta_g"], o["fragility"]["beta"])
            for o in doc["objects"]}
    pooled = doc["variant_analysis"][0]["pooled"]
    fits[f"rock_pooled_pgv_pga_{s}s"] = (pooled["lognormal_theta_g"], pooled["lognormal_beta"])
    out["variants"] = (variants_xml, fits)
    return out


@pytest.mark.parametrize("kind", ["bins", "vector", "variants"])
def test_openquake_reads_and_evaluates(exports, kind):
    nrml = openquake()
    path, fits = exports[kind]
    model = nrml.to_python(path)
    assert sorted(fid for _, fid in model) == sorted(fits), f"{kind}: OpenQuake reads one function per fit ({sorted(fits)})"
    assert {imt for imt, _ in model} == {"PGA"} and list(model.limitStates) == ["overturned"], f"{kind}: PGA, overturned"
    for (_, fid), functions in model.items():
        theta, beta = fits[fid]
        ff = functions.build(model.limitStates, 20, 1)[0]  # as a damage calculation builds it
        lower, upper = functions.minIML, functions.maxIML
        assert functions.nodamage <= lower < upper, f"{fid}: noDamageLimit {functions.nodamage} <= minIML {lower} < maxIML {upper}"
        pga = np.geomspace(0.01, 2 * upper, 400)
        engine = ff(pga)
        fitted = stats.norm.cdf(np.log(pga / theta) / beta)
        inside = (pga > functions.nodamage) & (pga <= upper)
        assert np.allclose(engine[inside], fitted[inside], rtol=1e-9, atol=1e-12), f"{fid}: OpenQuake's P = the fit's lognormal (theta {theta:.4g} g, beta {beta:.4g}) between noDamageLimit and maxIML"
        at_top = stats.norm.cdf(math.log(upper / theta) / beta)
        assert np.allclose(engine[pga > upper], at_top, rtol=1e-9), f"{fid}: above maxIML the engine holds P(maxIML)"
        below = pga <= functions.nodamage
        assert np.all(engine[below] == 0) and np.all(fitted[below] <= NO_DAMAGE_P * (1 + 1e-9)), f"{fid}: P = 0 at or below noDamageLimit, where the lognormal is below 1e-4"
        assert np.max(np.abs(engine[pga <= upper] - fitted[pga <= upper])) <= NO_DAMAGE_P * (1 + 1e-9), f"{fid}: no step bigger than 1e-4 from the fitted curve below maxIML"


def test_vector_coefficients_give_the_exported_function(exports):
    """The --vector-csv coefficients at the site's PGV/PGA give the theta, beta that --pgv-pga and
    the vector export report (no OpenQuake needed)."""
    (row,) = exports["coefficients"]
    theta, beta = next(iter(exports["vector"][1].values()))
    ln_s = math.log(SITE_PGV_PGA_S)
    t = math.exp(float(row["ln_theta_intercept"]) + float(row["ln_theta_slope"]) * ln_s)
    b = math.exp(float(row["ln_beta_intercept"]) + float(row["ln_beta_slope"]) * ln_s)
    assert abs(t / theta - 1) < 1e-9 and abs(b / beta - 1) < 1e-9, f"coefficients at {SITE_PGV_PGA_S} s: theta {t:.6g} g, beta {b:.6g} = the vector fit's {theta:.6g} g, {beta:.6g}"
    assert float(row["pgv_pga_min_s"]) < SITE_PGV_PGA_S < float(row["pgv_pga_max_s"]), "the PGV/PGA range of the records is given"
