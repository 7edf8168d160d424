#!/usr/bin/env python3
"""CTest `robustness_cube`: what reads and writes a campaign cube after the campaign (fragility,
hazard, plot, export) must neither lose nor corrupt it, nor answer from a damaged or incomplete
one; the campaign's own inputs (job, record list, variants) refused like scenes are. The harness
is robustness_test.py's (10 s of CPU and 2 GB per case; exit 2 with one `error:` line).

The oracles are independent of the code under test: the cube's bytes before and after (SHA-256
of the file), h5py's view of it, the CSV that `rigid export cells` writes to standard output,
and, for the checksums, a cube edited with h5py (a value changed, an attribute deleted).

usage: cube_robustness_test.py RIGID SOURCE_DIR
"""
import fcntl
import hashlib
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import robustness_test as rt  # noqa: E402  (the harness: run, check, write)

try:
    import h5py
    import numpy as np
except ImportError:
    print("skipped: needs python3-h5py and python3-numpy")
    sys.exit(77)

RIGID, SOURCE = rt.RIGID, rt.SOURCE
DEMO = rt.DEMO
TRIALS = 30  # two concurrent stores per trial
ERROR = "error"

# A tiny campaign: one block, three records, six scales, two rotations (36 cells, ~2 s).
JOB = """[campaign]
seed = 3
scales = [0.05, 0.1, 0.15, 0.2, 0.3, 0.6]
rotations = 2
[[object]]
scene = "block.toml"
[[record]]
motion = "stochastic_s1-X.AT2"
start = 2.0
end = 8.0
[[record]]
motion = "stochastic_s2-X.AT2"
start = 2.0
end = 8.0
[[record]]
motion = "mp_pulse_1s-X.AT2"
[run]
free_time_s = 1.0
"""


def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def rigid(args, cwd, **kw):
    return subprocess.run([RIGID] + args, cwd=cwd, capture_output=True, text=True, errors="replace", **kw)


def exported(cube, cwd):
    """The cells table of `cube` on standard output: the independent view of its contents."""
    p = rigid(["export", "cells", cube, "--csv"], cwd)
    return p.returncode, p.stdout


def leftovers(d, stem):
    """Files beside the cube that a command left behind (temporaries, locks)."""
    return sorted(n for n in os.listdir(d) if n.startswith(stem) and n != stem) + \
        sorted(n for n in os.listdir(d) if n.startswith("." + stem))


def make_fixture(d):
    for name in ("block.stl", "pedestal.stl", "block_a02.model", "block_a02.state.toml"):
        shutil.copy(os.path.join(rt.BLOCK_DIR, name), d)
    for name in ("stochastic_s1-X.AT2", "stochastic_s2-X.AT2", "mp_pulse_1s-X.AT2", "stochastic_s1-Y.AT2"):
        shutil.copy(os.path.join(DEMO, name), d)
    rt.write(d, "block.toml", 'model = "block_a02.model"\nstate = "block_a02.state.toml"\n')
    rt.write(d, "job.toml", JOB)
    p = rigid(["campaign", "job.toml", "--out", "ref.h5", "--progress", "none"], d)
    if p.returncode != 0:
        raise SystemExit("the fixture campaign failed: " + p.stderr)
    rt.write(d, "curve.csv", "pga_g,annual_rate\n0.01,0.1\n0.05,0.02\n0.1,0.005\n0.3,0.0005\n1.0,0.00002\n")
    rt.write(d, "flat.csv", "pga_g,annual_rate\n0.01,1e-30\n0.02,1e-30\n")
    os.mkfifo(os.path.join(d, "fifo.csv"))


class Cases:
    def __init__(self, d):
        self.d = d
        self.failed = []
        self.count = 0

    def fresh(self, name):
        """A private copy of the fixture cube."""
        path = os.path.join(self.d, name)
        shutil.copy(os.path.join(self.d, "ref.h5"), path)
        return path

    def ok(self, name, args):
        self.count += 1
        status, err, cpu, wall = rt.run(args, self.d)
        self.expect(name, status == 0, f"exit {status}: {err.strip()[:300]}")
        self.count -= 1

    def error(self, name, args, fragments):
        """Exit 2 and one `rigid: error:` line (`rigid fragility: error:` from the Python commands)
        naming every fragment, within the harness's limits."""
        self.count += 1
        status, err, cpu, wall = rt.run(args, self.d)
        lines = err.splitlines()
        problems = rt.refusal_problems(status, err, cpu, wall)
        problems += ["no '%s' in the message" % f for f in fragments if f not in err]
        print("%-4s %-48s %5.2f s CPU  exit %3d  %s" % ("FAIL" if problems else "ok", name, cpu, status,
                                                       (lines[0] if lines else "")[:150]))
        for p in problems:
            print("       " + p)
        if problems:
            self.failed.append(name)

    def expect(self, name, condition, detail=""):
        self.count += 1
        print("%-4s %-48s %s" % ("ok" if condition else "FAIL", name, detail if not condition else ""))
        if not condition:
            self.failed.append(name)


# --- the cases ------------------------------------------------------------------------------------

def concurrent_stores(c):
    """Two `rigid fragility` stores at once on one cube, TRIALS times: each exits 0 or refuses
    (exit 2, the lock named); at least one stores; the cube's cells are those of the fixture and
    its /fragility group is whole; nothing is left beside it."""
    d = c.d
    _, reference = exported("ref.h5", d)
    bad = []
    start = time.monotonic()
    for trial in range(TRIALS):
        cube = c.fresh("race.h5")
        procs = [subprocess.Popen([RIGID, "fragility", "race.h5", "--bootstrap", "20"], cwd=d,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True) for _ in range(2)]
        results = [(p.wait(), p.stderr.read()) for p in procs]
        codes = [s for s, _ in results]
        status, cells = exported("race.h5", d)
        problems = []
        for s, err in results:
            if s not in (0, 2) or (s == 2 and ("lock" not in err or len(err.splitlines()) != 1)):
                problems.append(f"exit {s}: {err.strip()[:200]}")
        if 0 not in codes:
            problems.append("neither stored")
        if status != 0 or cells != reference:
            problems.append("the cube's cells changed")
        with h5py.File(cube, "r") as f:
            if "fragility" not in f or "block" not in f["fragility"]:
                problems.append("no whole /fragility group")
        left = leftovers(d, "race.h5")
        if left:
            problems.append("left behind: " + ", ".join(left))
        if problems:
            bad.append(f"trial {trial}: " + "; ".join(problems))
    c.expect(f"{TRIALS} x two concurrent fragility stores", not bad,
             " | ".join(bad[:3]) + f" ({len(bad)} bad trials)")
    print(f"     ({TRIALS} trials in {time.monotonic() - start:.1f} s)")


def export_out_names(c):
    """--csv FILE of 17-23 characters: the file asked for, with the table of standard output."""
    d = c.d
    _, reference = exported("ref.h5", d)
    wrong = []
    for n in range(17, 24):
        name = ("0123456789abcdefghijklmnopqrstuvwxyz"[: n - 4]) + ".csv"
        p = rigid(["export", "cells", "ref.h5", "--csv", name], d)
        path = os.path.join(d, name)
        if p.returncode != 0 or not os.path.exists(path) or rt.read(path) != reference:
            wrong.append(f"{name}: exit {p.returncode}, exists {os.path.exists(path)}")
    c.expect("export cells --csv FILE of 17-23 characters", not wrong, "; ".join(wrong))


def outputs_over_inputs(c):
    """An output that is the cube (however spelled, or a hard link) is refused, the cube intact."""
    d = c.d
    cube = c.fresh("self.h5")
    os.link(cube, os.path.join(d, "self_link.h5"))
    before = sha(cube)
    c.error("fragility --nrml CUBE", ["fragility", "self.h5", "--no-store", "--nrml", "self.h5"], ["--nrml", "self.h5"])
    c.error("fragility --csv ./CUBE", ["fragility", "self.h5", "--no-store", "--csv", "./self.h5"], ["--csv"])
    c.error("fragility --csv HARD_LINK", ["fragility", "self.h5", "--no-store", "--csv", "self_link.h5"], ["--csv"])
    c.error("export cells --csv CUBE", ["export", "cells", "self.h5", "--csv", os.path.join(d, "self.h5")],
            ["self.h5", "input"])
    os.link(os.path.join(d, "curve.csv"), os.path.join(d, "curve_link.png"))
    c.error("hazard --plot a hard link of the curve", ["hazard", "self.h5", "--curve", "curve.csv", "--age", "1000",
                                                       "--plot", "curve_link.png"], ["--plot", "input"])
    c.error("plot table --out CUBE", ["plot", "table", "self.h5", "--out", "self_link.h5"], ["self_link.h5", "input"])
    c.expect("the cube is unchanged", sha(cube) == before)


def damaged_cubes(c):
    """A value changed with h5py where no checksum looked before, or a checksum deleted: every
    reader refuses; a resume too."""
    def damaged(name, edit):
        path = c.fresh(name)
        with h5py.File(path, "r+") as f:
            edit(f)
        return name

    def flip_outcome(f):
        o = f["objects/block/outcome"]
        v = o[()]
        v.flat[0] = 2 if v.flat[0] == 1 else 1
        o[...] = v

    def double_scale(f):
        s = f["axes/scale_g"]
        v = s[()]
        v[-1] *= 2
        s[...] = v

    def halve_pgv_pga(f):
        s = f["records/pgv_pga_s"]
        v = s[()]
        v[0] *= 0.5
        s[...] = v

    def drop_checksum(f):
        del f["objects/block"].attrs["datasets_sha256"]
        flip_outcome(f)

    def drop_axes_checksum(f):
        del f.attrs["axes_sha256"]
        double_scale(f)

    hazard = ["--curve", "curve.csv", "--age", "1000"]
    for name, edit, fragment in (("outcome.h5", flip_outcome, "checksum"), ("scale.h5", double_scale, "checksum"),
                                 ("pgvpga.h5", halve_pgv_pga, "checksum"), ("nosum.h5", drop_checksum, "datasets_sha256"),
                                 ("noaxes.h5", drop_axes_checksum, "axes_sha256")):
        cube = damaged(name, edit)
        before = sha(os.path.join(c.d, cube))
        c.error(f"fragility of a cube with {name[:-3]} damaged", ["fragility", cube, "--no-store"], [cube, fragment])
        c.error(f"hazard of a cube with {name[:-3]} damaged", ["hazard", cube] + hazard, [cube, fragment])
        c.error(f"plot of a cube with {name[:-3]} damaged", ["plot", "maps", cube, "--out", "maps_" + name], [cube, fragment])
        c.error(f"export of a cube with {name[:-3]} damaged", ["export", "cells", cube, "--csv"], [cube, fragment])
        c.error(f"resume over a cube with {name[:-3]} damaged",
                ["campaign", "job.toml", "--out", cube, "--progress", "none"], [cube])
        c.expect(f"the {name[:-3]} cube is left as it was", sha(os.path.join(c.d, cube)) == before)
    # a derived dataset that disagrees with its cells
    cube = damaged("derived.h5", lambda f: f["objects/block/probability"].__setitem__((0, 0), 0.123))
    c.error("plot of a cube with a derived value changed", ["plot", "maps", cube, "--out", "maps_derived"],
            [cube, "probability"])


def incomplete_cubes(c):
    """A campaign stopped mid-way (SIGTERM) and one running (its lock held): the fits say so,
    --require-complete refuses, a store into a running campaign's cube is refused."""
    d = c.d
    job = JOB.replace("rotations = 2", "rotations = 8")
    rt.write(d, "long.toml", job)
    p = subprocess.Popen([RIGID, "campaign", "long.toml", "--out", "stopped.h5", "--progress", "none",
                          "--checkpoint-interval", "0.2", "--grace", "0"], cwd=d,
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    journal = os.path.join(d, "stopped.h5.journal")
    for _ in range(3000):  # until ~20 of the 144 cells are in the journal
        if os.path.exists(journal) and os.path.getsize(journal) > 76 + 20 * 292:
            break
        time.sleep(0.01)
    p.send_signal(signal.SIGTERM)
    p.wait()
    with h5py.File(os.path.join(d, "stopped.h5"), "r") as f:
        not_run = int((f["objects/block/outcome"][()] == 0).sum())
    c.expect("the stopped campaign left cells not run", not_run > 0, f"{not_run} not run")
    p = rigid(["fragility", "stopped.h5", "--no-store", "--bootstrap", "20"], d)
    c.expect("fragility of a stopped campaign's cube warns", "incomplete" in p.stderr and "not run" in p.stderr,
             f"exit {p.returncode}: {p.stderr.strip()[:300]}")
    c.error("fragility --require-complete of a stopped campaign", ["fragility", "stopped.h5", "--require-complete",
                                                                   "--no-store"], ["stopped.h5", "not run"])
    c.error("hazard --require-complete of a stopped campaign", ["hazard", "stopped.h5", "--curve", "curve.csv",
                                                                "--age", "100", "--require-complete"], ["not run"])
    # a running campaign: its lock held (as the campaign holds it: flock on CUBE.lock)
    cube = c.fresh("running.h5")
    fd = os.open(cube + ".lock", os.O_RDWR | os.O_CREAT, 0o644)
    fcntl.flock(fd, fcntl.LOCK_EX)
    try:
        before = sha(cube)
        c.error("fragility store into a running campaign's cube", ["fragility", "running.h5", "--bootstrap", "20"],
                ["running.h5.lock"])
        c.expect("the running campaign's cube is unchanged", sha(cube) == before)
        p = rigid(["fragility", "running.h5", "--no-store", "--bootstrap", "20"], d)
        c.expect("fragility --no-store of a running campaign's cube warns",
                 p.returncode == 0 and "writing it now" in p.stderr, f"exit {p.returncode}: {p.stderr.strip()[:300]}")
        c.error("--require-complete of a running campaign's cube", ["fragility", "running.h5", "--no-store",
                                                                    "--require-complete"], ["writing it now"])
    finally:
        os.close(fd)


def full_disk_store(c):
    """A store that cannot write its copy (RLIMIT_FSIZE, a full disk's EFBIG): exit 2, the cube
    as it was, no temporary left."""
    d = c.d
    cube = c.fresh("full.h5")
    before = sha(cube)
    limit = os.path.getsize(cube) // 2

    def small_files():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    p = subprocess.run([RIGID, "fragility", "full.h5", "--bootstrap", "20"], cwd=d, capture_output=True, text=True,
                       preexec_fn=small_files)
    left = leftovers(d, "full.h5")
    c.expect("store on a full disk: exit 2, one line", p.returncode == 2 and len(p.stderr.splitlines()) == 1,
             f"exit {p.returncode}: {p.stderr.strip()[:300]}")
    c.expect("store on a full disk: cube intact, nothing left", sha(cube) == before and not left, ", ".join(left))


def command_lines(c):
    hz = ["hazard", "ref.h5", "--curve", "curve.csv", "--age", "1000"]
    c.error("fragility --seed -1", ["fragility", "ref.h5", "--no-store", "--seed", "-1"], ["--seed"])
    c.error("hazard --plot x.h5", hz + ["--plot", "x.h5"], ["--plot", "x.h5"])
    c.error("hazard --curve /dev/zero", ["hazard", "ref.h5", "--curve", "/dev/zero", "--age", "1000"],
            ["/dev/zero", "regular"])
    c.error("hazard --curve FIFO", ["hazard", "ref.h5", "--curve", "fifo.csv", "--age", "1000"], ["fifo.csv", "regular"])


def planted_cube(d):
    """A cube of outcomes drawn from a planted probit model (tests/python/synthetic_cube.py's
    writer, with the checksums of the current schema): a fit that has a vector estimate."""
    sys.path.insert(0, os.path.join(SOURCE, "src", "python"))  # rigidpy, for the checksums
    sys.path.insert(0, os.path.join(SOURCE, "tests", "python"))
    import synthetic_cube as tp
    rng = np.random.default_rng(20261126)
    pgv = np.exp(rng.uniform(np.log(0.035), np.log(0.5), tp.R))
    outcome = tp.planted_outcomes(rng, pgv, tp.MU0, tp.MU1, tp.SIGMA, extras=False)
    tp.write_cube(os.path.join(d, "planted.h5"), pgv, [("rock", outcome, {"alpha_rad": tp.ALPHA, "p_rad_s": tp.P})])
    return "planted.h5"


def hazard_prints(c):
    """No "x 0" or "x inf" scalings, no 300-digit return period."""
    d = c.d
    cube = planted_cube(d)
    for name, args in (("flat curve", ["hazard", cube, "--curve", "flat.csv", "--age", "1000"]),
                       ("--age 1e308", ["hazard", cube, "--curve", "curve.csv", "--age", "1e308"]),
                       ("--age 1e-300", ["hazard", cube, "--curve", "curve.csv", "--age", "1e-300"])):
        p = rigid(args, d)
        out = p.stdout
        longest = max((len(w) for w in out.replace(",", "").split()), default=0)
        c.expect(f"hazard on a {name}" if "curve" in name else f"hazard {name}",
                 p.returncode == 0 and " x 0 " not in out + " " and "x inf" not in out and "x 0\n" not in out
                 and longest < 30, f"exit {p.returncode}: {(p.stderr or out).strip()[-300:]}")


def write_stl(path, place):
    """The unit cube's 12 facets (robustness_test's, outward) with each vertex moved by `place`."""
    verts = [place(*v) for v in rt.CUBE_V]
    out = ["solid s"]
    for f in rt.CUBE_F:
        out.append(" facet normal 0 0 0\n  outer loop")
        out += ["   vertex %.17g %.17g %.17g" % verts[i - 1] for i in f]
        out.append("  endloop\n endfacet")
    rt.write(os.path.dirname(path), os.path.basename(path), "\n".join(out + ["endsolid s"]) + "\n")


def job_inputs(c):
    d = c.d
    base = JOB.split("[[record]]")[0]
    records = '[[record]]\nmotion = "stochastic_s1-X.AT2"\n[run]\nfree_time_s = 1.0\n'
    for label, name_line in (('"."', 'name = "."\n'), ("with NUL", 'name = "a\\u0000b"\n'),
                             ("with a newline", 'name = "a\\nb"\n'), ("with '/'", 'name = "a/b"\n')):
        job = base.replace('scene = "block.toml"\n', 'scene = "block.toml"\n' + name_line) + records
        path = rt.write(d, "name.toml", job)
        c.error(f"job object name {label}", ["campaign", path, "--dry-run"], ["name.toml:7:", "object name"])
    # variants must pass the scene checks, refused at the sweep's line
    sweep = base + records + "[sweep]\ncount = 2\n"
    # a block leaning over its base (a sheared prism, its centre of mass 0.05 m inside the base's
    # edge): an offset of 0.08 m keeps the centre inside the block but beyond the support
    write_stl(os.path.join(d, "leaning.stl"), lambda x, y, z: (0.2 * x + 0.1 * z, 0.2 * y, z))
    write_stl(os.path.join(d, "base.stl"), lambda x, y, z: (-0.3 + 0.8 * x, -0.2 + 0.6 * y, -0.3 + 0.3 * z))
    rt.write(d, "leaning.model", "block base.stl\n1 0 0 0\nblock leaning.stl\n0 0 0 0\n")
    rt.write(d, "leaning.toml", 'model = "leaning.model"\n')
    path = rt.write(d, "leaning_job.toml", (sweep + "com_offset_x_m = [0.08, 0.09]\n").replace("block.toml",
                                                                                                "leaning.toml"))
    c.error("variant: centre of mass beyond the support", ["campaign", path, "--out", "leaning.h5", "--dry-run"],
            ["leaning_job.toml:11:", "support polygon"])
    path = rt.write(d, "upright_job.toml", (sweep + "com_offset_x_m = [0.0, 0.01]\n").replace("block.toml",
                                                                                               "leaning.toml"))
    c.ok("variant: centre of mass within the support", ["campaign", path, "--out", "upright.h5", "--dry-run"])
    for label, line, fragment in (("size_scale 1e-6", "size_scale = [1e-6, 2e-6]\n", "radius"),
                                  ("size_scale 1e6", "size_scale = [1e6, 2e6]\n", "radius"),
                                  ("density 7e8", "density_kg_m3 = [7e8, 8e8]\n", "density")):
        path = rt.write(d, "variant.toml", sweep + line)
        c.error(f"variant {label}", ["campaign", path, "--out", "variant.h5", "--dry-run"],
                ["variant.toml:11:", fragment])
    # a record listed twice in a record list
    rt.write(d, "twice.tsv", "earthquake\tyear\tmagnitude\tfile\tstart\tend\n"
                             "a\t2000\t6\tstochastic_s1-X.AT2\t0\t5\nb\t2001\t6\tstochastic_s2-X.AT2\t0\t5\n"
                             "a\t2000\t6\tstochastic_s1-X.AT2\t0\t5\n")
    path = rt.write(d, "list.toml", 'records = "twice.tsv"\n' + base + '[run]\nfree_time_s = 1.0\n')
    c.error("a record listed twice", ["campaign", path, "--dry-run"], ["twice.tsv:4:", "line 2"])


def run_command(c):
    d = c.d
    motion = ["--motion", "stochastic_s1-X.AT2", "--target-pga", "0.2"]
    c.error("run --model rocking2d --dt", ["run", "block.toml", "--model", "rocking2d", "--dt", "1e-3"] + motion,
            ["--dt", "rocking2d"])
    # a 1e200 g drive once ran into a non-finite state; it is now refused before the run, as every
    # drive beyond 50 g is (motion::drive_sample_problem)
    p = rigid(["run", "block.toml", "--motion", "stochastic_s1-X.AT2", "--target-pga", "1e200"], d)
    c.expect("an absurd drive prints no outcome", p.returncode == 2 and "survived" not in p.stdout
             and "OVERTURNED" not in p.stdout and "50 g" in p.stderr,
             f"exit {p.returncode}: {p.stdout.strip()[:100]} | {p.stderr.strip()[:100]}")


def rerun_and_path_spelling(c):
    """A finished campaign run again keeps /fragility; the job named by another path resumes."""
    d = c.d
    cube = c.fresh("again.h5")
    p = rigid(["fragility", "again.h5", "--bootstrap", "20"], d)
    c.expect("the fits are stored", p.returncode == 0, p.stderr.strip()[:200])
    p = rigid(["campaign", "job.toml", "--out", "again.h5", "--progress", "none"], d)
    with h5py.File(cube, "r") as f:
        kept = "fragility" in f and "block" in f["fragility"]
    c.expect("a finished campaign run again keeps /fragility", p.returncode == 0 and kept,
             f"exit {p.returncode}, kept {kept}: {p.stderr.strip()[:200]}")
    # a job with an optional object that is absent (its note enters the job's text and hash)
    rt.write(d, "optional.toml", JOB + '[[object]]\nscene = "scans/absent.toml"\noptional = true\n')
    p = rigid(["campaign", "optional.toml", "--out", "spelled.h5", "--progress", "none"], d)
    c.expect("the job with an absent optional object runs", p.returncode == 0, p.stderr.strip()[:300])
    before = sha(os.path.join(d, "spelled.h5"))
    p = rigid(["campaign", os.path.join(d, "optional.toml"), "--out", "spelled.h5", "--progress", "none"], d)
    c.expect("the job by its absolute path resumes its cube", p.returncode == 0, p.stderr.strip()[:300])
    sub = os.path.join(d, "sub")
    os.makedirs(sub, exist_ok=True)
    p = rigid(["campaign", "../optional.toml", "--out", "../spelled.h5", "--progress", "none"], sub)
    c.expect("the job by a relative path from elsewhere resumes it", p.returncode == 0, p.stderr.strip()[:300])
    with h5py.File(os.path.join(d, "spelled.h5"), "r") as f:
        text = f.attrs["job_text"]
    c.expect("the job's text names no path of the job file", d not in text and before != "", text[-200:])


def main():
    if not os.access(RIGID, os.X_OK):
        print("no executable " + RIGID)
        return 1
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="rigid_cube_robustness_") as d:
        make_fixture(d)
        c = Cases(d)
        only = os.environ.get("RIGID_CUBE_CASES", "").split()
        for group in (export_out_names, outputs_over_inputs, command_lines, hazard_prints, damaged_cubes,
                      full_disk_store, incomplete_cubes, job_inputs, run_command, rerun_and_path_spelling,
                      concurrent_stores):
            if not only or group.__name__ in only:
                group(c)
    print("%d cases, %d failed, %.1f s" % (c.count, len(c.failed), time.monotonic() - start))
    for name in c.failed:
        print("FAILED: " + name)
    return 1 if c.failed else 0


if __name__ == "__main__":
    sys.exit(main())
