#!/usr/bin/env python3
"""CTest `robustness_import`: scans that must be refused, or imported with a warning, through the
real `rigid model import` and `rigid settle`, in the style of the `robustness` test (whose run and
check it uses): each case ends within 10 s of CPU and of wall time under a 2 GB address-space limit
with exit status 2 and one stderr line `rigid: error: ...` naming the problem (a warning case: exit
0 and one `rigid: warning:` line). The oracles are the files' own construction: a PLY truncated by
k bytes, a corner index past the declared vertices, a pedestal 10 m away from the rock, a cube in
millimetres are what the test wrote. A failed import must leave nothing behind: the output
directory it would have created does not exist afterwards.

usage: robustness_import_test.py RIGID SOURCE_DIR
"""
import os
import struct
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import robustness_test as base  # noqa: E402  (its run, check and inputs; reads the same argv)

base.WALL_LIMIT_S = 10  # the PLY cases: 10 s of wall time each (a hang or a 20 GB allocation is slow)

SCANS = os.path.join(base.SOURCE, "..", "shared", "scans")

# --- PLY files ---------------------------------------------------------------------------------

HALF = [(0.5 * x, 0.5 * y, 0.5 * z) for x, y, z in base.CUBE_V]
FACES0 = [tuple(i - 1 for i in f) for f in base.CUBE_F]  # PLY counts corners from 0


def ply_header(fmt, vertices, faces, count_type="uchar", index_type="int", end=True):
    lines = ["ply", "format %s 1.0" % fmt, "comment rigid robustness_import", "element vertex %d" % vertices,
             "property float x", "property float y", "property float z", "element face %d" % faces,
             "property list %s %s vertex_indices" % (count_type, index_type)]
    if end:
        lines.append("end_header")
    return ("\n".join(lines) + "\n").encode()


def binary_ply(vertices=HALF, faces=FACES0, endian="<", count_type="uchar", index_type="int", counts=None):
    """A binary PLY; `counts` overrides each face's declared corner count (the data stays 3 wide)."""
    fmt = "binary_little_endian" if endian == "<" else "binary_big_endian"
    code = {"uchar": "B", "ushort": "H", "int": "i", "uint": "I"}
    body = b"".join(struct.pack(endian + "3f", *v) for v in vertices)
    for k, f in enumerate(faces):
        n = len(f) if counts is None else counts[k]
        body += struct.pack(endian + code[count_type], n) + struct.pack(endian + "%d%s" % (len(f), code[index_type]), *f)
    return ply_header(fmt, len(vertices), len(faces), count_type, index_type) + body


def ascii_ply(vertices=HALF, faces=FACES0):
    body = "".join("%r %r %r\n" % v for v in vertices) + "".join("%d %s\n" % (len(f), " ".join(map(str, f)))
                                                                   for f in faces)
    return ply_header("ascii", len(vertices), len(faces)) + body.encode()


def write_bytes(d, name, data):
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)
    return name


def make_ply_inputs(d):
    """(name, file, fragments the error must name) for every malformed PLY."""
    good = binary_ply()
    write_bytes(d, "cube.ply", good)
    write_bytes(d, "cube_be.ply", binary_ply(endian=">"))
    write_bytes(d, "cube_ascii.ply", ascii_ply())
    bad = []
    for cut in (1, 7, 50, 150, 200):
        bad.append(("binary PLY truncated by %d bytes" % cut, write_bytes(d, "cut%d.ply" % cut, good[:len(good) - cut]),
                    ["truncated"]))
    faces = list(FACES0)
    faces[4] = (faces[4][0], -1, faces[4][2])
    bad.append(("negative corner index", write_bytes(d, "negative.ply", binary_ply(faces=faces)),
                ["face 4", "-1"]))
    faces[4] = (faces[4][0], 2000000000, faces[4][2])
    bad.append(("huge corner index", write_bytes(d, "huge_index.ply", binary_ply(faces=faces)),
                ["face 4", "2000000000"]))
    faces[4] = (faces[4][0], 8, faces[4][2])
    bad.append(("corner index one past the last vertex", write_bytes(d, "past.ply", binary_ply(faces=faces)),
                ["face 4", "8"]))
    counts = [3] * len(FACES0)
    counts[6] = 255
    bad.append(("list count 255", write_bytes(d, "count255.ply", binary_ply(counts=counts)), ["truncated"]))
    counts[6] = 65535
    bad.append(("list count 65535", write_bytes(d, "count65535.ply", binary_ply(count_type="ushort", counts=counts)),
                ["truncated"]))
    counts[6] = 0
    bad.append(("face with 0 corners", write_bytes(d, "zero.ply", binary_ply(counts=counts)), ["face 6", "0 corners"]))
    no_end = good.replace(b"end_header\n", b"")
    bad.append(("no end_header", write_bytes(d, "no_end.ply", no_end), ["end_header"]))
    header = ply_header("binary_little_endian", 2_000_000_000, 12)
    bad.append(("2e9 vertices declared in 200 bytes",
                write_bytes(d, "2e9.ply", header + b"\0" * (200 - len(header))), ["2000000000 vertex", "bytes"]))
    bad.append(("ASCII PLY: corner index past the vertices",
                write_bytes(d, "ascii_past.ply", ascii_ply().replace(b"\n3 0 2 1\n", b"\n3 0 2 99\n")), [":19:", "99"]))
    bad.append(("ASCII PLY truncated", write_bytes(d, "ascii_cut.ply", ascii_ply()[:-30]), ["truncated"]))
    # found by the PLY fuzzer: the check read the second format line (ascii), assimp the first
    # (binary), and assimp's post-processing crashed on the body it then made of the text
    two_formats = ascii_ply().replace(b"format ascii 1.0\n", b"format binary_big_endian 1.0\nformat ascii 1.0\n")
    bad.append(("two format lines", write_bytes(d, "two_formats.ply", two_formats), [":3:", "second format line"]))
    late = ascii_ply().replace(b"format ascii 1.0\n", b"").replace(b"end_header", b"format ascii 1.0\nend_header")
    bad.append(("format line after the elements", write_bytes(d, "late_format.ply", late), ["before the elements"]))
    # found by the PLY fuzzer: "property float\ry" is two words to the check and one to assimp,
    # whose post-processing then crashed on the body laid out by the other reading
    cr = binary_ply(endian=">").replace(b"property float y\n", b"property float\ry\n")
    bad.append(("carriage return inside a header line", write_bytes(d, "cr_inside.ply", cr),
                [":6:", "carriage return"]))
    # found by the PLY fuzzer too: a blank line after end_header, skipped by assimp before a
    # binary body (which then aborted) and read as the body's first byte by the check
    blank = binary_ply(endian=">").replace(b"end_header\n", b"end_header\n\n")
    bad.append(("blank line before a binary body", write_bytes(d, "blank_body.ply", blank),
                [":11:", "binary body begins"]))
    blank_lines = binary_ply(endian=">").replace(b"property float y\n", b"property float y\n\n\n")
    bad.append(("empty lines in the header", write_bytes(d, "blank_header.ply", blank_lines),
                [":7:", "empty line"]))
    write_bytes(d, "cube_crlf.ply", ascii_ply().replace(b"\n", b"\r\n"))  # CRLF line ends stay valid
    return bad


# --- scans, pedestals, scenes ------------------------------------------------------------------

def box_stl(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    out = ["solid box"]
    for f in base.CUBE_F:
        out.append(" facet normal 0 0 0\n  outer loop")
        out += ["   vertex %r %r %r" % v[i - 1] for i in f]
        out.append("  endloop\n endfacet")
    return "\n".join(out + ["endsolid box"]) + "\n"


def dome_obj(radius=0.5, rings=12, sectors=24):
    """A hemisphere on its flat base (z up): stable on the base, it rolls when laid on its side."""
    import math
    verts, faces = [(0.0, 0.0, 0.0)], []  # base centre
    for i in range(rings):
        phi = 0.5 * math.pi * i / rings
        for j in range(sectors):
            t = 2 * math.pi * j / sectors
            verts.append((radius * math.cos(phi) * math.cos(t), radius * math.cos(phi) * math.sin(t),
                          radius * math.sin(phi)))
    verts.append((0.0, 0.0, radius))
    top = len(verts)
    ring = lambda i, j: 2 + i * sectors + j % sectors
    for j in range(sectors):
        faces.append((1, ring(0, j + 1), ring(0, j)))
        for i in range(rings - 1):
            faces.append((ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)))
            faces.append((ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)))
        faces.append((ring(rings - 1, j), ring(rings - 1, j + 1), top))
    return base.obj_text(verts, faces)


def make_scene_inputs(d):
    base.write(d, "cube.obj", base.obj_text(HALF, base.CUBE_F))
    base.write(d, "dome.obj", dome_obj())
    # a pedestal scan 10 m beside the rock, and one under it (same units and origin)
    base.write(d, "far_pedestal.obj", base.obj_text([(x + 10, y, z - 0.5) for x, y, z in HALF], base.CUBE_F))
    base.write(d, "mm_cube.obj", base.obj_text([(1000 * x, 1000 * y, 1000 * z) for x, y, z in HALF], base.CUBE_F))
    base.write(d, "cm_cube.obj", base.obj_text([(0.01 * x, 0.01 * y, 0.01 * z) for x, y, z in HALF], base.CUBE_F))
    # a block 10 m beside its pedestal, for rigid settle
    base.write(d, "pedestal.stl", box_stl((-0.5, -0.5, -0.2), (0.5, 0.5, 0.0)))
    base.write(d, "block.stl", box_stl((-0.1, -0.1, 0.0), (0.1, 0.1, 0.5)))
    base.write(d, "beside_block.stl", box_stl((9.9, -0.1, 0.0), (10.1, 0.1, 0.5)))
    base.write(d, "on.model", "block pedestal.stl\n1 0 0 0\nblock block.stl\n0 0 0 0\n")
    base.write(d, "beside.model", "block pedestal.stl\n1 0 0 0\nblock beside_block.stl\n0 0 0 0\n")
    # a compound rock whose one contact piece covers only its top: nothing under its base
    base.write(d, "rock.stl", box_stl((-0.25, -0.25, 0.0), (0.25, 0.25, 0.5)))
    base.write(d, "top_piece.stl", box_stl((-0.25, -0.25, 0.3), (0.25, 0.25, 0.5)))
    base.write(d, "whole_piece.stl", box_stl((-0.25, -0.25, 0.0), (0.25, 0.25, 0.5)))
    scene = ('[[block]]\nname = "pedestal"\nstl = "pedestal.stl"\nfixed = true\n\n'
             '[[block]]\nname = "rock"\nstl = "rock.stl"\ncontact = ["%s"]\n')
    base.write(d, "uncovered.toml", scene % "top_piece.stl")
    base.write(d, "covered.toml", scene % "whole_piece.stl")
    base.write(d, "a_file", "not a directory\n")


def cases(d, bad_plys):
    e = "error"
    out = lambda sub: os.path.join(d, sub, "rock")
    imp = lambda scan, *extra, sub="imported": ["model", "import", scan, "--out", out(sub)] + list(extra)
    result = [("import a binary PLY cube", imp("cube.ply"), "ok", []),
              ("import a big-endian PLY cube", imp("cube_be.ply"), "ok", []),
              ("import an ASCII PLY cube", imp("cube_ascii.ply"), "ok", []),
              ("import an ASCII PLY cube with CRLF line ends", imp("cube_crlf.ply"), "ok", [])]
    for name, path, fragments in bad_plys:
        result.append(("PLY: " + name, imp(path, sub="fail_" + path), e, [path] + fragments))
        result.append(("PLY as --pedestal: " + name, imp("cube.obj", "--pedestal", path, sub="fail_ped_" + path), e,
                       [path] + fragments))
    result += [
        ("--split-z nan", imp("cube.obj", "--split-z", "nan", sub="fail_nan"), e, ["--split-z"]),
        ("--split-z inf", imp("cube.obj", "--split-z", "inf", sub="fail_inf"), e, ["--split-z"]),
        ("--out under a file", ["model", "import", "cube.obj", "--out", os.path.join(d, "a_file", "sub", "rock")], e,
         ["--out", "a_file"]),
        ("--pedestal 10 m beside the rock", imp("cube.obj", "--pedestal", "far_pedestal.obj", sub="fail_far"), e,
         ["far_pedestal.obj", "not under the rock"]),
        ("dome z-up imported with --up y", imp("dome.obj", "--up", "y", sub="fail_up"), e,
         ["dome.obj", "rests on nothing", "--up"]),
        ("dome z-up imported as it is", imp("dome.obj", sub="dome"), "ok", []),
        ("a cube in millimetres", imp("mm_cube.obj", sub="mm"), "warning", ["mm_cube.obj", "500 m", "--scale"]),
        ("a 5 mm cube", imp("cm_cube.obj", sub="cm"), "warning", ["cm_cube.obj", "0.005 m", "--scale"]),
        ("settle a block 10 m beside its pedestal", ["settle", "beside.model", "--out", "beside.state.toml"], e,
         ["beside.model", "rests on nothing"]),
        ("settle --max-time 1e9", ["settle", "on.model", "--out", "on.state.toml", "--max-time", "1e9"], e, ["steps"]),
        ("settle a block on its pedestal", ["settle", "on.model", "--out", "on.state.toml"], "ok", []),
        ("contact pieces that miss the base", ["inspect", "uncovered.toml"], e, ["rock.stl", "do not cover"]),
        ("contact pieces that cover the rock", ["inspect", "covered.toml"], "ok", []),
    ]
    return result


def real_scan_cases(d):
    """The real scan (skipped without ../shared): lying on its side it falls off its pedestal."""
    scan = os.path.join(SCANS, "sp1_rock.obj")
    if not os.path.exists(scan):
        print("SKIP real-scan cases: %s absent" % scan)
        return []
    return [("sp1_rock.obj (z up) imported with --up y", ["model", "import", scan, "--up", "y", "--out",
                                                          os.path.join(d, "fail_sp1", "rock")], "error",
             ["sp1_rock.obj", "rests on nothing", "--up"])]


def main():
    if not os.access(base.RIGID, os.X_OK):
        print("no executable " + base.RIGID)
        return 1
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="rigid_robustness_import_") as d:
        bad = make_ply_inputs(d)
        make_scene_inputs(d)
        all_cases = cases(d, bad) + real_scan_cases(d)
        failed = []
        for c in all_cases:
            ok = base.check(*c, d)
            # a failed import leaves nothing behind: the directory it would have made is absent
            out = c[1][c[1].index("--out") + 1] if "--out" in c[1] else None
            if ok and c[2] == "error" and c[1][:2] == ["model", "import"] and os.path.exists(os.path.dirname(out)):
                print("       FAIL: left %s behind: %s" % (os.path.dirname(out), os.listdir(os.path.dirname(out))))
                ok = False
            if not ok:
                failed.append(c[0])
    print("%d cases, %d failed, %.1f s" % (len(all_cases), len(failed), time.monotonic() - start))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
