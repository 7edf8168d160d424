#!/usr/bin/env python3
"""Layering check (CTest `layering`): no module includes a header of a layer above it.

Reads every `#include "..."` and `#include <...>` line of src/<module>/ and include/rigid/<module>/
and checks it against the dependencies src/CMakeLists.txt declares (read from its rigid_module()
calls and the `rigid` executable's link line; docs/architecture.md, "Layout and modules"), today:

  core <- geometry <- contact <- dynamics;  core <- motion, rocking;
  scenario <- dynamics, motion, rocking;  library, analysis, statistics <- scenario;
  study <- library, analysis;  io <- statistics;  job <- io, analysis;
  campaign <- job;  calibration <- core;  repair <- geometry;  scan <- io, repair, analysis;
  shaketable <- campaign, scan, calibration;  app <- shaketable, campaign, study, calibration, scan

(a module may include its own headers and those of every module below it, transitively), and the
third-party rules: the engine core (geometry .. scenario, library, analysis, statistics, study,
calibration) includes only Eigen and the standard library; only io includes HDF5,
toml++, nettle and assimp; only repair includes CGAL (linked through scan by app and tests/scan
alone: io and the tests that link it stay free of CGAL's compile); nlohmann-json is io's and above (io/json.hpp); only campaign includes MPI;
zlib is io's (gzip lab recordings) and campaign's (journal checksums); spdlog is campaign's and app's (campaign/log.hpp); only app includes CLI11; only rigidpy's extension (pyengine, over job) includes pybind11; POSIX headers (unistd.h, sys/...)
only io, scan (its staging folder), campaign and app. The required order (REQUIRED_ABOVE): library
and analysis above scenario; io above statistics; job above io, scenario and analysis; scan (the
scan import) above io and repair; campaign above job; the shake-table workflow above campaign,
scan and calibration; app above job, campaign, scan and the shake-table workflow. A quoted
include that is not "rigid/..." must be a private header of the module's own src/<module>/ folder.
No engine module (ENGINE) depends on a module outside the engine. app includes no geometry, contact
or dynamics header (NOT_INCLUDED), though it links them.

usage: layering_test.py SOURCE_DIR    exit 0 clean, 1 with one line per violation.
"""
import os
import re
import sys



def module_graph(root):
    """Direct dependencies of each module as src/CMakeLists.txt declares them: the DEPS of every
    rigid_module() call and the libraries the `rigid` executable (app) links."""
    with open(os.path.join(root, "src", "CMakeLists.txt"), encoding="utf-8") as f:
        text = f.read()
    graph = {"core": []}
    for name, deps in re.findall(r"^rigid_module\((\w+)\s+DEPS([^)]*)\)", text, re.M):
        graph[name] = re.findall(r"\brigid_(\w+)", deps)
    app = re.search(r"^target_link_libraries\(rigid\s+PRIVATE([^)]*)\)", text, re.M)
    graph["app"] = re.findall(r"\brigid_(\w+)", app.group(1)) if app else []
    # rigidpy's extension (src/pyengine, target _engine) links as the command line does
    engine = re.search(r"^\s*target_link_libraries\(_engine\s+PRIVATE([^)]*)\)", text, re.M)
    if engine:
        graph["pyengine"] = re.findall(r"\brigid_(\w+)", engine.group(1))
    return graph


DIRECT = {}  # module -> its direct dependencies (main() reads them)
ENGINE = {"core", "geometry", "contact", "dynamics", "motion", "rocking", "scenario", "library", "analysis",
          "statistics", "study", "calibration"}

# third-party family -> the modules that may include it
THIRD_PARTY = {
    "eigen": None,  # every module
    "std": None,
    "posix": {"io", "scan", "campaign", "app"},
    "hdf5": {"io"},
    "toml": {"io"},
    "nettle": {"io"},
    "assimp": {"io"},
    "cgal": {"repair"},
    "json": {"io", "campaign", "shaketable", "app"},
    "mpi": {"campaign"},
    "zlib": {"io", "campaign"},
    "spdlog": {"campaign", "app"},
    "cli11": {"app"},
    "pybind11": {"pyengine"},
}

# Where modules must sit, whatever CMake declares (module, modules it must be above): the job
# module (a job and its settings) is above the formats and the engine, below campaign and app; the
# scan import is above the formats and the repair of scans, below app; the cube's statistics are
# below the formats, which store what they compute.
REQUIRED_ABOVE = {
    "library": {"scenario"},
    "analysis": {"scenario"},
    "io": {"statistics"},
    "job": {"io", "scenario", "analysis"},
    "scan": {"io", "repair"},
    "campaign": {"job"},
    "shaketable": {"campaign", "scan", "calibration"},
    "app": {"job", "campaign", "scan", "shaketable"},
    "pyengine": {"job"},
}

# Modules a module links through others but may not include (module -> modules): the command line
# reaches the engine only through the case, the job and the campaign, so no engine internals
# (bodies, contacts, meshes) leak into what it prints.
NOT_INCLUDED = {
    "app": {"geometry", "contact", "dynamics"},
    "pyengine": {"geometry", "contact", "dynamics"},
}

# Deliberate exceptions: (module, included header) -> reason. Empty today.
ALLOWED_EXCEPTIONS = {}

POSIX = {"unistd.h", "fcntl.h", "signal.h", "errno.h", "pthread.h", "dirent.h"}


def family(header):
    if header.startswith("Eigen/"):
        return "eigen"
    if header.startswith("hdf5"):
        return "hdf5"
    if header.startswith("toml++/"):
        return "toml"
    if header.startswith("nettle/"):
        return "nettle"
    if header.startswith("assimp/"):
        return "assimp"
    if header.startswith("CGAL/"):
        return "cgal"
    if header.startswith("nlohmann/"):
        return "json"
    if header in ("mpi.h",):
        return "mpi"
    if header in ("zlib.h",):
        return "zlib"
    if header.startswith("spdlog/"):
        return "spdlog"
    if header.startswith("CLI/"):
        return "cli11"
    if header.startswith("pybind11/"):
        return "pybind11"
    if header in POSIX or header.startswith("sys/"):
        return "posix"
    if re.fullmatch(r"[a-z_]+", header):  # <vector>, <cmath>, <string_view>: the C++ library
        return "std"
    return None


def closure(module):
    seen, todo = set(), [module]
    while todo:
        m = todo.pop()
        if m not in seen:
            seen.add(m)
            todo.extend(DIRECT[m])
    return seen


INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def order_problems():
    """The required order (REQUIRED_ABOVE) against the declared graph: each module reaches the
    modules it must be above, and none of those reaches it back; and no engine module (ENGINE)
    reaches a module outside the engine."""
    problems = []
    for module, below in REQUIRED_ABOVE.items():
        if module not in DIRECT:
            problems.append(f"src/CMakeLists.txt: module {module} is missing")
            continue
        for other in sorted(below):
            if other not in closure(module):
                problems.append(f"src/CMakeLists.txt: {module} must be above {other}")
            elif other in DIRECT and module in closure(other):
                problems.append(f"src/CMakeLists.txt: {other} must be below {module}, not above it")
    # the engine core stands on itself: no engine module depends on io or anything above it
    for module in sorted(ENGINE & DIRECT.keys()):
        for other in sorted(closure(module) - ENGINE):
            problems.append(f"src/CMakeLists.txt: engine module {module} depends on {other}, outside the engine")
    return problems


def check(root):
    problems = order_problems()
    checked = 0
    for module in DIRECT:
        allowed = closure(module)
        folders = [os.path.join(root, "src", module), os.path.join(root, "include", "rigid", module)]
        for folder in folders:
            if not os.path.isdir(folder):
                continue
            for name in sorted(os.listdir(folder)):
                if not name.endswith((".cpp", ".hpp", ".h")):
                    continue
                path = os.path.join(folder, name)
                rel = os.path.relpath(path, root)
                with open(path, encoding="utf-8", errors="replace") as f:
                    for line_no, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if not m:
                            continue
                        checked += 1
                        kind, header = m.groups()
                        if (module, header) in ALLOWED_EXCEPTIONS:
                            continue
                        where = f"{rel}:{line_no}: {module} includes {kind}{header}{'>' if kind == '<' else kind}"
                        if kind == '"':
                            r = re.match(r"rigid/([a-z0-9_]+)/", header)
                            if r:
                                target = r.group(1)
                                if target not in DIRECT:
                                    problems.append(f"{where}: unknown module {target}")
                                elif target not in allowed:
                                    problems.append(f"{where}: {target} is not below {module} "
                                                    f"(allowed: {', '.join(sorted(allowed))})")
                                elif target in NOT_INCLUDED.get(module, ()):
                                    problems.append(f"{where}: {module} includes no {target} header "
                                                    f"(NOT_INCLUDED)")
                            elif not os.path.isfile(os.path.join(root, "src", module, header)):
                                problems.append(f"{where}: not a private header of src/{module}/")
                        else:
                            fam = family(header)
                            if fam is None:
                                problems.append(f"{where}: unknown third-party header (classify it in "
                                                f"tests/layering/layering_test.py)")
                            elif THIRD_PARTY[fam] is not None and module not in THIRD_PARTY[fam]:
                                who = ", ".join(sorted(THIRD_PARTY[fam]))
                                problems.append(f"{where}: {fam} is for {who} only")
    return problems, checked


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
    DIRECT.update(module_graph(root))
    problems, checked = check(os.path.abspath(root))
    for p in problems:
        print(p)
    print(f"layering: {checked} includes checked, {len(problems)} violations")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
