"""OpenQuake's CSV export of a classical calculation: its logic tree's realizations with their PGA
hazard curves at one site, read and checked; the reweighted curves written back in the same layout.

Files read from the export folder (the engine names them `<output>_<calc_id>.csv`; the copies in its
QA tests drop the id):
- `realizations_<id>.csv`: a comment line, then `rlz_id,branch_path,weight`;
- one `hazard_curve-rlz-NNN-PGA_<id>.csv` (or `..._PGA.csv`) per realization: the comment line holds
  `investigation_time=T` and `imt='PGA'`, then `lon,lat,depth,poe-IML,...`, one row per site; read by
  hazard.read_curve (PoE in [0, 1), not increasing with IML, annual rate -ln(1 - PoE) / T);
- when present, `hazard_curve-mean-PGA_<id>.csv` and `quantile_curve-Q-PGA_<id>.csv`: the engine's
  own statistics, for comparison.
The weighted mean of the realizations' PoEs is what the engine writes as the mean curve.
"""
import csv
import glob
import math
import os
import re
import shutil

import numpy as np

from . import hazard as hc
from .errors import InputError

# the weights a realizations file writes with 7-8 significant digits: their sum is 1 to this
WEIGHT_SUM_TOLERANCE = 1e-4

_RLZ_CURVE = re.compile(r"^hazard_curve-rlz-(\d+)[-_](.+?)(?:_(\d+))?\.csv$")
_STATISTIC_CURVE = re.compile(r"^(?:hazard_curve-(mean)|quantile_curve-([0-9.]+))[-_]PGA(?:_(\d+))?\.csv$")


class Branch:
    """One realization: its id, branch path, prior weight, the file and its curve (hazard.HazardCurve;
    annual rates) and the PoEs over the investigation time as written."""

    def __init__(self, rlz_id, branch_path, weight, path, curve, poe):
        self.rlz_id = rlz_id
        self.branch_path = branch_path
        self.weight = weight
        self.path = path
        self.curve = curve
        self.poe = poe


class LogicTreeCurves:
    """The realizations of one calculation at one site (`branches`), their common IMLs (g), the
    investigation time (years), the site's `lon,lat,depth`, the calculation id (may be ""), the
    realizations file, and the engine's own mean and quantile curves found beside them
    (`statistics`: {"mean" or the quantile as text: (path, PoEs)})."""

    def __init__(self, folder, realizations_path, calc_id, branches, imls, investigation_time, site, header_line,
                 statistics):
        self.folder = folder
        self.realizations_path = realizations_path
        self.calc_id = calc_id
        self.branches = branches
        self.imls = imls
        self.investigation_time = investigation_time
        self.site = site
        self.header_line = header_line  # the first comment line of the first realization's curve file
        self.statistics = statistics

    def weights(self):
        return np.array([b.weight for b in self.branches])

    def poes(self):
        """[branches, IMLs] probabilities of exceedance over the investigation time."""
        return np.array([b.poe for b in self.branches])


def read_export(folder, site=None):
    if not os.path.isdir(folder):
        raise InputError(f"{folder}: no such folder (an OpenQuake classical calculation's CSV export)")
    found = sorted(glob.glob(os.path.join(folder, "realizations*.csv")))
    if not found:
        raise InputError(f"{os.path.join(folder, 'realizations_*.csv')}: no such file (export the calculation's "
                         f"realizations with its hazard curves: oq export realizations, oq export hcurves)")
    if len(found) > 1:
        raise InputError(f"{folder}: {len(found)} realizations files ({', '.join(os.path.basename(f) for f in found)}): "
                         f"one calculation per folder")
    realizations_path = found[0]
    m = re.match(r"^realizations(?:_(\d+))?\.csv$", os.path.basename(realizations_path))
    calc_id = m.group(1) or "" if m else ""
    rows = read_realizations(realizations_path)
    curve_files = rlz_curve_files(folder, calc_id)
    branches, reference = [], None
    for line, rlz_id, path_text, weight in rows:
        path = curve_files.get(rlz_id)
        if path is None:
            raise InputError(f"{realizations_path}: line {line}: realization {rlz_id} has no hazard curve file "
                             f"hazard_curve-rlz-{rlz_id:03d}-PGA{'_' + calc_id if calc_id else ''}.csv in {folder}")
        try:
            curve = hc.read_curve(path, site)
        except hc.CurveError as e:
            raise InputError(str(e))
        check_openquake_curve(path, curve)
        if reference is None:
            reference = (path, curve)
        elif len(curve.pga_g) != len(reference[1].pga_g) or not np.allclose(curve.pga_g, reference[1].pga_g,
                                                                             rtol=1e-9, atol=0):
            raise InputError(f"{path}: line {header_line_of(path)}: IMLs {fmt_levels(curve.pga_g)} differ from "
                             f"{os.path.basename(reference[0])}'s {fmt_levels(reference[1].pga_g)}")
        elif curve.site != reference[1].site:
            raise InputError(f"{path}: site {curve.site} differs from {os.path.basename(reference[0])}'s "
                             f"{reference[1].site}")
        t = investigation_time_of(path)
        branches.append(Branch(rlz_id, path_text, weight, path, curve, -np.expm1(-curve.rate * t)))
    times = {investigation_time_of(b.path) for b in branches}
    if len(times) > 1:
        raise InputError(f"{branches[-1].path}: line 1: investigation times differ between the realizations' files "
                         f"({', '.join(f'{t:g}' for t in sorted(times))} years)")
    first = branches[0]
    with open(first.path, encoding="utf-8") as f:
        header_line = f.readline().rstrip("\n")
    statistics = read_statistics(folder, calc_id, first.curve, site)
    return LogicTreeCurves(folder, realizations_path, calc_id, branches, first.curve.pga_g, times.pop(),
                           first.curve.site, header_line, statistics)


def read_realizations(path):
    """[(line, rlz_id, branch_path, weight)] of a realizations file, the weights checked."""
    text = hc.read_text_input(path)
    rows, header = [], None
    for number, line in enumerate(text.splitlines(), start=1):
        if line.startswith("#") or not line.strip():
            continue
        cells = next(csv.reader([line]))
        if header is None:
            header = [c.strip() for c in cells]
            missing = [c for c in ("rlz_id", "branch_path", "weight") if c not in header]
            if missing:
                raise InputError(f"{path}: line {number}: no column {', '.join(missing)} (expected "
                                 f"rlz_id,branch_path,weight)")
            continue
        if len(cells) != len(header):
            raise InputError(f"{path}: line {number}: {len(cells)} columns, the header has {len(header)}")
        row = dict(zip(header, cells))
        try:
            rlz_id = int(row["rlz_id"])
        except ValueError:
            raise InputError(f"{path}: line {number}: rlz_id {row['rlz_id']!r} is not a whole number")
        w = hc._number(row["weight"])
        if w is None or not math.isfinite(w) or w < 0:
            raise InputError(f"{path}: line {number}: weight {row['weight']!r}: must be a number >= 0")
        if any(r[1] == rlz_id for r in rows):
            raise InputError(f"{path}: line {number}: realization {rlz_id} listed twice")
        rows.append((number, rlz_id, row["branch_path"].strip(), w))
    if not rows:
        raise InputError(f"{path}: no realization (expected rlz_id,branch_path,weight rows)")
    total = sum(w for _, _, _, w in rows)
    if abs(total - 1) > WEIGHT_SUM_TOLERANCE:
        raise InputError(f"{path}: lines {rows[0][0]}-{rows[-1][0]}: the weights sum to {total:.6g}, not 1")
    return rows


def rlz_curve_files(folder, calc_id):
    """{rlz_id: path} of the realizations' PGA curves; a folder whose realization curves are all of
    another IMT is refused (the fragilities are of PGA)."""
    files, other_imts = {}, set()
    for path in sorted(glob.glob(os.path.join(folder, "hazard_curve-rlz-*.csv"))):
        m = _RLZ_CURVE.match(os.path.basename(path))
        if not m or (calc_id and m.group(3) and m.group(3) != calc_id):
            continue
        if m.group(2) != "PGA":
            other_imts.add(m.group(2))
            continue
        files[int(m.group(1))] = path
    if not files and other_imts:
        raise InputError(f"{folder}: hazard curves of {', '.join(sorted(other_imts))} only, no PGA: the rock's "
                         f"fragility is a function of PGA")
    return files


def check_openquake_curve(path, curve):
    """An OpenQuake realization curve: PoEs over an investigation time (not annual rates), imt PGA."""
    if investigation_time_of(path) is None:
        raise InputError(f"{path}: line 1: no investigation_time=... in the first comment line (an OpenQuake "
                         f"hazard-curve export)")


def investigation_time_of(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        first = f.readline()
    m = re.search(r"investigation_time\s*=\s*([0-9.eE+-]+)", first)
    return float(m.group(1)) if m else None


def header_line_of(path):
    """The line number of the column header (the first line not a comment)."""
    with open(path, encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, start=1):
            if not line.startswith("#") and line.strip():
                return number
    return 1


def fmt_levels(a):
    a = list(a)
    shown = ", ".join(f"{v:g}" for v in a[:4])
    return f"[{shown}{', ...' if len(a) > 4 else ''}] ({len(a)} levels)"


def read_statistics(folder, calc_id, reference, site):
    """The engine's mean and quantile PGA curves of this calculation, when exported: {"mean" or "Q":
    (path, PoEs)}; files of other IMLs or sites are refused like a realization's."""
    out = {}
    for path in sorted(glob.glob(os.path.join(folder, "*_curve-*.csv"))):
        m = _STATISTIC_CURVE.match(os.path.basename(path))
        if not m or (calc_id and m.group(3) and m.group(3) != calc_id):
            continue
        try:
            curve = hc.read_curve(path, site)
        except hc.CurveError as e:
            raise InputError(str(e))
        if len(curve.pga_g) != len(reference.pga_g) or not np.allclose(curve.pga_g, reference.pga_g, rtol=1e-9):
            raise InputError(f"{path}: line {header_line_of(path)}: IMLs {fmt_levels(curve.pga_g)} differ from the "
                             f"realizations' {fmt_levels(reference.pga_g)}")
        t = investigation_time_of(path)
        out[m.group(1) or m.group(2)] = (path, -np.expm1(-curve.rate * t))
    return out


# --------------------------------------------------------------------------------------------
# Writing back


def write_export(folder, tree, posterior_weights, statistics, note):
    """The reweighted calculation in the engine's layout: realizations with the posterior weights,
    the realizations' curves as they were, and the mean and quantile curves ({"mean" or quantile:
    PoEs}) of the posterior. Returns the files written."""
    os.makedirs(folder, exist_ok=True)
    suffix = f"_{tree.calc_id}" if tree.calc_id else ""
    written = []
    path = os.path.join(folder, f"realizations{suffix}.csv")
    with open(path, "w", newline="") as f:
        f.write(f'#,,"{note}"\n')
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["rlz_id", "branch_path", "weight"])
        for b, weight in zip(tree.branches, posterior_weights):
            w.writerow([b.rlz_id, b.branch_path, f"{weight:.7E}"])
    written.append(path)
    lon_lat_depth = tree.site.split(",")
    levels = [f"poe-{a:.7f}" for a in tree.imls]
    for b in tree.branches:
        target = os.path.join(folder, os.path.basename(b.path))
        if os.path.abspath(target) != os.path.abspath(b.path):
            shutil.copyfile(b.path, target)  # the branches' curves are not changed, only their weights
            written.append(target)
    for name, poe in statistics.items():
        stem = "hazard_curve-mean" if name == "mean" else f"quantile_curve-{name}"
        kind = "mean" if name == "mean" else f"quantile-{name}"
        path = os.path.join(folder, f"{stem}-PGA{suffix}.csv")
        with open(path, "w", newline="") as f:
            write_curve(f, curve_header(tree, kind, note), lon_lat_depth, levels, poe)
        written.append(path)
    return written


def curve_header(tree, kind, note):
    return (f"generated_by='{note}', kind='{kind}', investigation_time={tree.investigation_time!r}, imt='PGA'")


def write_curve(f, header, lon_lat_depth, levels, poe):
    w = csv.writer(f, lineterminator="\n")
    f.write("#" + "," * (len(levels) + 2) + f'"{header}"\n')
    w.writerow(["lon", "lat", "depth"] + levels)
    w.writerow(lon_lat_depth + [f"{p:.6E}" for p in poe])
