"""A campaign whose [[object]] takes its physics from a shake-table calibration (job file
`calibration = "FILE"`), against independent oracles:

a. The members' mixture: a calibration of two member scenes of clearly different strength (the
   demo's blocks of slenderness 0.2 and 0.3 rad; three members, two of them of the first scene,
   so its weight is theirs summed: 0.5 + 0.25 = 0.75 by hand) runs as one campaign, and each
   member scene as an ordinary campaign of its own with the same seed. Every variant of the
   calibrated cube holds exactly the outcomes of its member's ordinary campaign (rotations are
   drawn per base object, as for any field rock, not from the members' lab headings); the cube
   carries the calibration's path, SHA-256 (hashlib here), weights (0.75, 0.25) and summary.
   `rigid fragility`'s pooled fragility is the weight-mixture of the members' own fragilities
   (their lognormals from the ordinary cubes, mixed and bisected here), its report names the
   calibration and the member count; `rigid hazard`'s rate of the calibrated rock is the
   weighted sum of the members' rates (the hazard integral is linear in the fragility).
b. Bad input, each one line `rigid: error: FILE:LINE: ...` and exit 2: a missing calibration, an
   edited one (checksum), a truncated one, another format version, a scene that is not the
   calibration's, two calibrated objects, a calibrated object beside another, with a [sweep].
c. A resume with the calibration replaced (a valid document, other weights) is refused; with the
   same calibration it resumes.
d. A scanned rock (a scene with NAME.import.json beside it, as `rigid model import` writes) on the
   default physics: the campaign summary says so in one line and names `calibration = `.

The calibration files are written here as calibration_document.cpp writes them: the envelope, the
body, and the SHA-256 of the compact dump (keys in order, numbers as written: only short decimals
here, which Python's json and nlohmann's dump spell alike); `rigid` refuses a checksum that does
not match, so a wrong dump here fails the test rather than passing it.

    /usr/bin/python3 -m pytest tests/python/test_calibrated_campaign.py --rigid RIGID
"""
import hashlib
import json
import math
import os
import shutil
import subprocess

import pytest

np = pytest.importorskip("numpy")
pytest.importorskip("h5py")
pytest.importorskip("scipy")
from scipy.special import ndtr  # noqa: E402

from rigidpy.cube import Cube  # noqa: E402

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DEMO_MODELS = os.path.join(SOURCE, "models", "demo")
DEMO_MOTIONS = os.path.join(SOURCE, "waveforms", "demo")
RECORDS = ["stochastic_s1-X.AT2", "stochastic_s2-X.AT2", "stochastic_s3-X.AT2", "mp_pulse_1s-X.AT2"]
WEIGHTS = [0.75, 0.25]  # block_a02's members 0.5 + 0.25, block_a03's 0.25, by hand

CAMPAIGN = """[campaign]
seed = 3
scales = [0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0, 1.3]
rotations = 2
"""
RECORD_TABLES = "".join(f'[[record]]\nmotion = "{r}"\n' + ('start = 2.0\nend = 8.0\n' if "stochastic" in r else "")
                        for r in RECORDS) + "[run]\nfree_time_s = 1.0\n"


def calibration_document(body, version=2):
    """The document write_calibration_document writes for `body` (SOURCE_DATE_EPOCH 0)."""
    doc = {"format": "rigid calibration", "format_version": version, "rigid_version": "test",
           "created": "1970-01-01T00:00:00Z", "command_line": "test_calibrated_campaign.py"}
    doc.update(body)
    doc["sha256"] = hashlib.sha256(json.dumps(doc, separators=(",", ":"), ensure_ascii=False).encode()).hexdigest()
    return doc


def calibration_body(weights=(0.5, 0.25, 0.25)):
    return {"scene": "block_a02.toml",
            "parameters": {"contact": {"value": "rigid"}, "friction": {"value": 0.6}},
            "in_sample": {"log_score": 0.5},
            "ensemble": [{"scene": "block_a02.toml", "rotations_deg": [0, 5], "weight": weights[0], "lapse": 0.1},
                         {"scene": "block_a02.toml", "rotations_deg": [10], "weight": weights[1], "lapse": 0},
                         {"scene": "block_a03.toml", "rotations_deg": [0], "weight": weights[2], "lapse": 0}]}


def write_json(path, doc):
    with open(path, "w") as f:
        json.dump(doc, f, indent=2)


def run(cmd, cwd):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=300)


def job_text(objects, extra=""):
    return CAMPAIGN + objects + extra + RECORD_TABLES


@pytest.fixture(scope="module")
def work(rigid, tmp_path_factory):
    """The calibration, its job and the members' ordinary jobs, run once: {name: path}."""
    d = str(tmp_path_factory.mktemp("calibrated"))
    for name in os.listdir(DEMO_MODELS):
        if name.startswith(("block_a02", "block_a03")):
            shutil.copy(os.path.join(DEMO_MODELS, name), d)
    for r in RECORDS:
        shutil.copy(os.path.join(DEMO_MOTIONS, r), d)
    write_json(os.path.join(d, "rock.calibration.json"), calibration_document(calibration_body()))
    jobs = {"calibrated": '[[object]]\nname = "rock"\ncalibration = "rock.calibration.json"\n',
            "a02": '[[object]]\nname = "rock"\nscene = "block_a02.toml"\n',
            "a03": '[[object]]\nname = "rock"\nscene = "block_a03.toml"\n'}
    out = {"dir": d}
    for name, objects in jobs.items():
        with open(os.path.join(d, name + ".toml"), "w") as f:
            f.write(job_text(objects))
        r = run([rigid, "campaign", name + ".toml", "--out", name + ".h5", "--progress", "none"], d)
        assert r.returncode == 0, r.stderr
        out[name] = os.path.join(d, name + ".h5")
        out[name + "_stdout"] = r.stdout
    return out


def lognormal_of(rigid, cube, cwd):
    r = run([rigid, "fragility", cube, "--json", "--no-store", "--bootstrap", "20"], cwd)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def test_variants_are_the_members_campaigns(work):
    cal = Cube(work["calibrated"])
    assert cal.variants.count == 2
    for v, member in enumerate(["a02", "a03"]):
        theirs = Cube(work[member]).objects[0]
        ours = [o for o in cal.objects if o.variant == v][0]
        assert np.array_equal(ours.outcome, theirs.outcome), f"variant {v} differs from {member}'s own campaign"
    # the two members are clearly different rocks: the oracle could tell them apart
    assert not np.array_equal(cal.objects[0].outcome, cal.objects[1].outcome)
    c = cal.calibrations["rock"]
    path = os.path.join(work["dir"], "rock.calibration.json")
    assert os.path.samefile(os.path.join(work["dir"], c.path), path)  # as the job names it, like scenes
    with open(path, "rb") as f:
        assert c.sha256 == hashlib.sha256(f.read()).hexdigest()
    assert np.allclose(c.weights, WEIGHTS, rtol=0, atol=1e-15)
    assert c.summary["rigid_version"] == "test" and c.summary["created"] == "1970-01-01T00:00:00Z"
    assert c.summary["parameters"]["friction"]["value"] == 0.6 and "in_sample" in c.summary
    assert "calibrated" in work["calibrated_stdout"] and "rock.calibration.json" in work["calibrated_stdout"]


def mixture_median(lognormals, weights):
    """Bisection on ln a of sum_v w_v Phi(ln(a / theta_v) / beta_v) = 1/2."""
    def p(a):
        return sum(w * ndtr(math.log(a / t) / b) for w, (t, b) in zip(weights, lognormals))
    lo, hi = math.log(1e-4), math.log(1e3)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if p(math.exp(mid)) < 0.5 else (lo, mid)
    return math.exp(0.5 * (lo + hi))


def test_pooled_fragility_is_the_weight_mixture(rigid, work):
    d = work["dir"]
    members = []
    for name in ("a02", "a03"):
        frag = lognormal_of(rigid, work[name], d)["objects"][0]["vector"]
        members.append(frag)
    doc = lognormal_of(rigid, work["calibrated"], d)
    analysis = doc["variant_analysis"][0]
    per_variant = [(f["fragility"]["theta_g"], f["fragility"]["beta"]) for f in doc["objects"]]
    # each variant's fragility is its member's own, fitted from the same outcomes
    own = [(float(m["lognormal_theta_g"]), float(m["lognormal_beta"])) if "lognormal_theta_g" in m else None
           for m in members]
    for v, o in enumerate(own):
        if o is not None:
            assert per_variant[v][0] == pytest.approx(o[0], rel=1e-9)
    assert per_variant[0][0] < per_variant[1][0], "the slenderer block topples at a lower PGA"
    pooled = analysis["pooled"]
    assert pooled["median_g"] == pytest.approx(mixture_median(per_variant, WEIGHTS), rel=1e-6)
    # not the equally weighted mixture, which the oracle tells apart
    assert abs(mixture_median(per_variant, [0.5, 0.5]) - pooled["median_g"]) > 1e-3
    assert analysis["calibration"]["members"] == 2
    assert analysis["calibration"]["weights"] == pytest.approx(WEIGHTS)
    r = run([rigid, "fragility", work["calibrated"], "--no-store", "--bootstrap", "20"], d)
    assert r.returncode == 0, r.stderr
    assert "rock.calibration.json" in r.stdout and "2 member scenes" in r.stdout


def test_hazard_rate_is_the_weighted_sum_of_the_members(rigid, work):
    d = work["dir"]
    with open(os.path.join(d, "curve.csv"), "w") as f:
        f.write("pga_g,annual_rate\n")
        for a in np.geomspace(0.01, 3.0, 60):
            f.write(f"{a:.6g},{1e-3 * (a / 0.1) ** -2.5:.6g}\n")

    def rate(cube):
        r = run([rigid, "hazard", cube, "--curve", "curve.csv", "--age", "1000", "--json", "--bootstrap", "20"], d)
        assert r.returncode == 0, r.stderr
        return json.loads(r.stdout)

    members = [rate(work[n]) for n in ("a02", "a03")]
    ours = rate(work["calibrated"])
    assert ours["calibration"]["members"] == 2
    key = "annual_toppling_rate"
    expect = sum(w * m[key] for w, m in zip(WEIGHTS, members))
    assert ours[key] == pytest.approx(expect, rel=1e-6)


def refused(r, *fragments):
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert len(lines) == 1 and lines[0].startswith("rigid: error: "), r.stderr
    for f in fragments:
        assert f in lines[0], (f, lines[0])


def test_bad_calibrations_are_refused(rigid, work):
    d = work["dir"]
    good = calibration_document(calibration_body())
    edited = dict(good, ensemble=calibration_body((0.5, 0.25, 0.5))["ensemble"])  # the old checksum
    write_json(os.path.join(d, "edited.calibration.json"), edited)
    with open(os.path.join(d, "rock.calibration.json")) as f:
        text = f.read()
    with open(os.path.join(d, "truncated.calibration.json"), "w") as f:
        f.write(text[: len(text) // 2])
    write_json(os.path.join(d, "v3.calibration.json"), calibration_document(calibration_body(), version=3))
    cases = {
        "missing": ('[[object]]\ncalibration = "none.calibration.json"\n', "", ["bad.toml:", "none.calibration.json"]),
        "edited": ('[[object]]\ncalibration = "edited.calibration.json"\n', "", ["edited.calibration.json", "checksum"]),
        "truncated": ('[[object]]\ncalibration = "truncated.calibration.json"\n', "", ["truncated.calibration.json"]),
        "version": ('[[object]]\ncalibration = "v3.calibration.json"\n', "", ["v3.calibration.json", "version 3"]),
        "other scene": ('[[object]]\nscene = "block_a03.toml"\ncalibration = "rock.calibration.json"\n', "",
                        ["bad.toml:5:", "not the calibration's scene"]),
        "two calibrated": ('[[object]]\nname = "a"\ncalibration = "rock.calibration.json"\n'
                           '[[object]]\nname = "b"\ncalibration = "rock.calibration.json"\n', "",
                           ["bad.toml:8:", "one calibrated [[object]]"]),
        "beside another": ('[[object]]\nname = "a"\ncalibration = "rock.calibration.json"\n'
                           '[[object]]\nname = "b"\nscene = "block_a03.toml"\n', "",
                           ["bad.toml:5:", "only object"]),
        "with a sweep": ('[[object]]\ncalibration = "rock.calibration.json"\n',
                         '[sweep]\nmethod = "lhs"\ncount = 2\nfriction = [0.4, 0.9]\n', ["bad.toml:", "[sweep]"]),
    }
    for name, (objects, extra, fragments) in cases.items():
        with open(os.path.join(d, "bad.toml"), "w") as f:
            f.write(job_text(objects, extra))
        r = run([rigid, "campaign", "bad.toml", "--out", "bad.h5", "--progress", "none"], d)
        refused(r, *fragments)
        assert not os.path.exists(os.path.join(d, "bad.h5")), name


def test_resume_with_a_replaced_calibration_is_refused(rigid, work):
    d = work["dir"]
    shutil.copy(work["calibrated"], os.path.join(d, "resume.h5"))
    r = run([rigid, "campaign", "calibrated.toml", "--out", "resume.h5", "--progress", "none"], d)
    assert r.returncode == 0, r.stderr  # the same inputs: nothing left to run
    path = os.path.join(d, "rock.calibration.json")
    with open(path) as f:
        kept = f.read()
    try:
        write_json(path, calibration_document(calibration_body((0.25, 0.25, 0.5))))
        with open(work["calibrated"], "rb") as f:
            before = hashlib.sha256(f.read()).hexdigest()
        r = run([rigid, "campaign", "calibrated.toml", "--out", "resume.h5", "--progress", "none"], d)
        refused(r)
        with open(work["calibrated"], "rb") as f:
            assert hashlib.sha256(f.read()).hexdigest() == before
    finally:
        with open(path, "w") as f:
            f.write(kept)


def test_scanned_rock_on_default_physics_is_named(rigid, work):
    d = os.path.join(work["dir"], "scan")
    os.makedirs(d, exist_ok=True)
    for name in os.listdir(work["dir"]):
        if name.startswith("block_a02") or name in RECORDS:
            shutil.copy(os.path.join(work["dir"], name), d)
    with open(os.path.join(d, "job.toml"), "w") as f:
        f.write(job_text('[[object]]\nname = "rock"\nscene = "block_a02.toml"\n'))
    r = run([rigid, "campaign", "job.toml", "--out", "plain.h5", "--progress", "none"], d)
    assert r.returncode == 0, r.stderr
    assert "uncalibrated" not in r.stdout, "a scene without an import report is not a scan"
    with open(os.path.join(d, "block_a02.import.json"), "w") as f:
        f.write("{}\n")
    r = run([rigid, "campaign", "job.toml", "--out", "scan.h5", "--progress", "none"], d)
    assert r.returncode == 0, r.stderr
    notes = [line for line in r.stdout.splitlines() if "uncalibrated" in line]
    assert len(notes) == 1 and "calibration = " in notes[0] and "rigid shaketable" in notes[0], r.stdout
