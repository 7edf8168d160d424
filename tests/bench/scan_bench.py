#!/usr/bin/env python3
"""Scan benchmarks, the figures of docs/rocks.md; not a CTest (timings are no tests).

1. `rigid model import` of a generated 1e6-facet closed rock (a subdivided icosahedron with
   seeded bumps, binary STL): median wall time of 3 runs and the peak resident memory.
2. Cost per step of the real scan (../shared/scans/sp1_rock.obj) as one hull against its convex
   decomposition, on the same 10 s synthetic record: median of 3 `rigid run --json` each.

usage: scan_bench.py RIGID SOURCE_DIR [--facets N]
"""
import json
import os
import resource
import statistics
import struct
import subprocess
import sys
import tempfile
import time

import numpy as np

RIGID, SOURCE = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
FACETS = int(sys.argv[sys.argv.index("--facets") + 1]) if "--facets" in sys.argv else 1_000_000
SCAN = os.path.join(SOURCE, "..", "shared", "scans", "sp1_rock.obj")
RECORD = os.path.join(SOURCE, "waveforms", "demo", "stochastic_s1-X.AT2")


def icosphere(facets):
    """Unit icosphere subdivided until it has at least `facets` triangles (20 * 4^k)."""
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    v = [np.array(p, float) / np.linalg.norm(p) for p in v]
    while len(f) < facets:
        cache, nf = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = v[a] + v[b]
                v.append(m / np.linalg.norm(m))
                cache[key] = len(v) - 1
            return cache[key]

        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    return np.array(v), np.array(f)


def write_rock_stl(path, facets):
    v, f = icosphere(facets)
    rng = np.random.default_rng(13)
    # a lumpy boulder 0.8 x 0.6 x 0.5 m: smooth bumps (radial, so the surface stays simple)
    centres = rng.normal(size=(12, 3))
    centres /= np.linalg.norm(centres, axis=1)[:, None]
    bump = sum(0.06 * np.exp(-8 * np.sum((v - c) ** 2, axis=1)) for c in centres)
    p = v * (1 + bump)[:, None] * np.array([0.4, 0.3, 0.25])
    tri = p[f].astype("<f4")
    with open(path, "wb") as out:
        out.write(b"rigid scan benchmark".ljust(80, b" "))
        out.write(struct.pack("<I", len(f)))
        rec = np.zeros(len(f), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
        rec["v"] = tri
        out.write(rec.tobytes())
    return len(f)


def timed(args):
    start = time.monotonic()
    p = subprocess.run([RIGID] + args, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("failed: rigid %s\n%s" % (" ".join(args), p.stderr))
    return time.monotonic() - start, p.stdout


def main():
    with tempfile.TemporaryDirectory(prefix="rigid_scan_bench_") as d:
        stl = os.path.join(d, "boulder.stl")
        n = write_rock_stl(stl, FACETS)
        walls = [timed(["model", "import", stl, "--out", os.path.join(d, "b%d" % k, "boulder")])[0] for k in range(3)]
        rss_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
        print("import of a %d-facet binary STL (%.0f MB): median %.2f s wall of 3 (%s), peak RSS %.0f MB"
              % (n, os.path.getsize(stl) / 1e6, statistics.median(walls), ", ".join("%.2f" % w for w in walls), rss_mb))
        if not os.path.exists(SCAN):
            print("step cost: skipped (../shared/scans is absent)")
            return 0
        rows = []
        for shape in ("hull", "decompose"):
            scene = os.path.join(d, shape, "sp1")
            out = timed(["model", "import", SCAN, "--out", scene, "--flatten-base", "0.005", "--contact-shape", shape])[1]
            pieces = json.load(open(scene + ".import.json"))["bodies"][-1]["pieces"]
            per_step = []
            for _ in range(3):
                r = json.loads(timed(["run", scene + ".toml", "--motion", RECORD, "--target-pga", "0.15", "--json"])[1])
                per_step.append(1e6 * r["wall_s"] / max(r["steps"], 1))
            rows.append((shape, pieces, statistics.median(per_step), r["steps"], r["overturned"]))
        for shape, pieces, us, steps, over in rows:
            print("sp1_rock as %-9s: %3d pieces, %7.1f us per step (median of 3), %d steps, overturned %s"
                  % (shape, pieces, us, steps, over))
        print("decomposed / hull cost per step: %.1fx" % (rows[1][2] / rows[0][2]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
