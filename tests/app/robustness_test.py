#!/usr/bin/env python3
"""CTest `robustness` (docs/robustness.md): every bad input a deliberate adversarial pass found, through
the real command line. Each case must end within 10 s under a 2 GB address-space limit with exit
status 2 and exactly one stderr line `rigid: error: ...` (the inward mesh: exit 0 and exactly one
`rigid: warning:` line). The 10 s are CPU seconds (RLIMIT_CPU), so a loaded CI machine does not
fail a case; a hang is still killed after WALL_LIMIT_S. The inputs are made in a temporary directory from the bundled block
(models/library/block_a02) and records (waveforms/demo).

usage: robustness_test.py RIGID SOURCE_DIR
"""
import os
import re
import resource
import shutil
import struct
import subprocess
import sys
import tempfile
import time

TIME_LIMIT_S = 10  # CPU seconds per case
WALL_LIMIT_S = 60  # wall seconds per case (a blocked read uses no CPU)
MEMORY_LIMIT = 2 << 30  # bytes of address space
# Facets of the large convex mesh: the old O(facets x vertices) convexity check took 9.5 s for
# 160k facets; 200k now take about a second (1e6 in about 9 s of CPU, too close to the limit on
# a loaded CI machine).
SPHERE_FACETS = 200_000

RIGID, SOURCE = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
BLOCK_DIR = os.path.join(SOURCE, "models", "library", "block_a02")
DEMO = os.path.join(SOURCE, "waveforms", "demo")


def limit_memory_and_cpu():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
    resource.setrlimit(resource.RLIMIT_CPU, (TIME_LIMIT_S, TIME_LIMIT_S))


def child_cpu_s():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(args, cwd):
    """(exit status, stderr, CPU seconds, wall seconds)"""
    start, cpu = time.monotonic(), child_cpu_s()
    try:
        p = subprocess.run(["timeout", "-s", "KILL", str(WALL_LIMIT_S), RIGID] + args, cwd=cwd, capture_output=True,
                           text=True, errors="replace", preexec_fn=limit_memory_and_cpu, timeout=WALL_LIMIT_S + 5)
        status, err = p.returncode, p.stderr
    except subprocess.TimeoutExpired:
        status, err = 124, ""
    return status, err, child_cpu_s() - cpu, time.monotonic() - start


def refusal_problems(status, err, cpu, wall):
    """What keeps a run from being a clean refusal: over the limits, an exit other than 2, stderr
    other than one `rigid: error:` line (`rigid fragility: error:` from the Python commands)."""
    lines = err.splitlines()
    problems = []
    if cpu > TIME_LIMIT_S or wall > WALL_LIMIT_S:
        problems.append("took %.1f s CPU, %.1f s wall" % (cpu, wall))
    if status != 2:
        problems.append("exit %d, not 2" % status)
    if len(lines) != 1 or not re.match(r"rigid( [a-z]+)?: error: ", lines[0]):
        problems.append("stderr is not one 'rigid: error:' line: " + " | ".join(lines[:4])[:400])
    return problems


# --- inputs -------------------------------------------------------------------------------------

def write(d, name, text):
    path = os.path.join(d, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def read(path):
    with open(path) as f:
        return f.read()


def scaled_ascii_stl(src, factor, flip=False):
    """The binary or ASCII STL `src` as ASCII text, coordinates times factor, optionally inward."""
    data = open(src, "rb").read()
    facets = []
    if data[:5] == b"solid" and b"facet" in data[:400]:
        verts = [list(map(float, line.split()[1:4])) for line in data.decode().splitlines()
                 if line.strip().startswith("vertex")]
        facets = [verts[i:i + 3] for i in range(0, len(verts), 3)]
    else:
        n = struct.unpack_from("<I", data, 80)[0]
        for k in range(n):
            vals = struct.unpack_from("<12f", data, 84 + 50 * k)
            facets.append([vals[3:6], vals[6:9], vals[9:12]])
    out = ["solid s"]
    for tri in facets:
        if flip:
            tri = [tri[0], tri[2], tri[1]]
        out.append(" facet normal 0 0 0\n  outer loop")
        out += ["   vertex %.17g %.17g %.17g" % tuple(c * factor for c in v) for v in tri]
        out.append("  endloop\n endfacet")
    return "\n".join(out + ["endsolid s"]) + "\n"


def sphere_stl(path, facets):
    """A convex UV sphere of about `facets` facets, binary STL."""
    import math
    n_lon = int(math.sqrt(facets / 2))
    n_lat = n_lon
    pts = [[(math.sin(math.pi * i / n_lat) * math.cos(2 * math.pi * j / n_lon),
             math.sin(math.pi * i / n_lat) * math.sin(2 * math.pi * j / n_lon),
             math.cos(math.pi * i / n_lat)) for j in range(n_lon)] for i in range(1, n_lat)]
    top, bottom = (0.0, 0.0, 1.0), (0.0, 0.0, -1.0)
    lift = lambda p: (p[0], p[1], p[2] + 5.0)  # clear of the pedestal
    pts = [[lift(p) for p in row] for row in pts]
    top, bottom = lift(top), lift(bottom)
    tris = []
    for j in range(n_lon):
        k = (j + 1) % n_lon
        tris.append((top, pts[0][j], pts[0][k]))
        tris.append((bottom, pts[-1][k], pts[-1][j]))
        for i in range(n_lat - 2):
            a, b, c, d = pts[i][j], pts[i][k], pts[i + 1][j], pts[i + 1][k]
            tris.append((a, c, d))
            tris.append((a, d, b))
    with open(path, "wb") as f:
        f.write(b"big sphere".ljust(80, b" ") + struct.pack("<I", len(tris)))
        pack = struct.Struct("<12fH").pack
        f.write(b"".join(pack(0, 0, 0, *a, *b, *c, 0) for a, b, c in tris))
    return len(tris)


def make_inputs(d):
    for name in ("block.stl", "pedestal.stl", "block_a02.model", "block_a02.state.toml"):
        shutil.copy(os.path.join(BLOCK_DIR, name), d)
    for c in "XYZ":
        shutil.copy(os.path.join(DEMO, "stochastic_s1-%s.AT2" % c), d)
    physics = '[physics]\ncontact = "%s"\ndensity = %s\nnormal_stiffness = %s\n'
    write(d, "block.toml", 'model = "block_a02.model"\nstate = "block_a02.state.toml"\n')
    for name, contact, density, k in (("soft", "penalty", "2600", "1e-30"), ("stiff", "penalty", "2600", "1e30"),
                                      ("light", "penalty", "1e-300", "1e8"), ("light_rigid", "rigid", "1e-300", "1e8")):
        write(d, name + ".toml", 'model = "block_a02.model"\n' + physics % (contact, density, k))
    write(d, "unfixed.model", "block pedestal.stl\n0 0 0 0\nblock block.stl\n0 0 0 0\n")
    write(d, "twice.model", "block pedestal.stl\n1 0 0 0\nblock block.stl\n0 0 0 0\nblock block.stl\n0 0 0 0\n")
    state = read(os.path.join(d, "block_a02.state.toml"))
    block_at = state.index('name = "block"')
    z_line = state.index("position", block_at)
    pos = state[z_line:state.index("\n", z_line)]
    xs = [float(v) for v in pos[pos.index("[") + 1:pos.index("]")].split(",")]
    sunk = state[:z_line] + "position = [%r, %r, %r]" % (xs[0], xs[1], xs[2] - 0.5) + state[state.index("\n", z_line):]
    write(d, "sunk.state.toml", sunk)
    write(d, "sunk.toml", 'model = "block_a02.model"\nstate = "sunk.state.toml"\n')
    q_line = state.index("orientation", block_at)
    zero_q = state[:q_line] + "orientation = [0.0, 0.0, 0.0, 0.0]" + state[state.index("\n", q_line):]
    write(d, "zero_q.state.toml", zero_q)
    write(d, "zero_q.toml", 'model = "block_a02.model"\nstate = "zero_q.state.toml"\n')
    # a block a billionth of the size
    write(d, "tiny_block.stl", scaled_ascii_stl(os.path.join(d, "block.stl"), 1e-9))
    write(d, "tiny_pedestal.stl", scaled_ascii_stl(os.path.join(d, "pedestal.stl"), 1e-9))
    write(d, "tiny.model", "block tiny_pedestal.stl\n1 0 0 0\nblock tiny_block.stl\n0 0 0 0\n")
    # an inward mesh
    write(d, "inward.stl", scaled_ascii_stl(os.path.join(d, "block.stl"), 1.0, flip=True))
    write(d, "inward.model", "block pedestal.stl\n1 0 0 0\nblock inward.stl\n0 0 0 0\n")
    # special files
    os.mkfifo(os.path.join(d, "fifo.stl"))
    os.mkfifo(os.path.join(d, "fifo-X.AT2"))
    os.mkdir(os.path.join(d, "dir-X.AT2"))
    write(d, "fifo.model", "block pedestal.stl\n1 0 0 0\nblock fifo.stl\n0 0 0 0\n")
    write(d, "devzero.model", "block pedestal.stl\n1 0 0 0\nblock /dev/zero\n0 0 0 0\n")
    # TOML values of the wrong type
    write(d, "fixed_string.toml", '[[block]]\nstl = "pedestal.stl"\nfixed = "true"\n[[block]]\nstl = "block.stl"\n')
    write(d, "rule_number.toml", 'model = "block_a02.model"\n[failure]\nrule = 5\n')
    # a centre of mass moved outside its block (the block is 0.2 m wide), of an unknown block
    write(d, "com_outside.toml", 'model = "block_a02.model"\n[centre_of_mass_offset]\nblock = [0.5, 0.0, 0.0]\n')
    write(d, "com_unknown.toml", 'model = "block_a02.model"\n[centre_of_mass_offset]\nrock = [0.01, 0.0, 0.0]\n')
    # job files
    job = ('[campaign]\nscales = %s\nrotations = %d\n[[object]]\nscene = "block.toml"\n%s'
           '[[record]]\nmotion = "stochastic_s1-X.AT2"\n%s[run]\n%s')

    def job_file(name, run="", scales="[0.2]", rotations=1, obj="", rec=""):
        return write(d, name, job % (scales, rotations, obj, rec, run))
    job_file("dt10.job.toml", "dt_s = 10.0\n")
    job_file("dt_tiny.job.toml", "dt_s = 1e-12\n")
    job_file("model5.job.toml", "model = 5\n")
    job_file("integrator5.job.toml", "integrator = 5\n")
    job_file("name5.job.toml", obj="name = 5\n")
    job_file("huge.job.toml", scales='"0.001:100:0.001"', rotations=1000)
    job_file("window.job.toml", rec="start = 100.0\n")
    job_file("ok.job.toml")
    # bad sweeps (after an empty [run]): refused before any work
    job_file("sweep_negative.job.toml", "[sweep]\ncount = 4\nfriction = [-0.5, 0.8]\n")
    job_file("sweep_empty.job.toml", "[sweep]\ncount = 4\nrestitution = [0.3, 0.1]\n")
    job_file("sweep_unknown.job.toml", "[sweep]\ncount = 4\nviscosity = [0.1, 0.2]\n")
    job_file("sweep_outside.job.toml", "[sweep]\ncount = 2\ncom_offset_x_m = [0.3, 0.5]\n")
    # lab (shake-table) recordings: a good one, and jobs naming them
    write(d, "table.txt", "Time [s]\tAcceleration [g]\tDisplacement [V]\n" +
          "".join("%.5f\t%.6f\t%.4f\n" % (i / 800.0, 0.1 * ((i * 7919) % 13 - 6) / 6.0, 0.0) for i in range(800)))
    os.mkfifo(os.path.join(d, "fifo.txt.gz"))
    lab_job = ('[campaign]\nscales = %s\nrotations = 1\n[[object]]\nscene = "block.toml"\n'
               '[[record]]\nlab = "%s"\n%s')
    write(d, "lab_missing.job.toml", lab_job % ('"as recorded"', "none.txt.gz", ""))
    write(d, "lab_badkey.job.toml", lab_job % ('"as recorded"', "table.txt", "[lab]\nchanel = \"acceleration\"\n"))
    write(d, "lab_badunit.job.toml", lab_job % ('"as recorded"', "table.txt", "[lab]\nacceleration_unit = \"furlong\"\n"))
    write(d, "lab_both.job.toml", lab_job % ('"as recorded"', "table.txt", 'motion = "stochastic_s1-X.AT2"\n'))
    write(d, "lab_scales.job.toml", lab_job % ('"as recoded"', "table.txt", ""))
    sphere_facets = sphere_stl(os.path.join(d, "sphere.stl"), SPHERE_FACETS)
    write(d, "sphere.model", "block pedestal.stl\n1 0 0 0\nblock sphere.stl\n0 0 0 0\n")
    return sphere_facets


# --- cases ----------------------------------------------------------------------------------------

CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_F = [(1, 3, 2), (1, 4, 3), (5, 6, 7), (5, 7, 8), (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 4, 8), (3, 8, 7),
          (4, 1, 5), (4, 5, 8)]


def obj_text(vertices, faces):
    return "".join("v %r %r %r\n" % v for v in vertices) + "".join("f %d %d %d\n" % f for f in faces)


def make_scan_inputs(d):
    """OBJ scans for rigid model import: a good cube (0.5 m) and one of each defect."""
    half = [(0.5 * x, 0.5 * y, 0.5 * z) for x, y, z in CUBE_V]
    write(d, "cube.obj", obj_text(half, CUBE_F))
    write(d, "open.obj", obj_text(half, CUBE_F[:-1]))  # a hole: facet 11 missing
    # a second cube sharing the first's edge 2-3 (x = 0.5, y = 0.5..): that edge has four facets
    other = [(x + 0.5, y + 0.5, z) for x, y, z in half]
    write(d, "nonmanifold.obj", obj_text(half + other, CUBE_F + [tuple(i + 8 for i in f) for f in CUBE_F]))
    # the top corner above (0, 0) pushed down through the bottom face: its facets cross the base
    folded = list(half)
    folded[4] = (0.35, 0.3, -0.2)
    write(d, "folded.obj", obj_text(folded, CUBE_F))
    write(d, "flat.obj", obj_text([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(1, 2, 3), (1, 3, 2)]))
    write(d, "nan.obj", obj_text(half, CUBE_F).replace("v 0.5 0.5 0.5", "v nan 0.5 0.5"))
    write(d, "rock.xyz", "this is no mesh\n")


def cases(d, sphere_facets):
    motion = ["--motion", "stochastic_s1-X.AT2", "--target-pga", "0.2"]
    demo = ["run", "block.toml"] + motion
    camp = lambda job, *extra: ["campaign", job, "--out", os.path.join(d, job + ".h5")] + list(extra)
    e = "error"
    imp = lambda scan, *extra: ["model", "import", scan, "--out", os.path.join(d, "imported", "rock")] + list(extra)
    return [
        # wrong answers with exit 0
        ("--dt 0.05 (step far above the contact time scale)", demo + ["--dt", "0.05"], e, ["--dt", "exceeds"]),
        ("--dt 0.01", demo + ["--dt", "0.01"], e, ["exceeds"]),
        ("--dt 0.1", demo + ["--dt", "0.1"], e, ["exceeds"]),
        ("--safety 50", demo + ["--safety", "50"], e, ["--safety"]),
        ("dt_s = 10 in a job", camp("dt10.job.toml"), e, ["dt10.job.toml:", "exceeds"]),
        ("--duration 1e308", demo + ["--duration", "1e308"], e, ["steps"]),
        ("--free-time nan", demo + ["--free-time", "nan"], e, ["--free-time"]),
        ("stiffness 1e-30", ["run", "soft.toml"] + motion, e, ["stiffness"]),
        ("no fixed block", ["run", "unfixed.model"] + motion, e, ["unfixed.model", "fixed"]),
        ("start 0.5 m inside the pedestal", ["run", "sunk.toml"] + motion, e, ["sunk.state.toml", "overlap"]),
        ("the same STL twice", ["run", "twice.model"] + motion, e, ["twice.model:5", "block.stl"]),
        ("zero quaternion in a state", ["run", "zero_q.toml"] + motion, e, ["zero_q.state.toml:", "quaternion"]),
        # hangs
        ("1e-9 m block", ["run", "tiny.model"] + motion, e, ["tiny_"]),
        ("stiffness 1e30", ["run", "stiff.toml"] + motion, e, ["steps"]),
        ("density 1e-300 (penalty)", ["run", "light.toml"] + motion, e, ["density"]),
        ("density 1e-300 (rigid)", ["run", "light_rigid.toml"] + motion, e, ["density"]),
        ("--dt 1e-12", demo + ["--dt", "1e-12"], e, ["steps"]),
        ("dt_s = 1e-12, dry run", camp("dt_tiny.job.toml", "--dry-run"), e, ["dt_tiny.job.toml:", "steps"]),
        ("%d-facet STL" % sphere_facets, ["inspect", "sphere.model"], "ok", []),
        ("/dev/zero as STL", ["run", "devzero.model"], e, ["/dev/zero", "regular"]),
        ("/dev/zero as model", ["run", "/dev/zero"], e, ["/dev/zero", "regular"]),
        ("/dev/zero as job", ["campaign", "/dev/zero", "--dry-run"], e, ["/dev/zero", "regular"]),
        ("FIFO as STL", ["run", "fifo.model"], e, ["fifo.stl", "regular"]),
        ("FIFO as AT2", ["run", "block.toml", "--motion", "fifo-X.AT2"], e, ["fifo-X.AT2", "regular"]),
        ("centre of mass outside the block", ["inspect", "com_outside.toml"], e, ["com_outside.toml:3", "outside the block"]),
        ("centre of mass of an unknown block", ["run", "com_unknown.toml"] + motion, e, ["com_unknown.toml:3", "'rock'"]),
        # wrong TOML types
        ('fixed = "true"', ["run", "fixed_string.toml"] + motion, e, ["fixed_string.toml:3", "fixed", "boolean"]),
        ("rule = 5", ["run", "rule_number.toml"] + motion, e, ["rule_number.toml:3", "rule", "string"]),
        ("model = 5 in a job", camp("model5.job.toml", "--dry-run"), e, ["model5.job.toml:", "model", "string"]),
        ("integrator = 5 in a job", camp("integrator5.job.toml", "--dry-run"), e, ["integrator", "string"]),
        ("name = 5 in a job", camp("name5.job.toml", "--dry-run"), e, ["name5.job.toml:", "name", "string"]),
        # command-line values
        ("--duration 0", demo + ["--duration", "0"], e, ["--duration"]),
        ("--dt 0", demo + ["--dt", "0"], e, ["--dt"]),
        ("--safety 0", demo + ["--safety", "0"], e, ["--safety"]),
        ("--start nan", demo + ["--start", "nan"], e, ["--start"]),
        ("--factor ''", demo + ["--factor", ""], e, ["--factor"]),
        ("--checkpoint-interval -1", camp("ok.job.toml", "--checkpoint-interval", "-1"), e, ["--checkpoint-interval"]),
        ("--checkpoint-interval nan", camp("ok.job.toml", "--checkpoint-interval", "nan"), e, ["--checkpoint-interval"]),
        ("--grace -1", camp("ok.job.toml", "--grace", "-1"), e, ["--grace"]),
        ("--grace nan", camp("ok.job.toml", "--grace", "nan"), e, ["--grace"]),
        ("--solver-tolerance nan", demo + ["--solver-tolerance", "nan"], e, ["--solver-tolerance"]),
        ("--solver-tolerance 0", demo + ["--solver-tolerance", "0"], e, ["--solver-tolerance"]),
        ("--solver-max-sweeps 2.5", demo + ["--solver-max-sweeps", "2.5"], e, ["--solver-max-sweeps"]),
        ("--solver-max-sweeps 0", camp("ok.job.toml", "--solver-max-sweeps", "0"), e, ["--solver-max-sweeps"]),
        # the rest
        ("inward mesh", ["run", "inward.model", "--duration", "0.05"], "warning", ["inward.stl", "inward"]),
        ("--rotation 1e308", demo + ["--rotation", "1e308"], e, ["--rotation"]),
        ("1e8-task job, dry run", camp("huge.job.toml", "--dry-run"), e, ["huge.job.toml:", "cells"]),
        ("window past the record in a job", camp("window.job.toml", "--dry-run"), e, ["window.job.toml:", "window"]),
        ("sweep: negative friction", camp("sweep_negative.job.toml"), e, ["sweep_negative.job.toml:11:", "friction must be greater than 0"]),
        ("sweep: empty range", camp("sweep_empty.job.toml"), e, ["sweep_empty.job.toml:11:", "range [0.3, 0.1] is empty"]),
        ("sweep: unknown parameter", camp("sweep_unknown.job.toml"), e, ["sweep_unknown.job.toml:11:", "unknown parameter 'viscosity'"]),
        ("sweep: centre of mass outside the block", camp("sweep_outside.job.toml"), e,
         ["sweep_outside.job.toml:9:", "variant 0", "outside the block"]),
        ("window past the record on the command line", demo + ["--start", "100"], e, ["--start", "window"]),
        ("AT2 path that is a directory", ["run", "block.toml", "--motion", "dir-X.AT2"], e, ["dir-X.AT2", "directory"]),
        # lab recordings (rigid run/motion info --lab, [[record]] lab = ... in jobs)
        ("FIFO as a lab recording", ["run", "block.toml", "--lab", "fifo.txt.gz"], e, ["fifo.txt.gz", "regular"]),
        ("/dev/zero as a lab recording", ["motion", "info", "--lab", "/dev/zero"], e, ["/dev/zero", "regular"]),
        ("a lab recording of 1 s", ["run", "block.toml", "--lab", "table.txt", "--duration", "0.05"], "ok", []),
        ("--lab and --motion together", demo + ["--lab", "table.txt"], e, ["--lab"]),
        ("--lab-scale nan", ["run", "block.toml", "--lab", "table.txt", "--lab-scale", "nan"], e, ["--lab-scale"]),
        ("--lab-channel velocity", ["motion", "info", "--lab", "table.txt", "--lab-channel", "velocity"], e, ["--lab-channel"]),
        ("--lab-filter-order 40", ["motion", "info", "--lab", "table.txt", "--lab-filter-order", "40"], e, ["--lab-filter-order"]),
        ("missing lab recording in a job", camp("lab_missing.job.toml", "--dry-run"), e, ["lab_missing.job.toml:6:", "none.txt.gz"]),
        ("unknown [lab] key in a job", camp("lab_badkey.job.toml", "--dry-run"), e, ["lab_badkey.job.toml:", "chanel"]),
        ("unknown unit in a job's [lab]", camp("lab_badunit.job.toml", "--dry-run"), e, ["lab_badunit.job.toml:8:", "furlong"]),
        ("lab and motion in one [[record]]", camp("lab_both.job.toml", "--dry-run"), e, ["lab_both.job.toml:6:", "one of them"]),
        ('scales = "as recoded"', camp("lab_scales.job.toml", "--dry-run"), e, ["lab_scales.job.toml:2:", "as recorded"]),
        # scans (rigid model import)
        ("import a good cube", imp("cube.obj"), "ok", []),
        ("import an open mesh", imp("open.obj"), e, ["open.obj", "open edge", "3 open edges, at facets"]),
        ("import a non-manifold edge", imp("nonmanifold.obj"), e, ["nonmanifold.obj", "non-manifold"]),
        ("import a self-intersection", imp("folded.obj"), e, ["folded.obj", "crosses facet"]),
        ("import a mesh with no volume", imp("flat.obj"), e, ["flat.obj", "volume"]),
        ("import NaN coordinates", imp("nan.obj"), e, ["nan.obj", "NaN"]),
        ("import an unknown format", imp("rock.xyz"), e, ["rock.xyz"]),
        ("import a missing file", imp("none.obj"), e, ["none.obj", "not found"]),
        ("import --up w", imp("cube.obj", "--up", "w"), e, ["--up"]),
        ("import --scale -1", imp("cube.obj", "--scale", "-1"), e, ["--scale"]),
        ("import --split-z above the rock", imp("cube.obj", "--split-z", "3"), e, ["cube.obj", "--split-z", "misses"]),
        ("import a good cube split in two", imp("cube.obj", "--split-z", "0.2"), "ok", []),
        ("import --contact-shape blob", imp("cube.obj", "--contact-shape", "blob"), e, ["--contact-shape"]),
    ]


def check(name, args, expect, fragments, d):
    status, err, cpu, wall = run(args, d)
    lines = err.splitlines()
    problems = []
    if cpu > TIME_LIMIT_S or wall > WALL_LIMIT_S or status in (124, -9, 137, -24, 152):
        problems.append("took %.1f s CPU, %.1f s wall (exit %d)" % (cpu, wall, status))
    if expect == "error":
        if status != 2:
            problems.append("exit %d, not 2" % status)
        if len(lines) != 1 or not lines[0].startswith("rigid: error: "):
            problems.append("stderr is not one 'rigid: error:' line")
    elif expect == "warning":
        if status != 0:
            problems.append("exit %d, not 0" % status)
        if len(lines) != 1 or not lines[0].startswith("rigid: warning: "):
            problems.append("stderr is not one 'rigid: warning:' line")
    elif status != 0:
        problems.append("exit %d, not 0" % status)
    problems += ["no '%s' in the message" % f for f in fragments if f not in err]
    verdict = "FAIL" if problems else "ok"
    print("%-4s %-48s %5.2f s CPU %5.2f s wall  exit %3d  %s" % (verdict, name, cpu, wall, status,
                                                                 (lines[0] if lines else "")[:150]))
    for p in problems:
        print("       " + p)
    if problems and len(lines) > 1:
        print("       stderr: " + " | ".join(lines[:4])[:400])
    return not problems


def main():
    if not os.access(RIGID, os.X_OK):
        print("no executable " + RIGID)
        return 1
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="rigid_robustness_") as d:
        facets = make_inputs(d)
        make_scan_inputs(d)
        all_cases = cases(d, facets)
        failed = [c[0] for c in all_cases if not check(*c, d)]
    print("%d cases, %d failed, %.1f s" % (len(all_cases), len(failed), time.monotonic() - start))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
