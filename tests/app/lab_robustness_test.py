#!/usr/bin/env python3
"""CTest `robustness_lab`: what the shake-table path reads, through the real command line, with
robustness_test.py's harness (10 s CPU, 2 GB, exit 2 and one `rigid: error:` line naming file and
line). The inputs are made here, each bad one at a line drawn at random (seeded by RIGID_LAB_SEED,
printed), so the fixes are checked on inputs they were not written for:

- record names with commas, quotes, line breaks and 700 characters: `rigid export cells` gives rows
  of the header's width (Python's csv module) holding the cube's names (h5py);
- test lists: a UTF-8 byte-order mark and quoted fields are read; blank and `?` outcomes are
  accepted by predict; a directory, FIFO or /dev/zero as a motion file is named as such;
- lab recordings and AT2 records: a non-finite or absurd sample (beyond 50 g after units and
  scale), a 1e308 volts_to_length, --lab-scale 1e8, --factor 1e8 and a job's 1000 g scale are
  refused naming file and line where there is one; a gzip bomb is refused under 1.5 GB;
- a mesh with a NaN vertex is refused at its line, with or without --repair;
- a campaign run "as recorded": `rigid fragility` fits its simulated cells at the records' own
  PGAs (h5py's count of simulated cells against the fit's) and `plot maps` draws no PGA 0.

usage: lab_robustness_test.py RIGID SOURCE_DIR
"""
import csv
import hashlib
import io
import json
import math
import os
import random
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import robustness_test as rt  # noqa: E402  (the harness: limits, run)

RIGID, SOURCE = rt.RIGID, rt.SOURCE
SEED = int(os.environ.get("RIGID_LAB_SEED", str(int(time.time()) % 100000)))
rng = random.Random(SEED)
failed = []
count = 0


def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def report(name, problems, detail=""):
    global count
    count += 1
    print("%-4s %-58s %s" % ("FAIL" if problems else "ok", name, detail[:160]))
    for p in problems:
        print("       " + p)
    if problems:
        failed.append(name)


def error(name, args, cwd, where=None, fragments=(), absent=(), memory=None):
    """Exit 2 and exactly one `rigid...: error:` line; `where` = (file, line) it must start with
    (line None: any line number), every fragment in it, no absent one."""
    if memory:
        limit = lambda: (resource.setrlimit(resource.RLIMIT_AS, (memory, memory)),  # noqa: E731
                         resource.setrlimit(resource.RLIMIT_CPU, (rt.TIME_LIMIT_S, rt.TIME_LIMIT_S)))
        start = time.monotonic()
        p = subprocess.run([RIGID] + args, cwd=cwd, capture_output=True, text=True, errors="replace",
                           preexec_fn=limit, timeout=rt.WALL_LIMIT_S)
        status, err, cpu, wall = p.returncode, p.stderr, 0.0, time.monotonic() - start
    else:
        status, err, cpu, wall = rt.run(args, cwd)
    lines = err.splitlines()
    problems = rt.refusal_problems(status, err, cpu, wall)
    if where and not problems:
        file, line = where
        text = lines[0][lines[0].find(": error: ") + len(": error: "):]
        head = re.escape(file) + ":" + (str(line) if line is not None else r"\d+") + ": "
        if not re.match(head, text):
            problems.append("does not start with %s:%s:" % (file, line if line is not None else "LINE"))
    problems += ["no '%s' in the message" % f for f in fragments if f not in err]
    problems += ["'%s' in the message" % f for f in absent if f in err]
    report(name, problems, lines[0] if lines else "")
    return err


def expect(name, condition, detail=""):
    report(name, [] if condition else [detail or "condition false"])


# --- inputs ---------------------------------------------------------------------------------------

def lab_recording(path, n=1200, dt=0.005, bad=None, gz=False):
    """A table recording in the default format (tab, header, time s, acceleration g, displacement V):
    a 2 Hz sine. bad = (sample index, column, text) puts text in that cell; returns its line."""
    rows = ["time\tacceleration\tdisplacement"]
    for i in range(n):
        t = i * dt
        a = 0.05 * math.sin(2 * math.pi * 2 * t)
        d = -a * 9.80665 / (2 * math.pi * 2) ** 2 / 5.9797e-4 / 0.0254
        cells = ["%.6f" % t, "%.6g" % a, "%.6g" % d]
        if bad and bad[0] == i:
            cells[bad[1]] = bad[2]
        rows.append("\t".join(cells))
    data = ("\n".join(rows) + "\n").encode()
    with open(path, "wb") as f:
        f.write(gzip_bytes(data) if gz else data)
    return bad[0] + 2 if bad else None  # header is line 1


def gzip_bytes(data):
    c = zlib.compressobj(6, zlib.DEFLATED, 31)
    return c.compress(data) + c.flush()


def at2(path, values, dt=0.01):
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", "TEST, 1/1/2000, STATION, 000",
             "ACCELERATION TIME SERIES IN UNITS OF G", "NPTS= %d, DT= %.4f SEC" % (len(values), dt)]
    for k in range(0, len(values), 5):
        lines.append("".join("%15.7E" % v for v in values[k:k + 5]))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def pulse(n=600, amplitude=0.2):
    return [amplitude * math.sin(2 * math.pi * i / 100) if i < 200 else 0.0 for i in range(n)]


def campaign(d, job, text, out, label):
    """Writes and runs a job (one process); False, and a failed case, when it does not finish."""
    rt.write(d, job, text)
    p = subprocess.run([RIGID, "campaign", job, "--out", out, "--progress", "none"], cwd=d, capture_output=True,
                       text=True)
    if p.returncode != 0:
        expect(label + ": the campaign runs", False, p.stderr.strip()[:300])
    return p.returncode == 0


def setup_block(d):
    for name in ("block.stl", "pedestal.stl", "block_a02.model", "block_a02.state.toml"):
        shutil.copy(os.path.join(rt.BLOCK_DIR, name), d)
    rt.write(d, "block.toml", 'model = "block_a02.model"\nstate = "block_a02.state.toml"\n')


# --- the cases ------------------------------------------------------------------------------------

def lab_samples(d):
    """A non-finite or absurd lab sample is refused at its line; so are the scale and V factor that
    make one."""
    n = 1200
    for label, column, text in (("1e308 acceleration", 1, "1e308"), ("1e198 g acceleration", 1, "1e198"),
                                ("60 g acceleration", 1, "60"), ("1e308 V displacement", 2, "1e308")):
        i = rng.randrange(n)
        path = os.path.join(d, "rec_%d.txt" % column)
        line = lab_recording(path, n, bad=(i, column, text))
        error("lab: %s at line %d" % (label, line), ["motion", "info", "--lab", path], d, (path, line))
    i = rng.randrange(n)
    path = os.path.join(d, "rec.txt.gz")
    line = lab_recording(path, n, bad=(i, 1, "-1e300"), gz=True)
    error("lab gz: -1e300 g at line %d" % line, ["motion", "info", "--lab", path], d, (path, line))
    good = os.path.join(d, "good.txt")
    lab_recording(good, n)
    p = subprocess.run([RIGID, "motion", "info", "--lab", good, "--json"], cwd=d, capture_output=True, text=True)
    pga = json.loads(p.stdout)["pga_g"] if p.returncode == 0 else None
    expect("lab: the good recording reads (PGA about 0.05 g)", pga is not None and 0.03 < pga < 0.07,
           "exit %d %s" % (p.returncode, p.stderr.strip()[:200]))
    error("lab: --lab-volts-to-length 1e308", ["motion", "info", "--lab", good, "--lab-volts-to-length", "1e308"], d,
          (good, None))
    toml = rt.write(d, "v.toml", "[lab]\nvolts_to_length = 1e308\n")
    error("lab: [lab] volts_to_length = 1e308", ["motion", "info", "--lab", good, "--lab-format", toml], d,
          (good, None))
    error("run --lab --lab-scale 1e8", ["run", "block.toml", "--lab", good, "--lab-scale", "1e8"], d, (good, None),
          ["50 g"])
    error("run --lab --lab-scale -1e4", ["run", "block.toml", "--lab", good, "--lab-scale", "-1e4"], d, (good, None))


def at2_samples(d):
    """An absurd AT2 value at its line; an absurd --factor or job scale named."""
    values = pulse()
    k = rng.randrange(len(values))
    values[k] = rng.choice([1e198, -75.0, 1e30])
    path = os.path.join(d, "big-X.AT2")
    at2(path, values)
    error("AT2: %.3g g at line %d" % (values[k], 5 + k // 5), ["motion", "info", path], d, (path, 5 + k // 5))
    good = os.path.join(d, "small-X.AT2")
    at2(good, pulse())
    for factor in ("1e8", "-300", "251"):
        error("run --motion --factor %s" % factor, ["run", "block.toml", "--motion", good, "--factor", factor], d,
              None, ["50 g"])
    error("run --motion --target-pga 80", ["run", "block.toml", "--motion", good, "--target-pga", "80"], d, None,
          ["50 g"])
    job = ('[campaign]\nseed = 1\nscales = [0.1, %s]\nrotations = 1\n[[object]]\nscene = "block.toml"\n'
           '[[record]]\nmotion = "small-X.AT2"\n' % rng.choice(["300", "1000", "1e6"]))
    rt.write(d, "big.toml", job)
    line = job.splitlines().index("[[record]]") + 1
    error("campaign: a scale beyond 50 g", ["campaign", "big.toml", "--out", "big.h5", "--dry-run"], d,
          ("big.toml", line), ["50 g"])
    expect("campaign: no cube written", not os.path.exists(os.path.join(d, "big.h5")))


def gzip_bomb(d):
    """A gzip file inflating past the 1 GB limit: refused under a 1.5 GB address space."""
    path = os.path.join(d, "bomb.txt.gz")
    c = zlib.compressobj(1, zlib.DEFLATED, 31)
    chunk = b"0.0\t0.0\t0.0\n" * (1 << 16)  # 768 kB
    with open(path, "wb") as f:
        f.write(c.compress(b"time\tacceleration\tdisplacement\n"))
        for _ in range((1 << 30) // len(chunk) + 8):
            f.write(c.compress(chunk))
        f.write(c.flush())
    error("lab: gzip bomb (> 1 GB) under 1.5 GB", ["motion", "info", "--lab", path], d, (path, None),
          ["more than 1 GB"], memory=3 << 29)
    os.unlink(path)


def not_regular(d):
    """A directory, a FIFO and /dev/zero as motion files: named as such, never waited on."""
    good = os.path.join(d, "good.txt")
    os.makedirs(os.path.join(d, "adir"), exist_ok=True)
    if not os.path.exists(os.path.join(d, "afifo")):
        os.mkfifo(os.path.join(d, "afifo"))
    kinds = (("adir", "directory"), ("afifo", "FIFO"), ("/dev/zero", "character device"))
    for target, word in kinds:
        error("motion info --lab %s" % target, ["motion", "info", "--lab", target], d, None, [word], ["not found"])
        error("motion info %s as AT2" % target, ["motion", "info", "x=" + target], d, None, [word], ["not found"])
    for target, word in kinds:
        rows = [(1, "a", good), (2, "b", good), (3, "c", good)]
        k = rng.randrange(len(rows))
        rows[k] = (rows[k][0], rows[k][1], target)
        text = "test_no,record,file,overturned\n" + "".join("%d,%s,%s,%d\n" % (n, r, f, n % 2) for n, r, f in rows)
        rt.write(d, "list.csv", text)
        error("test list: %s as a motion file" % target,
              ["shaketable", "predict", "none.toml", "--tests", "list.csv", "--out", "p.csv"], d,
              ("list.csv", k + 2), [word], ["not found"])
        job = '[campaign]\nseed = 1\nscales = [0.1]\nrotations = 1\n[[object]]\nscene = "block.toml"\n' \
              '[[record]]\nlab = "%s"\n' % target
        rt.write(d, "rec.toml", job)
        error("job: %s as a lab recording" % target, ["campaign", "rec.toml", "--out", "r.h5", "--dry-run"], d,
              ("rec.toml", 7), [word], ["not found"])


def test_lists(d):
    """Byte-order mark, quotes and unknown outcomes in a test list, read through predict (the list is
    read before the scene: reaching the scene's error means the list was accepted)."""
    good = "good.txt"
    names = ['a, "quoted" name', "x" * 700, "plain", 'line\nbreak']
    rows = [[str(n + 1), names[n], "0.2", "0.1", good, rng.choice(["", "?", "1", "0"])] for n in range(len(names))]
    rows[rng.randrange(len(rows))][5] = rng.choice(["", "?"])
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\r\n").writerows([["test_no", "record", "pgv_over_pga_s", "pga_g", "file",
                                                       "overturned"]] + rows)
    with open(os.path.join(d, "bom.csv"), "w", encoding="utf-8-sig", newline="") as f:
        f.write(buf.getvalue())
    error("predict: BOM, quoted names, blank/? outcomes accepted",
          ["shaketable", "predict", "none.toml", "--tests", "bom.csv", "--out", "p.csv"], d, None,
          ["none.toml", "not found"], ["bom.csv"])
    rt.write(d, "bad_outcome.csv", "test_no,file,overturned\n1,good.txt,1\n2,good.txt,maybe\n")
    error("test list: outcome 'maybe'", ["shaketable", "predict", "none.toml", "--tests", "bad_outcome.csv", "--out",
                                         "p.csv"], d, ("bad_outcome.csv", 3), ["maybe"])
    rt.write(d, "open_quote.csv", 'test_no,file\n1,good.txt\n2,"good.txt\n')
    error("test list: a quote never closed", ["shaketable", "predict", "none.toml", "--tests", "open_quote.csv",
                                              "--out", "p.csv"], d, ("open_quote.csv", 3), ["quote"])


def export_names(d):
    """Record names with commas, quotes, a line break and 700 characters: `rigid export cells` rows of
    the header's width holding the cube's names."""
    at2(os.path.join(d, "small-X.AT2"), pulse())
    names = ['has, comma', 'has "quotes"', "y" * 700, "two\nlines"]
    rng.shuffle(names)
    job = '[campaign]\nseed = 1\nscales = [0.05]\nrotations = 1\n[[object]]\nscene = "block.toml"\n'
    for n in names:
        job += '[[record]]\nmotion = "small-X.AT2"\nname = %s\n' % json.dumps(n)
    if not campaign(d, "names.toml", job, "names.h5", "export"):
        return
    import h5py
    with h5py.File(os.path.join(d, "names.h5"), "r") as f:
        stored = list(f["axes/record"].asstr()[()])
    p = subprocess.run([RIGID, "export", "cells", "names.h5", "--csv"], cwd=d, capture_output=True)
    rows = list(csv.reader(io.StringIO(p.stdout.decode(), newline="")))
    widths = {len(r) for r in rows}
    expect("export cells: every row of the header's width", p.returncode == 0 and len(widths) == 1,
           "widths %s" % sorted(widths))
    column = rows[0].index("record") if rows else 0
    expect("export cells: the names as the cube holds them", [r[column] for r in rows[1:]] == stored,
           str([r[column][:30] for r in rows[1:]]))


def nan_vertex(d):
    """A vertex that is not a finite number, refused at its line with or without --repair."""
    verts = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    faces = [(1, 3, 2), (1, 4, 3), (5, 6, 7), (5, 7, 8), (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 4, 8),
             (3, 8, 7), (4, 1, 5), (4, 5, 8)]
    k = rng.randrange(len(verts))
    word = rng.choice(["nan", "NaN", "inf", "-inf", "1e999"])
    lines = ["# cube"] + ["v %s %s %s" % tuple((word if (i == k and c == rng.randrange(3)) else str(x))
                                                for c, x in enumerate(v)) for i, v in enumerate(verts)]
    if not any(word in l for l in lines):
        lines[k + 1] = "v %s 0 0" % word
    bad_line = next(i + 1 for i, l in enumerate(lines) if word in l)
    lines += ["f %d %d %d" % f for f in faces]
    rt.write(d, "nan.obj", "\n".join(lines) + "\n")
    for extra in ([], ["--repair"]):
        error("import: OBJ vertex %s at line %d %s" % (word, bad_line, " ".join(extra)),
              ["model", "import", "nan.obj", "--out", "nanrock/rock"] + extra, d, ("nan.obj", bad_line),
              ["not a finite number"], ["--repair mends it"])
    ply = ["ply", "format ascii 1.0", "element vertex 8", "property float x", "property float y", "property float z",
           "element face 12", "property list uchar int vertex_indices", "end_header"]
    ply += ["%s %s %s" % v for v in verts] + ["3 %d %d %d" % tuple(i - 1 for i in f) for f in faces]
    ply[9 + k] = "%s 0 0" % word
    rt.write(d, "nan.ply", "\n".join(ply) + "\n")
    error("import: PLY vertex %s at line %d --repair" % (word, 10 + k),
          ["model", "import", "nan.ply", "--out", "nanrock/rock", "--repair"], d, ("nan.ply", 10 + k),
          ["not a finite number"], ["--repair mends it"])


def as_recorded(d):
    """A campaign run "as recorded": fitted at the records' own PGAs, mapped without a PGA 0."""
    for name, amp in (("r1", 0.05), ("r2", 0.15), ("r3", 0.4), ("r4", 0.9)):
        at2(os.path.join(d, name + "-X.AT2"), pulse(amplitude=amp))
    job = '[campaign]\nseed = 1\nscales = "as recorded"\nrotations = 1\n[[object]]\nscene = "block.toml"\n'
    job += "".join('[[record]]\nmotion = "%s-X.AT2"\n' % n for n in ("r1", "r2", "r3", "r4"))
    job += "[run]\nfree_time_s = 1.0\n"
    if not campaign(d, "asrec.toml", job, "asrec.h5", "as recorded"):
        return
    import h5py
    with h5py.File(os.path.join(d, "asrec.h5"), "r") as f:
        scale = f["axes/scale_g"][()].tolist()
        outcome = f["objects/block/outcome"][()]
        pga = f["records/gmroti_pga_g"][()].tolist()
    simulated = int(((outcome == 1) | (outcome == 2)).sum())
    expect("as recorded: the cube's scale axis is [0.0]", scale == [0.0], str(scale))
    before = sha(os.path.join(d, "asrec.h5"))
    p = subprocess.run([RIGID, "fragility", "asrec.h5", "--no-store", "--bootstrap", "20", "--csv", "asrec_frag.csv"],
                       cwd=d, capture_output=True, text=True)
    expect("as recorded: fragility fits (exit 0)", p.returncode == 0 and "no simulated cell" not in p.stderr,
           "exit %d %s" % (p.returncode, p.stderr.strip()[:300]))
    if p.returncode == 0:
        with open(os.path.join(d, "asrec_frag.csv"), newline="") as f:
            bins = [r for r in csv.DictReader(f) if r["fit"] == "bin"]
        cells = sum(int(r["n_cells"]) for r in bins)
        expect("as recorded: the bins' fits count every simulated cell (h5py: %d)" % simulated, cells == simulated,
               "the fits count %d" % cells)
    expect("as recorded: fragility --no-store leaves the cube", sha(os.path.join(d, "asrec.h5")) == before)
    p = subprocess.run([RIGID, "plot", "maps", "asrec.h5", "--out", "asrec_plots"], cwd=d, capture_output=True,
                       text=True)
    expect("as recorded: plot maps runs", p.returncode == 0, p.stderr.strip()[:300])
    expect("as recorded: plot maps names no PGA 0", "PGA 0 g" not in p.stdout + p.stderr, p.stdout[-300:])
    sys.path.insert(0, os.path.join(SOURCE, "src", "python"))
    from rigidpy.cube import Cube
    cube = Cube(os.path.join(d, "asrec.h5"))
    expect("as recorded: rigidpy's scale axis is the records' PGAs",
           sorted(set(round(v, 12) for v in pga)) == [round(v, 12) for v in cube.scales], str(cube.scales))
    expect("as recorded: not incomplete", cube.incomplete("done") is None, str(cube.incomplete("done")))


def main():
    if not os.access(RIGID, os.X_OK):
        print("no executable " + RIGID)
        return 1
    print("seed %d (RIGID_LAB_SEED to repeat)" % SEED)
    start = time.monotonic()
    only = os.environ.get("RIGID_LAB_CASES", "").split()
    with tempfile.TemporaryDirectory(prefix="rigid_lab_robustness_") as d:
        setup_block(d)
        lab_recording(os.path.join(d, "good.txt"))
        for group in (lab_samples, at2_samples, not_regular, test_lists, export_names, nan_vertex, as_recorded,
                      gzip_bomb):
            if not only or group.__name__ in only:
                group(d)
    print("%d cases, %d failed, %.1f s" % (count, len(failed), time.monotonic() - start))
    for name in failed:
        print("FAILED: " + name)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
