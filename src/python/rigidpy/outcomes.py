"""The cube's outcome codes and the rules that turn a cell's outcome into a count: the one Python
copy of io::overturn_probability (src/io/cube.cpp). Every module that counts outcomes asks here.

Two rules, for two questions:
- the cube's `probability` (maps, tables, agreement): overturned and the stop rule's inferred
  cells count as overturned, survived as not; not-run and failed cells are unknown;
- the fits (fit.py says why): simulated cells only, overturned and survived; inferred cells are
  the stop rule's assumption, not simulations, and are left out with not-run and failed ones.
"""
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
    over = np.sum((outcome == OVERTURNED) | (outcome == INFERRED), axis=2)
    known_ = over + np.sum(outcome == SURVIVED, axis=2)
    return over, known_


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
    known_ = counts["survived"] + counts["overturned"] + counts["inferred"]
    return (counts["overturned"] + counts["inferred"]) / known_ if known_ else float("nan"), known_
