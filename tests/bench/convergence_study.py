#!/usr/bin/python3
"""The convergence study of the contact solve (docs/accuracy.md, "Convergence of the contact
solve"): does a campaign's outcome depend on where the rigid contact solve stops?

Runs every job of a set twice, at the default settings and at `--accuracy reference` (the
converged oracle once the converging solver is in; before it, a smaller step with the same solve),
then compares each pair cell by cell with `python3 -m rigidpy.outcome_agreement --pair` (flips
and their distance from the failure rule, capped contact solves, fitted median and dispersion) and
writes its tables:

    /usr/bin/python3 tests/bench/convergence_study.py [--set hard|shipped|quick] [--np 2] [--check]
        [--rigid build/bin/rigid] [--out DIR] [--default-args "..."] [--reference-args "..."]

Sets: `hard` (jobs/convergence/*.toml but quick.toml: slender, stacked, compound, sliding, long
free rocking and 3-10 g scenes, over 1,000 cells), `shipped` (jobs/demo.toml and
jobs/uncertainty_demo.toml), `quick` (jobs/convergence/quick.toml, a few dozen cells, for CI).
OUT (default out/convergence, out/convergence_shipped, out/convergence_quick) holds JOB.default.h5
and JOB.reference.h5 (written anew each time: a cube of the same job from an older engine would
otherwise count as done; --resume continues an interrupted study), study.md, study.csv, flips.csv
and timings.csv (wall time of each campaign). --default-args / --reference-args add flags to those
campaigns (e.g. a solver tolerance once `rigid campaign` has one). Exit status: 0, 1 when a
campaign failed or --check found a target missed, 2 bad input.

`--write-scenes` (re)writes the hard set's scenes in models/convergence/ (boxes: ASCII STL meshes
and TOML scenes resting flush, exactly at equilibrium, so they need no saved state).

The scanned rock of ../shared/scans (SP1) is imported where the jobs look for it (SCAN_IMPORTS: the
demo's hull, as `bash setup.sh demo` imports it, and the hard set's compound body), when the scan is
there and the import is not; jobs name it `optional`, and a job of absent optional objects only is
left out.
"""
import argparse
import csv
import glob
import os
import shlex
import subprocess
import sys
import time
import tomllib

SOURCE_DIR = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SETTINGS = ("default", "reference")


def jobs_of(name):
    hard = sorted(p for p in glob.glob(os.path.join(SOURCE_DIR, "jobs", "convergence", "*.toml"))
                  if os.path.basename(p) != "quick.toml")
    return {"hard": hard,
            "shipped": [os.path.join(SOURCE_DIR, "jobs", j) for j in ("demo.toml", "uncertainty_demo.toml")],
            "quick": [os.path.join(SOURCE_DIR, "jobs", "convergence", "quick.toml")]}[name]


# ---------------------------------------------------------------------------------------------
# The hard set's box scenes (x, y half-widths and heights in m; boxes stacked flush from z = 0)


def box_stl(path, name, lo, hi):
    """An axis-aligned box as an ASCII STL, outward facets (12 triangles)."""
    x = (lo[0], hi[0])
    y = (lo[1], hi[1])
    z = (lo[2], hi[2])
    v = [(x[i], y[j], z[k]) for i in (0, 1) for j in (0, 1) for k in (0, 1)]  # index 4i + 2j + k
    quads = (((0, 1, 3, 2), (-1, 0, 0)), ((4, 6, 7, 5), (1, 0, 0)), ((0, 4, 5, 1), (0, -1, 0)),
             ((2, 3, 7, 6), (0, 1, 0)), ((0, 2, 6, 4), (0, 0, -1)), ((1, 5, 7, 3), (0, 0, 1)))
    lines = [f"solid {name}"]
    for (a, b, c, d), n in quads:
        for tri in ((a, b, c), (a, c, d)):
            lines.append(f"  facet normal {n[0]} {n[1]} {n[2]}\n    outer loop")
            lines += [f"      vertex {v[i][0]!r} {v[i][1]!r} {v[i][2]!r}" for i in tri]
            lines.append("    endloop\n  endfacet")
    lines.append(f"endsolid {name}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


# name: (description, pedestal (half x, half y, height), free boxes (half x, half y, height, x offset),
#        friction, failure rule)
SCENES = {
    "slender_a005": ("A slender block, alpha 0.05 rad: 1.5 m tall, 0.075 m wide, 0.4 m deep",
                     (0.0575, 0.22, 0.2), [(0.0375, 0.2, 1.5, 0.0)], 0.6, "below"),
    "stack3": ("Three boxes stacked, each set 3-4 cm off the one below: 0.5, 0.4 and 0.3 m wide, 1.4 m in all",
               (0.27, 0.27, 0.3), [(0.25, 0.25, 0.5, 0.0), (0.2, 0.2, 0.4, 0.04), (0.15, 0.15, 0.5, 0.07)], 0.6,
               "below"),
    "sliding": ("A squat block (0.8 x 0.8 x 0.3 m, tan alpha 2.7) on a pedestal 0.1 m wider on every side, friction "
                "0.4: it slides face to face and fails when it has slid off",
                (0.5, 0.5, 0.2), [(0.4, 0.4, 0.3, 0.0)], 0.4, "below"),
    "tall_a015": ("A tall block, alpha 0.15 rad: 2.5 m tall, 0.378 m wide, 0.5 m deep, for long free rocking",
                  (0.209, 0.27, 0.3), [(0.189, 0.25, 2.5, 0.0)], 0.6, "below"),
    "stocky_a05": ("A stocky block, alpha 0.5 rad: 0.8 m tall, 0.437 m wide, 0.5 m deep, for 3-10 g",
                   (0.2385, 0.27, 0.2), [(0.2185, 0.25, 0.8, 0.0)], 0.6, "below"),
    "stocky_a07": ("A stocky block, alpha 0.7 rad: 0.6 m tall, 0.507 m wide, 0.5 m deep, for 3-10 g",
                   (0.2735, 0.27, 0.2), [(0.2535, 0.25, 0.6, 0.0)], 0.6, "below"),
}


def write_scenes(root):
    for name, (description, pedestal, boxes, friction, rule) in SCENES.items():
        d = os.path.join(root, name)
        os.makedirs(d, exist_ok=True)
        px, py, ph = pedestal
        box_stl(os.path.join(d, "pedestal.stl"), "pedestal", (-px, -py, -ph), (px, py, 0.0))
        blocks = ['[[block]]\nname = "pedestal"\nstl = "pedestal.stl"\nfixed = true\n']
        z = 0.0
        for i, (hx, hy, h, dx) in enumerate(boxes):
            piece = f"box{i + 1}"
            box_stl(os.path.join(d, f"{piece}.stl"), piece, (dx - hx, -hy, z), (dx + hx, hy, z + h))
            blocks.append(f'[[block]]\nname = "{piece}"\nstl = "{piece}.stl"\n')
            z += h
        with open(os.path.join(d, f"{name}.toml"), "w") as f:
            f.write(f"# {description}; boxes resting flush (exactly at equilibrium: no saved state).\n"
                    f"# The convergence study's hard set (docs/accuracy.md). Regenerate: "
                    f"/usr/bin/python3 tests/bench/convergence_study.py --write-scenes\n\n"
                    f'[physics]\ncontact = "rigid"\ndensity = 2600.0\nfriction = {friction}\n\n'
                    f'[failure]\nrule = "{rule}"\n\n' + "\n".join(blocks))
        print(f"wrote {d}")


# ---------------------------------------------------------------------------------------------
# The campaigns and the comparison


# The scanned rock's imports: the demo's (setup.sh demo: its convex hull as contact shape) and the
# hard set's compound body (the scan's convex decomposition)
SCAN_IMPORTS = {"sp1_rock": [], "sp1_rock_compound": ["--contact-shape", "decompose"]}


def import_scans(rigid):
    """The SP1 scan of ../shared/scans, imported where a job looks for it, unless already there."""
    scan = os.path.join(SOURCE_DIR, "..", "shared", "scans", "sp1_rock.obj")
    for name, flags in SCAN_IMPORTS.items():
        prefix = os.path.join(SOURCE_DIR, "models", "scans", name, name)
        if os.path.isfile(prefix + ".toml") or not os.path.isfile(scan):
            continue
        subprocess.run([rigid, "model", "import", scan, "--out", prefix, "--flatten-base", "0.005", *flags],
                       cwd=SOURCE_DIR, check=True, stdout=subprocess.DEVNULL)


def has_objects(job):
    """False for a job whose every object is optional and absent (the scan job without ../shared)."""
    with open(job, "rb") as f:
        objects = tomllib.load(f).get("object", [])
    here = os.path.dirname(job)
    return any(not o.get("optional", False) or os.path.isfile(os.path.join(here, o.get("scene", "")))
               for o in objects)


def campaign(args, job, setting, out):
    extra = shlex.split(args.reference_args if setting == "reference" else args.default_args)
    command = [args.rigid, "campaign", job, "--out", out, "--progress", "none"] + (
        ["--accuracy", "reference"] if setting == "reference" else []) + extra
    if args.np > 1:
        command = ["mpirun", "--oversubscribe", "-np", str(args.np)] + command
    # Open MPI refuses to start as root unless told it may (containers, cloud machines)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    start = time.monotonic()
    p = subprocess.run(command, cwd=SOURCE_DIR, capture_output=True, text=True, env=env)
    wall = time.monotonic() - start
    last = [line for line in p.stdout.splitlines() + p.stderr.splitlines() if line.strip()][-3:]
    print(f"  {os.path.basename(job)} {setting}: {wall:.1f} s, exit {p.returncode}" +
          "".join(f"\n    {line}" for line in last), flush=True)
    if p.returncode != 0:
        sys.stderr.write(p.stderr)
    return p.returncode, wall


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--set", choices=("hard", "shipped", "quick"), default="hard")
    p.add_argument("--rigid", default=os.path.join(SOURCE_DIR, "build", "bin", "rigid"))
    p.add_argument("--out", default=None,
                   help="default out/convergence, out/convergence_shipped or out/convergence_quick")
    p.add_argument("--np", type=int, default=2, help="MPI ranks per campaign (1: no mpirun)")
    p.add_argument("--default-args", default="", help="extra flags of the default campaigns")
    p.add_argument("--reference-args", default="", help="extra flags of the reference campaigns")
    p.add_argument("--jobs", default="",
                   help="comma-separated job names of the set to run (e.g. slender,sliding); default all")
    p.add_argument("--check", action="store_true", help="exit 1 unless the study's targets hold")
    p.add_argument("--resume", action="store_true",
                   help="resume the cubes already in OUT (after an interruption) instead of starting anew")
    p.add_argument("--write-scenes", action="store_true", help="write models/convergence/ and exit")
    args = p.parse_args(argv)
    if args.write_scenes:
        write_scenes(os.path.join(SOURCE_DIR, "models", "convergence"))
        return 0
    if not os.access(args.rigid, os.X_OK):
        sys.stderr.write(f"convergence_study: error: {args.rigid}: not an executable (build first, or --rigid)\n")
        return 2
    if args.np < 1:
        sys.stderr.write("convergence_study: error: --np must be at least 1\n")
        return 2
    args.rigid = os.path.abspath(args.rigid)
    out = os.path.abspath(args.out or os.path.join(SOURCE_DIR, "out", "convergence" + ("" if args.set == "hard"
                                                                                         else "_" + args.set)))
    os.makedirs(out, exist_ok=True)
    import_scans(args.rigid)
    env_ok = True
    pairs, timings = [], []
    start = time.monotonic()
    chosen = [j for j in args.jobs.split(",") if j]
    jobs = [j for j in jobs_of(args.set) if not chosen or os.path.splitext(os.path.basename(j))[0] in chosen]
    if chosen and len(jobs) != len(chosen):
        print(f"convergence_study: error: --jobs {args.jobs}: not all are jobs of the set {args.set}", file=sys.stderr)
        sys.exit(2)
    for job in jobs:
        name = os.path.splitext(os.path.basename(job))[0]
        if not has_objects(job):
            print(f"  {os.path.basename(job)}: left out (its optional objects are absent)")
            continue
        cubes = {s: os.path.join(out, f"{name}.{s}.h5") for s in SETTINGS}
        for s in SETTINGS:
            if not args.resume:  # a cube of the same job from an older engine would count as done
                for stale in glob.glob(glob.escape(cubes[s]) + "*"):
                    os.remove(stale)
            status, wall = campaign(args, job, s, cubes[s])
            timings.append((name, s, f"{wall:.1f}", status))
            env_ok &= status == 0
        pairs += ["--pair", cubes["reference"], cubes["default"]]
    with open(os.path.join(out, "timings.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(("job", "setting", "wall_s", "exit_status"))
        w.writerows(timings)
    print(f"campaigns: {time.monotonic() - start:.1f} s in all", flush=True)
    if not env_ok:
        sys.stderr.write("convergence_study: a campaign failed; the comparison is left out\n")
        return 1
    compare = [sys.executable, "-m", "rigidpy.outcome_agreement", *pairs, "--markdown", os.path.join(out, "study.md"),
               "--csv", os.path.join(out, "study.csv"), "--flips-csv", os.path.join(out, "flips.csv")]
    env = dict(os.environ, PYTHONPATH=os.path.join(SOURCE_DIR, "src", "python"))
    status = subprocess.run(compare + (["--check"] if args.check else []), env=env).returncode
    with open(os.path.join(out, "study.md")) as f:
        print(f.read())
    print(f"wrote {out}/study.md, study.csv, flips.csv, timings.csv")
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
