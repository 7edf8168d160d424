"""Synthetic cubes in the documented layout (docs/cube.md), written here with h5py, with outcomes
drawn from a KNOWN probit model: the planted parameters are an independent oracle for the fits
(test_plot.py, test_hazard.py, test_outputs.py). The derived datasets are re-implemented here
independently of rigidpy."""
import math

import h5py
import numpy as np

from rigidpy import checksums as cube_checksums  # synthetic cubes carry the checksums of the current schema

EDGES = [0.0, 0.06, 0.08, 0.10, 0.12, 0.15, 0.20, 0.25, 0.35, math.inf]
SCALES = np.round(np.arange(1, 21) * 0.1, 10)       # 0.1 .. 2.0 g
R, A = 80, 4
# planted model in un-normalised variables: u = ln(PGA/g), x = ln(PGV/PGA / 1 s)
MU0, MU1, SIGMA = -1.8, -0.5, 0.35
ALPHA, P = 0.2, 2.2                                  # attributes of the normalised copy


def phi(z):
    return 0.5 * math.erfc(-z / math.sqrt(2.0))


def bin_of(v, edges=None):
    edges = EDGES if edges is None else edges
    for i in range(len(edges) - 1):
        if edges[i] <= v < edges[i + 1]:
            return i
    return -1


def derived(outcome, pgv_pga, edges=None):
    """Independent re-implementation of the cube's probability and fragility."""
    over = ((outcome == 2) | (outcome == 3)).sum(axis=2)
    known = over + (outcome == 1).sum(axis=2)
    prob = np.full(known.shape, np.nan)
    prob[known > 0] = over[known > 0] / known[known > 0]
    B = len(EDGES) - 1
    frag = np.full((len(SCALES), B), np.nan)
    count = np.zeros((len(SCALES), B), dtype=np.int32)
    for s in range(len(SCALES)):
        for b in range(B):
            vals = [prob[r, s] for r in range(len(pgv_pga)) if bin_of(pgv_pga[r], edges) == b and not np.isnan(prob[r, s])]
            if vals:
                frag[s, b] = sum(vals) / len(vals)
                count[s, b] = len(vals)
    return prob, frag, count


def planted_outcomes(rng, pgv_pga, mu0, mu1, sigma, extras=True):
    out = np.zeros((len(pgv_pga), len(SCALES), A), dtype=np.int8)
    for r, v in enumerate(pgv_pga):
        mu = mu0 + mu1 * math.log(v)
        for s, g in enumerate(SCALES):
            p = phi((math.log(g) - mu) / sigma)
            out[r, s, :] = np.where(rng.random(A) < p, 2, 1)
    if extras:  # relabel some overturned as inferred and lose some cells: neither biases the fit
        out[(out == 2) & (rng.random(out.shape) < 0.2)] = 3
        out[rng.random(out.shape) < 0.03] = 4
        out[rng.random(out.shape) < 0.02] = 0
    return out


def write_cube(path, pgv_pga, objects, root_attrs=None, wall_s=None):
    """objects: list of (name, outcome [R,S,A], attrs dict[, cell datasets dict, e.g. max_tilt_deg,
    unconverged_steps]); wall_s: each cell's wall time, when given."""
    str_t = h5py.string_dtype("utf-8")
    names = [f"rec{r:03d}" for r in range(len(pgv_pga))]
    with h5py.File(path, "w") as f:
        f.attrs["schema_version"] = np.int32(1)
        f.attrs["units"] = "SI unless the name says otherwise"
        for k, v in (root_attrs or {}).items():
            f.attrs[k] = v
        ax = f.create_group("axes")
        ax.create_dataset("record", data=np.array(names, dtype=object), dtype=str_t)
        ax.create_dataset("scale_g", data=SCALES.astype(float))
        ax.create_dataset("rotation", data=np.arange(A, dtype=np.int32))
        ax.create_dataset("pgv_pga_bin", data=np.arange(len(EDGES) - 1, dtype=np.int32))
        ax.create_dataset("pgv_pga_edges_s", data=np.array(EDGES, float))
        rec = f.create_group("records")
        rec.create_dataset("name", data=np.array(names, dtype=object), dtype=str_t)
        rec.create_dataset("pgv_pga_s", data=np.asarray(pgv_pga, float))
        rec.create_dataset("gmroti_pga_g", data=np.full(len(pgv_pga), 0.3))
        objs = f.create_group("objects")
        for i, (name, outcome, attrs, *cells) in enumerate(objects):
            g = objs.create_group(name)
            g.attrs["index"] = np.int32(i)
            g.attrs["scene"] = f"{name}.toml"
            for k, v in attrs.items():
                g.attrs[k] = v
            prob, frag, count = derived(outcome, pgv_pga)
            g.create_dataset("outcome", data=outcome)
            g.create_dataset("probability", data=prob)
            g.create_dataset("fragility", data=frag)
            g.create_dataset("fragility_count", data=count)
            if wall_s is not None:
                g.create_dataset("wall_s", data=np.full(outcome.shape, float(wall_s)))
            for key, values in (cells[0] if cells else {}).items():
                g.create_dataset(key, data=values)
        cube_checksums.seal(f)



if __name__ == "__main__":
    # `python3 tests/python/synthetic_cube.py OUT.h5`: a cube of one rock drawn from the planted probit
    # model (median toppling PGA about 0.3 g at PGV/PGA 0.1 s), for worked examples that need a
    # cube without running a campaign (README: the logic-tree reweighting)
    import sys

    if len(sys.argv) != 2:
        sys.exit("usage: synthetic_cube.py OUT.h5")
    rng = np.random.default_rng(20260301)
    pgv = np.exp(rng.uniform(math.log(0.035), math.log(0.5), R))
    write_cube(sys.argv[1], pgv, [("rock", planted_outcomes(rng, pgv, MU0, MU1, SIGMA), {"alpha_rad": ALPHA, "p_rad_s": P})])
