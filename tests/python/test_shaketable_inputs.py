"""CTest `shaketable_inputs_python`: what the shake-table commands read is never lost or misread.
A small synthetic lab (an asymmetric prism and sine recordings of three motions, written by
test_shaketable's helpers) and a two-stage calibration small enough for seconds:

- no output replaces an input: `predict --out` set to the calibration file, a recording or the
  scene's contact mesh is refused with one line and exit 2, and every file keeps its SHA-256;
- a calibration into a folder holding another one is refused before it writes anything (the
  work folder's files keep their digests), the same one resumes, outcomes that changed are named
  as such, and --restart starts over;
- outputs that cannot be written are refused before any campaign: OUT.toml a directory, bad --bins;
- cross-validation with one recorded motion is reported unavailable, not as a perfect score;
- the old spelling --flatten-mm gives the scene that --flatten-base gives.

    /usr/bin/python3 -m pytest tests/python/test_shaketable_inputs.py --rigid RIGID
"""
import hashlib
import json
import os

import pytest

from test_shaketable import run, write_motion, write_prism, write_tests

COLUMNS = ["test_no", "record", "pgv_over_pga_s", "pga_g", "file", "overturned"]
DESIGN = ["--contact-models", "rigid", "--restitution", "0", "--friction", "0.6", "--headings", "4",
          "--refine-step", "20", "--progress", "none"]


def digests(folder):
    """SHA-256 of every file below folder (or of the one file), by relative path."""
    if os.path.isfile(folder):
        return {"": hashlib.sha256(open(folder, "rb").read()).hexdigest()}
    out = {}
    for root, _, files in os.walk(folder):
        for name in files:
            path = os.path.join(root, name)
            out[os.path.relpath(path, folder)] = hashlib.sha256(open(path, "rb").read()).hexdigest()
    return out


def one_line(r):
    lines = r.stderr.strip().splitlines()
    return r.returncode == 2 and len(lines) == 1, lines


@pytest.fixture(scope="module")
def lab(rigid, tmp_path_factory):
    """The prism, 6 tests of 3 sine motions with mixed outcomes (planted with `rigid run`), and a
    calibration of them."""
    tmp = str(tmp_path_factory.mktemp("lab"))
    write_prism(os.path.join(tmp, "prism.obj"))
    os.makedirs(os.path.join(tmp, "motions"))
    r = run(rigid, "model", "import", os.path.join(tmp, "prism.obj"), "--out", os.path.join(tmp, "planted", "prism"),
            "--pedestal-margin", "0.5", "--tilt-rule", "30", "--max-vertices", "64")
    assert r.returncode == 0, r.stderr
    rows = []
    for number, (freq, amp) in enumerate(((0.8, 0.08), (0.8, 0.3), (1.6, 0.1), (1.6, 0.5), (3.0, 0.15), (3.0, 0.9)), 1):
        name = "Test%03d.txt.gz" % number
        write_motion(os.path.join(tmp, "motions", name), freq, amp)
        out = run(rigid, "run", os.path.join(tmp, "planted", "prism.toml"), "--lab", os.path.join(tmp, "motions", name),
                  "--rotation", "60", "--json")
        assert out.returncode == 0, out.stderr
        rows.append({"test_no": number, "record": "sine_%gHz" % freq, "pgv_over_pga_s": "", "pga_g": amp,
                     "file": "motions/" + name, "overturned": int(bool(json.loads(out.stdout)["overturned"]))})
    assert 0 < sum(r["overturned"] for r in rows) < len(rows), "mixed planted outcomes"
    write_tests(os.path.join(tmp, "tests.csv"), rows, COLUMNS)
    r = run(rigid, "shaketable", "calibrate", "prism.obj", "--tests", "tests.csv", "--out", "cal/prism",
            "--flatten-base", "0", *DESIGN, cwd=tmp)
    assert r.returncode == 0, r.stderr
    return tmp, rows


def test_no_output_replaces_an_input(rigid, lab):
    tmp, _ = lab
    scene = os.path.join(tmp, "cal", "prism.toml")
    with open(scene) as f:
        mesh = next(line.split("'")[1] for line in f if line.strip().startswith("contact = ["))
    for target in (os.path.join(tmp, "cal", "prism.calibration.json"), os.path.join(tmp, "motions", "Test002.txt.gz"),
                   os.path.normpath(os.path.join(tmp, "cal", mesh))):
        before = digests(target)
        r = run(rigid, "shaketable", "predict", scene, "--tests", os.path.join(tmp, "tests.csv"), "--out", target,
                "--progress", "none")
        ok, lines = one_line(r)
        assert ok and "input" in lines[0], "predict --out %s refused: %s" % (target, lines)
        assert digests(target) == before, "%s unchanged" % target
    # bad bin edges: refused before the campaign
    r = run(rigid, "shaketable", "fragility", scene, "--tests", os.path.join(tmp, "tests.csv"), "--out",
            os.path.join(tmp, "frag"), "--bins", "0.3,0.1", "--progress", "none")
    ok, lines = one_line(r)
    assert ok and "--bins" in lines[0], "bad --bins refused: %s" % lines
    assert not os.path.exists(os.path.join(tmp, "frag.fragility.work")), "refused before the campaign"


def test_a_calibration_resumes_only_what_it_started(rigid, lab):
    tmp, rows = lab
    work = os.path.join(tmp, "cal", "prism.calibration")
    before = digests(os.path.join(tmp, "cal"))
    # other options into the same OUT: refused before anything is written
    r = run(rigid, "shaketable", "calibrate", "prism.obj", "--tests", "tests.csv", "--out", "cal/prism",
            "--flatten-base", "0", "--max-vertices", "40", *DESIGN, cwd=tmp)
    ok, lines = one_line(r)
    assert ok and "--restart" in lines[0] and "max vertices" in lines[0], "changed options refused: %s" % lines
    assert digests(os.path.join(tmp, "cal")) == before, "nothing written by the refused calibration"
    # the same calibration resumes: its campaigns are done, its results the same
    r = run(rigid, "shaketable", "calibrate", "prism.obj", "--tests", "tests.csv", "--out", "cal/prism",
            "--flatten-base", "0", *DESIGN, cwd=tmp)
    assert r.returncode == 0, r.stderr
    after = digests(os.path.join(tmp, "cal"))
    assert {k: v for k, v in after.items() if not k.endswith(".json")} == \
        {k: v for k, v in before.items() if not k.endswith(".json")}, "a resumed calibration rewrites the same files"
    # outcomes that changed: named, and --restart starts over
    flipped = [dict(x, overturned=1 - x["overturned"]) if x["test_no"] == 1 else x for x in rows]
    write_tests(os.path.join(tmp, "tests_flipped.csv"), flipped, COLUMNS)
    r = run(rigid, "shaketable", "calibrate", "prism.obj", "--tests", "tests_flipped.csv", "--out", "cal/prism",
            "--flatten-base", "0", *DESIGN, cwd=tmp)
    ok, lines = one_line(r)
    assert ok and "outcomes" in lines[0] and "--restart" in lines[0], "changed outcomes named: %s" % lines
    r = run(rigid, "shaketable", "calibrate", "prism.obj", "--tests", "tests_flipped.csv", "--out", "cal/prism",
            "--flatten-base", "0", "--restart", *DESIGN, cwd=tmp)
    assert r.returncode == 0, r.stderr
    assert os.path.exists(os.path.join(work, "calibration.manifest"))


def test_outputs_that_cannot_be_written_are_refused_first(rigid, lab):
    tmp, _ = lab
    os.makedirs(os.path.join(tmp, "blocked", "x.toml"))
    r = run(rigid, "shaketable", "calibrate", "prism.obj", "--tests", "tests.csv", "--out", "blocked/x",
            "--flatten-base", "0", *DESIGN, cwd=tmp)
    ok, lines = one_line(r)
    assert ok and "directory" in lines[0], "OUT.toml a directory: %s" % lines
    assert not os.path.exists(os.path.join(tmp, "blocked", "x.calibration")), "refused before any work"


def test_cross_validation_needs_three_motions(rigid, lab):
    tmp, rows = lab
    mixed = [m for m in sorted({x["record"] for x in rows}) if len({x["overturned"] for x in rows if x["record"] == m}) == 2]
    assert mixed, "a motion with both outcomes (the lab's first motion stands at 0.08 g, falls at 0.3 g)"
    one = [x for x in rows if x["record"] == mixed[0]]
    write_tests(os.path.join(tmp, "one_motion.csv"), one, COLUMNS)
    r = run(rigid, "shaketable", "calibrate", "prism.obj", "--tests", "one_motion.csv", "--out", "one/prism",
            "--flatten-base", "0", *DESIGN, cwd=tmp)
    assert r.returncode == 0, r.stderr
    assert "cross-validated: not available" in r.stdout, r.stdout
    with open(os.path.join(tmp, "one", "prism.calibration.json")) as f:
        cal = json.load(f)
    assert cal["cross_validated"]["available"] is False, cal["cross_validated"]


def test_the_old_spelling_gives_the_same_scene(rigid, lab):
    tmp, _ = lab
    results = {}
    for flag, value in (("--flatten-base", "0.002"), ("--flatten-mm", "2")):
        out = flag.strip("-")
        r = run(rigid, "shaketable", "calibrate", "prism.obj", "--tests", "tests.csv", "--out", out + "/prism",
                flag, value, *DESIGN, cwd=tmp)
        assert r.returncode == 0, r.stderr
        with open(os.path.join(tmp, out, "prism.calibration.json")) as f:
            results[flag] = (json.load(f)["parameters"], digests(os.path.join(tmp, out, "prism.state.toml")), r.stderr)
    assert results["--flatten-base"][:2] == results["--flatten-mm"][:2], "the same calibration from either spelling"
    assert "--flatten-base" in results["--flatten-mm"][2], "the old spelling is noted: %s" % results["--flatten-mm"][2]
    r = run(rigid, "shaketable", "calibrate", "prism.obj", "--tests", "tests.csv", "--out", "both/prism",
            "--flatten-mm", "0", "--flatten-base", "0", *DESIGN, cwd=tmp)
    ok, lines = one_line(r)
    assert ok and "give only --flatten-base" in lines[0], lines
