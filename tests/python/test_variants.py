"""Campaigns with a variant axis (epistemic uncertainty) on the Python side, against independent
oracles, on cubes written here with h5py in the layout documented at the top of src/io/cube.cpp:

a. Planted fragilities: variant v's outcomes drawn from a lognormal (theta_v, beta_v); each
   variant's fit recovers theta_v (its 90 % interval covers it in most variants, the estimate
   within 15 %); the pooled mixture equals the mean of the planted lognormal CDFs within sampling
   error, its median the planted mixture's median (bisection here).
b. Sensitivity: theta_v = f(A) with B irrelevant -> Spearman rho(A) > 0.9 and PRCC(A) > 0.9, rho(B)
   and PRCC(B) with intervals covering 0; swapping the roles swaps the ranking; rho equals
   scipy.stats.spearmanr on the same (parameter, reported theta) pairs, PRCC the partial correlation
   read off the inverse of the rank correlation matrix (a second method).
c. Deterministic variants (outcomes separated by a threshold scale) get the empirical threshold
   (geometric mean of the neighbouring scales), flagged, and the sensitivity still ranks them.
d. The reader: one ObjectData per (object, variant), per-variant attributes, Cube.variants; `rigid
   plot table|maps` name variants `rock [vK]`; the hazard's pooled rate equals the closed form of the
   mixture of the reported lognormals under a power-law curve, --variant K that of variant K.
e. Bad input: --variant out of range, --variant on a cube without variants: one stderr line naming
   the cube and the problem, exit 2.

    /usr/bin/python3 -m pytest tests/python/test_variants.py [--rigid RIGID]

With --rigid (the built executable) `rigid fragility|hazard|plot` go through it, else through the
package's launchers. Skipped without numpy, scipy, h5py or matplotlib.
"""
import csv
import json
import math
import os

import pytest

np = pytest.importorskip("numpy")
h5py = pytest.importorskip("h5py")
pytest.importorskip("matplotlib")
from scipy import stats  # noqa: E402
from scipy.special import ndtr  # noqa: E402

import synthetic_cube as tp  # noqa: E402  (the axes of the synthetic cubes and the cube-derived datasets)
from rigidpy import checksums as cube_checksums  # noqa: E402
from rigidpy import fit as ff  # noqa: E402
from rigidpy.cube import Cube  # noqa: E402

RECORDS = 20
PGV_PGA = 0.15  # every record: the vector fit reduces to the scalar lognormal (one PGV/PGA)


# --------------------------------------------------------------------------------------------
# A variant cube, as the spec lays it out


def write_variant_cube(path, objects, parameters, method="lhs", seed=7):
    """objects: [(name, outcome [V, R, S, A], {per-variant dataset: values [V]})]; parameters:
    [(name, units, values [V] numbers or strings)]. Axes and records as tests/python/test_plot.py's
    cubes (its SCALES, EDGES), every record at PGV/PGA = PGV_PGA."""
    V = len(parameters[0][2])
    R = objects[0][1].shape[1]
    pgv = np.full(R, PGV_PGA)
    str_t = h5py.string_dtype("utf-8")
    names = [f"rec{r:03d}" for r in range(R)]
    with h5py.File(path, "w") as f:
        f.attrs["schema_version"] = np.int32(2)
        ax = f.create_group("axes")
        ax.create_dataset("record", data=np.array(names, dtype=object), dtype=str_t)
        ax.create_dataset("scale_g", data=tp.SCALES.astype(float))
        ax.create_dataset("rotation", data=np.arange(tp.A, dtype=np.int32))
        ax.create_dataset("pgv_pga_bin", data=np.arange(len(tp.EDGES) - 1, dtype=np.int32))
        ax.create_dataset("pgv_pga_edges_s", data=np.array(tp.EDGES, float))
        rec = f.create_group("records")
        rec.create_dataset("name", data=np.array(names, dtype=object), dtype=str_t)
        rec.create_dataset("pgv_pga_s", data=pgv)
        var = f.create_group("variants")
        var.attrs["method"] = method
        var.attrs["seed"] = np.uint64(seed)
        var.attrs["count"] = np.int32(V)
        var.attrs["parameters"] = " ".join(n for n, _, _ in parameters)
        scale = var.create_dataset("variant", data=np.arange(V, dtype=np.int32))
        scale.make_scale("variant")
        scale.attrs["long_name"] = "variant index"
        for name, units, values in parameters:
            if isinstance(values[0], str):
                ds = var.create_dataset(name, data=np.array(values, dtype=object), dtype=str_t)
            else:
                ds = var.create_dataset(name, data=np.asarray(values, float))
                ds.attrs["units"] = units
            ds.attrs["description"] = f"{name} of each variant"
            ds.attrs["long_name"] = name
            ds.dims[0].attach_scale(scale)
        objs = f.create_group("objects")
        for i, (name, outcome, per_variant) in enumerate(objects):
            g = objs.create_group(name)
            g.attrs["index"] = np.int32(i)
            g.attrs["scene"] = f"{name}.toml"
            g.attrs["variants"] = np.int32(V)
            own = g.create_dataset("variant", data=np.arange(V, dtype=np.int32))
            own.make_scale("variant")
            derived = [tp.derived(outcome[v], pgv) for v in range(V)]
            for key, data in (("outcome", outcome), ("probability", np.array([d[0] for d in derived])),
                              ("fragility", np.array([d[1] for d in derived])),
                              ("fragility_count", np.array([d[2] for d in derived]))):
                ds = g.create_dataset(key, data=data)
                ds.dims[0].attach_scale(own)
            for key, values in per_variant.items():
                g.create_dataset(key, data=np.asarray(values, float)).dims[0].attach_scale(own)
            g.create_dataset("physics_json", data=np.array(['{"friction": 0.6}'] * V, dtype=object), dtype=str_t)
            g.create_dataset("support_polygon_m", data=np.array(["0 0 1 0 1 1"] + [""] * (V - 1), dtype=object),
                             dtype=str_t)
        cube_checksums.seal(f)


def lognormal_outcome(rng, theta, beta, records=RECORDS):
    """[R, S, A]: every cell simulated, overturned (2) with probability Phi(ln(PGA/theta)/beta)."""
    p = ndtr(np.log(tp.SCALES / theta) / beta)
    return np.where(rng.random((records, len(tp.SCALES), tp.A)) < p[None, :, None], 2, 1).astype(np.int8)


def threshold_outcome(threshold_g, records=RECORDS):
    """Deterministic: overturned at every scale >= threshold, survived below."""
    over = tp.SCALES >= threshold_g
    return np.broadcast_to(np.where(over, 2, 1)[None, :, None], (records, len(tp.SCALES), tp.A)).astype(np.int8).copy()


def lhs(rng, n, lo, hi):
    """A Latin hypercube column: one value per stratum, strata shuffled."""
    return lo + (hi - lo) * (rng.permutation(n) + rng.random(n)) / n


def fragility_json(tool, cube, *extra):
    p = tool("fragility", cube, "--json", *extra)
    if p.returncode != 0:
        assert False, f"rigid fragility {cube} {' '.join(extra)}: exit {p.returncode} {p.stderr.strip()}"
        return None
    return json.loads(p.stdout)


# --------------------------------------------------------------------------------------------
# a. planted per-variant lognormals, the pooled mixture


def planted(tmp, tool):
    rng = np.random.default_rng(20261125)
    V = 12
    theta = lhs(rng, V, 0.3, 1.1)
    beta = lhs(rng, V, 0.2, 0.6)
    outcome = np.array([lognormal_outcome(rng, t, b) for t, b in zip(theta, beta)])
    alpha = 0.15 + 0.1 * rng.random(V)
    cube = os.path.join(tmp, "planted.h5")
    write_variant_cube(cube, [("rock", outcome, {"alpha_rad": alpha, "p_rad_s": np.full(V, 2.0)})],
                       [("friction", "1", lhs(rng, V, 0.4, 0.9)), ("contact", "", ["rigid", "penalty"] * (V // 2))])

    c = Cube(cube)
    assert (c.variants is not None and c.variants.count == V and c.variants.method == "lhs" and c.variants.seed == 7
          and [p[0] for p in c.variants.parameters] == ["friction", "contact"]
          and c.variants.parameters[1][2][:2] == ["rigid", "penalty"]), "reader: Cube.variants (count, method, seed, parameters with numbers and text)"
    assert (len(c.objects) == V and [o.variant for o in c.objects] == list(range(V))
          and all(o.name == "rock" for o in c.objects) and c.objects[3].label == "rock [v3]"
          and all(abs(o.attrs["alpha_rad"] - alpha[o.variant]) < 1e-15 for o in c.objects)
          and np.array_equal(c.objects[5].outcome, outcome[5]) and c.objects[5].fragility.shape == (len(tp.SCALES), 9)
          and list(c.objects[0].attrs["support_polygon_m"]) == [0, 0, 1, 0, 1, 1]
          and "support_polygon_m" not in c.objects[1].attrs), "reader: one ObjectData per variant, labelled rock [vK], with its alpha_rad and its cells"

    csv_path, xml_path = os.path.join(tmp, "planted.csv"), os.path.join(tmp, "planted.xml")
    doc = fragility_json(tool, cube, "--bootstrap", "60", "--csv", csv_path, "--nrml", xml_path)
    if doc is None:
        return
    fr = [o["fragility"] for o in doc["objects"]]
    covered = sum(f["theta_interval_g"][0] <= t <= f["theta_interval_g"][1] for f, t in zip(fr, theta))
    worst = max(abs(f["theta_g"] / t - 1) for f, t in zip(fr, theta))
    assert covered >= V - 3 and worst < 0.15, (f"per-variant fits: planted theta inside the 90 % interval in {covered}/{V} variants (>= {V - 3}), "
          f"largest relative error {100 * worst:.1f} % (< 15 %)")
    bcov = sum(f["beta_interval"][0] <= b <= f["beta_interval"][1] for f, b in zip(fr, beta))
    assert bcov >= V - 3, f"per-variant fits: planted beta inside its interval in {bcov}/{V} variants"

    pooled = doc["variant_analysis"][0]["pooled"]
    a = np.array(pooled["pga_g"])
    truth = np.mean([ndtr(np.log(a / t) / b) for t, b in zip(theta, beta)], axis=0)
    gap = float(np.max(np.abs(np.array(pooled["mixture_probability"]) - truth)))
    assert gap < 0.04, (f"pooled mixture = mean of the planted lognormal CDFs within {gap:.3f} (< 0.04) over "
                      f"{a[0]:.3g}-{a[-1]:.3g} g")
    lo, hi = math.log(0.01), math.log(20.0)
    for _ in range(100):  # the planted mixture's median, by bisection here
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if np.mean(ndtr((mid - np.log(theta)) / beta)) < 0.5 else (lo, mid)
    planted_median = math.exp(lo)
    assert abs(pooled["median_g"] / planted_median - 1) < 0.06, f"pooled median {pooled['median_g']:.4f} g vs planted mixture's {planted_median:.4f} g (< 6 %)"
    t_rep = np.array([f["theta_g"] for f in fr])
    b_rep = np.array([f["beta"] for f in fr])
    ok = (abs(pooled["lognormal_theta_g"] - math.exp(np.mean(np.log(t_rep)))) < 1e-9
          and abs(pooled["lognormal_beta"] - math.sqrt(np.mean(b_rep**2) + np.var(np.log(t_rep)))) < 1e-9
          and np.allclose(pooled["theta_percentiles_g"], np.percentile(t_rep, [5, 50, 95]), rtol=1e-12))
    assert ok, ("pooled lognormal: ln C mean and variance of the mixture of the reported fits; theta 5/50/95 % "
              "over variants")
    band_lo, band_hi = np.array(pooled["band_lower"]), np.array(pooled["band_upper"])
    curves = np.array([ndtr(np.log(a / t) / b) for t, b in zip(t_rep, b_rep)])
    assert (np.allclose(band_lo, np.percentile(curves, 5, axis=0)) and np.allclose(band_hi, np.percentile(curves, 95, axis=0))
          and np.all(band_lo <= pooled["mixture_probability"]) and np.all(pooled["mixture_probability"] <= band_hi)), "5-95 % band of P_v(a) over variants, the mixture inside it"

    with open(csv_path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert (list(rows[0])[:2] == ["object", "variant"] and {r["variant"] for r in rows} == {str(v) for v in range(V)} | {"pooled"}
          and sum(r["fit"] == "scalar" for r in rows) == V), f"CSV: a variant column, each variant's rows and the pooled row ({len(rows)} rows)"
    import xml.etree.ElementTree as ET
    ids = [fn.get("id") for fn in ET.parse(xml_path).getroot().iter("{http://openquake.org/xmlns/nrml/0.5}fragilityFunction")]
    assert len(ids) == V + 1 and ids[-1].startswith("rock_pooled") and ids[3].startswith("rock_v3_"), f"NRML: one function per variant and the pooled one ({ids[0]}, ..., {ids[-1]})"
    with h5py.File(cube, "r") as f:
        g = f["fragility/rock"]
        ok = (int(g.attrs["variants"]) == V and "v11" in g and "theta_g" in g["v11"]
              and np.allclose(g["variant_fragility/theta_g"][...], t_rep)
              and abs(g["pooled"].attrs["median_g"] - pooled["median_g"]) < 1e-12
              and np.array_equal(f["objects/rock/outcome"][...], outcome) and "sensitivity" in g)
    assert ok, ("cube: /fragility/rock holds each variant (v0..), the per-variant lognormals, pooled, sensitivity; "
              "cells untouched")

    # the table through the plot tool, and the maps' band figure
    out = os.path.join(tmp, "table.md")
    p = tool("plot", "table", cube, "--out", out, "--variant", "3")
    text = open(out).read() if p.returncode == 0 else ""
    assert p.returncode == 0 and "rock [v3]" in text and "rock [v4]" not in text, f"rigid plot table --variant 3: the row is named rock [v3] (exit {p.returncode} {p.stderr.strip()})"
    maps = os.path.join(tmp, "maps")
    p = tool("plot", "maps", cube, "--out", maps)
    files = sorted(os.listdir(maps)) if os.path.isdir(maps) else []
    assert p.returncode == 0 and files == ["fit.json", "rock_pooled_map.png", "rock_variants.png"], f"rigid plot maps: the band figure and the pooled map by default ({files}) {p.stderr.strip()}"
    p = tool("plot", "maps", cube, "--out", maps, "--variant", "2")
    assert p.returncode == 0 and os.path.isfile(os.path.join(maps, "rock_v2_map.png")), "rigid plot maps --variant 2: that variant's map (rock_v2_map.png)"
    return cube, theta, beta


# --------------------------------------------------------------------------------------------
# b. the sensitivity oracle


def test_sensitivity_oracle(tmp, tool):
    rng = np.random.default_rng(424242)
    V = 30
    a_values, b_values = lhs(rng, V, 0.4, 1.0), lhs(rng, V, 2400.0, 2800.0)
    results = {}
    for driver in ("friction", "density_kg_m3"):
        driving = a_values if driver == "friction" else (b_values - 2400.0) / 400.0 * 0.6 + 0.4
        theta = 0.25 * np.exp(1.6 * (driving - 0.4))  # monotone in the driver only: 0.25-0.65 g
        outcome = np.array([lognormal_outcome(rng, t, 0.3) for t in theta])
        cube = os.path.join(tmp, f"sens_{driver}.h5")
        # alpha derived from friction (monotone): its PRCC given the varied parameters is undefined
        write_variant_cube(cube, [("rock", outcome, {"alpha_rad": 0.1 + 0.2 * a_values})],
                           [("friction", "1", a_values), ("density_kg_m3", "kg m-3", b_values)])
        doc = fragility_json(tool, cube, "--bootstrap", "20", "--no-store", "--seed", "5")
        if doc is None:
            return
        an = doc["variant_analysis"][0]
        rows = {r["parameter"]: r for r in an["sensitivity"]}
        results[driver] = (an, rows)
        other = "density_kg_m3" if driver == "friction" else "friction"
        d, o = rows[driver], rows[other]
        assert d["rho_theta"] > 0.9 and d["prcc_theta"] > 0.9, f"theta = f({driver}): rho {d['rho_theta']:.3f}, PRCC {d['prcc_theta']:.3f} (> 0.9)"
        lo, hi = o["rho_theta_interval"]
        plo, phi = o["prcc_theta_interval"]
        assert abs(o["rho_theta"]) < 0.35 and lo < 0 < hi and plo < 0 < phi, (f"{other} irrelevant: rho {o['rho_theta']:+.3f} [{lo:+.3f}, {hi:+.3f}], PRCC {o['prcc_theta']:+.3f} "
              f"[{plo:+.3f}, {phi:+.3f}]: intervals cover 0")
        varied = [r["parameter"] for r in an["sensitivity"] if r["kind"] != "derived"]
        assert varied == [driver, other], f"ranking by |rho(theta)|: {[r['parameter'] for r in an['sensitivity']]}"
        thetas = [v["theta_g"] for v in an["variant_fragility"]]
        worst = 0.0
        for name, values in (("friction", a_values), ("density_kg_m3", b_values)):
            worst = max(worst, abs(stats.spearmanr(values, thetas)[0] - rows[name]["rho_theta"]))
        betas = [v["beta"] for v in an["variant_fragility"]]
        worst = max(worst, abs(stats.spearmanr(a_values, betas)[0] - rows["friction"]["rho_beta"]))
        assert worst < 1e-12, f"rho equals scipy.stats.spearmanr on the reported thetas and betas ({worst:.1e})"
        # PRCC by a second method: the partial correlation from the inverse of the rank correlation
        # matrix of (friction, density, theta), -P_xy / sqrt(P_xx P_yy)
        ranks = np.array([stats.rankdata(v) for v in (a_values, b_values, thetas)])
        precision = np.linalg.inv(np.corrcoef(ranks))
        worst = 0.0
        for i, name in enumerate(("friction", "density_kg_m3")):
            partial = -precision[i, 2] / math.sqrt(precision[i, i] * precision[2, 2])
            worst = max(worst, abs(partial - rows[name]["prcc_theta"]))
        assert worst < 1e-9, f"PRCC equals the partial correlation from the inverse rank correlation matrix ({worst:.1e})"
        al = rows["alpha_rad"]
        assert (al["kind"] == "derived" and abs(al["rho_theta"] - rows["friction"]["rho_theta"]) < 1e-12
              and al["prcc_theta"] is None and "determined" in al["note"]), f"derived alpha_rad (monotone in friction): rho as friction's, no PRCC ({al['note']})"
    if len(results) == 2:
        first = [r["parameter"] for r in results["friction"][0]["sensitivity"] if r["kind"] != "derived"][0]
        swapped = [r["parameter"] for r in results["density_kg_m3"][0]["sensitivity"] if r["kind"] != "derived"][0]
        assert first == "friction" and swapped == "density_kg_m3", f"swapping the roles swaps the ranking (first: {first}, then {swapped})"


# --------------------------------------------------------------------------------------------
# c. deterministic (separated) variants


def test_quasi_separated():
    """One mixed scale between all-survived and all-overturned ones (quasi-complete separation: the
    probit's slope diverges too): the step sits at the mixed scale; two mixed scales are a fit's."""
    scales = np.array([0.1, 0.2, 0.3, 0.4])
    outcome = np.ones((2, 4, 3), np.int8)
    outcome[:, 3, :] = 2
    outcome[0, 2, 0] = 2
    t = ff.empirical_threshold(ff.Cells(outcome, scales, np.array([0.1, 0.1])))
    assert t is not None and t["theta_g"] == 0.3 and t["between_g"] == [0.2, 0.4], f"quasi-complete separation: the step at the one mixed scale ({t})"
    outcome[1, 1, 0] = 2
    assert ff.empirical_threshold(ff.Cells(outcome, scales, np.array([0.1, 0.1]))) is None, "two mixed scales: no threshold (the probit fit applies)"


def test_deterministic(tmp, tool):
    thresholds = [0.35, 0.55, 0.75, 0.95, 1.25, 1.55]  # between scales (0.1 g apart)
    size = [0.8, 1.0, 1.2, 1.4, 1.7, 2.0]
    outcome = np.array([threshold_outcome(t, records=4) for t in thresholds])
    cube = os.path.join(tmp, "threshold.h5")
    write_variant_cube(cube, [("block", outcome, {})],
                       [("size_scale", "1", size), ("contact", "", ["rigid", "penalty", "rigid", "penalty", "rigid", "penalty"])],
                       method="list")
    doc = fragility_json(tool, cube, "--bootstrap", "20", "--no-store")
    if doc is None:
        return
    an = doc["variant_analysis"][0]
    worst, flagged = 0.0, 0
    for t, v in zip(thresholds, an["variant_fragility"]):
        below = tp.SCALES[tp.SCALES < t].max()
        above = tp.SCALES[tp.SCALES >= t].min()
        worst = max(worst, abs(v["theta_g"] / math.sqrt(below * above) - 1))
        flagged += v["source"] == "empirical threshold" and v["beta"] == 0
    assert worst < 1e-12 and flagged == len(thresholds), (f"separated variants: theta = sqrt(highest survived x lowest overturned scale), flagged "
          f"({flagged}/{len(thresholds)}; worst {worst:.1e})")
    rows = {r["parameter"]: r for r in an["sensitivity"]}
    assert (abs(rows["size_scale"]["rho_theta"] - 1) < 1e-12 and an["sensitivity"][0]["parameter"] == "size_scale"
          and rows["size_scale"]["rho_beta"] is None and "text (category order: rigid, penalty)" == rows["contact"]["kind"]), (f"sensitivity on thresholds: rho(size_scale) = {rows['size_scale']['rho_theta']}, beta left out; "
          f"contact by category order")
    p = tool("fragility", cube, "--bootstrap", "20", "--no-store")
    assert p.returncode == 0 and "empirical threshold" in p.stdout and "block [v5]" in p.stdout, "the table says which thetas are empirical thresholds"
    # a threshold is a step: the rate of toppling is the hazard curve's rate at the threshold
    k, k0 = 2.0, 1e-5
    curve = os.path.join(tmp, "steps.csv")
    with open(curve, "w") as f:
        for a in np.geomspace(0.01, 5.0, 25):
            f.write(f"{a!r},{k0 * a ** -k!r}\n")
    p = tool("hazard", cube, "--curve", curve, "--age", "1000", "--variant", "2", "--json", "--bootstrap", "20")
    if p.returncode == 0:
        r = json.loads(p.stdout)
        t = an["variant_fragility"][2]["theta_g"]
        assert abs(r["annual_toppling_rate"] / (k0 * t ** -k) - 1) < 1e-9 and r["fragility"][0]["source"] == "empirical threshold", f"hazard --variant 2 (a threshold): rate {r['annual_toppling_rate']:.6e} = H(theta) {k0 * t ** -k:.6e}"
    else:
        assert False, f"hazard --variant 2 of the thresholds: exit {p.returncode} {p.stderr.strip()}"
    p = tool("hazard", cube, "--curve", curve, "--age", "1000", "--json", "--bootstrap", "20")
    if p.returncode == 0:
        r = json.loads(p.stdout)
        want = np.mean([k0 * v["theta_g"] ** -k for v in an["variant_fragility"]])
        assert abs(r["annual_toppling_rate"] / want - 1) < 1e-9, f"pooled hazard of thresholds: rate {r['annual_toppling_rate']:.6e} = mean of H(theta_v) {want:.6e}"
    else:
        assert False, f"pooled hazard of the thresholds: exit {p.returncode} {p.stderr.strip()}"


# --------------------------------------------------------------------------------------------
# d. hazard, e. bad input


def hazard(tmp, cube, tool):
    k, k0, years = 2.5, 2e-5, 10000.0
    curve = os.path.join(tmp, "power.csv")
    with open(curve, "w") as f:
        for a in np.geomspace(0.01, 5.0, 25):
            f.write(f"{a!r},{k0 * a ** -k!r}\n")
    p = tool("hazard", cube, "--curve", curve, "--age", str(years), "--bootstrap", "40", "--json")
    assert p.returncode == 0, f"rigid hazard (pooled) exit {p.returncode} {p.stderr.strip()}"
    if p.returncode != 0:
        return
    r = json.loads(p.stdout)
    per = [(v["lognormals"][0]["theta_g"], v["lognormals"][0]["beta"]) for v in r["variant_fragility"]]
    rates = [k0 * t ** -k * math.exp(0.5 * k * k * b * b) for t, b in per]
    exact = float(np.mean(rates))
    lo, hi = r["annual_toppling_rate_interval"]
    assert abs(r["annual_toppling_rate"] / exact - 1) < 0.005 and lo < r["annual_toppling_rate"] < hi, (f"pooled rate {r['annual_toppling_rate']:.4e} = mean over variants of the closed form {exact:.4e}, "
          f"inside its aleatory interval [{lo:.3e}, {hi:.3e}]")
    survivals = np.exp(-np.array(rates) * years)
    elo, ehi = r["survival_probability_epistemic_range"]
    want = np.percentile(survivals, [5, 95])
    assert abs(elo - want[0]) < 0.005 and abs(ehi - want[1]) < 0.005 and elo <= r["survival_probability"] <= ehi, (f"survival {r['survival_probability']:.4f}, epistemic 5-95 % over variants [{elo:.4f}, {ehi:.4f}] "
          f"(closed forms [{want[0]:.4f}, {want[1]:.4f}])")
    p = tool("hazard", cube, "--curve", curve, "--age", str(years), "--bootstrap", "40", "--json", "--variant", "4")
    if p.returncode == 0:
        r4 = json.loads(p.stdout)
        f0 = r4["fragility"][0]
        exact4 = k0 * f0["theta_g"] ** -k * math.exp(0.5 * k * k * f0["beta"] ** 2)
        assert (abs(r4["annual_toppling_rate"] / exact4 - 1) < 0.005 and r4["object"] == "rock [v4]"
              and abs(f0["theta_g"] - per[4][0]) < 1e-9), f"--variant 4: rate {r4['annual_toppling_rate']:.4e} = closed form of variant 4's lognormal {exact4:.4e}"
    else:
        assert False, f"rigid hazard --variant 4: exit {p.returncode} {p.stderr.strip()}"
    return curve


def bad_input_case(tool, name, args, fragments):
    p = tool(*args)
    lines = [ln for ln in p.stderr.splitlines() if ln.strip()]
    ok = p.returncode == 2 and len(lines) == 1 and "error" in lines[0] and all(f in lines[0] for f in fragments)
    assert ok, f"bad input, {name}: exit {p.returncode}, {len(lines)} stderr line(s): {lines[0] if lines else ''}"


def bad_inputs(tool, tmp, cube, curve):
    plain = os.path.join(tmp, "plain.h5")
    rng = np.random.default_rng(1)
    tp.write_cube(plain, np.full(RECORDS, PGV_PGA), [("rock", lognormal_outcome(rng, 0.5, 0.3), {})])
    hazard = ["--curve", curve, "--age", "1000", "--bootstrap", "20"]
    for what, args in (("fragility", ["fragility", cube, "--no-store"]), ("hazard", ["hazard", cube, *hazard]),
                       ("plot maps", ["plot", "maps", cube, "--out", os.path.join(tmp, "m")])):
        bad_input_case(tool, f"{what} --variant 12 of 12 variants", args + ["--variant", "12"], [cube, "--variant 12", "out of range"])
    bad_input_case(tool, "fragility --variant -1", ["fragility", cube, "--no-store", "--variant", "-1"], [cube, "out of range"])
    bad_input_case(tool, "fragility --variant on a cube without variants", ["fragility", plain, "--no-store", "--variant", "0"],
                   [plain, "no variants"])
    bad_input_case(tool, "hazard --variant on a cube without variants", ["hazard", plain, *hazard, "--variant", "1"],
                   [plain, "no variants"])
    bad_input_case(tool, "plot table --variant on a cube without variants",
                   ["plot", "table", plain, "--out", os.path.join(tmp, "t.md"), "--variant", "0"], [plain, "no variants"])
    bad_input_case(tool, "--variant not a number", ["fragility", cube, "--variant", "two"], ["--variant"])


def test_planted_hazard_and_bad_inputs(tmp, tool):
    cube = planted(tmp, tool)[0]
    curve = hazard(tmp, cube, tool)
    bad_inputs(tool, tmp, cube, curve)
