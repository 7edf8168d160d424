#!/usr/bin/env python3
"""CTest `cli_vocabulary` (docs/user-guide.md, "One vocabulary"): the command line's own rules,
through the real executable, each against a stated oracle:

- a misspelt command or option: exit 2 and exactly the one line written below, naming the
  nearest known name and the --help of the subcommand concerned; under `mpirun -np 2`, one line;
- old spellings (export's --out, plot table's --scale): the note written below, word for word, and
  outputs byte-identical to the new spelling's (the mechanism's own cases: command_line_test.cpp);
- `rigid export cells CUBE`, `--csv`, `--csv FILE` and the old `--csv --out FILE`: the same bytes;
- `rigid plot table --scale` (old) and `--target-pga`: the note, byte-identical tables;
- defaults shown in --help: the values the source sets (io's for the lab format);
- `rigid inspect`: the law the scene runs and only its parameters; a symmetric block's centroid
  x and y printed as 0.0000; --json: one object per block with every key it had, plus `contact`.

usage: cli_vocabulary_test.py RIGID SOURCE_DIR CUBE    (CUBE: io_cube_test's fixture)
"""
import csv
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile

RIGID, SOURCE, CUBE = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
BLOCK = os.path.join(SOURCE, "models", "library", "block_a02")
failures = []


def rigid(args, cwd=None, env=None):
    return subprocess.run([RIGID] + args, cwd=cwd, capture_output=True, text=True, env=env, timeout=120)


def expect(name, ok, detail=""):
    print(("ok    " if ok else "FAIL  ") + name + ("" if ok else f": {detail}"))
    if not ok:
        failures.append(name)


def expect_usage_error(args, line):
    p = rigid(args)
    expect(f"rigid {' '.join(args)}: exit 2", p.returncode == 2, f"exit {p.returncode}, stderr {p.stderr!r}")
    expect(f"rigid {' '.join(args)}: the one line", p.stderr == line + "\n", f"{p.stderr!r} != {line!r}")


def did_you_mean():
    expect_usage_error(["campain"], "rigid: error: unknown command 'campain'; did you mean 'campaign'? (see rigid --help)")
    expect_usage_error(["model", "imprt"],
                       "rigid: error: unknown command 'imprt'; did you mean 'import'? (see rigid model --help)")
    expect_usage_error(["model", "import", "rock.stl", "--out", "x/rock", "--flaten-base", "0.005"],
                       "rigid: error: unknown option '--flaten-base'; did you mean '--flatten-base'? "
                       "(see rigid model import --help)")
    expect_usage_error(["inspect", "a.toml", "--jsno"],
                       "rigid: error: unknown option '--jsno'; did you mean '--json'? (see rigid inspect --help)")
    expect_usage_error(["frobnicate"], "rigid: error: unknown command 'frobnicate' (see rigid --help)")
    expect_usage_error(["model"],
                       "rigid: error: rigid model needs a command: library, import or block (see rigid model --help)")
    expect_usage_error(["model", "import", "r.stl", "--out", "x/r", "--tilt-rlue", "30"],
                       "rigid: error: unknown option '--tilt-rlue'; did you mean '--tilt-rule'? "
                       "(see rigid model import --help)")
    expect_usage_error(["export", "cells", "c.h5", "--csv", "--cvs", "x"],
                       "rigid: error: unknown option '--cvs'; did you mean '--csv'? (see rigid export cells --help)")
    # under mpirun every rank parses the line; one prints
    mpirun = shutil.which("mpirun")
    if mpirun is None:
        print("skip  mpirun -np 2: no mpirun")
        return
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([mpirun, "--oversubscribe", "-np", "2", RIGID, "campain"], capture_output=True, text=True,
                       env=env, timeout=120)
    lines = [l for l in (p.stdout + p.stderr).splitlines() if l.startswith("rigid: ")]
    expect("mpirun -np 2 rigid campain: exit 2", p.returncode == 2, p.returncode)
    expect("mpirun -np 2 rigid campain: one line", lines == [
        "rigid: error: unknown command 'campain'; did you mean 'campaign'? (see rigid --help)"], repr(lines))


def export_cells(tmp):
    runs = {
        "no flag": (["export", "cells", CUBE], None),
        "--csv": (["export", "cells", CUBE, "--csv"], None),
        "--csv -": (["export", "cells", CUBE, "--csv", "-"], None),
        "--csv FILE": (["export", "cells", CUBE, "--csv", os.path.join(tmp, "new.csv")], os.path.join(tmp, "new.csv")),
        "--csv --out FILE (old)": (["export", "cells", CUBE, "--csv", "--out", os.path.join(tmp, "old.csv")],
                                   os.path.join(tmp, "old.csv")),
        "--csv before the cube": (["export", "cells", "--csv", CUBE], None),
    }
    texts = {}
    for name, (args, path) in runs.items():
        p = subprocess.run([RIGID] + args, capture_output=True)
        expect(f"export cells {name}: exit 0", p.returncode == 0, p.stderr)
        texts[name] = open(path, "rb").read() if path else p.stdout
        note = b"rigid: note: --out is now --csv; the old spelling goes in the next release\n"
        expect(f"export cells {name}: stderr", p.stderr == (note if "old" in name else b""), p.stderr)
    expect_usage_error(["export", "cells", CUBE, "--csv", os.path.join(tmp, "a.csv"), "--out", os.path.join(tmp, "b.csv")],
                       "rigid: error: --out: is the old spelling of --csv; give only --csv (see rigid export cells --help)")
    first = texts["no flag"]
    expect("export cells: a CSV table", first.startswith(b"object,") and first.count(b"\n") > 2, first[:80])
    for name, text in texts.items():
        expect(f"export cells {name}: the same bytes", text == first)
    return first.decode()


def plot_table(tmp, cells):
    """`rigid plot table --scale` (Python's old spelling) against --target-pga, at a scale of the cube."""
    scale = next(csv.DictReader(io.StringIO(cells)))["scale_g"]
    outs = {}
    for spelling in ("--target-pga", "--scale"):
        d = os.path.join(tmp, "table" + spelling)
        os.makedirs(d)
        p = rigid(["plot", "table", CUBE, "--out", os.path.join(d, "t.md"), spelling, scale])
        expect(f"plot table {spelling}: exit 0", p.returncode == 0, p.stderr)
        outs[spelling] = (p, d)
    old, new = outs["--scale"], outs["--target-pga"]
    expect("plot table --scale: the note", old[0].stderr == "rigid: note: --scale is now --target-pga; the old "
           "spelling goes in the next release\n", repr(old[0].stderr))
    expect("plot table --target-pga: no note", new[0].stderr == "", repr(new[0].stderr))
    same = all(open(os.path.join(new[1], n), "rb").read() == open(os.path.join(old[1], n), "rb").read()
               for n in ("t.md", "t.csv"))
    expect("plot table --scale and --target-pga: byte-identical files", same)


def defaults_shown():
    # CLI11 2.1 prints a default after the type: `--scale FLOAT=1`
    shown = {
        ("model", "import"): ["--flatten-base FLOAT=0 ", "--scale FLOAT=1 "],
        ("motion", "synth"): ["--pga-g FLOAT=0.3 ", "--seed UINT=1 ", "--components INT=3 "],
        ("run",): ["--free-time FLOAT=5 ", "--accuracy TEXT=fast ", "--lab-band-hz TEXT=0.1,25 ",
                   "--lab-delimiter TEXT=tab "],
        ("campaign",): ["--progress TEXT:{auto,bar,log,none}=auto", "--log-interval FLOAT=10 "],
        ("model", "block"): ["--alpha FLOAT=0.2 "],
        ("model", "library"): ["--out DIR=models/library "],
    }
    for command, pieces in shown.items():
        text = rigid(list(command) + ["--help"]).stdout
        for piece in pieces:
            expect(f"rigid {' '.join(command)} --help shows {piece}", piece in text, text[:200])
    for command, kind in ((["model", "import"], "Output prefix DIR/NAME"), (["settle"], "Output file:"),
                          (["campaign"], "Output file:"), (["study", "accuracy"], "Output directory"),
                          (["model", "library"], "Output directory"), (["motion", "synth"], "Output prefix DIR/NAME")):
        text = rigid(command + ["--help"]).stdout
        expect(f"rigid {' '.join(command)} --help: --out is an {kind}", kind in text)


def inspect(tmp):
    scene = os.path.join(BLOCK, "block_a02.toml")
    p = rigid(["inspect", scene])
    expect("inspect: exit 0", p.returncode == 0, p.stderr)
    contact = [l for l in p.stdout.splitlines() if l.startswith("contact")]
    expect("inspect, rigid contact: its law, no springs", len(contact) == 1 and contact[0].startswith("contact: rigid")
           and "restitution 0" in contact[0] and "K_N" not in contact[0] and "damping" not in contact[0], contact)
    centroid = [l for l in p.stdout.splitlines() if "centroid" in l]
    expect("inspect: symmetric blocks' centroids at x = y = 0.0000",
           len(centroid) == 2 and all(l.strip().startswith("centroid (0.0000, 0.0000, ") for l in centroid), centroid)
    expect("inspect: no exponent of a rounding error", "e-1" not in p.stdout, p.stdout)
    penalty = os.path.join(tmp, "penalty.toml")
    with open(penalty, "w") as f:
        f.write(f'model = "{os.path.join(BLOCK, "block_a02.model")}"\n[physics]\ncontact = "penalty"\n'
                'normal_stiffness = 5e5\ndamping = 4.0\n')
    p = rigid(["inspect", penalty])
    contact = [l for l in p.stdout.splitlines() if l.startswith("contact")]
    expect("inspect, penalty contact: its springs, no restitution",
           len(contact) == 1 and contact[0].startswith("contact: penalty") and "K_N 5e+05 N/m^1.5" in contact[0]
           and "damping 4 s/m" in contact[0] and "restitution" not in contact[0], contact)
    p = rigid(["inspect", scene, "--json"])
    blocks = [json.loads(l) for l in p.stdout.splitlines()]
    keys = {"block", "fixed", "vertices", "faces", "volume_m3", "mass_kg", "centroid_m", "centre_of_mass_m",
            "principal_moments_kg_m2", "bounding_radius_m", "checks", "contact"}
    expect("inspect --json: one object per block, every key", len(blocks) == 2 and all(keys <= set(b) for b in blocks),
           [sorted(b) for b in blocks])
    expect("inspect --json: the rigid law", all(b["contact"] == {"method": "rigid", "friction": 0.6, "restitution": 0.0}
                                               for b in blocks), [b.get("contact") for b in blocks])
    expect("inspect --json: the free block's rocking parameters", "rocking" in blocks[1] and "rocking" not in blocks[0])


def main():
    with tempfile.TemporaryDirectory() as tmp:
        did_you_mean()
        plot_table(tmp, export_cells(tmp))
        defaults_shown()
        inspect(tmp)
    print(f"cli_vocabulary: {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
