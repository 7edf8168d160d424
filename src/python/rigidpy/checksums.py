"""The checksums of a campaign cube, verified as src/io/cube_read.cpp verifies them (what they
cover: kAxesChecksumCovers and kChecksumCovers in src/io/cube_hdf5.hpp): the root attribute
axes_sha256 over the axes, the records and the variant table, and each object group's
datasets_sha256 over its cell datasets. From schema_version 3 both are required: a cube without
them was altered; a cube of version 1 or 2 without them was written before they existed, and is
read with a warning (old_cube_warning)."""
import hashlib

import numpy as np

CHECKSUMMED_SCHEMA_VERSION = 3

AXES_DATASETS = ("axes/record", "axes/scale_g", "axes/pgv_pga_edges_s", "records/name", "records/source",
                 "records/earthquake", "records/alignment", "records/inputs_sha256", "records/start_s", "records/end_s",
                 "records/gmroti_pga_g", "records/gmroti_pgv_cm_s", "records/pgv_pga_s", "records/listed_pga_g",
                 "records/listed_pgv_cm_s")
CELL_DATASETS = ("outcome", "rotation_deg", "failure_time_s", "max_tilt_deg", "max_slip_m", "failure_reason",
                 "failure_message")


class ChecksumError(Exception):
    pass


def _text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def _feed(h, ds):
    """A dataset's values as stored: numbers little-endian, strings as uint64 length + UTF-8."""
    if ds.dtype.kind in "OSU":
        for s in ds.asstr()[()].ravel():
            b = s.encode("utf-8")
            h.update(len(b).to_bytes(8, "little"))
            h.update(b)
    else:
        values = np.asarray(ds[()])
        h.update(np.ascontiguousarray(values.astype(values.dtype.newbyteorder("<"))).tobytes())


def axes_sha256(f):
    """Over AXES_DATASETS in order (the C++ writer stores every one of them; a dataset absent from
    the file contributes nothing, so one deleted after writing changes the hash)."""
    h = hashlib.sha256()
    for path in AXES_DATASETS:
        if path in f:
            _feed(h, f[path])
    if "variants" in f:
        for name in _text(f["variants"].attrs.get("parameters", "")).split():
            _feed(h, f["variants"][name])
    return h.hexdigest()


def cells_sha256(g):
    h = hashlib.sha256()
    for name in CELL_DATASETS:
        if name in g:  # failure_message: absent from cubes written before it
            _feed(h, g[name])
    return h.hexdigest()


def verify(f, path):
    """ChecksumError naming what changed; returns the schema version."""
    version = int(f.attrs["schema_version"])
    checked = version >= CHECKSUMMED_SCHEMA_VERSION
    if "axes_sha256" in f.attrs:
        stored, now = _text(f.attrs["axes_sha256"]), axes_sha256(f)
        if stored != now:
            raise ChecksumError(f"{path}: axes, records or variant table changed since written (checksum mismatch); "
                                f"axes_sha256 is {stored[:12]}..., they hash to {now[:12]}...")
    elif checked:
        raise ChecksumError(f"{path}: no axes_sha256 (every schema_version {version} cube has one): the cube was altered")
    for name in f["objects"]:
        g = f["objects"][name]
        if "datasets_sha256" in g.attrs:
            stored, now = _text(g.attrs["datasets_sha256"]), cells_sha256(g)
            if stored != now:
                raise ChecksumError(f"{path}: /objects/{name}: datasets changed since written (checksum mismatch); "
                                    f"datasets_sha256 is {stored[:12]}..., the datasets hash to {now[:12]}...")
        elif checked:
            raise ChecksumError(f"{path}: /objects/{name}: no datasets_sha256 (every schema_version {version} cube "
                                f"has one): the cube was altered")
    return version


def old_cube_warning(path, version):
    """The warning for a cube whose schema predates the checksums of its axes and records, or None."""
    if version >= CHECKSUMMED_SCHEMA_VERSION:
        return None
    return (f"{path}: schema_version {version} cube, written before checksums covered its axes and records: "
            f"those are read unchecked")


def seal(f):
    """Makes an h5py file open for writing a cube of the current schema: its checksums as the C++
    writer computes them (for writers of synthetic cubes, as the tests have)."""
    f.attrs["schema_version"] = np.int32(CHECKSUMMED_SCHEMA_VERSION)
    f.attrs["axes_sha256"] = axes_sha256(f)
    for name in f["objects"]:
        g = f["objects"][name]
        g.attrs["datasets_sha256"] = cells_sha256(g)
