"""The one reader of a campaign cube (docs/cube.md; layout at the top of src/io/cube.cpp): the
axes, the records and every object's cells, checksums verified, the derived datasets recomputed
from the cells and stored ones that disagree refused. Everything in this package that reads a
cube reads it through Cube."""
import json
import math
import os
import sys

import h5py
import numpy as np

from . import checksums as cube_checksums
from .errors import InputError
from .outcomes import NOT_RUN, bins_of_records, fragility_from_probability, probability_from_outcome


NOT_RECORDED = -1  # unconverged_steps of a cell not simulated, or of a cube written before the count
# /axes/scale_g of a campaign run `scales = "as recorded"` (docs/cube.md): one scale, 0.0, each
# record simulated at its own amplitude
AS_RECORDED_SCALE = 0.0


def _strings(ds):
    return [s for s in ds.asstr()[()]]


class ObjectData:
    """One object of a cube, or one variant of it (a cube with a variant axis: one ObjectData per
    (object, variant), all with the base object's name)."""

    def __init__(self, name, attrs, outcome, probability, fragility, count, variant=None, unconverged_steps=None):
        self.name = name
        self.attrs = attrs
        self.outcome = outcome          # [R, S, A] int8
        self.probability = probability  # [R, S]
        self.fragility = fragility      # [S, B]
        self.count = count              # [S, B]
        self.variant = variant          # None without variants, else 0..V-1
        # [R, S, A] int32: steps of each cell's run whose contact solve stopped at its sweep cap;
        # NOT_RECORDED (-1) where not simulated, or for every cell of a cube written before the count
        self.unconverged_steps = unconverged_steps
        # [R, S, A] bool or None: cells the reader added to lay an as-recorded cube on a PGA axis
        # (Cube.as_recorded); they are not run and no campaign will run them
        self.padding = None

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


class Calibration:
    """Where a calibrated object's physics comes from (job file `calibration = ...`; attributes
    of its group, docs/cube.md): the calibration file, its SHA-256, each variant's weight (the
    members' share, summing to 1) and the summary (the document's rigid_version, created, scene,
    chosen `parameters` and the scores present, as a dict)."""

    def __init__(self, attrs, count):
        self.path = _text(attrs["calibration"])
        self.sha256 = _text(attrs.get("calibration_sha256", ""))
        self.weights = np.asarray(attrs.get("calibration_weights", np.full(count, 1.0 / count)), float).ravel()
        try:
            self.summary = json.loads(_text(attrs.get("calibration_summary", "{}")))
        except ValueError:
            self.summary = {}
        if len(self.weights) != count or not np.all(self.weights > 0):
            raise KeyError(f"calibration_weights of {len(self.weights)} positive values for {count} variants")


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

    def __init__(self, path, wall_times=False, peaks=False):
        self._wall_times = wall_times  # also read each object's wall_s (outcome_agreement)
        self._peaks = peaks  # also read each object's max_tilt_deg and max_slip_m (outcome_agreement)
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
                self.as_recorded = len(self.scales) == 1 and self.scales[0] == AS_RECORDED_SCALE
                if self.as_recorded:
                    self.record_pga_g = f["records/gmroti_pga_g"][()].astype(float)
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
                self.calibrations = {}  # object name -> Calibration, for a calibrated object
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
                    if "calibration" in attrs:
                        self.calibrations[name] = Calibration(attrs, self.variants.count)
                    for v in range(self.variants.count):
                        items.append(((index, v), self._object_data(name, g, variant_attrs(g, attrs, v), v)))
            except KeyError as e:
                raise InputError(f"{path}: not a Rigid fragility cube (missing {e})")
        items.sort(key=lambda t: t[0])
        self.objects = [o for _, o in items]
        if self.as_recorded:
            self._lay_on_record_pgas()
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
        # a diagnostic outside the checksum, read as stored; absent from older cubes: not recorded
        steps = (np.asarray(read("unconverged_steps"), np.int32) if "unconverged_steps" in g
                 else np.full(outcome.shape, NOT_RECORDED, np.int32))
        if steps.shape != outcome.shape:
            raise InputError(f"{self.path}: /objects/{name}/unconverged_steps of shape {steps.shape}, "
                             f"its outcome has {outcome.shape}")
        data = ObjectData(name, attrs, outcome, np.asarray(prob, float), np.asarray(frag, float),
                          np.asarray(cnt, int), variant, steps)
        if self._wall_times:
            data.wall_s = np.asarray(read("wall_s"), float)
        if self._peaks:
            data.max_tilt_deg = np.asarray(read("max_tilt_deg"), float)
            data.max_slip_m = np.asarray(read("max_slip_m"), float)
        return data

    def _lay_on_record_pgas(self):
        """An as-recorded cube has no scale axis: its one scale, 0.0, means "each record at its own
        amplitude". Every reader of the cube asks for P(overturn) against PGA, so the reader gives
        it one: the scale axis becomes the records' measured GMRotI50 PGAs (sorted, distinct) and
        record r's cells sit at its own PGA; the other cells of its row are padding (not run, never
        counted as incomplete)."""
        pga = self.record_pga_g
        if len(pga) != len(self.records) or not np.all(np.isfinite(pga) & (pga > 0)):
            raise InputError(f"{self.path}: an as-recorded cube (scale 0.0) needs each record's measured "
                             f"PGA (/records/gmroti_pga_g, positive)")
        axis = np.unique(pga)
        rows, cols = np.arange(len(pga)), np.searchsorted(axis, pga)

        def spread(cells, fill):
            out = np.full((cells.shape[0], len(axis)) + cells.shape[2:], fill, cells.dtype)
            out[rows, cols] = cells[:, 0]
            return out

        for o in self.objects:
            o.outcome = spread(o.outcome, NOT_RUN)
            o.unconverged_steps = spread(o.unconverged_steps, NOT_RECORDED)
            for key in ("wall_s", "max_tilt_deg", "max_slip_m"):
                if hasattr(o, key):
                    setattr(o, key, spread(getattr(o, key), np.nan))
            o.padding = spread(np.zeros(o.outcome[:, :1].shape, bool), True)
            o.probability = np.asarray(probability_from_outcome(o.outcome), float)
            frag, cnt = fragility_from_probability(o.probability, self.pgv_pga, self.edges)
            o.fragility, o.count = np.asarray(frag, float), np.asarray(cnt, int)
        self.scales = axis

    def counted_outcome(self, o):
        """o.outcome with the padding of an as-recorded cube set to -1 (no outcome code): for counts
        of cells."""
        return o.outcome if o.padding is None else np.where(o.padding, np.int8(-1), o.outcome)

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

    def variant_weights(self, name):
        """The weight of each variant of object `name` in its pooled fragility: its calibration's
        (members' share of the weight) for a calibrated object, else equal weights."""
        if name in self.calibrations:
            return self.calibrations[name].weights
        n = self.variants.count if self.variants is not None else 1
        return np.full(n, 1.0 / n)

    def bin_of_records(self):
        return bins_of_records(self.edges, self.pgv_pga)

    def incomplete(self, state):
        """Why fits of this cube are provisional (cells not run; `state` of
        cube_files.campaign_state, taken before any lock of ours), or None when it is complete."""
        total = sum(int((self.counted_outcome(o) >= 0).sum()) for o in self.objects)
        not_run = sum(int((self.counted_outcome(o) == NOT_RUN).sum()) for o in self.objects)
        parts = []
        if not_run:
            parts.append(f"{not_run} of {total} cells ({100 * not_run / total:.0f} %) not run")
        if state == "running":
            parts.append(f"a campaign (or a store) is writing it now ({self.path}.lock is held)")
        elif state == "stopped" and not_run:
            parts.append(f"its campaign stopped before the end ({self.path}.journal is there; run the campaign "
                         f"again to finish it)")
        return f"{self.path}: incomplete cube: " + "; ".join(parts) if parts else None
