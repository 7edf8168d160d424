"""The cube's outcome codes and the rules of its derived datasets: which outcomes count, the
overturning probability, the PGV/PGA bins and the fragility surface. The one Python copy of the
C++ statistics module (include/rigid/statistics/overturn.hpp and fragility_surface.hpp, which the
cube writer uses); every module that counts outcomes or bins records asks here, and the cube reader
(cube.py) recomputes the stored derived datasets with these functions and refuses ones that disagree.

Two rules, for two questions:
- the cube's `probability` (maps, tables, agreement): overturned and the stop rule's inferred
  cells count as overturned, survived as not; not-run and failed cells are unknown;
- the fits (fit.py says why): simulated cells only, overturned and survived; inferred cells are
  the stop rule's assumption, not simulations, and are left out with not-run and failed ones.
"""
import bisect
import math

import numpy as np

NOT_RUN, SURVIVED, OVERTURNED, INFERRED, FAILED = 0, 1, 2, 3, 4
CODES = (("not_run", NOT_RUN), ("survived", SURVIVED), ("overturned", OVERTURNED),
         ("inferred", INFERRED), ("failed", FAILED))

COUNTS_AS_OVERTURNED = (OVERTURNED, INFERRED)
KNOWN = (SURVIVED, OVERTURNED, INFERRED)
SIMULATED_KNOWN = (SURVIVED, OVERTURNED)
RAN = (SURVIVED, OVERTURNED, FAILED)  # cells a simulation ran for (their wall time counts)


def counts_as_overturned(outcome):
    """Mask of cells the cube's probability counts as overturned (overturned or inferred)."""
    return np.isin(outcome, COUNTS_AS_OVERTURNED)


def known(outcome):
    """Mask of cells whose outcome the cube's probability counts (survived, overturned, inferred)."""
    return np.isin(outcome, KNOWN)


def overturned_and_known(outcome):
    """(overturned, known) cells per (record, scale) over the rotations (axis 2), the rule of the
    cube's `probability`: overturned and inferred count as overturned, survived as not."""
    return np.sum(counts_as_overturned(outcome), axis=2), np.sum(known(outcome), axis=2)


def probability_from_outcome(outcome):
    """The cube's `probability` [record, scale]: overturned / known, NaN where nothing is known."""
    over, known_ = overturned_and_known(outcome)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(known_ > 0, over / np.maximum(known_, 1), np.nan)


def simulated_counts(outcome):
    """(overturned, simulated) per (record, scale) over the rotations (axis 2): survived and
    overturned cells only (inferred, not-run and failed cells left out), the fits' rule."""
    over = np.sum(outcome == OVERTURNED, axis=2)
    return over, over + np.sum(outcome == SURVIVED, axis=2)


def outcome_counts(outcome):
    """How many cells hold each outcome code, by name."""
    return {name: int(np.sum(outcome == code)) for name, code in CODES}


def overturn_fraction(counts):
    """(fraction counted as overturned, known cells) of outcome_counts, the probability rule."""
    over = sum(counts[name] for name, code in CODES if code in COUNTS_AS_OVERTURNED)
    known_ = sum(counts[name] for name, code in CODES if code in KNOWN)
    return over / known_ if known_ else float("nan"), known_


def pgv_pga_bin(edges, v):
    """Bin of a PGV/PGA value (s): i with edges[i] <= v < edges[i+1], the last bin also holding
    v == edges[-1]; -1 when v is NaN or outside the edges (statistics::pgv_pga_bin)."""
    if len(edges) < 2 or math.isnan(v) or v < edges[0] or v > edges[-1]:
        return -1
    return min(bisect.bisect_right(edges, v) - 1, len(edges) - 2)


def bins_of_records(edges, pgv_pga):
    """pgv_pga_bin of each record's PGV/PGA, as an int array (-1: in no bin)."""
    return np.array([pgv_pga_bin(edges, v) for v in pgv_pga], dtype=int)


def fragility_from_probability(prob, pgv_pga, edges):
    """The cube's `fragility` [scale, bin] and `fragility_count`: per scale and bin, the mean of
    `prob` [record, scale] over the records of the bin whose probability is known (NaN and a count
    of 0 where none is); a record in no bin counts nowhere (statistics::fragility_surface)."""
    R, S = prob.shape
    B = len(edges) - 1
    total = np.zeros((S, B))
    count = np.zeros((S, B), dtype=int)
    bins = bins_of_records(edges, pgv_pga)
    for r in range(R):
        b = bins[r]
        if b < 0:
            continue
        ok = np.isfinite(prob[r])
        total[ok, b] += prob[r, ok]
        count[ok, b] += 1
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(count > 0, total / np.maximum(count, 1), np.nan), count
