#!/usr/bin/python3
"""Fragility maps, per-record curves, a probit fit, 3D-vs-2D difference maps and scenario tables
from Rigid's HDF5 fragility cubes (docs/cube.md; physics.md sections 1, 11).

    rigid_plot.py maps  CUBE --out DIR [--object NAME]... [--variant K] [--pgv-pga S] [--alpha [NAME=]RAD]...
                        [--p [NAME=]RAD_S]...
    rigid_plot.py diff  CUBE_A CUBE_B --out DIR [--label-a 3D] [--label-b 2D] [--object NAME]... [--variant K]
    rigid_plot.py table CUBE [CUBE...] --out FILE.md [--scale G] [--layout auto|objects|records] [--variant K]

A cube with a variant axis (epistemic variants of every object, layout at the top of src/io/cube.cpp) is
read as one object per (object, variant), named `rock [v3]` in tables and titles (files `rock_v3_...`);
--object NAME selects every variant of NAME, --variant K only variant K. `maps` draws by default,
per object, the variants' fragility curves with their 5-95 % band and the pooled (mixture) curve
(NAME_variants.png) and the map of the pooled cells (NAME_pooled_map.png); --variant K that
variant's map and records figures.

`rigid plot ARGS...` runs this file with Debian's /usr/bin/python3 (python3-numpy, python3-h5py,
python3-matplotlib, python3-scipy). The fit is fragility_fit.py's (shared with `rigid fragility`).

The fit ("this project's fit", NOT the coefficients of Purvance et al. 2008, which we do not have):

    P(overturn) = Phi((u - mu(x)) / sigma(x)),   u = ln(PGA / (g tan alpha)),
                                                 x = ln((PGV/PGA) p / alpha),
    mu(x) = m0 + m1 x (+ m2 x^2 ...),  ln sigma(x) = s0 (+ s1 x ...)   (--mu-degree, --sigma-degree)

fitted by maximum likelihood to the binomial outcomes of every simulated cell (record, scale,
rotation): overturned and survived; the stop rule's inferred cells, not-run and failed cells are
left out (fragility_fit.py says why). PGA is the cell's scale (target
GMRotI50 PGA, g), PGV/PGA the record's `pgv_pga_s` (scaling does not change it).
alpha (rad) and p (rad/s) come from the command line (--alpha, --p; one value for all objects or
NAME=VALUE per object), else from the attributes `alpha_rad` / `p_rad_s` of the object group, else
of the root group; without alpha u = ln(PGA / g) and without alpha or p x = ln(PGV/PGA / 1 s).
The normalisation only shifts the coefficients (u and x move by constants, and mu is a polynomial),
so the fitted probabilities and the 1/50/99 % contours are the same either way; it matters only
when comparing coefficients between blocks. The k % contour is the curve P = k/100, i.e.
PGA = g tan(alpha) exp(mu(x) + sigma(x) Phi^-1(k/100)); it is drawn only over the records'
PGV/PGA range (polynomials are not extrapolated).

Exit status: 0 done, 2 bad input (missing file, no such object, incompatible cubes), 1 internal.
"""
import argparse
import csv
import json
import math
import os
import re
import sys

try:
    import h5py
    import numpy as np
    import cube_checksums
    import cube_files
    import fragility_fit
    from fragility_fit import fit_mu, fit_probit, fit_sigma, norm_ppf, simulated_counts
except ImportError as e:  # pragma: no cover
    sys.stderr.write(f"rigid_plot: error: {e}; install python3-numpy python3-h5py python3-matplotlib "
                     f"python3-scipy and run with /usr/bin/python3 (this is {sys.executable})\n")
    sys.exit(2)

DPI = 120
FIGURE_FORMATS = ("png", "pdf", "svg")
NOT_RUN, SURVIVED, OVERTURNED, INFERRED, FAILED = 0, 1, 2, 3, 4
FIT_LABEL = "this project's probit fit (not Purvance et al. 2008)"
CONTOUR_LEVELS = (1, 50, 99)
CONTOUR_STYLE = {1: dict(ls=(0, (1.2, 1.6)), lw=2.0), 50: dict(ls="-", lw=2.2),
                 99: dict(ls=(0, (5, 2.5)), lw=2.0)}
# The study's reported mismatch (2D model minus Rigid 3D, mean and sd over cells; physics.md 11).
STUDY_MISMATCH_2D_MINUS_3D = {0.1: (0.03, 0.12), 0.2: (0.02, 0.08), 0.3: (0.02, 0.10), 0.4: (0.03, 0.14)}


class InputError(Exception):
    pass


# matplotlib is imported by the commands that draw, not at start: `rigid fragility` and `rigid hazard`
# read cubes through this module and would otherwise pay about a second per call for it.
plt = mcolors = mpatches = mlines = pe = mticker = None


def load_matplotlib():
    global plt, mcolors, mpatches, mlines, pe, mticker
    if plt is not None:
        return
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as pyplot
        from matplotlib import colors, lines, patheffects, patches, ticker
    except ImportError as e:  # pragma: no cover
        sys.stderr.write(f"rigid plot: error: {e}; install python3-matplotlib and run with /usr/bin/python3 "
                         f"(this is {sys.executable})\n")
        sys.exit(2)
    plt, mcolors, mpatches, mlines, pe, mticker = pyplot, colors, patches, lines, patheffects, ticker


# --------------------------------------------------------------------------------------------
# Reading cubes


def _strings(ds):
    return [s for s in ds.asstr()[()]]


class ObjectData:
    """One object of a cube, or one variant of it (a cube with a variant axis: one ObjectData per
    (object, variant), all with the base object's name)."""

    def __init__(self, name, attrs, outcome, probability, fragility, count, variant=None):
        self.name = name
        self.attrs = attrs
        self.outcome = outcome          # [R, S, A] int8
        self.probability = probability  # [R, S]
        self.fragility = fragility      # [S, B]
        self.count = count              # [S, B]
        self.variant = variant          # None without variants, else 0..V-1

    @property
    def label(self):
        """The name in tables, titles and file names: `rock`, or `rock [v3]` for a variant."""
        return self.name if self.variant is None else f"{self.name} [v{self.variant}]"


class VariantTable:
    """/variants of a cube with a variant axis: count, method, seed and the varied parameters as
    (name, units, values): a float array, or a list of str for a text parameter."""

    def __init__(self, group):
        self.count = int(group.attrs["count"])
        self.method = _text(group.attrs.get("method", ""))
        self.seed = int(group.attrs.get("seed", 0))
        self.parameters = []
        self.descriptions = {}
        for name in _text(group.attrs.get("parameters", "")).split():
            ds = group[name]
            if ds.dtype.kind in "OSU":
                values = _strings(ds)
            else:
                values = ds[()].astype(float)
            if len(values) != self.count:
                raise KeyError(f"variants/{name} of {len(values)} values for {self.count} variants")
            self.parameters.append((name, _text(ds.attrs.get("units", "")), values))
            self.descriptions[name] = _text(ds.attrs.get("description", ""))


def _text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


# Per-variant values that a cube without variants keeps as group attributes; with variants they
# are datasets [variant] (spec "On disk"), presented here as attributes of each variant's ObjectData.
VARIANT_NUMBERS = ("alpha_rad", "p_rad_s", "rocking_radius_m", "weakest_azimuth_deg")
VARIANT_TEXTS = ("physics_json", "inputs_sha256")


def variant_attrs(group, attrs, v):
    """The attributes of variant v: the group's, plus its row of the per-variant datasets (NaN and
    "" mean the variant has none, as a missing attribute does without variants)."""
    out = dict(attrs)
    for key in VARIANT_NUMBERS:
        if key in group:
            value = float(group[key][v])
            if math.isfinite(value):
                out[key] = value
    for key in VARIANT_TEXTS:
        if key in group:
            out[key] = _strings(group[key])[v]
    if "alpha_by_azimuth_rad" in group:
        out["alpha_by_azimuth_rad"] = group["alpha_by_azimuth_rad"][v].astype(float)
    if "support_polygon_m" in group:
        text = _strings(group["support_polygon_m"])[v].split()
        if text:
            out["support_polygon_m"] = np.array([float(t) for t in text])
    return out


class Cube:
    """The parts of a cube the plots need, read once. Reads both layouts: without variants
    (schema 1) and with a variant axis (schema 2, layout at the top of src/io/cube.cpp), where each
    (object, variant) becomes one ObjectData, in object then variant order."""

    def __init__(self, path):
        if not os.path.isfile(path):
            raise InputError(f"{path}: no such file")
        try:
            f = h5py.File(path, "r")
        except OSError as e:
            raise InputError(f"{path}: not an HDF5 file ({e})")
        self.path = path
        self.label = os.path.splitext(os.path.basename(path))[0]
        with f:
            try:
                version = cube_checksums.verify(f, path)
            except cube_checksums.ChecksumError as e:
                raise InputError(str(e))
            except KeyError as e:
                raise InputError(f"{path}: not a Rigid fragility cube (missing {e})")
            if warning := cube_checksums.old_cube_warning(path, version):
                sys.stderr.write(f"rigid: warning: {warning}\n")
            try:
                self.records = _strings(f["axes/record"])
                self.scales = f["axes/scale_g"][()].astype(float)
                self.edges = f["axes/pgv_pga_edges_s"][()].astype(float)
                self.pgv_pga = f["records/pgv_pga_s"][()].astype(float)
                rec = f["records"]
                R = len(self.records)
                self.windows = list(zip(_strings(rec["source"]) if "source" in rec else [""] * R,
                                        rec["start_s"][()] if "start_s" in rec else [0.0] * R,
                                        rec["end_s"][()] if "end_s" in rec else [math.inf] * R))
                self.root_attrs = {k: f.attrs[k] for k in f.attrs}
                self.variants = VariantTable(f["variants"]) if "variants" in f else None
                groups = f["objects"]
                items = []
                for name in groups:
                    g = groups[name]
                    attrs = {a: g.attrs[a] for a in g.attrs}
                    index = int(attrs.get("index", len(items)))
                    if self.variants is None:
                        items.append(((index, 0), self._object_data(name, g, attrs, None)))
                        continue
                    if int(attrs.get("variants", -1)) != self.variants.count:
                        raise InputError(f"{path}: object {name}: attribute variants = {attrs.get('variants')}, "
                                         f"but the cube has {self.variants.count} variants")
                    for v in range(self.variants.count):
                        items.append(((index, v), self._object_data(name, g, variant_attrs(g, attrs, v), v)))
            except KeyError as e:
                raise InputError(f"{path}: not a Rigid fragility cube (missing {e})")
        items.sort(key=lambda t: t[0])
        self.objects = [o for _, o in items]
        R, S, B = len(self.records), len(self.scales), len(self.edges) - 1
        for o in self.objects:
            if o.outcome.shape[:2] != (R, S) or o.fragility.shape != (S, B):
                raise InputError(f"{path}: object {o.label}: datasets do not match the axes")

    def _object_data(self, name, g, attrs, variant):
        """One object's (variant's) cells; with variants the datasets' first axis is the variant."""
        def read(key):
            return g[key][()] if variant is None else g[key][variant]
        outcome = read("outcome").astype(np.int8)
        # the derived datasets are recomputed from the checksummed cells, and stored ones that
        # disagree are refused: no result rests on a number no checksum covers
        prob = probability_from_outcome(outcome)
        frag, cnt = fragility_from_probability(prob, self.pgv_pga, self.edges)
        for key, mine in (("probability", prob), ("fragility", frag), ("fragility_count", cnt)):
            if key in g:
                stored = np.asarray(read(key), float)
                if stored.shape != mine.shape or not np.allclose(stored, mine, rtol=1e-12, atol=0, equal_nan=True):
                    raise InputError(f"{self.path}: /objects/{name}/{key} does not follow from its cells "
                                     f"(the file was altered)")
        return ObjectData(name, attrs, outcome, np.asarray(prob, float), np.asarray(frag, float),
                          np.asarray(cnt, int), variant)

    def base_names(self):
        names = []
        for o in self.objects:
            if o.name not in names:
                names.append(o.name)
        return names

    def object(self, name, variant=None):
        for o in self.objects:
            if o.name == name and (variant is None or o.variant == variant):
                return o
        raise InputError(f"{self.path}: no object {name!r} (objects: {', '.join(self.base_names())})")

    def check_variant(self, variant):
        """--variant K: refused on a cube without variants and outside 0..V-1."""
        if variant is None:
            return
        if self.variants is None:
            raise InputError(f"{self.path}: --variant {variant}: the cube has no variants")
        if not 0 <= variant < self.variants.count:
            raise InputError(f"{self.path}: --variant {variant} out of range (the cube has "
                             f"{self.variants.count} variants, 0-{self.variants.count - 1})")

    def select(self, names, variant=None):
        """The objects named (every variant of each; all objects without names), or only variant K."""
        self.check_variant(variant)
        chosen = [o for n in names for o in self.objects if o.name == n] if names else list(self.objects)
        for n in names or []:
            self.object(n)  # an unknown name: InputError naming the cube
        return [o for o in chosen if variant is None or o.variant == variant]

    def bin_of_records(self):
        return np.array([pgv_pga_bin(self.edges, v) for v in self.pgv_pga], dtype=int)

    def incomplete(self, state):
        """Why fits of this cube are provisional (cells not run; `state` of
        cube_files.campaign_state, taken before any lock of ours), or None when it is complete."""
        total = sum(o.outcome.size for o in self.objects)
        not_run = sum(int((o.outcome == NOT_RUN).sum()) for o in self.objects)
        parts = []
        if not_run:
            parts.append(f"{not_run} of {total} cells ({100 * not_run / total:.0f} %) not run")
        if state == "running":
            parts.append(f"a campaign (or a store) is writing it now ({self.path}.lock is held)")
        elif state == "stopped" and not_run:
            parts.append(f"its campaign stopped before the end ({self.path}.journal is there; run the campaign "
                         f"again to finish it)")
        return f"{self.path}: incomplete cube: " + "; ".join(parts) if parts else None


def pgv_pga_bin(edges, v):
    """Bin i holds edges[i] <= v < edges[i+1]; the last bin also its upper edge; -1 outside."""
    if not np.isfinite(v) and not (v == math.inf and edges[-1] == math.inf):
        return -1
    B = len(edges) - 1
    for i in range(B):
        if edges[i] <= v < edges[i + 1] or (i == B - 1 and v == edges[-1]):
            return i
    return -1


def overturned_and_known(outcome):
    """(overturned, known) cells per (record, scale) over the rotations: the one Python copy of the
    rule of the cube's `probability` (io::overturn_probability, src/io/cube.cpp): overturned and
    inferred count as overturned, survived as not, not-run and failed cells are left out."""
    over = np.sum((outcome == OVERTURNED) | (outcome == INFERRED), axis=2)
    known = over + np.sum(outcome == SURVIVED, axis=2)
    return over, known


def probability_from_outcome(outcome):
    """The cube's `probability` for cubes that do not store it (written by io::overturn_probability
    since schema 1; Cube reads the stored one when it is there)."""
    over, known = overturned_and_known(outcome)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(known > 0, over / np.maximum(known, 1), np.nan)


def fragility_from_probability(prob, pgv_pga, edges):
    R, S = prob.shape
    B = len(edges) - 1
    total = np.zeros((S, B))
    count = np.zeros((S, B), dtype=int)
    for r in range(R):
        b = pgv_pga_bin(edges, pgv_pga[r])
        if b < 0:
            continue
        ok = np.isfinite(prob[r])
        total[ok, b] += prob[r, ok]
        count[ok, b] += 1
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(count > 0, total / np.maximum(count, 1), np.nan), count


# --------------------------------------------------------------------------------------------
# Block parameters and the fit of one object


def parse_per_object(values, option):
    """['0.2', 'rock_a=0.3'] -> (default or None, {name: value})."""
    default, per = None, {}
    for v in values or []:
        if "=" in v:
            name, _, num = v.rpartition("=")
        else:
            name, num = None, v
        try:
            val = float(num)
        except ValueError:
            raise InputError(f"{option} {v!r}: expected a number or NAME=NUMBER")
        if not (val > 0 and math.isfinite(val)):
            raise InputError(f"{option} {v!r}: must be positive")
        if name is None:
            default = val
        else:
            per[name] = val
    return default, per


def block_parameter(cube, obj, attr, cli):
    default, per = cli
    if obj.name in per:
        return per[obj.name], "command line"
    if default is not None:
        return default, "command line"
    for where, attrs in (("object attribute", obj.attrs), ("root attribute", cube.root_attrs)):
        if attr in attrs:
            try:
                v = float(np.asarray(attrs[attr]).reshape(-1)[0])
            except (TypeError, ValueError):
                continue
            if v > 0 and math.isfinite(v):
                return v, f"{where} {attr}"
    return None, "unknown"


class Normalisation:
    def __init__(self, alpha, alpha_src, p, p_src):
        self.alpha, self.alpha_src, self.p, self.p_src = alpha, alpha_src, p, p_src
        self.u_shift = -math.log(math.tan(alpha)) if alpha else 0.0          # u = ln(PGA_g) + u_shift
        self.x_shift = math.log(p / alpha) if (alpha and p) else 0.0          # x = ln(PGV/PGA) + x_shift

    def describe(self):
        u = "ln(PGA / (g tan alpha))" if self.alpha else "ln(PGA / g)  (alpha unknown: not normalised)"
        x = ("ln((PGV/PGA) p / alpha)" if (self.alpha and self.p)
             else "ln(PGV/PGA / 1 s)  (alpha or p unknown: not normalised)")
        return u, x

    def pga_g(self, u):
        return np.exp(np.asarray(u) - self.u_shift)

    def x_of(self, pgv_pga):
        return np.log(np.asarray(pgv_pga, float)) + self.x_shift


def fit_object(cube, obj, norm, mu_degree, sigma_degree):
    """Binomial rows (u, x, k, n) of one object and its fit; None fit if too little data."""
    over, known = simulated_counts(obj.outcome)
    n = known.astype(float)          # [R, S]
    k = over.astype(float)
    R, S = n.shape
    rec_ok = np.isfinite(cube.pgv_pga) & (cube.pgv_pga > 0)
    rows = [(r, s) for r in range(R) for s in range(S) if n[r, s] > 0 and rec_ok[r] and cube.scales[s] > 0]
    info = {"object": obj.label, "label": FIT_LABEL,
            "model": "P = Phi((u - mu(x)) / sigma(x)), mu polynomial in x, ln sigma polynomial in x",
            "u": norm.describe()[0], "x": norm.describe()[1],
            "alpha_rad": norm.alpha, "alpha_source": norm.alpha_src,
            "p_rad_s": norm.p, "p_source": norm.p_src,
            "outcomes": "simulated cells (record, scale, rotation): overturned = 1, survived = 0; inferred cells left out",
            "n_cells": int(sum(n[r, s] for r, s in rows)),
            "n_overturned": int(sum(k[r, s] for r, s in rows)),
            "n_records": int(len({r for r, _ in rows}))}
    if not rows:
        info["fit"] = None
        info["reason"] = "no known cells"
        return info, None
    rr = np.array([r for r, _ in rows])
    ss = np.array([s for _, s in rows])
    u = np.log(cube.scales[ss]) + norm.u_shift
    x = norm.x_of(cube.pgv_pga[rr])
    kk, nn = k[rr, ss], n[rr, ss]
    distinct_x = len(np.unique(np.round(x, 12)))
    md = min(mu_degree, distinct_x - 1)
    sd = min(sigma_degree, distinct_x - 1)
    info["mu_degree"], info["sigma_degree"] = md, sd
    if md < mu_degree or sd < sigma_degree:
        info["degree_note"] = f"reduced to the {distinct_x} distinct PGV/PGA values"
    n_par = md + sd + 2
    if info["n_overturned"] < 2 or info["n_cells"] - info["n_overturned"] < 2 or info["n_cells"] < n_par + 3:
        info["fit"] = None
        info["reason"] = "too little data (needs >= 2 overturned, >= 2 survived, > parameters + 2 cells)"
        return info, None
    if n_par > distinct_x:
        info["warning"] = (f"{n_par} parameters for {distinct_x} distinct PGV/PGA values: the fit interpolates "
                           "between few records; lower --mu-degree/--sigma-degree")
    fit = fit_probit(u, x, kk, nn, md, sd)
    info["fit"] = fit
    if fit["separated"]:
        info["reason"] = ("no finite maximum-likelihood estimate: the outcomes are (quasi-)separated "
                          "(sigma -> 0); contours not drawn")
        return info, None
    info["x_range"] = [float(x.min()), float(x.max())]
    info["pgv_pga_range_s"] = [float(cube.pgv_pga[rr].min()), float(cube.pgv_pga[rr].max())]
    # the contour PGA at each bin's median record PGV/PGA, for tables
    bins = cube.bin_of_records()
    table = []
    for b in range(len(cube.edges) - 1):
        sel = [r for r in set(rr.tolist()) if bins[r] == b]
        if not sel:
            continue
        v = float(np.median(cube.pgv_pga[sel]))
        row = {"bin": b, "pgv_pga_s": v}
        for lev in CONTOUR_LEVELS:
            row[f"pga_g_{lev}pct"] = float(contour_pga(fit, norm, np.array([v]), lev)[0])
        table.append(row)
    info["contours_at_bin_median_pgv_pga"] = table
    return info, fit


def contour_pga(fit, norm, pgv_pga, level_pct):
    x = norm.x_of(pgv_pga)
    q = norm_ppf(level_pct / 100.0)
    return norm.pga_g(fit_mu(fit, x) + fit_sigma(fit, x) * q)


def fit_probability(fit, norm, pga_g, pgv_pga):
    return fragility_fit.fit_probability(fit, np.log(pga_g) + norm.u_shift, norm.x_of(pgv_pga))


# --------------------------------------------------------------------------------------------
# Drawing


def safe_name(name):
    return re.sub(r"[^A-Za-z0-9._-]+", "_", name) or "object"


def file_stem(obj):
    """The start of an object's file names: `rock`, or `rock_v3` for variant 3."""
    return safe_name(obj.name) + ("" if obj.variant is None else f"_v{obj.variant}")


def scale_cell_edges(scales):
    s = np.asarray(scales, float)
    if len(s) == 1:
        w = 0.05 * s[0] if s[0] > 0 else 0.05
        return np.array([s[0] - w, s[0] + w])
    mid = 0.5 * (s[1:] + s[:-1])
    return np.concatenate([[s[0] - (mid[0] - s[0])], mid, [s[-1] + (s[-1] - mid[-1])]])


def display_y_edges(edges, pgv_pga):
    """Bin edges for a log axis: open or zero outer edges clipped to the records' range."""
    e = np.array(edges, float)
    finite = pgv_pga[np.isfinite(pgv_pga) & (pgv_pga > 0)]
    lo_data = finite.min() if finite.size else None
    hi_data = finite.max() if finite.size else None
    if not e[0] > 0:
        inner = e[1] if len(e) > 2 else 0.1
        lo = inner / 2.0
        if lo_data is not None:
            lo = min(lo, 0.85 * lo_data)
        e[0] = min(lo, 0.9 * inner)
    if not np.isfinite(e[-1]):
        inner = e[-2]
        hi = inner * 1.6
        if hi_data is not None:
            hi = max(hi, 1.15 * hi_data)
        e[-1] = max(hi, 1.1 * inner)
    return e


def _fmt_edge(v):
    if v == 0:
        return "0"
    if not np.isfinite(v):
        return "\u221e"
    return f"{v:.3g}"


class MapRows:
    """The rows of a map: one per PGV/PGA bin that holds records, equal heights, one above the other
    (row k spans y = k..k+1); bins without records are left out, also between bins with records, so
    the y axis is not continuous and each row is labelled with its own bin. Within a row PGV/PGA runs
    on a log scale between the bin's edges (open outer edges clipped to the records' range)."""

    def __init__(self, edges, pgv_pga):
        edges = np.asarray(edges, float)
        pgv_pga = np.asarray(pgv_pga, float)
        B = len(edges) - 1
        bins = np.array([pgv_pga_bin(edges, v) for v in pgv_pga], dtype=int)
        self.records_in_bin = np.bincount(bins[bins >= 0], minlength=B)
        self.bins = np.flatnonzero(self.records_in_bin)
        if self.bins.size == 0:  # no record in any bin: show every bin (all hatched)
            self.bins = np.arange(B)
        self.edges = edges
        self.log_edges = np.log(display_y_edges(edges, pgv_pga))

    def __len__(self):
        return len(self.bins)

    def y(self, pgv_pga):
        """Row coordinates of PGV/PGA values; NaN for values in no row (matplotlib breaks lines there)."""
        v = np.atleast_1d(np.asarray(pgv_pga, float))
        out = np.full(v.shape, np.nan)
        with np.errstate(divide="ignore", invalid="ignore"):
            lv = np.log(v)
        for k, b in enumerate(self.bins):
            lo, hi = self.log_edges[b], self.log_edges[b + 1]
            inside = (lv >= lo) & (lv <= hi)
            out[inside] = k + (lv[inside] - lo) / (hi - lo)
        return out

    def label(self, k):
        b = self.bins[k]
        return f"{_fmt_edge(self.edges[b])}\u2013{_fmt_edge(self.edges[b + 1])}"


def _setup_map_axes(ax, cube, rows, scale_edges):
    ax.set_ylim(0, len(rows))
    ax.set_xlim(scale_edges[0], scale_edges[-1])
    ax.yaxis.set_major_locator(mticker.FixedLocator([k + 0.5 for k in range(len(rows))]))
    ax.yaxis.set_major_formatter(mticker.FixedFormatter([rows.label(k) for k in range(len(rows))]))
    ax.yaxis.set_minor_locator(mticker.NullLocator())
    ax.tick_params(axis="y", length=0)
    S = len(cube.scales)
    step = 1 if S <= 12 else int(math.ceil(S / 12))
    ax.set_xticks(cube.scales[::step])
    ax.set_xticklabels([f"{v:g}" for v in cube.scales[::step]])
    ax.set_xlabel("PGA = target GMRotI50 PGA (g)")
    ax.set_ylabel("PGV/PGA bin (s), the bins with records")


def _hatch_background(ax, scale_edges, rows):
    ax.add_patch(mpatches.Rectangle((scale_edges[0], 0), scale_edges[-1] - scale_edges[0], len(rows),
                                    facecolor="white", edgecolor="0.7", hatch="///", lw=0, zorder=0))


def draw_surface(ax, cube, values, count, cmap, norm, counts="none", rows=None):
    """Cells coloured by value over (scale, PGV/PGA bin), one row per bin with records (`rows`,
    default: the cube's); cells without a value show the hatched background.
    counts: "none"; "deviations": print a cell's record count only where it is below its bin's
    number of records (not-run or failed cells); "all": print every cell's count.
    Returns (mesh, rows, scale_edges, whether a hatched cell shows)."""
    rows = MapRows(cube.edges, cube.pgv_pga) if rows is None else rows
    scale_edges = scale_cell_edges(cube.scales)
    _hatch_background(ax, scale_edges, rows)
    data = np.ma.masked_invalid(np.asarray(values, float).T[rows.bins])  # [shown bins, S]
    mesh = ax.pcolormesh(scale_edges, np.arange(len(rows) + 1), data, cmap=cmap, norm=norm, edgecolors="0.35",
                         linewidth=0.4, zorder=1)
    _setup_map_axes(ax, cube, rows, scale_edges)
    if counts != "none" and count is not None:
        bins = cube.bin_of_records()
        in_bin = np.bincount(bins[bins >= 0], minlength=len(cube.edges) - 1)  # this cube's records
        for k, b in enumerate(rows.bins):
            for s in range(data.shape[1]):
                if np.ma.is_masked(data[k, s]):
                    continue
                if counts == "deviations" and count[s, b] >= in_bin[b]:
                    continue
                rgba = cmap(norm(data[k, s]))
                lum = 0.299 * rgba[0] + 0.587 * rgba[1] + 0.114 * rgba[2]
                ax.text(0.5 * (scale_edges[s] + scale_edges[s + 1]), k + 0.5, str(int(count[s, b])),
                        ha="center", va="center", fontsize=7, color="black" if lum > 0.5 else "white",
                        zorder=3)
    return mesh, rows, scale_edges, bool(np.ma.getmaskarray(data).any())


def add_bin_totals(ax, rows):
    """The number of records of each row's bin, as labels on the right-hand axis."""
    sec = ax.secondary_yaxis("right")
    sec.yaxis.set_major_locator(mticker.FixedLocator([k + 0.5 for k in range(len(rows))]))
    sec.yaxis.set_major_formatter(mticker.FixedFormatter([f"{rows.records_in_bin[b]}" for b in rows.bins]))
    sec.yaxis.set_minor_locator(mticker.NullLocator())
    sec.tick_params(axis="y", length=0, labelsize=8)
    sec.set_ylabel("records in bin", fontsize=9)
    return sec


def draw_contours(ax, rows, fit, norm_, pgv_range, color="black", label_prefix="", levels=CONTOUR_LEVELS):
    """The fit's k % contours as PGA(PGV/PGA) curves over the records' PGV/PGA range, in the rows'
    coordinates (broken where PGV/PGA lies in a bin without records)."""
    handles = []
    v = np.geomspace(pgv_range[0], pgv_range[1], 200) if pgv_range[1] > pgv_range[0] else np.array(pgv_range)
    y = rows.y(v)
    for lev in levels:
        pga = contour_pga(fit, norm_, v, lev)
        style = CONTOUR_STYLE[lev]
        x0, x1 = ax.get_xlim()
        where = ""
        if not np.any((pga >= x0) & (pga <= x1)):
            where = " (left of the plot)" if np.all(pga < x0) else (" (right of the plot)" if np.all(pga > x1)
                                                                   else " (outside the plot)")
        (line,) = ax.plot(pga, y, color=color, ls=style["ls"], lw=style["lw"], zorder=4,
                          path_effects=[pe.Stroke(linewidth=style["lw"] + 2.2, foreground="white"), pe.Normal()],
                          label=f"{label_prefix}{lev} % contour{where}")
        ax.set_xlim(x0, x1)
        if len(v) == 1:
            line.set_marker("o")
        handles.append(line)
    return handles


def counts_mode(cube, option):
    """--counts on: every cell; off: none; auto: cells whose count is below their bin's records."""
    return {"on": "all", "off": "none"}.get(option, "deviations")


def plot_map(cube, obj, fit, norm_, info, path, counts):
    load_matplotlib()
    fig, ax = plt.subplots(figsize=(9.5, 6.2), dpi=DPI)
    cmap = plt.get_cmap("viridis")
    cnorm = mcolors.Normalize(0.0, 1.0)
    mesh, rows, _, hatched = draw_surface(ax, cube, obj.fragility, obj.count, cmap, cnorm, counts)
    add_bin_totals(ax, rows)
    cb = fig.colorbar(mesh, ax=ax, ticks=[0, 0.25, 0.5, 0.75, 1.0], pad=0.09)
    cb.set_label("P(overturn): mean over the records of the cell")
    handles = [mpatches.Patch(facecolor="white", edgecolor="0.5", hatch="///",
                              label="no simulated cell (not run or failed)")] if hatched else []
    if fit is not None:
        handles += draw_contours(ax, rows, fit, norm_, info["pgv_pga_range_s"])
        sig = fit_sigma(fit, np.array(info["x_range"]))
        sig_txt = f"{sig.min():.2g}" if abs(sig[0] - sig[1]) < 1e-9 else f"{sig.min():.2g}\u2013{sig.max():.2g}"
        fit_text = (f"{FIT_LABEL}: {info['n_cells']} cells of {info['n_records']} records, "
                    f"\u03c3 = {sig_txt} (ln PGA)")
    else:
        fit_text = f"no fit: {info.get('reason', '')}"
    alpha_txt = f", alpha = {norm_.alpha:.3g} rad" if norm_.alpha else ""
    note = {"all": "cell numbers: records averaged",
            "deviations": "cell numbers: records averaged where fewer than the bin's (not run/failed)",
            "none": "each cell: mean over the bin's records"}[counts]
    ax.set_title(f"{obj.label}{alpha_txt}: binned overturning probability\n"
                 f"cube {os.path.basename(cube.path)}; {note}", fontsize=11)
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=4, fontsize=9,
              frameon=False, title=fit_text, title_fontsize=9)
    fig.tight_layout()
    cube_files.save_figure(fig, path, "--out", INPUTS, dpi=DPI)
    plt.close(fig)


RECORDS_LISTED = 6  # panels with at most this many records name them


def record_label(cube, r):
    return f"{cube.records[r]} ({cube.pgv_pga[r]:.3g} s)"


def plot_records(cube, obj, fit, norm_, path):
    """One panel per PGV/PGA bin that holds records (bins without are left out, not drawn empty)."""
    load_matplotlib()
    bins = cube.bin_of_records()
    shown = [b for b in range(len(cube.edges) - 1) if np.any(bins == b)] or [0]
    ncol = min(3, len(shown))
    nrow = int(math.ceil(len(shown) / ncol))
    # a panel of up to RECORDS_LISTED records names them in a legend to its right, off the curves;
    # the figure widens by the longest name (about 0.06 in per character at 7 pt)
    listed = [r for b in shown if np.sum(bins == b) <= RECORDS_LISTED for r in np.flatnonzero(bins == b)]
    legend_in = (0.5 + 0.06 * max(len(record_label(cube, r)) for r in listed)) if listed else 0.0
    fig, axes = plt.subplots(nrow, ncol, figsize=((4.1 + legend_in) * ncol + 1.2, 2.9 * nrow + 1.3), dpi=DPI,
                             sharex=True, sharey=True, squeeze=False)
    finite = cube.pgv_pga[np.isfinite(cube.pgv_pga) & (cube.pgv_pga > 0)]
    lo, hi = (finite.min(), finite.max()) if finite.size else (0.05, 0.5)
    if hi <= lo:
        lo, hi = lo / 1.2, hi * 1.2
    cnorm = mcolors.LogNorm(lo, hi)
    cmap = mcolors.LinearSegmentedColormap.from_list(
        "plasma_trunc", plt.get_cmap("plasma")(np.linspace(0.0, 0.82, 256)))  # no pale yellow on white
    marker = "o" if len(cube.scales) <= 25 else None
    sgrid = np.linspace(max(cube.scales.min() * 0.5, 1e-3), cube.scales.max(), 200)
    for i in range(nrow * ncol):
        ax = axes[i // ncol][i % ncol]
        if i >= len(shown):
            ax.set_visible(False)
            continue
        b = shown[i]
        recs = [r for r in range(len(cube.records)) if bins[r] == b]
        ax.set_title(f"PGV/PGA {_fmt_edge(cube.edges[b])}\u2013{_fmt_edge(cube.edges[b + 1])} s "
                     f"({len(recs)} record{'s' if len(recs) != 1 else ''})", fontsize=9)
        ax.grid(True, color="0.88", lw=0.6)
        ax.set_ylim(-0.05, 1.05)
        ax.set_yticks([0, 0.5, 1])
        if not recs:  # only when no bin holds a record: the one panel says so
            ax.text(0.5, 0.5, "no records", transform=ax.transAxes, ha="center", va="center", color="0.5")
            continue
        for r in recs:  # above the bin mean, so a bin of one record still shows its colour
            ax.plot(cube.scales, obj.probability[r], color=cmap(cnorm(cube.pgv_pga[r])), lw=1.3,
                    marker=marker, ms=3.5, alpha=0.85, zorder=7, label=record_label(cube, r))
        if len(recs) <= RECORDS_LISTED:
            ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, fontsize=7, frameon=False,
                      handlelength=1.5)
        ax.plot(cube.scales, obj.fragility[:, b], color="black", lw=2.6, ls="--", zorder=5)
        if fit is not None:
            v = float(np.median(cube.pgv_pga[recs]))
            ax.plot(sgrid, fit_probability(fit, norm_, sgrid, v), color="tab:green", lw=2.0, zorder=6)
    for ax in axes[-1]:
        ax.set_xlabel("PGA (g)")
    for row in axes:
        row[0].set_ylabel("P(overturn)")
    handles = [mlines.Line2D([], [], color="0.4", lw=1.2, marker=marker, ms=3,
                             label="one record (colour = its PGV/PGA)"),
               mlines.Line2D([], [], color="black", lw=2.0, ls="--", label="bin mean (the map's cells)")]
    if fit is not None:
        handles.append(mlines.Line2D([], [], color="tab:green", lw=2.0,
                                     label=f"{FIT_LABEL}, at the bin's median PGV/PGA"))
    alpha_txt = f" (alpha = {norm_.alpha:.3g} rad)" if norm_.alpha else ""
    fig.suptitle(f"{obj.label}{alpha_txt}: P(overturn) per record vs PGA, one panel per PGV/PGA bin\n"
                 f"P = fraction of rotations overturned (inferred counted as overturned); "
                 f"cube {os.path.basename(cube.path)}", fontsize=11)
    fig.legend(handles=handles, loc="lower center", ncol=3, fontsize=9, frameon=False)
    fig.tight_layout(rect=(0, 0.05, 0.9, 1))
    cax = fig.add_axes([0.915, 0.15, 0.018, 0.7])
    sm = plt.cm.ScalarMappable(norm=cnorm, cmap=cmap)
    cb = fig.colorbar(sm, cax=cax)
    cb.set_label("record PGV/PGA (s)")
    ticks = [lo] + [e for e in cube.edges if lo * 1.08 < e < hi / 1.08] + [hi]
    cb.set_ticks(ticks)
    cb.set_ticklabels([f"{t:.3g}" for t in ticks])
    cb.ax.yaxis.set_minor_locator(mticker.NullLocator())
    cube_files.save_figure(fig, path, "--out", INPUTS, dpi=DPI)
    plt.close(fig)


# --------------------------------------------------------------------------------------------
# Variants: every variant's fragility curve, the epistemic band, the pooled curve


def variant_lognormal(cube, obj, args, pgv_pga_s):
    """(theta_g, beta, how) of one variant at PGV/PGA `pgv_pga_s`: the map's fit there (median
    and sigma of ln PGA), else the scalar fit over all records, else the empirical threshold of
    separated outcomes (a step), else None."""
    norm_ = normalisation_for(cube, obj, args)
    info, fit = fit_object(cube, obj, norm_, args.mu_degree, args.sigma_degree)
    if fit is not None:
        theta = float(contour_pga(fit, norm_, np.array([pgv_pga_s]), 50)[0])
        return theta, float(fit_sigma(fit, norm_.x_of([pgv_pga_s]))[0]), "fit"
    # the same fallbacks, in the same order, as rigid fragility's pool (rigid_fragility.fragility_source)
    cells = fragility_fit.Cells(obj.outcome, cube.scales, cube.pgv_pga)
    scalar = fragility_fit.lognormal_fit(*fragility_fit.scalar_rows(cells, cells.records_with_cells()))
    if scalar is not None:
        return scalar["theta_g"], scalar["beta"], "scalar fit (all records)"
    step = fragility_fit.empirical_threshold(cells)
    if step is not None:
        return step["theta_g"], 0.0, "empirical threshold"
    return None, None, info.get("reason", "no fit")


def plot_variant_band(cube, name, curves, pooled, pgv_pga_s, path):
    load_matplotlib()
    fig, ax = plt.subplots(figsize=(11, 5.6), dpi=DPI)
    a = pooled["pga_g"]
    for k, (theta, beta, how) in curves:
        ax.plot(a, fragility_fit.lognormal_probability(a, theta, beta), color="0.55", lw=0.7,
                ls=":" if how == "empirical threshold" else "-", zorder=2)
    lo, hi = pooled["percentiles"][0], pooled["percentiles"][-1]
    ax.fill_between(a, pooled["band_lower"], pooled["band_upper"], color="tab:blue", alpha=0.25, lw=0, zorder=1,
                    label=f"{lo}-{hi} % of the variants' P(PGA) (epistemic band)")
    ax.plot(a, pooled["mixture_probability"], color="black", lw=2.6, zorder=4,
            label=f"pooled: mean over variants (median {pooled['median_g']:.3g} g)")
    ax.plot([], [], color="0.55", lw=0.7, label="one variant (dotted: empirical threshold, a step)")
    ax.set_xscale("log")
    ax.set_xlim(a[0], a[-1])
    ax.xaxis.set_major_formatter(mticker.FormatStrFormatter("%g"))
    if a[-1] / a[0] < 100:  # a decade or two: label the minor ticks too, else one label shows
        ax.xaxis.set_minor_formatter(mticker.FormatStrFormatter("%g"))
        ax.tick_params(axis="x", which="minor", labelsize=7)
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("PGA = target GMRotI50 PGA (g)")
    ax.set_ylabel("P(overturn)")
    ax.grid(True, which="both", color="0.9", lw=0.6)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, borderaxespad=0)  # off the curves
    ax.set_title(f"{name}: fragility of {len(curves)} variants at PGV/PGA {pgv_pga_s:.3g} s\n"
                 f"{FIT_LABEL}; cube {os.path.basename(cube.path)}", fontsize=10)
    fig.tight_layout()
    cube_files.save_figure(fig, path, "--out", INPUTS, dpi=DPI)
    plt.close(fig)


def variant_maps(cube, variants, args, counts):
    """The band figure and the pooled map of one object's variants; returns its fit.json entry."""
    name = variants[0].name
    pgv_pga_s = args.pgv_pga if args.pgv_pga is not None else float(np.median(
        cube.pgv_pga[np.isfinite(cube.pgv_pga) & (cube.pgv_pga > 0)]))
    curves, missing = [], []
    for o in variants:
        theta, beta, how = variant_lognormal(cube, o, args, pgv_pga_s)
        (curves.append((o.variant, (theta, beta, how))) if theta is not None else missing.append((o.variant, how)))
    base = os.path.join(args.out, safe_name(name))
    entry = {"object": name, "variants": len(variants), "pgv_pga_s": pgv_pga_s,
             "variant_fragility": [{"variant": k, "theta_g": t, "beta": b, "source": how} for k, (t, b, how) in curves],
             "variants_without_fragility": [{"variant": k, "reason": why} for k, why in missing], "files": []}
    if curves:
        lognormals = [(t, b) for _, (t, b, _) in curves]
        spread = max([b for _, b in lognormals] + [0.1])
        grid = np.geomspace(min(t for t, _ in lognormals) * math.exp(-3 * spread),
                            max(t for t, _ in lognormals) * math.exp(3 * spread), 400)
        pooled = fragility_fit.pooled_fragility(lognormals, grid)
        plot_variant_band(cube, name, curves, pooled, pgv_pga_s, base + "_variants." + args.format)
        entry["pooled"] = {k: pooled[k] for k in ("n_variants", "median_g", "lognormal_theta_g", "lognormal_beta",
                                                  "lognormal_method", "theta_percentiles_g", "beta_percentiles")}
        entry["files"].append(base + "_variants." + args.format)
        print(f"{name}: {len(curves)} of {len(variants)} variants with a fragility at PGV/PGA {pgv_pga_s:.3g} s; "
              f"pooled median {pooled['median_g']:.4g} g, theta 5/50/95 % over variants "
              f"{', '.join(f'{v:.3g}' for v in pooled['theta_percentiles_g'])} g")
    else:
        print(f"{name}: no variant has a fragility ({missing[0][1]})")
    # the pooled cells: a cell's mean over variants (the mixture's binned fragility); the count is
    # the fewest records any variant has there, so "auto" still marks cells some variant lacks
    stack = np.array([o.fragility for o in variants])
    defined = np.isfinite(stack).sum(axis=0)
    frag = np.where(defined > 0, np.nansum(stack, axis=0) / np.maximum(defined, 1), np.nan)
    pooled_obj = ObjectData(f"{name} (pooled over {len(variants)} variants)", {}, None, None, frag,
                            np.min([o.count for o in variants], axis=0))
    plot_map(cube, pooled_obj, None, Normalisation(None, "", None, ""),
             {"reason": f"each cell the mean over variants of its records' mean; the variants' fits are in "
                       f"{os.path.basename(base)}_variants.{args.format}"},
             base + "_pooled_map." + args.format, counts)
    entry["files"].append(base + "_pooled_map." + args.format)
    print(f"  wrote {', '.join(entry['files'])}")
    return entry


# --------------------------------------------------------------------------------------------
# Subcommands


def normalisation_for(cube, obj, args):
    alpha, asrc = block_parameter(cube, obj, "alpha_rad", parse_per_object(args.alpha, "--alpha"))
    p, psrc = block_parameter(cube, obj, "p_rad_s", parse_per_object(args.p, "--p"))
    if alpha is not None and not alpha < math.pi / 2:
        raise InputError(f"{obj.label}: alpha = {alpha} rad is not below pi/2")
    return Normalisation(alpha, asrc, p, psrc)


def _json_clean(v):
    """Strict JSON: non-finite numbers become null."""
    if isinstance(v, dict):
        return {k: _json_clean(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_json_clean(x) for x in v]
    if isinstance(v, (float, np.floating)):
        return float(v) if math.isfinite(v) else None
    if isinstance(v, np.integer):
        return int(v)
    return v


def fit_summary(obj, info, f, norm_):
    """The fit in words a reader can use: its median PGA and dispersion at the records' median
    PGV/PGA, and the coefficients with what they multiply."""
    x_mid = float(np.mean(info["x_range"]))
    sig = float(fit_sigma(f, np.array([x_mid]))[0])
    mu = f["mu_coefficients"]
    theta = float(norm_.pga_g(float(np.polyval(mu[::-1], x_mid))))
    u, x = norm_.describe()
    terms = " + ".join([f"{mu[0]:.4g}"] + [f"({c:.4g}) x" + (f"^{k}" if k > 1 else "") for k, c in enumerate(mu) if k])
    return (f"{obj.label}: {info['n_cells']} cells ({info['n_overturned']} overturned) of {info['n_records']} records; "
            f"at mid PGV/PGA of the records: median PGA {theta:.3g} g, dispersion sigma {sig:.3g} (of ln PGA)\n"
            f"  fit P = Phi((u - mu(x)) / sigma(x)), u = {u}, x = {x}: mu(x) = {terms}, "
            f"ln sigma = {', '.join(f'{c:.4g}' for c in f['log_sigma_coefficients'])} (fit.json has them all)")


def cmd_maps(args):
    state = cube_files.campaign_state(args.cube)
    cube = Cube(args.cube)
    if problem := cube.incomplete(state):
        sys.stderr.write(f"rigid plot: warning: {problem}; the maps show the cells run so far\n")
    objs = cube.select(args.object, args.variant)
    os.makedirs(args.out, exist_ok=True)
    summary = {"cube": os.path.abspath(cube.path), "label": FIT_LABEL,
               "contour_levels_pct": list(CONTOUR_LEVELS), "objects": []}
    show = counts_mode(cube, args.counts)
    if cube.variants is not None and args.variant is None:
        # With variants the default is, per object, ONE figure of every variant's fragility curve
        # with the epistemic band and the pooled curve, and ONE map: the pooled cells (the mean over
        # variants of each cell's binned probability, which is the mixture's binned fragility).
        # A map and a records figure per variant would be 2 V figures of near-identical surfaces
        # that nobody compares by eye; --variant K draws them for the one variant wanted.
        for name in [n for n in cube.base_names() if any(o.name == n for o in objs)]:
            summary["objects"].append(variant_maps(cube, [o for o in objs if o.name == name], args, show))
        objs = []
    for obj in objs:
        norm_ = normalisation_for(cube, obj, args)
        info, fit = fit_object(cube, obj, norm_, args.mu_degree, args.sigma_degree)
        base = os.path.join(args.out, file_stem(obj))
        info["files"] = [f"{base}_map.{args.format}", f"{base}_records.{args.format}"]
        plot_map(cube, obj, fit, norm_, info, info["files"][0], show)
        plot_records(cube, obj, fit, norm_, info["files"][1])
        summary["objects"].append(info)
        f = info.get("fit")
        if f is not None and fit is not None:
            print(fit_summary(obj, info, f, norm_))
        else:
            print(f"{obj.label}: {info['n_cells']} cells, no fit: {info.get('reason')}")
        if "warning" in info:
            print(f"  warning: {info['warning']}")
        print(f"  wrote {', '.join(info['files'])}")
    jpath = os.path.join(args.out, "fit.json")
    with cube_files.output_text(jpath, "--out", INPUTS) as fh:
        json.dump(_json_clean(summary), fh, indent=2, allow_nan=False)
        fh.write("\n")
    print(f"wrote {jpath}")
    return 0


def _fmt(v, digits=3):
    return "" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.{digits}f}"


def _sfmt(v, digits=3):
    """Signed: +0.050, -0.042, 0.000."""
    if v is None or not math.isfinite(v):
        return ""
    return f"{v:+.{digits}f}" if round(v, digits) != 0 else f"{0:.{digits}f}"


def mismatch(a, b):
    """Per-cell A - B where both are defined: (diff [S,B] with NaN elsewhere, n, mean, sd)."""
    d = a - b
    ok = np.isfinite(d)
    vals = d[ok]
    n = int(vals.size)
    mean = float(vals.mean()) if n else float("nan")
    sd = float(vals.std(ddof=1)) if n > 1 else (0.0 if n == 1 else float("nan"))
    return np.where(ok, d, np.nan), n, mean, sd


def _common_scales(ca, cb):
    ia, ib = [], []
    for i, s in enumerate(ca.scales):
        j = np.where(np.abs(cb.scales - s) <= 1e-9 * max(1.0, abs(s)))[0]
        if j.size:
            ia.append(i)
            ib.append(int(j[0]))
    return np.array(ia, int), np.array(ib, int)


class _View:
    """A cube restricted to some scales (for side-by-side drawing of two cubes)."""

    def __init__(self, cube, idx):
        self.path, self.records, self.edges, self.pgv_pga = cube.path, cube.records, cube.edges, cube.pgv_pga
        self.scales = cube.scales[idx]

    def bin_of_records(self):
        return np.array([pgv_pga_bin(self.edges, v) for v in self.pgv_pga], dtype=int)


def plot_diff(view_a, view_b, name, fa, ca_, fb, cb_, d, stats, la, lb, fits, path, counts):
    load_matplotlib()
    fig = plt.figure(figsize=(19.5, 6.4), dpi=DPI)
    outer = fig.add_gridspec(1, 2, width_ratios=[2.1, 1.08], wspace=0.2,
                             left=0.06, right=0.965, bottom=0.2, top=0.84)
    left = outer[0].subgridspec(1, 3, width_ratios=[1, 1, 0.045], wspace=0.07)
    right = outer[1].subgridspec(1, 2, width_ratios=[1, 0.045], wspace=0.06)
    ax_a, ax_b, cax_p = fig.add_subplot(left[0]), fig.add_subplot(left[1]), fig.add_subplot(left[2])
    ax_d, cax_d = fig.add_subplot(right[0]), fig.add_subplot(right[1])
    cmap = plt.get_cmap("viridis")
    pn = mcolors.Normalize(0.0, 1.0)
    # the same rows in the three panels: the bins with records in either cube
    rows = MapRows(view_a.edges, np.concatenate([view_a.pgv_pga, view_b.pgv_pga]))
    for ax, v, frag, cnt, lab, fit in ((ax_a, view_a, fa, ca_, la, fits[0]), (ax_b, view_b, fb, cb_, lb, fits[1])):
        mesh, _, _, _ = draw_surface(ax, v, frag, cnt, cmap, pn, counts, rows)
        ax.set_title(f"{lab}: P(overturn)  ({os.path.basename(v.path)})", fontsize=10)
        if fit is not None:
            draw_contours(ax, rows, fit[0], fit[1], fit[2]["pgv_pga_range_s"])
    fig.colorbar(mesh, cax=cax_p, ticks=[0, 0.25, 0.5, 0.75, 1], label="P(overturn)")
    dmap = plt.get_cmap("RdBu_r")
    dn = mcolors.Normalize(-1.0, 1.0)
    mesh_d, _, _, _ = draw_surface(ax_d, view_a, d, None, dmap, dn, "none", rows)
    handles = []
    for fit, color, lab in ((fits[0], "black", la), (fits[1], "tab:orange", lb)):
        if fit is not None:
            handles += draw_contours(ax_d, rows, fit[0], fit[1], fit[2]["pgv_pga_range_s"], color=color,
                                     label_prefix=f"{lab} ", levels=(50,))
    ax_d.set_title(f"difference {la} \u2212 {lb} (red: {la} more fragile)\n"
                   f"mean \u00b1 sd = {stats[1]:+.3f} \u00b1 {stats[2]:.3f} over {stats[0]} cells", fontsize=10)
    for ax in (ax_b, ax_d):
        ax.set_ylabel("")
    ax_b.tick_params(axis="y", labelleft=False)
    fig.colorbar(mesh_d, cax=cax_d, ticks=[-1, -0.5, 0, 0.5, 1], label=f"P({la}) \u2212 P({lb})")
    leg = [mpatches.Patch(facecolor="white", edgecolor="0.5", hatch="///", label="no cell in both cubes")]
    if fits[0] is not None or fits[1] is not None:
        leg += [mlines.Line2D([], [], color="black", lw=2, ls=CONTOUR_STYLE[k]["ls"], label=f"{k} % contour")
                for k in CONTOUR_LEVELS]
        leg += [mlines.Line2D([], [], color=h.get_color(), lw=2, label=f"{h.get_label()} (right)") for h in handles]
    fig.legend(handles=leg, loc="lower center", ncol=len(leg), fontsize=9, frameon=False,
               title=FIT_LABEL if len(leg) > 1 else None, title_fontsize=9)
    fig.suptitle(f"{name}: {la} vs {lb}, binned fragility (each cell: mean over the bin's records)", fontsize=12)
    cube_files.save_figure(fig, path, "--out", INPUTS, dpi=DPI)
    plt.close(fig)


def cmd_diff(args):
    ca, cb = Cube(args.cube_a), Cube(args.cube_b)
    if len(ca.edges) != len(cb.edges) or not np.array_equal(ca.edges, cb.edges):
        raise InputError(f"the cubes have different PGV/PGA bin edges ({ca.edges.tolist()} vs {cb.edges.tolist()})")
    ia, ib = _common_scales(ca, cb)
    if ia.size == 0:
        raise InputError("the cubes share no scale")
    # objects are matched by name and variant (a variant cube against its own kind)
    labels_b = {o.label for o in cb.objects}
    objs = ca.select(args.object, args.variant)
    common = [o for o in objs if o.label in labels_b]
    if not common:
        raise InputError(f"no object name in both cubes ({[o.label for o in ca.objects]} vs {sorted(labels_b)})")
    os.makedirs(args.out, exist_ok=True)
    la, lb = args.label_a, args.label_b
    va, vb = _View(ca, ia), _View(cb, ib)
    show = counts_mode(ca, args.counts)
    print(f"sign convention: difference = {la} \u2212 {lb} (A \u2212 B: {ca.path} minus {cb.path}); "
          f"positive = {la} more fragile. The study (report section 3.5) reported 2D model minus Rigid 3D.")
    rows = []
    for oa in common:
        ob = cb.object(oa.name, oa.variant)
        fa, fb = oa.fragility[ia], ob.fragility[ib]
        d, n, mean, sd = mismatch(fa, fb)
        mad = float(np.nanmean(np.abs(d))) if n else float("nan")
        norm_a = normalisation_for(ca, oa, args)
        fits = []
        for cube, o, nrm in ((ca, oa, norm_a), (cb, ob, normalisation_for(cb, ob, args))):
            info, fit = fit_object(cube, o, nrm, args.mu_degree, args.sigma_degree)
            fits.append((fit, nrm, info) if fit is not None else None)
        png = os.path.join(args.out, file_stem(oa) + "_diff." + args.format)
        plot_diff(va, vb, oa.label, fa, oa.count[ia], fb, ob.count[ib], d, (n, mean, sd), la, lb, fits, png, show)
        ref = None
        if norm_a.alpha is not None:
            for key, val in STUDY_MISMATCH_2D_MINUS_3D.items():
                if abs(norm_a.alpha - key) < 1e-6:
                    ref = val
        rows.append({"object": oa.label, "alpha_rad": norm_a.alpha, "n_cells": n, "mean_a_minus_b": mean,
                     "sd": sd, "mean_b_minus_a": -mean if n else float("nan"), "mean_abs": mad,
                     "study_2d_minus_3d": ref, "png": png})
        print(f"{oa.label}: {la} \u2212 {lb} = {mean:+.4f} \u00b1 {sd:.4f} (mean \u00b1 sd over {n} cells; "
              f"{lb} \u2212 {la} = {-mean:+.4f}; mean |diff| {mad:.4f})  -> {png}")
    skipped = [o.label for o in objs if o.label not in labels_b]
    if skipped:
        print(f"not in {cb.path}: {', '.join(skipped)}")
    csv_path = os.path.join(args.out, "mismatch.csv")
    with cube_files.output_text(csv_path, "--out", INPUTS, newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["object", "alpha_rad", "n_cells", f"mean_{la}_minus_{lb}", "sd", f"mean_{lb}_minus_{la}",
                    "mean_abs_diff", "study_2D_minus_3D_mean", "study_2D_minus_3D_sd"])
        for r in rows:
            w.writerow([r["object"], "" if r["alpha_rad"] is None else f"{r['alpha_rad']:g}", r["n_cells"],
                        _fmt(r["mean_a_minus_b"], 6), _fmt(r["sd"], 6), _fmt(r["mean_b_minus_a"], 6),
                        _fmt(r["mean_abs"], 6), "" if r["study_2d_minus_3d"] is None else r["study_2d_minus_3d"][0],
                        "" if r["study_2d_minus_3d"] is None else r["study_2d_minus_3d"][1]])
    md_path = os.path.join(args.out, "mismatch.md")
    with cube_files.output_text(md_path, "--out", INPUTS) as fh:
        fh.write(f"# Binned fragility mismatch: {la} \u2212 {lb}\n\n")
        fh.write(f"- A ({la}): `{ca.path}`\n- B ({lb}): `{cb.path}`\n")
        fh.write(f"- Sign: **{la} \u2212 {lb}** per cell (positive: {la} more fragile); the column "
                 f"{lb} \u2212 {la} is its negative. The study reported 2D model minus Rigid 3D.\n")
        fh.write("- Cells: (scale, PGV/PGA bin) defined in both cubes (scales common to both); "
                 "mean and sample sd (n \u2212 1) over cells, unweighted.\n\n")
        fh.write(f"| object | alpha (rad) | cells | {la} \u2212 {lb} mean \u00b1 sd | {lb} \u2212 {la} mean | "
                 f"mean \\|diff\\| | study 2D \u2212 3D |\n|---|---|---|---|---|---|---|\n")
        for r in rows:
            ref = "" if r["study_2d_minus_3d"] is None else f"{r['study_2d_minus_3d'][0]:.2f} \u00b1 {r['study_2d_minus_3d'][1]:.2f}"
            alpha = "" if r["alpha_rad"] is None else f"{r['alpha_rad']:g}"
            fh.write(f"| {r['object']} | {alpha} | {r['n_cells']} | {_sfmt(r['mean_a_minus_b'])} \u00b1 {_fmt(r['sd'])} | "
                     f"{_sfmt(r['mean_b_minus_a'])} | {_fmt(r['mean_abs'])} | {ref} |\n")
    print(f"wrote {csv_path}, {md_path}")
    return 0


def outcome_counts(outcome, scale_index=None):
    o = outcome if scale_index is None else outcome[:, scale_index:scale_index + 1, :]
    return {name: int(np.sum(o == code)) for name, code in
            (("not_run", NOT_RUN), ("survived", SURVIVED), ("overturned", OVERTURNED),
             ("inferred", INFERRED), ("failed", FAILED))}


def _fraction(c):
    known = c["survived"] + c["overturned"] + c["inferred"]
    return (c["overturned"] + c["inferred"]) / known if known else float("nan"), known


def cmd_table(args):
    cubes = [Cube(p) for p in args.cubes]
    multi = len(cubes) > 1
    records = []
    seen = {}
    differing = []
    for c in cubes:
        for r, w in zip(c.records, c.windows):
            if r not in records:
                records.append(r)
                seen[r] = w
            elif (os.path.basename(seen[r][0]), float(seen[r][1]), float(seen[r][2])) != \
                    (os.path.basename(w[0]), float(w[1]), float(w[2])) and r not in differing:
                differing.append(r)
    if differing:
        sys.stderr.write("rigid plot: warning: records matched by name differ in source or time window "
                         f"between cubes: {', '.join(differing)}\n")
    rows = []  # (row label, {record: counts}, all counts, cube, object)
    long_rows = []
    for c in cubes:
        si = None
        if args.scale is not None:
            j = np.where(np.abs(c.scales - args.scale) <= 1e-9 * max(1.0, abs(args.scale)))[0]
            if j.size == 0:
                raise InputError(f"{c.path}: no scale {args.scale:g} g (scales: {', '.join(f'{v:g}' for v in c.scales)})")
            si = int(j[0])
        for o in c.select(args.object, args.variant):
            per = {}
            for r, name in enumerate(c.records):
                cnt = outcome_counts(o.outcome[r:r + 1], si)
                per[name] = cnt
                frac, known = _fraction(cnt)
                long_rows.append([c.label, o.label, name, "all" if si is None else f"{c.scales[si]:g}",
                                  cnt["survived"], cnt["overturned"], cnt["inferred"], cnt["not_run"],
                                  cnt["failed"], known, _fmt(frac, 6)])
            allc = outcome_counts(o.outcome, si)
            frac, known = _fraction(allc)
            long_rows.append([c.label, o.label, "all", "all" if si is None else f"{c.scales[si]:g}",
                              allc["survived"], allc["overturned"], allc["inferred"], allc["not_run"],
                              allc["failed"], known, _fmt(frac, 6)])
            rows.append((f"{c.label}: {o.label}" if multi else o.label, per, allc))

    def cell(cnt):
        if cnt is None:
            return "\u2013"
        frac, known = _fraction(cnt)
        if known == 0:
            return "n/a"
        txt = f"{frac:.2f}"
        if args.counts:
            txt += f" ({cnt['overturned'] + cnt['inferred']}/{known})"
        if cnt["failed"]:
            txt += "\u2020"
        return txt

    layout = args.layout
    if layout == "auto":
        layout = "records" if len(records) > 10 and len(records) > len(rows) else "objects"
    where = "all scales" if args.scale is None else f"scale {args.scale:g} g"
    lines = [f"# Scenario table: overturn fraction ({where})", "",
             "Overturn fraction = (overturned + inferred) / (overturned + inferred + survived) over the "
             f"cells (scale, rotation) at {where}; not-run and failed cells are left out "
             "(\u2020: some failed; \u2013: record not in that cube; n/a: no known cell)."
             + (" Parentheses: overturned/known cells." if args.counts else ""),
             "", "Cubes: " + ", ".join(f"`{c.path}`" for c in cubes), ""]
    if differing:
        lines[-1:-1] = ["", "Records are matched by name; these differ in source file or time window between "
                        "the cubes: " + ", ".join(differing) + "."]
    if layout == "objects":
        head = ["object"] + records + ["all"]
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "---|" * len(head))
        for label, per, allc in rows:
            lines.append("| " + " | ".join([label] + [cell(per.get(r)) for r in records] + [cell(allc)]) + " |")
    else:
        head = ["record"] + [label for label, _, _ in rows]
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "---|" * len(head))
        for r in records:
            lines.append("| " + " | ".join([r] + [cell(per.get(r)) for _, per, _ in rows]) + " |")
        lines.append("| **all** | " + " | ".join(cell(allc) for _, _, allc in rows) + " |")
    out = args.out
    d = os.path.dirname(os.path.abspath(out))
    os.makedirs(d, exist_ok=True)
    with cube_files.output_text(out, "--out", INPUTS) as fh:
        fh.write("\n".join(lines) + "\n")
    csv_path = os.path.splitext(out)[0] + ".csv"
    with cube_files.output_text(csv_path, "--out", INPUTS, newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["cube", "object", "record", "scale_g", "survived", "overturned", "inferred", "not_run",
                    "failed", "known", "overturn_fraction"])
        w.writerows(long_rows)
    print("\n".join(lines))
    print(f"wrote {out}, {csv_path}")
    return 0


class OneLineParser(argparse.ArgumentParser):
    """A bad command line is bad input like any other: one line naming the problem, exit 2."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (--help for the options)\n")


def build_parser():
    p = OneLineParser(
        prog="rigid plot",
        description="Fragility maps, per-record curves, a probit fit (this project's, not Purvance's), "
                    "difference maps and scenario tables from Rigid fragility cubes (HDF5).",
        epilog="Run with Debian's /usr/bin/python3 (python3-numpy, python3-h5py, python3-matplotlib). "
               "Exit status: 0 done, 2 bad input, 1 internal error.")
    sub = p.add_subparsers(dest="command", required=True, metavar="{maps,diff,table}")

    def variant_option(sp):
        sp.add_argument("--variant", type=int, metavar="K",
                        help="a cube with variants: only variant K (0-based); default: all variants")

    def fit_options(sp):
        sp.add_argument("--alpha", action="append", metavar="[NAME=]RAD",
                        help="block slenderness alpha (rad) for the fit's normalisation, for all objects or "
                             "NAME=RAD per object (repeatable); default: attribute alpha_rad of the object or root "
                             "group, else none (PGA not normalised)")
        sp.add_argument("--p", action="append", metavar="[NAME=]RAD_S",
                        help="block frequency parameter p (rad/s), like --alpha; default: attribute p_rad_s, "
                             "else none (PGV/PGA not normalised)")
        sp.add_argument("--mu-degree", type=int, default=1, choices=range(0, 4), metavar="D",
                        help="degree of the polynomial mu(x) (default 1)")
        sp.add_argument("--sigma-degree", type=int, default=0, choices=range(0, 3), metavar="D",
                        help="degree of the polynomial ln sigma(x) (default 0: constant sigma)")
        sp.add_argument("--counts", choices=("auto", "on", "off"), default="auto",
                        help="print the number of records in each map cell (auto: when there are <= 25 scales)")
        sp.add_argument("--format", choices=FIGURE_FORMATS, default="png",
                        help="figure file format: png (default; raster at 120 dpi), pdf or svg (vector, for a paper)")

    m = sub.add_parser("maps", help="per object: fragility map PNG with the fit's 1/50/99 %% contours, "
                                    "per-record curves PNG, fit.json")
    m.add_argument("cube", help="campaign cube (HDF5)")
    m.add_argument("--out", required=True, help="output directory")
    m.add_argument("--object", action="append", help="only this object (repeatable; every variant of it); default: all")
    variant_option(m)
    m.add_argument("--pgv-pga", type=float, metavar="S",
                   help="with variants: the PGV/PGA (s) of the variants' fragility curves (default: the records' median)")
    fit_options(m)
    m.set_defaults(func=cmd_maps)

    d = sub.add_parser("diff", help="difference map A - B per object present in both, mismatch mean +- sd "
                                    "(CSV, markdown)")
    d.add_argument("cube_a", metavar="CUBE_A")
    d.add_argument("cube_b", metavar="CUBE_B")
    d.add_argument("--out", required=True, help="output directory")
    d.add_argument("--label-a", default="3D", help="name of cube A in plots and tables (default 3D)")
    d.add_argument("--label-b", default="2D", help="name of cube B (default 2D)")
    d.add_argument("--object", action="append", help="only this object (repeatable; every variant of it)")
    variant_option(d)
    fit_options(d)
    d.set_defaults(func=cmd_diff)

    t = sub.add_parser("table", help="scenario table: objects x records, overturn fraction (markdown + CSV)")
    t.add_argument("cubes", nargs="+", metavar="CUBE")
    t.add_argument("--out", required=True, help="markdown file; the CSV (long format, with counts) goes beside it")
    t.add_argument("--scale", type=float, help="only this scale (g); default: all scales")
    t.add_argument("--object", action="append", help="only this object (repeatable; every variant of it)")
    variant_option(t)
    t.add_argument("--layout", choices=("auto", "objects", "records"), default="auto",
                   help="rows are objects (records as columns, plus 'all') or records (plus an 'all' row); "
                        "auto: records as rows when there are more than 10")
    t.add_argument("--counts", action="store_true", help="add overturned/known cell counts to each entry")
    t.set_defaults(func=cmd_table)
    return p


# The cubes a command reads: no output may be written over one of them.
INPUTS = []


def main(argv=None):
    args = build_parser().parse_args(argv)
    INPUTS[:] = [p for key in ("cube", "cube_a", "cube_b") for p in [getattr(args, key, None)] if p]
    INPUTS.extend(getattr(args, "cubes", None) or [])
    try:
        return args.func(args)
    except (InputError, cube_files.OutputError) as e:
        sys.stderr.write(f"rigid plot: error: {e}\n")
        return 2
    except OSError as e:
        sys.stderr.write(f"rigid plot: error: {e}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main())
