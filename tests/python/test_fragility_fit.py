"""Fragility fits against independent oracles (docs/hazard.md):

1. Planted parameters: Bernoulli cells drawn from a known lognormal fragility (theta, beta) on a
   campaign's layout (records x scales x rotations, the study's stop rule), fitted; over 200
   replicates the bias of beta is < 5 % of beta and the 90 % bootstrap intervals (records
   resampled) cover the truth in 85-95 % of replicates.
2. The scalar fit equals statsmodels' binomial GLM with a probit link to 1e-6 on the same data.
3. The vector fit recovers a planted mu(x), sigma(x).

Skipped when numpy/scipy/statsmodels are missing.
"""
import math

import pytest

np = pytest.importorskip("numpy")
sm = pytest.importorskip("statsmodels.api", reason="install python3-statsmodels")
from scipy.special import ndtr  # noqa: E402

from rigidpy import fit as ff  # noqa: E402
from rigidpy.outcomes import INFERRED, OVERTURNED, SURVIVED  # noqa: E402

# A campaign's layout: 20 records, scales 0.1-2.0 g by 0.1 (the demo's), 4 rotations, the stop rule
# (a record ends after STOP_AFTER scales whose rotations all overturned; the rest is inferred).
RECORDS, ROTATIONS, STOP_AFTER = 20, 4, 3
SCALES = np.round(np.arange(1, 21) * 0.1, 10)


def planted_outcome(rng, theta, beta, record_sd=0.0):
    """outcome [R, S, A] as a campaign with the stop rule writes it. record_sd: a per-record shift of
    ln theta (records differ; the fit's beta then includes it)."""
    out = np.zeros((RECORDS, len(SCALES), ROTATIONS), dtype=np.int8)
    for r in range(RECORDS):
        shift = rng.normal(0.0, record_sd) if record_sd > 0 else 0.0
        p = ndtr((np.log(SCALES / theta) - shift) / beta)
        full = 0
        for s in range(len(SCALES)):
            if full >= STOP_AFTER:
                out[r, s, :] = INFERRED
                continue
            over = rng.random(ROTATIONS) < p[s]
            out[r, s, :] = np.where(over, OVERTURNED, SURVIVED)
            full = full + 1 if over.all() else 0
    return out


def test_planted_recovery():
    theta, beta = 0.45, 0.40
    rng = np.random.default_rng(20261125)
    replicates, boot = 200, 200
    est_beta, est_theta, cover_theta, cover_beta = [], [], 0, 0
    for _ in range(replicates):
        cells = ff.Cells(planted_outcome(rng, theta, beta), SCALES, np.full(RECORDS, 0.1))
        fit = ff.scalar_fragility(cells, None, rng, boot, level=0.9)
        est_theta.append(fit["theta_g"])
        est_beta.append(fit["beta"])
        lo, hi = fit["theta_interval_g"]
        cover_theta += lo <= theta <= hi
        lo, hi = fit["beta_interval"]
        cover_beta += lo <= beta <= hi
    bias_beta = (np.mean(est_beta) - beta) / beta
    bias_theta = (np.mean(est_theta) - theta) / theta
    print(f"planted theta {theta} g, beta {beta}: mean fit theta {np.mean(est_theta):.4f} g, beta "
          f"{np.mean(est_beta):.4f}; 90 % intervals cover theta {cover_theta}/{replicates}, beta {cover_beta}/{replicates}")
    assert abs(bias_beta) < 0.05, f"bias of beta {100 * bias_beta:+.2f} % of beta (< 5 %)"
    assert abs(bias_theta) < 0.05, f"bias of theta {100 * bias_theta:+.2f} % of theta (< 5 %)"
    assert 0.85 <= cover_theta / replicates <= 0.95, f"theta coverage {cover_theta / replicates:.3f} in [0.85, 0.95]"
    assert 0.85 <= cover_beta / replicates <= 0.95, f"beta coverage {cover_beta / replicates:.3f} in [0.85, 0.95]"
    # the inferred cells counted as overturned trials (the old fit's rule): the bias, printed
    rng = np.random.default_rng(7)
    biased = []
    for _ in range(50):
        out = planted_outcome(rng, theta, beta)
        over = np.sum((out == OVERTURNED) | (out == INFERRED), axis=2).sum(axis=0)
        known = over + np.sum(out == SURVIVED, axis=2).sum(axis=0)
        biased.append(ff.lognormal_fit(np.log(SCALES), over.astype(float), known.astype(float))["beta"])
    print(f"(for the record: counting inferred cells as overturned trials gives mean beta {np.mean(biased):.4f}, "
          f"truth {beta})")


def test_statsmodels_agreement():
    rng = np.random.default_rng(3)
    for theta, beta in ((0.3, 0.25), (0.6, 0.5), (1.1, 0.8)):
        cells = ff.Cells(planted_outcome(rng, theta, beta, record_sd=0.2), SCALES, np.full(RECORDS, 0.1))
        u, k, n = ff.scalar_rows(cells, cells.records_with_cells())
        ours = ff.lognormal_fit(u, k, n)
        keep = n > 0
        glm = sm.GLM(np.column_stack([k[keep], n[keep] - k[keep]]), sm.add_constant(u[keep]),
                     family=sm.families.Binomial(link=sm.families.links.probit())).fit(tol=1e-13)
        b0, b1 = glm.params
        theta_sm, beta_sm = math.exp(-b0 / b1), 1.0 / b1
        worst = max(abs(ours["theta_g"] / theta_sm - 1), abs(ours["beta"] / beta_sm - 1))
        assert worst < 1e-6, (f"theta {ours['theta_g']:.8f} vs statsmodels {theta_sm:.8f}, beta {ours['beta']:.8f} vs "
                            f"{beta_sm:.8f}: relative difference {worst:.1e} < 1e-6")


def test_vector_recovery():
    # P = Phi((u - m0 - m1 x) / exp(s0 + s1 x)) on 60 records spread in x, 20 scales, 8 rotations
    m0, m1, s0, s1 = -0.6, 0.5, math.log(0.35), 0.3
    rng = np.random.default_rng(11)
    x = rng.uniform(-1.5, 1.0, 60)
    u = np.log(SCALES)
    z = (u[None, :] - (m0 + m1 * x[:, None])) / np.exp(s0 + s1 * x[:, None])
    k = rng.binomial(8, ndtr(z))
    uu, xx = np.broadcast_to(u, k.shape).ravel(), np.broadcast_to(x[:, None], k.shape).ravel()
    fit = ff.fit_probit(uu, xx, k.ravel(), np.full(k.size, 8.0), 1, 1)
    est = fit["mu_coefficients"] + fit["log_sigma_coefficients"]
    se = fit["mu_se"] + fit["log_sigma_se"]
    worst = max(abs(e - t) / s for e, t, s in zip(est, (m0, m1, s0, s1), se))
    assert worst < 4, f"vector fit: planted (m0, m1, s0, s1) recovered within {worst:.2f} standard errors (< 4)"

