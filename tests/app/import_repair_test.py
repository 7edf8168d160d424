#!/usr/bin/env python3
"""CTest `import_repair`: `rigid model import --repair` mends a scan with one self-intersection and
one small hole, through the real command line.

For a synthetic rock (a subdivided icosahedron, 0.5 m radius) and, when ../shared is present, the
real scan sp1_rock.obj, the test damages the mesh itself:
  - one vertex is moved past a neighbour and lifted, until one of its facets crosses a facet that
    shares no corner with it (checked here, independently of Rigid, by segment-triangle tests);
  - one facet far from it is deleted (a hole of three edges).
Without --repair the import must exit 2 naming a facet; with --repair it must exit 0, report what
changed (facets removed and added, one hole filled), and the repaired rock's volume must lie
within 0.5 % of the undamaged mesh's volume, computed here by the divergence theorem.

usage: import_repair_test.py RIGID SOURCE_DIR
"""
import json
import math
import os
import subprocess
import sys
import tempfile

RIGID, SOURCE = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
SCAN = os.path.join(SOURCE, "..", "shared", "scans", "sp1_rock.obj")
VOLUME_TOLERANCE = 0.005


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a, b, s=1.0):
    return (a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def volume(verts, faces):
    return abs(sum(dot(verts[a], cross(verts[b], verts[c])) for a, b, c in faces) / 6)


def segment_crosses_triangle(p, q, a, b, c):
    """Whether the segment pq passes through the triangle's interior (Moller-Trumbore)."""
    d = sub(q, p)
    e1, e2 = sub(b, a), sub(c, a)
    h = cross(d, e2)
    det = dot(e1, h)
    if abs(det) < 1e-14:
        return False
    s = sub(p, a)
    u = dot(s, h) / det
    qv = cross(s, e1)
    v = dot(d, qv) / det
    t = dot(e2, qv) / det
    eps = 1e-6
    return eps < u and eps < v and u + v < 1 - eps and eps < t < 1 - eps


def triangles_cross(t1, t2):
    return any(segment_crosses_triangle(t1[i], t1[(i + 1) % 3], *t2) for i in range(3)) or \
        any(segment_crosses_triangle(t2[i], t2[(i + 1) % 3], *t1) for i in range(3))


def read_obj(path):
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                verts.append(tuple(float(x) for x in w[1:4]))
            elif w[0] == "f":
                faces.append(tuple(int(x.split("/")[0]) - 1 for x in w[1:4]))
    return verts, faces


def write_obj(path, verts, faces):
    with open(path, "w") as f:
        f.write("".join("v %r %r %r\n" % v for v in verts))
        f.write("".join("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in faces))


def icosphere(radius=0.5, levels=3):
    t = (1 + math.sqrt(5)) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
             (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
             (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
             (8, 6, 7), (9, 8, 1)]
    verts = [tuple(radius * x / norm(v) for x in v) for v in verts]
    for _ in range(levels):
        mid, out = {}, []

        def midpoint(i, j):
            key = (min(i, j), max(i, j))
            if key not in mid:
                m = add(verts[i], verts[j])
                verts.append(tuple(radius * x / norm(m) for x in m))
                mid[key] = len(verts) - 1
            return mid[key]
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = out
    # a flat base to rest on: the points below z = -0.35 r lifted onto that plane
    floor = -0.35 * radius
    verts = [(x, y, max(z, floor)) for x, y, z in verts]
    return verts, faces


def damage(verts, faces):
    """(verts, faces, moved vertex, crossing pair): one vertex moved so that one of its facets
    crosses a facet sharing no corner with it, and one far facet deleted."""
    around = {}
    for k, f in enumerate(faces):
        for v in f:
            around.setdefault(v, []).append(k)
    for v in range(0, len(verts), max(1, len(verts) // 50)):
        ring = sorted({u for k in around[v] for u in faces[k] if u != v})
        nearby = {k2 for u in ring for k2 in around[u]} | {k3 for u in ring for k2 in around[u] for w in faces[k2]
                                                          for k3 in around[w]}
        normal = (0.0, 0.0, 0.0)
        for k in around[v]:
            a, b, c = (verts[i] for i in faces[k])
            normal = add(normal, cross(sub(b, a), sub(c, a)))
        normal = tuple(x / norm(normal) for x in normal)
        for u in ring:
            edge = norm(sub(verts[u], verts[v]))
            for lift in (0.5, 1.0, 2.0):
                moved = add(add(verts[v], sub(verts[u], verts[v]), 2.0), normal, lift * edge)
                trial = list(verts)
                trial[v] = moved
                for k in around[v]:
                    t1 = [trial[i] for i in faces[k]]
                    for k2 in nearby:
                        if set(faces[k2]) & set(faces[k]):
                            continue
                        if triangles_cross(t1, [trial[i] for i in faces[k2]]):
                            far = max(range(len(faces)), key=lambda j: norm(sub(verts[faces[j][0]], verts[v])))
                            return trial, faces[:far] + faces[far + 1:], v, (k, k2)
    raise RuntimeError("no vertex move made a crossing")


def run(args, cwd):
    p = subprocess.run([RIGID] + args, cwd=cwd, capture_output=True, text=True, timeout=600)
    return p.returncode, p.stdout, p.stderr


def check_case(label, verts, faces, d):
    problems = []
    original = volume(verts, faces)
    bad_verts, bad_faces, v, pair = damage(verts, faces)
    crossing = os.path.join(d, label + "_crossing.obj")
    write_obj(crossing, bad_verts, faces)
    damaged = os.path.join(d, label + "_damaged.obj")
    write_obj(damaged, bad_verts, bad_faces)
    print("%s: %d facets, vertex %d moved (facet %d crosses facet %d), one far facet deleted"
          % (label, len(faces), v, pair[0], pair[1]))
    # refused without --repair, naming a facet: the crossing alone, then with the hole too
    for path, fragments in ((crossing, ["crosses facet", "--repair"]), (damaged, ["open edge", "facets"])):
        status, _, err = run(["model", "import", path, "--out", os.path.join(d, "refused", label)], d)
        lines = err.splitlines()
        ok = status == 2 and len(lines) == 1 and lines[0].startswith("rigid: error: ") and \
            all(f in err for f in fragments)
        print("  %-4s without --repair: exit %d: %s" % ("ok" if ok else "FAIL", status, err.strip()[:200]))
        if not ok:
            problems.append("%s: not refused as expected" % os.path.basename(path))
    status, out, err = run(["model", "import", damaged, "--repair", "--out", os.path.join(d, label, "rock")], d)
    report_line = [line for line in out.splitlines() if "--repair:" in line]
    print("  with --repair: exit %d; %s" % (status, report_line[0] if report_line else out.strip()[:300]))
    if status != 0:
        problems.append("--repair: exit %d: %s" % (status, err.strip()[:300]))
        return problems
    with open(os.path.join(d, label, "rock.import.json")) as f:
        report = json.load(f)
    repair = report["repair"][0]
    if not (repair["holes_filled"] == 1 and repair["facets_added"] >= 1 and repair["facets_removed"] >= 1):
        problems.append("--repair report: %s" % repair)
    if not report_line:
        problems.append("no --repair line on stdout")
    repaired = report["bodies"][0]["mesh_volume_m3"]
    change = repaired / original - 1
    print("  volume %.6g m^3 undamaged (divergence theorem), %.6g m^3 repaired: %+.3f %%"
          % (original, repaired, 100 * change))
    if not abs(change) <= VOLUME_TOLERANCE:
        problems.append("repaired volume off by %+.3f %%" % (100 * change))
    return problems


def main():
    problems = []
    with tempfile.TemporaryDirectory(prefix="rigid_import_repair_") as d:
        verts, faces = icosphere()
        problems += check_case("icosphere", verts, faces, d)
        if os.path.exists(SCAN):
            verts, faces = read_obj(SCAN)
            problems += check_case("sp1_rock", verts, faces, d)
        else:
            print("SKIP sp1_rock: %s absent" % SCAN)
    for p in problems:
        print("FAIL " + p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
