"""CTest `shaketable_python`: `rigid shaketable calibrate` and `predict` on a synthetic lab whose
outcomes the model itself generated, so the truth is known.

- Planted recovery: an asymmetric prism (a scan this test writes) stands on a table turned by a
  planted heading of 60 deg; sine motions of three frequencies and six amplitudes, written as a
  lab exports them (gzip, tab-separated, time / acceleration in g / displacement in V), are run
  one by one with `rigid run --lab --rotation 60`, and their outcomes become the test list.
  Calibration over a ring of headings must find the heading again (modulo 180 deg: the table
  pushes both ways), fit the outcomes it was given (in-sample accuracy 1) and write a scene that
  `rigid run` accepts.
- Prediction never reads the outcome column: the same predictions with it removed or shuffled;
  they reproduce the planted outcomes (all but at most one test at the rock's threshold, where
  turning the rock rather than the motion changes the round-off).
- Fragility: the lab's fit (outcomes at measured PGAs) and the calibrated model's (the same
  motions scaled over a grid) agree, since the model made the lab's outcomes; the lab fit alone
  recovers a planted probit (theta, beta) from Bernoulli outcomes drawn with it.
- Bad test lists and scans: one line naming the file (and line), exit 2.

    /usr/bin/python3 -m pytest tests/python/test_shaketable.py --rigid RIGID
"""
import csv
import gzip
import io
import json
import math
import os
import random
import subprocess

import pytest

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def run(rigid, *args, cwd=None):
    return subprocess.run([rigid, *args], capture_output=True, text=True, env=ENV, cwd=cwd, timeout=900)


def write_prism(path, tilt_x=0.0, h=0.9):
    """A prism h m tall on an irregular convex pentagon (no mirror symmetry); tilt_x leans it."""
    base = [(0.16, 0.0), (0.05, 0.12), (-0.11, 0.08), (-0.13, -0.06), (0.04, -0.11)]
    v = [(x, y, 0.0) for x, y in base] + [(x + tilt_x, y, h) for x, y in base]
    n = len(base)
    faces = [[n - 1 - k for k in range(n)], [n + k for k in range(n)]]  # bottom (outward down), top
    for k in range(n):
        a, b = k, (k + 1) % n
        faces.append([a, b, n + b])
        faces.append([a, n + b, n + a])
    with open(path, "w") as f:
        for p in v:
            f.write("v %.6f %.6f %.6f\n" % p)
        for face in faces:
            for i in range(1, len(face) - 1):
                f.write("f %d %d %d\n" % (face[0] + 1, face[i] + 1, face[i + 1] + 1))


def write_motion(path, freq, amp_g, duration=4.0, dt=0.005):
    """A sine of the table: acceleration in g, displacement in V (the lab's 5.9797e-4 in per V)."""
    w = 2 * math.pi * freq
    with gzip.open(path, "wt") as f:
        f.write("Time [s]\tAcceleration [g]\tDisplacement [V]\n")
        for i in range(int(duration / dt) + 1):
            t = i * dt
            a = amp_g * math.sin(w * t)
            x = -amp_g * 9.80665 / (w * w) * math.sin(w * t)  # m
            f.write("%.5f\t%.7f\t%.7f\n" % (t, a, x / 0.0254 / 5.9797e-4))


def write_tests(path, rows, columns):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)


def check_fragility_thresholds(work, rows):
    import h5py
    import numpy as np
    with h5py.File(os.path.join(work, "fragility.h5"), "r") as f:
        scales = f["axes/scale_g"][()]
    with open(os.path.join(work, "motions.csv")) as fh:
        motions = [m["record"] for m in csv.DictReader(fh)]
    # the calibrated model's P(overturn) per motion and PGA, as the command wrote it for the fit
    with open(os.path.join(work, "model.csv")) as fh:
        model = list(csv.DictReader(fh))
    ratio = scales[1] / scales[0]  # the grid is geometric
    for r, record in enumerate(motions):
        p = [float(m["p_overturn"]) for m in model if int(m["record_index"]) == r]
        first = next((s for s, q in zip(scales, p) if q >= 0.5), math.inf)
        tests = sorted((float(x["pga_g"]), x["overturned"]) for x in rows if x["record"] == record)
        over = [a for a, o in tests if o]
        low = max([a for a, o in tests if not o and (not over or a < over[0])], default=0.0)
        high = over[0] if over else math.inf
        if not over:
            continue
        assert low / ratio < first <= high * ratio, "%s: the model first overturns at %.2f g, the lab between %.3f and %.3f g" % (record, first, low, high)


def check_probability_quality(cal, rows, tmp):
    """The calibration's probability quality as written: each reliability table holds every test
    once (and every overturn), the held-out scores cover every motion's tests, the figure and the
    likelihood table it draws are there."""
    overturned = sum(r["overturned"] for r in rows)
    for part in ("in_sample", "cross_validated"):
        q = cal[part]
        assert q["log_loss"] > 0 and 0 <= q["brier"] <= 1, "%s: Brier %s, log loss %s" % (part, q["brier"], q["log_loss"])
        bins = q["reliability"]
        assert len(bins) == 10 and sum(b["tests"] for b in bins) == len(rows), "%s: every test in one bin" % part
        assert sum(b["overturned"] for b in bins) == overturned, "%s: every overturn in its bin" % part
        for b in bins:
            if b["tests"]:
                lo, hi = b["frequency_interval"]
                assert b["p_low"] <= b["mean_p"] <= b["p_high"] and lo <= b["frequency"] <= hi, b
    by = cal["cross_validated"]["by_motion"]
    assert sorted(m["record"] for m in by) == sorted({r["record"] for r in rows}), "one row per recorded motion"
    assert sum(m["tests"] for m in by) == len(rows) and sum(m["overturned"] for m in by) == overturned
    # the whole is the tests' mean of the motions' own scores
    brier = sum(m["brier"] * m["tests"] for m in by) / len(rows)
    assert abs(brier - cal["cross_validated"]["brier"]) < 1e-9, "by-motion Brier scores add up to the whole"
    assert os.path.getsize(os.path.join(tmp, "cal", "prism.calibration.png")) > 10000, "the calibration's figure"
    with open(os.path.join(tmp, "cal", "prism.calibration", "likelihood.csv")) as fh:
        lik = list(csv.DictReader(fh))
    assert {int(r["stage"]) for r in lik} == {1, 2} and sum(r["stage"] == "1" for r in lik) == 12, "stage 1: 12 headings"
    best = max(float(r["log_likelihood"]) for r in lik if r["stage"] == "2")
    assert abs(best - cal["log_likelihood"]) < 1e-9, "the figure's best is the calibration's"


def check_inferred_cells(work):
    """model.csv against the cube: where the stop rule inferred every cell of a (motion, PGA), the
    model's P is 1 with its full weight (the rule says overturned) and the fit leaves it out."""
    import h5py
    import numpy as np
    with h5py.File(os.path.join(work, "fragility.h5"), "r") as f:
        # [V, R, S, A]: a cube without variants stores [R, S, A]
        outcome = np.concatenate([np.asarray(f["objects"][name]["outcome"][()]).reshape((-1,) + f["objects"][name]["outcome"].shape[-3:])
                                  for name in f["objects"]])
    with open(os.path.join(work, "model.csv")) as fh:
        model = list(csv.DictReader(fh))
    scales = sorted({float(m["scale_g"]) for m in model})
    inferred = (outcome == 3).all(axis=(0, 3))  # [record, scale]: every object, every rotation
    simulated = np.isin(outcome, (1, 2)).all(axis=(0, 3))
    assert inferred.any(), "the grid reaches past the stop rule for some motion"
    for m in model:
        r, s = int(m["record_index"]), scales.index(float(m["scale_g"]))
        if inferred[r, s]:
            assert float(m["p_overturn"]) == 1.0 and float(m["cells"]) > 0 and m["simulated"] == "0", m
        if simulated[r, s]:
            assert m["simulated"] == "1" and float(m["cells"]) > 0, m


def test_planted_lab_fit():
    """The lab fit on outcomes drawn from a known probit: 20 planted labs of 25 motions x 8 tests
    at PGAs spread around the median. The fit must find theta and beta, and its 90 % interval must
    cover theta in about 90 % of the labs (at least 16 of 20)."""
    np = pytest.importorskip("numpy")
    from rigidpy import fit as ff
    from rigidpy import shaketable as sf
    theta, beta = 0.4, 0.35
    errors, betas, covered = [], [], 0
    for lab in range(20):
        rng = np.random.default_rng(lab)
        rows = []
        for m in range(25):
            for a in theta * np.exp(rng.uniform(-2.5, 2.5, 8) * beta):
                p = 0.5 * math.erfc(-math.log(a / theta) / beta / math.sqrt(2))
                rows.append({"record": "m%d" % m, "measured_pga_g": a, "overturned": int(rng.uniform() < p)})
        cells = sf.lab_cells(rows, {"m%d" % m: m for m in range(25)})
        r = ff.scalar_fragility(cells, np.arange(25), np.random.default_rng(1), 200, 0.9)
        lo, hi = r["theta_interval_g"]
        errors.append(abs(math.log(r["theta_g"] / theta)))
        betas.append(r["beta"])
        covered += lo <= theta <= hi
    assert float(np.median(errors)) < 0.1 and 0.25 < float(np.median(betas)) < 0.45 and covered >= 16, ("lab fit recovers planted probits: median |ln theta/0.4| %.3f, median beta %.2f (0.35), 90 %% interval "
          "covers theta in %d of 20" % (float(np.median(errors)), float(np.median(betas)), covered))


def test_calibrate_predict_and_fragility(rigid, tmp):
    scan = os.path.join(tmp, "prism.obj")
    write_prism(scan)
    os.makedirs(os.path.join(tmp, "motions"))
    # the planted model: the imported prism, rigid contact, tilt rule, on a wide table
    planted = os.path.join(tmp, "planted", "prism")
    r = run(rigid, "model", "import", scan, "--out", planted, "--pedestal-margin", "0.5", "--tilt-rule", "30",
            "--max-vertices", "64")
    assert r.returncode == 0, "planted model imports (%s)" % r.stderr.strip()[:200]
    rows = []
    number = 1
    for freq, amps in ((0.8, (0.08, 0.12, 0.16, 0.2, 0.25, 0.3)), (1.6, (0.1, 0.15, 0.2, 0.3, 0.4, 0.5)),
                       (3.0, (0.15, 0.25, 0.35, 0.5, 0.7, 0.9))):
        for amp in amps:
            name = "Test%03d.txt.gz" % number
            write_motion(os.path.join(tmp, "motions", name), freq, amp)
            out = run(rigid, "run", planted + ".toml", "--lab", os.path.join(tmp, "motions", name), "--rotation", "60",
                      "--json")
            over = json.loads(out.stdout)["overturned"] if out.returncode == 0 else None
            rows.append({"test_no": number, "record": "sine_%gHz" % freq, "pgv_over_pga_s": "", "pga_g": amp,
                         "file": "motions/" + name, "overturned": int(bool(over))})
            number += 1
    overturned = sum(r["overturned"] for r in rows)
    assert 0 < overturned < len(rows), "planted outcomes mixed: %d of %d overturned" % (overturned, len(rows))
    columns = ["test_no", "record", "pgv_over_pga_s", "pga_g", "file", "overturned"]
    tests = os.path.join(tmp, "tests.csv")
    write_tests(tests, rows, columns)

    out = os.path.join(tmp, "cal", "prism")
    # relative paths, run from the lab's folder: the designed jobs in the work folder must still
    # find the scan's scenes and the recordings
    r = run(rigid, "shaketable", "calibrate", "prism.obj", "--tests", "tests.csv", "--out", "cal/prism", "--flatten-base", "0",
            "--contact-models", "rigid", "--restitution", "0", "--friction", "0.6", "--headings", "12",
            "--refine-step", "10", "--progress", "none", cwd=tmp)
    assert r.returncode == 0, "calibrate runs (%s)" % r.stderr.strip()[-300:]
    if r.returncode == 0:
        with open(out + ".calibration.json") as f:
            cal = json.load(f)
        h = cal["parameters"]["heading_deg"]["value"]
        off = abs(math.remainder(h - 60.0, 180.0))
        assert off <= 10.0 + 1e-9, "heading recovered: %.1f deg (planted 60, modulo 180)" % h
        assert cal["in_sample"]["accuracy"] == 1.0, ("in-sample accuracy %.3f on outcomes the model made" %
              cal["in_sample"]["accuracy"])
        assert cal["cross_validated"]["tests"] == len(rows), "cross-validation covers every test"
        assert len(cal["stages"]) == 2 and len(cal["stages"][0]["parameter_sets"]) == 1, "both stages reported"
        # one value given for restitution and friction: not dimensions of the design, so no extension stage
        for name in ("restitution", "friction"):
            p = cal["parameters"][name]
            assert p["status"] == "fixed (one value given)" and p["values_tried"] == [p["value"]], (
                "%s given one value is fixed: %s" % (name, p))
        assert cal["parameters"]["lapse"]["status"] in ("interior", "at a physical limit"), cal["parameters"]["lapse"]
        assert [s["stage"] for s in cal["stages"]] == [1, 2] and cal["stages"][1]["purpose"].startswith("stage 2 ("), (
            "each stage says what it did")
        check_probability_quality(cal, rows, tmp)
        rr = run(rigid, "run", out + ".toml", "--lab", os.path.join(tmp, "motions", "Test001.txt.gz"))
        assert rr.returncode == 0, "the calibrated scene runs (%s)" % rr.stderr.strip()[:200]

        # predict: the outcome column is never read
        preds = []
        for variant in ("with", "without", "shuffled"):
            t = os.path.join(tmp, "tests_%s.csv" % variant)
            rs = [dict(x) for x in rows]
            cols = columns
            if variant == "without":
                cols = columns[:-1]
            if variant == "shuffled":
                flips = [x["overturned"] for x in rs]
                random.Random(3).shuffle(flips)
                for x, y in zip(rs, flips):
                    x["overturned"] = y
            write_tests(t, rs, cols)
            p = os.path.join(tmp, "pred_%s.csv" % variant)
            rp = run(rigid, "shaketable", "predict", out + ".toml", "--tests", t, "--out", p, "--progress", "none")
            assert rp.returncode == 0, "predict (%s outcomes) runs (%s)" % (variant, rp.stderr.strip()[-200:])
            preds.append(open(p).read() if rp.returncode == 0 else None)
            if variant == "with":
                assert "accuracy" in rp.stdout, "predict scores against the outcomes it has"
                assert "log loss" in rp.stdout and "reliability" in rp.stdout, "predict's probability quality"
                bins = [l for l in rp.stdout.splitlines() if " tests, mean P " in l]
                assert sum(int(l.split(":")[1].split()[0]) for l in bins) == len(rows), "every test in one bin: %s" % bins
            if variant == "without":
                assert "accuracy" not in rp.stdout, "predict without outcomes prints no score"
        assert preds[0] is not None and preds[0] == preds[1] == preds[2], "predictions identical with the outcomes kept, removed and shuffled"
        # the measured values under names of their own: a sine's recorded PGA is its amplitude
        predicted = list(csv.DictReader(io.StringIO(preds[0]))) if preds[0] else []
        assert predicted and "pga_g" not in predicted[0] and "pgv_over_pga_s" not in predicted[0], (
            "the prediction CSV does not reuse the test list's column names: %s" % list(predicted[0]))
        # a sine a sin(wt) from rest: PGA a, PGV 2a/w (v = a (1 - cos wt) / w), so PGV/PGA 1/(pi f);
        # the lab's processing of the recording moves them by a few per cent
        for p, x in zip(predicted, rows):
            f_hz = float(x["record"][len("sine_"):-len("Hz")])
            assert abs(float(p["measured_pga_g"]) / float(x["pga_g"]) - 1) < 0.07 and abs(
                float(p["measured_pgv_over_pga_s"]) * math.pi * f_hz - 1) < 0.07, (
                "test %s: measured PGA %s g and PGV/PGA %s s are the recording's (a sine of %s g at %g Hz: "
                "%.3f s)" % (p["test_no"], p["measured_pga_g"], p["measured_pgv_over_pga_s"], x["pga_g"], f_hz,
                             1 / (math.pi * f_hz)))
        # the calibrated scene turns the rock instead of the motion: the same physics, other round-off,
        # so a test at the rock's very threshold may go the other way
        got = [int(l.split(",")[-1]) for l in preds[0].strip().splitlines()[1:]] if preds[0] else []
        agree = sum(int(a == b["overturned"]) for a, b in zip(got, rows))
        assert len(got) == len(rows) and agree >= len(rows) - 1, "predict reproduces the planted outcomes: %d of %d" % (agree, len(rows))

        # fragility: the lab's outcomes came from the model, so where a motion both stood and
        # overturned in the lab, its threshold there (between its strongest test below the first
        # overturn and that overturn) holds the PGA at which the model, scaling that motion's
        # recording over the grid, first overturns with P >= 0.5 (a motion that never overturned
        # says nothing: rocking is not monotonic in amplitude, the model may overturn between tests)
        fo = os.path.join(tmp, "frag", "prism")
        rf = run(rigid, "shaketable", "fragility", "cal/prism.toml", "--tests", "tests.csv", "--out", "frag/prism",
                 "--max-pga", "1.0", "--bootstrap", "100", "--progress", "none", cwd=tmp)
        assert rf.returncode == 0, "fragility runs (%s)" % rf.stderr.strip()[-300:]
        if rf.returncode == 0:
            check_fragility_thresholds(fo + ".fragility.work", rows)
            check_inferred_cells(fo + ".fragility.work")
            with open(fo + ".fragility.csv") as f:
                table = {(x["pgv_pga_bin"], x["source"]): x for x in csv.DictReader(f)}
            assert all(("all motions", s) in table for s in ("lab", "model")) and len(table) == 8, "the table has lab and model rows for 3 bins and all motions"
            assert os.path.getsize(fo + ".fragility.png") > 10000, "the figure is written"
        t = os.path.join(tmp, "tests_without.csv")
        rf = run(rigid, "shaketable", "fragility", out + ".toml", "--tests", t, "--out", fo + "_x", "--progress", "none")
        lines = rf.stderr.strip().splitlines()
        assert rf.returncode == 2 and len(lines) == 1 and "overturned" in lines[0], "fragility without outcomes: one line, exit 2 (%s)" % lines


    # bad input: one line naming the file, exit 2
    def bad(name, text, expect, extra=()):
        t = os.path.join(tmp, name)
        with open(t, "w") as f:
            f.write(text)
        r = run(rigid, "shaketable", "calibrate", scan, "--tests", t, "--out", os.path.join(tmp, "bad", name), *extra)
        lines = r.stderr.strip().splitlines()
        assert r.returncode == 2 and len(lines) == 1 and expect in lines[0] and name in lines[0], "%s: exit %d, %s" % (name, r.returncode, lines)

    head = "test_no,record,pgv_over_pga_s,pga_g,file,overturned\n"
    bad("no_file_column.csv", "test_no,record,overturned\n1,a,0\n", "no 'file' column")
    bad("missing_motion.csv", head + "1,a,,0.1,motions/Test001.txt.gz,0\n2,a,,0.1,motions/nope.txt.gz,1\n",
        "missing_motion.csv:3")
    bad("duplicate.csv", head + "1,a,,0.1,motions/Test001.txt.gz,0\n1,a,,0.1,motions/Test002.txt.gz,1\n", "listed twice")
    bad("empty.csv", head, "no test")
    bad("all_equal.csv", head + "1,a,,0.1,motions/Test001.txt.gz,1\n2,a,,0.1,motions/Test002.txt.gz,1\n",
        "cannot identify")
    bad("bad_outcome.csv", head + "1,a,,0.1,motions/Test001.txt.gz,yes\n", "is not 0, 1")
    r = run(rigid, "shaketable", "predict", os.path.join(tmp, "planted", "prism.toml"), "--tests", tests, "--out", tests)
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1 and "tests.csv" in lines[0] and os.path.getsize(tests) > 0, "predict --out over its test list refused, the list intact: %s" % lines
    # a scan that will not stand: the prism leaning beyond its base
    leaning = os.path.join(tmp, "leaning.obj")
    write_prism(leaning, tilt_x=0.6)
    r = run(rigid, "shaketable", "calibrate", leaning, "--tests", tests, "--out", os.path.join(tmp, "lean", "x"),
            "--flatten-base", "0", "--contact-models", "rigid", "--progress", "none")
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1 and "leaning.obj" in lines[0], "a scan that cannot stand: %s" % lines

