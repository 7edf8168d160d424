"""A rock's exposure age as dating reports it, and the probability that the rock survived it.

Cosmogenic exposure ages come as a value with a one-sigma uncertainty. Three readings:
- fixed: the age is known (no --age-sd);
- normal: mean and standard deviation in years, truncated to positive ages (a normal with a large
  sd puts mass below 0 that no rock has);
- lognormal: the same mean and standard deviation, as a lognormal (positive by construction; ages
  from several nuclide concentrations are often closer to it when the sd is a large share).

For a Poisson toppling rate nu, the rock survives an age t with probability exp(-nu t), and an
uncertain age gives S(nu) = E[exp(-nu T)] (Baker et al. 2013, BSSA 103(3)). For the truncated
normal this has a closed form; for the lognormal it is integrated on +-8 sd of ln T by Simpson's
rule, the grid of hazard.py's toppling rate.
"""
import math

import numpy as np
from scipy import integrate
from scipy.special import log_ndtr

from . import hazard as hc
from .errors import InputError

KINDS = ("normal", "lognormal")


class ExposureAge:
    def __init__(self, years, sd_years=None, kind="normal"):
        if not (math.isfinite(years) and years > 0):
            raise InputError(f"--age {years:g}: must be a positive number of years")
        if sd_years is not None and not (math.isfinite(sd_years) and sd_years >= 0):
            raise InputError(f"--age-sd {sd_years:g}: must be a number of years >= 0")
        if kind not in KINDS:
            raise InputError(f"--age-dist {kind!r}: expected one of {', '.join(KINDS)}")
        self.years = float(years)
        self.sd_years = float(sd_years) if sd_years else 0.0
        self.kind = kind if self.sd_years > 0 else "fixed"

    def describe(self):
        if self.kind == "fixed":
            return f"{self.years:g} years"
        return f"{self.years:g} +- {self.sd_years:g} years ({self.kind})"

    def survival(self, rate):
        """E[exp(-rate T)] for one rate or an array of rates (per year)."""
        nu = np.asarray(rate, float)
        if self.kind == "fixed":  # hazard.survival's own arithmetic, so `rigid hazard` agrees to the last bit
            return np.vectorize(lambda r: hc.survival(r, self.years), otypes=[float])(nu)
        if self.kind == "normal":
            return self._truncated_normal(nu)
        return self._lognormal(nu)

    def _truncated_normal(self, nu):
        # T ~ N(m, s^2) restricted to T > 0: E[e^{-nu T}] = e^{-nu m + nu^2 s^2 / 2}
        # Phi((m - nu s^2)/s) / Phi(m/s), taken in logs (both factors under/overflow on their own)
        m, s = self.years, self.sd_years
        log_value = -nu * m + 0.5 * (nu * s) ** 2 + log_ndtr((m - nu * s * s) / s) - log_ndtr(m / s)
        return np.exp(log_value)

    def _lognormal(self, nu):
        sigma2 = math.log1p((self.sd_years / self.years) ** 2)
        mu, sigma = math.log(self.years) - 0.5 * sigma2, math.sqrt(sigma2)
        z = np.linspace(-8.0, 8.0, 1601)
        density = np.exp(-0.5 * z * z) / math.sqrt(2.0 * math.pi)
        t = np.exp(mu + sigma * z)
        flat = np.atleast_1d(nu).ravel()
        values = np.array([integrate.simpson(np.exp(-r * t) * density, x=z) for r in flat])
        return values.reshape(np.shape(nu))
