"""The survival-weighted logic tree (Baker, Whitney & Wein 2013, BSSA 103(3)): rocks that have stood
for their exposure ages reweight the branches of a hazard model's logic tree.

Per branch k with hazard curve lambda_k(a) and per rock r:
- toppling rate nu_kr = integral P_r(topple | a) |d lambda_k(a)| (hazard.mixture_rate);
- survival S_kr = E[exp(-nu_kr T_r)], the expectation over the rock's exposure age T_r
  (exposure_age.py) and over its fragility's uncertainty (the members of hazard_command.RockFragility:
  the bootstrap replicates, or a calibration ensemble's weighted members);
- the rocks' survivals multiply, S_k = prod_r S_kr: given the branch, the rocks topple independently
  (docs/hazard.md says when that fails);
- posterior weight w'_k = w_k S_k / sum_j w_j S_j; or Stirling et al.'s (2021, BSSA 111(5)) pruning:
  branches with S_k < P get weight 0, the others keep their prior weights, renormalised.

The mean hazard curve is the weighted mean of the branches' probabilities of exceedance over the
investigation time (what OpenQuake writes), and a fractile q the weighted quantile at each level:
the branches sorted, their cumulative weights, and the value interpolated linearly at q.
"""
import numpy as np

from . import hazard as hc

FRACTILES = (0.05, 0.16, 0.5, 0.84, 0.95)
RATES_OF_INTEREST = (1e-4, 4e-4)  # annual rates of exceedance at which PGA is reported


class RockEvidence:
    """One rock: its fragility (hazard_command.RockFragility) and its exposure age (ExposureAge)."""

    def __init__(self, name, fragility, age):
        self.name = name
        self.fragility = fragility
        self.age = age

    def toppling_rate(self, curve):
        """nu of the fitted fragility (per year)."""
        return hc.mixture_rate(curve, self.fragility.mixture)[0]

    def survival(self, curve):
        """E[exp(-nu T)] over the age and the fragility's members."""
        weights = np.array([w for w, _ in self.fragility.members])
        rates = np.array([hc.mixture_rate(curve, m)[0] for _, m in self.fragility.members])
        return float(np.sum(weights * self.age.survival(rates)) / weights.sum())


def branch_evidence(branches, rocks):
    """[branch][rock] (toppling rate, survival)."""
    return [[(r.toppling_rate(b.curve), r.survival(b.curve)) for r in rocks] for b in branches]


def posterior_weights(prior, survival, prune=None):
    """w' of each branch from the prior weights and the survivals (one per branch); `prune` P:
    Stirling's rule. None when no branch keeps any weight (every survival 0, or all pruned)."""
    prior, survival = np.asarray(prior, float), np.asarray(survival, float)
    kept = prior * ((survival >= prune) if prune is not None else survival)
    total = kept.sum()
    if not total > 0:
        return None
    return kept / total


def weighted_quantile(values, weights, q):
    """The q-quantile of each column of values [branches, levels] under the branch weights: the
    values sorted, cumulative weights, linear interpolation at q (OpenQuake's rule for its quantile
    curves)."""
    values = np.asarray(values, float)
    weights = np.asarray(weights, float)
    out = np.empty(values.shape[1])
    for j in range(values.shape[1]):
        order = np.argsort(values[:, j], kind="stable")
        keep = weights[order] > 0  # a pruned branch is no part of the distribution
        out[j] = np.interp(q, np.cumsum(weights[order][keep]), values[order, j][keep])
    return out


def curve_statistics(poes, weights):
    """{"mean": PoEs, "0.05": PoEs, ...} of the branches' PoEs [branches, levels] under the weights."""
    out = {"mean": np.asarray(weights, float) @ np.asarray(poes, float)}
    for q in FRACTILES:
        out[fractile_name(q)] = weighted_quantile(poes, weights, q)
    return out


def fractile_name(q):
    return f"{q:g}"


def annual_rates(poe, investigation_time):
    return -np.log1p(-np.asarray(poe, float)) / investigation_time


def pga_at_rates(imls, poe, investigation_time):
    """{rate: PGA (g)} exceeded at the annual rates of RATES_OF_INTEREST on a curve of PoEs."""
    rate = annual_rates(poe, investigation_time)
    return {r: hc.pga_at_rate(imls, rate, r) for r in RATES_OF_INTEREST}
