"""CTest `shaketable_transfer_python`: `rigid shaketable transfer` carries a calibration's physics
to another rock, checked on a synthetic lab of two rocks that share one planted contact law.

- Oracle, the planted simulator: a tall prism (0.9 m) and a stocky one (0.55 m) on the same
  irregular pentagon (test_shaketable's scan) stand on tables turned by planted headings (60 and
  20 deg) and are shaken by sine recordings; `rigid run --lab --rotation` on each imported prism,
  with the import's own contact law (rigid, no bounce), gives their outcomes. The tall prism is
  calibrated (a small design that holds the planted law); its calibration is carried to the
  stocky scan and predicts the stocky prism's tests, which transfer never reads:
  - heading given (--heading 20, no spread): the planted physics on the planted heading, so every
    test but at most one at the rock's threshold (turning the rock rather than the motion changes
    the round-off, as in test_shaketable) must agree;
  - heading unknown (a ring of 12): a test can go wrong only where the stocky prism's outcome
    depends on its heading; the amplitudes lie away from its thresholds at the planted heading
    (STOCKY_AMPLITUDES), so at least 7 of the 9 must agree, more than "never overturns" gets;
  - the check can fail: the tall prism's own calibrated scene on the stocky prism's tests agrees
    less often than the carried physics with the heading given.
- The document: source_calibration's SHA-256 is the file's (hashlib), the ensemble's weights add
  to the source's, every member sees the whole ring (or, with --heading, the ring's headings
  within the spread, worked by hand), and nothing is scored; `predict` and `fragility` read it
  as they read calibrate's.
- Bad input: an edited, truncated or other-version calibration, a missing calibration or scan,
  a scan that tips while settling, bad --heading values: one line, exit 2.
- Resume: a second run reuses the imports; another scan or calibration into the same OUT is
  refused until --restart.

    /usr/bin/python3 -m pytest tests/python/test_shaketable_transfer.py --rigid RIGID
"""
import csv
import hashlib
import json
import math
import os

import pytest

from test_shaketable import run, write_motion, write_prism, write_tests

COLUMNS = ["test_no", "record", "pgv_over_pga_s", "pga_g", "file", "overturned"]
IMPORT = ["--pedestal-margin", "0.5", "--tilt-rule", "30", "--max-vertices", "64"]
TALL, STOCKY = 0.9, 0.55
TALL_HEADING, STOCKY_HEADING = 60.0, 20.0
FREQUENCIES = (0.8, 1.6, 3.0)
TALL_AMPLITUDES = {0.8: (0.08, 0.16, 0.3), 1.6: (0.1, 0.2, 0.5), 3.0: (0.15, 0.35, 0.9)}
# the stocky prism at its planted heading falls at 0.7 g (0.8 and 1.6 Hz, not at 0.5 g) and at 3 Hz
# stands at 1.2 g and falls at 2.5 g at every heading tried; the tall prism falls at 0.3-0.5 g
# (0.8 and 1.6 Hz) and 1.2 g (3 Hz): amplitudes between the two tell the rocks apart
STOCKY_AMPLITUDES = {0.8: (0.2, 0.4, 0.9), 1.6: (0.25, 0.5, 0.9), 3.0: (0.5, 1.2, 2.5)}


def one_line(r):
    lines = r.stderr.strip().splitlines()
    return r.returncode == 2 and len(lines) == 1, lines


def planted_lab(rigid, tmp, name, height, heading, amplitudes, first):
    """Writes NAME.obj, its planted scene, the motions and NAME_tests.csv; returns the rows."""
    scan = os.path.join(tmp, name + ".obj")
    write_prism(scan, h=height)
    planted = os.path.join(tmp, "planted", name)
    r = run(rigid, "model", "import", scan, "--out", planted, *IMPORT)
    assert r.returncode == 0, r.stderr
    rows, number = [], first
    for freq in FREQUENCIES:
        for amp in amplitudes[freq]:
            motion = "motions/Test%03d.txt.gz" % number
            write_motion(os.path.join(tmp, motion), freq, amp)
            out = run(rigid, "run", planted + ".toml", "--lab", os.path.join(tmp, motion), "--rotation", str(heading),
                      "--json")
            assert out.returncode == 0, out.stderr
            rows.append({"test_no": number, "record": "sine_%gHz" % freq, "pgv_over_pga_s": "", "pga_g": amp,
                         "file": motion, "overturned": int(bool(json.loads(out.stdout)["overturned"]))})
            number += 1
    assert 0 < sum(x["overturned"] for x in rows) < len(rows), "%s: mixed planted outcomes" % name
    write_tests(os.path.join(tmp, name + "_tests.csv"), rows, COLUMNS)
    return rows


@pytest.fixture(scope="module")
def lab(rigid, tmp_path_factory):
    tmp = str(tmp_path_factory.mktemp("transfer"))
    os.makedirs(os.path.join(tmp, "motions"))
    tall = planted_lab(rigid, tmp, "tall", TALL, TALL_HEADING, TALL_AMPLITUDES, 1)
    stocky = planted_lab(rigid, tmp, "stocky", STOCKY, STOCKY_HEADING, STOCKY_AMPLITUDES, 101)
    # the design holds the planted law (rigid, restitution 0, friction 0.6) and others
    r = run(rigid, "shaketable", "calibrate", "tall.obj", "--tests", "tall_tests.csv", "--out", "cal/tall",
            "--flatten-base", "0", "--contact-models", "rigid", "--restitution", "0,0.5", "--friction", "0.6,0.9",
            "--headings", "6", "--refine-step", "20", "--progress", "none", *IMPORT, cwd=tmp)
    assert r.returncode == 0, r.stderr
    return tmp, tall, stocky


def predictions(rigid, tmp, scene, name):
    out = os.path.join(tmp, name + ".csv")
    r = run(rigid, "shaketable", "predict", scene, "--tests", "stocky_tests.csv", "--out", out, "--progress", "none",
            cwd=tmp)
    assert r.returncode == 0, r.stderr
    with open(out) as f:
        return {int(x["test_no"]): int(x["predicted"]) for x in csv.DictReader(f)}


def test_transfer_predicts_the_other_rock(rigid, lab):
    tmp, _, stocky = lab
    truth = {x["test_no"]: x["overturned"] for x in stocky}
    agree = lambda got: sum(int(got[k] == v) for k, v in truth.items())

    r = run(rigid, "shaketable", "transfer", "cal/tall.calibration.json", "stocky.obj", "--out", "tr/stocky", *IMPORT,
            cwd=tmp)
    assert r.returncode == 0, r.stderr
    with open(os.path.join(tmp, "tr", "stocky.calibration.json")) as f:
        doc = json.load(f)
    with open(os.path.join(tmp, "cal", "tall.calibration.json")) as f:
        source = json.load(f)
    source_sha = hashlib.sha256(open(os.path.join(tmp, "cal", "tall.calibration.json"), "rb").read()).hexdigest()
    assert doc["source_calibration"]["sha256"] == source_sha, "the source calibration's SHA-256 recorded"
    assert doc["transfer"]["heading_known"] is False and doc["transfer"]["rotations_deg"] == [30.0 * k for k in range(12)]
    assert all(m["rotations_deg"] == doc["transfer"]["rotations_deg"] for m in doc["ensemble"]), "each member sees the ring"
    assert math.isclose(sum(m["weight"] for m in doc["ensemble"]), sum(m["weight"] for m in source["ensemble"])), \
        "the merged members' weights add to the source's"
    assert not {"in_sample", "cross_validated", "parameters"} & set(doc), "a transfer has no scores"
    unknown = predictions(rigid, tmp, "tr/stocky.toml", "unknown")
    stood = len(truth) - sum(truth.values())
    assert agree(unknown) >= 7 and agree(unknown) > stood, "heading unknown: %d of 9 stocky outcomes predicted (never " \
        "overturns: %d)" % (agree(unknown), stood)

    r = run(rigid, "shaketable", "transfer", "cal/tall.calibration.json", "stocky.obj", "--out", "tr20/stocky",
            "--heading", str(STOCKY_HEADING), *IMPORT, cwd=tmp)
    assert r.returncode == 0, r.stderr
    with open(os.path.join(tmp, "tr20", "stocky.calibration.json")) as f:
        t = json.load(f)["transfer"]
    assert t["heading_known"] and t["heading_deg"] == STOCKY_HEADING and t["rotations_deg"] == [0.0], t
    # a spread keeps the ring's headings within it (30 deg steps: 60 deg either side is five)
    r = run(rigid, "shaketable", "transfer", "cal/tall.calibration.json", "stocky.obj", "--out", "spread/stocky",
            "--heading", "20", "--heading-spread", "60", *IMPORT, cwd=tmp)
    assert r.returncode == 0, r.stderr
    with open(os.path.join(tmp, "spread", "stocky.calibration.json")) as f:
        rotations = json.load(f)["transfer"]["rotations_deg"]
    assert rotations == [-60.0, -30.0, 0.0, 30.0, 60.0], rotations
    known = predictions(rigid, tmp, "tr20/stocky.toml", "known")
    assert agree(known) >= len(truth) - 1, "heading given: %d of %d stocky outcomes predicted" % (agree(known), len(truth))
    # fragility reads the transferred calibration as it reads calibrate's
    r = run(rigid, "shaketable", "fragility", "tr20/stocky.toml", "--tests", "stocky_tests.csv", "--out", "frag/stocky",
            "--max-pga", "1.5", "--bootstrap", "50", "--progress", "none", cwd=tmp)
    assert r.returncode == 0, r.stderr
    with open(os.path.join(tmp, "frag", "stocky.fragility.csv")) as f:
        assert any(x["source"] == "model" for x in csv.DictReader(f)), "the model's rows from the carried ensemble"
    # the oracle can tell: the tall prism's own scene is not the stocky prism
    own = predictions(rigid, tmp, "cal/tall.toml", "tall_scene")
    assert agree(own) < agree(known), "the tall prism's scene predicts %d, the carried physics %d" % (agree(own), agree(known))


def test_bad_input(rigid, lab):
    tmp = lab[0]
    calibration = os.path.join(tmp, "cal", "tall.calibration.json")
    with open(calibration) as f:
        text = f.read()
    doc = json.loads(text)

    def refused(cal, scan="stocky.obj", extra=(), expect=""):
        r = run(rigid, "shaketable", "transfer", cal, scan, "--out", "bad/x", *extra, cwd=tmp)
        ok, lines = one_line(r)
        assert ok and expect in lines[0], "%s %s %s: %s" % (cal, scan, extra, lines)
        return lines[0]

    edited = dict(doc)
    edited["ensemble"] = [dict(m, weight=m["weight"] * 2) for m in doc["ensemble"]]
    cases = {"edited.json": json.dumps(edited, indent=2), "truncated.json": text[: len(text) // 2],
             "version.json": json.dumps(dict(doc, format_version=3), indent=2)}
    for name, body in cases.items():
        with open(os.path.join(tmp, name), "w") as f:
            f.write(body)
    assert "edited.json" in refused("edited.json", expect="checksum")
    assert "truncated.json" in refused("truncated.json", expect="truncated")
    assert "version.json" in refused("version.json", expect="version 3")
    refused("missing.json", expect="missing.json")
    refused(calibration, "nowhere.obj", expect="nowhere.obj")
    write_prism(os.path.join(tmp, "leaning.obj"), tilt_x=0.6)
    line = refused(calibration, "leaning.obj", expect="leaning.obj")
    assert "rigid" in line and "settling" in line, line
    for flags, expect in ((["--heading", "north"], "--heading"), (["--heading", "nan"], "--heading"),
                          (["--heading", "400"], "--heading"), (["--heading-spread", "30"], "--heading"),
                          (["--heading", "10", "--heading-spread", "-5"], "--heading-spread"),
                          (["--headings", "2"], "--headings")):
        refused(calibration, extra=flags, expect=expect)
    assert not os.path.exists(os.path.join(tmp, "bad", "x.calibration.json")), "nothing written"


def test_a_rerun_resumes_and_changed_inputs_are_refused(rigid, lab):
    tmp = lab[0]
    args = ["shaketable", "transfer", "cal/tall.calibration.json", "stocky.obj", "--out", "again/stocky", *IMPORT]
    r = run(rigid, *args, cwd=tmp)
    assert r.returncode == 0, r.stderr
    scene = open(os.path.join(tmp, "again", "stocky.toml")).read()
    r = run(rigid, *args, cwd=tmp)
    assert r.returncode == 0 and "imported by an earlier run" in r.stdout, r.stdout + r.stderr
    assert open(os.path.join(tmp, "again", "stocky.toml")).read() == scene, "the same scene again"
    # another scan under the same name, another calibration: refused, named
    write_prism(os.path.join(tmp, "stocky2.obj"), h=0.5)
    os.replace(os.path.join(tmp, "stocky.obj"), os.path.join(tmp, "stocky.keep"))
    os.replace(os.path.join(tmp, "stocky2.obj"), os.path.join(tmp, "stocky.obj"))
    try:
        ok, lines = one_line(run(rigid, *args, cwd=tmp))
        assert ok and "scan:" in lines[0] and "--restart" in lines[0], lines
    finally:
        os.replace(os.path.join(tmp, "stocky.keep"), os.path.join(tmp, "stocky.obj"))
    other = ["shaketable", "transfer", "tr/stocky.calibration.json", "stocky.obj", "--out", "again/stocky", *IMPORT]
    ok, lines = one_line(run(rigid, *other, cwd=tmp))
    assert ok and "calibration:" in lines[0], lines
    r = run(rigid, *other, "--restart", cwd=tmp)
    assert r.returncode == 0, r.stderr


def write_turned_box(path, turn_deg, half_x=0.1, half_y=0.25, h=0.9):
    """A box 2 half_x by 2 half_y by h, turned turn_deg about the vertical."""
    c, s = math.cos(math.radians(turn_deg)), math.sin(math.radians(turn_deg))
    corners = [(x, y, z) for z in (0.0, h) for x, y in ((-half_x, -half_y), (half_x, -half_y), (half_x, half_y),
                                                        (-half_x, half_y))]
    v = [(c * x - s * y, s * x + c * y, z) for x, y, z in corners]
    quads = [(3, 2, 1, 0), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    with open(path, "w") as f:
        for p in v:
            f.write("v %.9f %.9f %.9f\n" % p)
        for a, b, q, d in quads:
            f.write("f %d %d %d\nf %d %d %d\n" % (a + 1, b + 1, q + 1, a + 1, q + 1, d + 1))


def test_weakest_heading_is_the_narrow_axis_either_way(rigid, lab):
    # oracle: a box tips most easily across its narrow side, so the table's axis along the box's
    # short (x) side, turned 30 deg, is a heading of 30 deg; the window takes the axis both ways
    tmp = lab[0]
    write_turned_box(os.path.join(tmp, "box.obj"), 30.0)
    r = run(rigid, "shaketable", "transfer", "cal/tall.calibration.json", "box.obj", "--out", "weak/box",
            "--heading", "weakest", "--heading-spread", "30", *IMPORT, cwd=tmp)
    assert r.returncode == 0, r.stderr
    with open(os.path.join(tmp, "weak", "box.calibration.json")) as f:
        t = json.load(f)["transfer"]
    assert abs(t["heading_deg"] - 30.0) <= 0.5 and not t["heading_known"], t
    assert t["rotations_deg"] == [-150.0, -30.0, 0.0, 30.0, 150.0, 180.0], t["rotations_deg"]
    r = run(rigid, "shaketable", "transfer", "cal/tall.calibration.json", "box.obj", "--out", "weak2/box",
            "--heading", "weakest", "--heading-spread", "90", *IMPORT, cwd=tmp)
    ok, lines = one_line(r)
    assert ok and "--heading-spread" in lines[0], lines
