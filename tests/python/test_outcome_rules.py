"""The cube's rules in Python (src/python/rigidpy/outcomes.py, the copy of the C++ statistics
module) against values worked by hand: a 2x2x2 outcome array (records x scales x rotations), its
probabilities, the binned fragility surface with an empty bin and a record outside every bin, and
the bins' edges. tests/statistics/overturn_test.cpp works the same example for the C++ rules.

    /usr/bin/python3 -m pytest tests/python/test_outcome_rules.py
"""
import math

import pytest

np = pytest.importorskip("numpy")

from rigidpy.outcomes import (FAILED, INFERRED, NOT_RUN, OVERTURNED, SURVIVED,  # noqa: E402
                              fragility_from_probability, outcome_counts, overturn_fraction, pgv_pga_bin,
                              probability_from_outcome)

NAN = float("nan")
OUTCOME = np.array([[[SURVIVED, OVERTURNED],   # r0 s0: 1 of 2 known overturned -> 1/2
                     [INFERRED, OVERTURNED]],  # r0 s1: inferred counts as overturned -> 2/2
                    [[FAILED, NOT_RUN],        # r1 s0: nothing known -> NaN
                     [SURVIVED, FAILED]]],     # r1 s1: failed left out, 0 of 1 -> 0
                   dtype=np.int8)


def same(a, b):
    return np.array_equal(np.asarray(a, float), np.asarray(b, float), equal_nan=True)


def test_probability_of_a_two_by_two_by_two_array():
    assert same(probability_from_outcome(OUTCOME), [[0.5, 1.0], [NAN, 0.0]])


def test_counts_follow_the_same_rule():
    counts = outcome_counts(OUTCOME)
    assert counts == {"not_run": 1, "survived": 2, "overturned": 2, "inferred": 1, "failed": 2}
    frac, known = overturn_fraction(counts)
    assert (frac, known) == (3 / 5, 5)
    assert math.isnan(overturn_fraction(outcome_counts(OUTCOME[1, 0]))[0])


def test_fragility_with_an_empty_bin_and_a_record_outside_every_bin():
    prob = np.array([[0.5, 1.0],    # record 0, PGV/PGA 0.05 s: bin 0
                     [NAN, 0.0],    # record 1, 0.07 s: bin 0, unknown at scale 0
                     [1.0, 1.0]])   # record 2, 0.40 s: above the last edge, in no bin
    edges = [0.0, 0.1, 0.2, 0.3]   # bin 1 holds no record
    frag, count = fragility_from_probability(prob, np.array([0.05, 0.07, 0.40]), edges)
    assert same(frag, [[0.5, NAN, NAN], [0.5, NAN, NAN]])
    assert count.tolist() == [[1, 0, 0], [2, 0, 0]]


def test_bins_are_closed_below_and_the_last_also_above():
    e = [0.0, 0.1, 0.2]
    assert [pgv_pga_bin(e, v) for v in (0.0, 0.05, 0.1, 0.2, 0.2000001, -0.01, NAN)] == [0, 0, 1, 1, -1, -1, -1]
    d = [0.0, 0.06, 0.08, 0.10, 0.12, 0.15, 0.20, 0.25, 0.35, math.inf]
    assert [pgv_pga_bin(d, v) for v in (0.033309, 0.50236, math.inf)] == [0, 8, 8]
    assert pgv_pga_bin(np.array([-math.inf, 0.0, 1.0]), -math.inf) == 0  # as statistics::pgv_pga_bin
