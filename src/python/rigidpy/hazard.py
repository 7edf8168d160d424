"""PGA hazard curves (annual rate of exceedance against PGA) read from CSV, and the rate at which
a rock with a lognormal fragility topples under them.

Layouts read (the first that fits):
- two columns, PGA in g and annual rate of exceedance, with or without a header line;
- OpenQuake's hazard-curve export: a first comment line holding `investigation_time=T` and
  `imt='PGA'`, then `lon,lat,depth,poe-0.005,poe-0.007,...` (probabilities of exceedance in T
  years, turned into annual rates by -ln(1 - poe) / T, the Poisson assumption the engine uses);
- the USGS nshmp-haz layout: `name,lon,lat,0.0025,0.0045,...` (annual rates), one row per site.
Wide files with several sites need `site` (the row's name, `lon,lat`, or its 0-based index).

The rate: a rock whose toppling PGA C is lognormal (median theta, dispersion beta) topples at the
annual rate lambda = integral P(C <= a) |dH(a)| = E[H(C)] (by parts; P(0) H(0) and P(inf) H(inf)
vanish). The expectation is taken over ln C on +-8 beta by Simpson's rule, H interpolated
linearly in log-log between the curve's points and extended beyond its ends by the power law of
its end segments; the share of lambda from the extension is reported, since it is not data.
For H = k0 a^-k the rate has the closed form k0 theta^-k exp(k^2 beta^2 / 2).
"""
import csv
import math
import os
import re
import stat

import numpy as np
from scipy import integrate, optimize
from scipy.special import ndtr


class CurveError(Exception):
    """Bad input: the message names the file and line."""


class HazardCurve:
    def __init__(self, pga_g, rate, source, site=""):
        self.pga_g = np.asarray(pga_g, float)
        self.rate = np.asarray(rate, float)
        self.source = source
        self.site = site
        positive = self.rate > 0
        # rates of 0 end the curve: nothing exceeds those PGAs (no extension past them)
        self.top = int(np.argmax(~positive)) if not positive.all() else len(self.rate)
        self.ln_a = np.log(self.pga_g[: self.top])
        self.ln_h = np.log(self.rate[: self.top])

    def __call__(self, a):
        """Annual rate of exceeding PGA a (g)."""
        x = np.log(np.asarray(a, float))
        la, lh = self.ln_a, self.ln_h
        if len(la) == 1:
            return np.where(x <= la[0], math.exp(lh[0]), 0.0)
        y = np.interp(x, la, lh)
        lo_slope = (lh[1] - lh[0]) / (la[1] - la[0])
        hi_slope = (lh[-1] - lh[-2]) / (la[-1] - la[-2])
        y = np.where(x < la[0], lh[0] + lo_slope * (x - la[0]), y)
        y = np.where(x > la[-1], lh[-1] + hi_slope * (x - la[-1]), y)
        h = np.exp(y)
        if self.top < len(self.rate):  # the curve reached 0: nothing beyond its last positive PGA
            h = np.where(x > la[-1], 0.0, h)
        return h

    def scaled(self, rate_factor=1.0, pga_factor=1.0):
        return HazardCurve(self.pga_g * pga_factor, self.rate * rate_factor, self.source, self.site)


def _number(text):
    try:
        v = float(text)
    except ValueError:
        return None
    return v


# Largest hazard curve file read (unit: bytes): the C++ readers' limit for text inputs
# (src/io/input_file.hpp); a curve of every site of a national model is a few MB.
MAX_CURVE_BYTES = 64 << 20


def read_text_input(path, max_bytes=MAX_CURVE_BYTES):
    """The text of a regular file of at most max_bytes, as the C++ side reads its inputs: a
    FIFO, device or directory would block or grow memory without bound, so it is refused (the
    file is opened without blocking and checked on its descriptor, then read bounded)."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except FileNotFoundError:
        raise CurveError(f"{path}: no such file")
    except OSError as e:
        raise CurveError(f"{path}: cannot read ({e.strerror})")
    with os.fdopen(fd, "rb") as f:
        st = os.fstat(fd)
        if stat.S_ISDIR(st.st_mode):
            raise CurveError(f"{path}: is a directory, not a file")
        if not stat.S_ISREG(st.st_mode):
            raise CurveError(f"{path}: not a regular file (a FIFO, device or socket)")
        if st.st_size > max_bytes:
            raise CurveError(f"{path}: file larger than {max_bytes >> 20} MB")
        data = f.read(max_bytes + 1)
    if len(data) > max_bytes:
        raise CurveError(f"{path}: file larger than {max_bytes >> 20} MB")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise CurveError(f"{path}: cannot read ({e})")


def read_curve(path, site=None):
    """The hazard curve of `path` (layouts in the module docstring)."""
    lines = read_text_input(path).splitlines()
    investigation_time, imt = None, None
    rows = []  # (line number, cells)
    for number, line in enumerate(lines, start=1):
        if line.startswith("#"):
            m = re.search(r"investigation_time\s*=\s*([0-9.eE+-]+)", line)
            if m:
                investigation_time = _number(m.group(1))
            m = re.search(r"imt\s*=\s*'?\"?([A-Za-z0-9().]+)", line)
            if m:
                imt = m.group(1)
            continue
        if not line.strip():
            continue
        rows.append((number, next(csv.reader([line]))))
    if not rows:
        raise CurveError(f"{path}: no data (expected PGA in g and annual rate of exceedance)")
    if imt is not None and imt.upper() != "PGA":
        raise CurveError(f"{path}: line 1: the curve is for {imt}, not PGA")
    header_line, header = rows[0]
    numeric_header = [_number(c) for c in header]
    if len(header) == 2:
        body = rows if all(v is not None for v in numeric_header) else rows[1:]
        return _long_curve(path, body, header_line)
    poe_columns = [i for i, c in enumerate(header) if c.strip().lower().startswith("poe-")]
    if poe_columns:
        if not investigation_time or investigation_time <= 0:
            raise CurveError(f"{path}: line 1: OpenQuake curve without investigation_time=... in its first comment line")
        imls = [_number(header[i].strip()[4:]) for i in poe_columns]
        if any(v is None for v in imls):
            raise CurveError(f"{path}: line {header_line}: a poe-IML column whose IML is not a number")
        return _wide_curve(path, header, rows[1:], poe_columns, imls, site, header_line, investigation_time)
    iml_columns = [i for i, v in enumerate(numeric_header) if v is not None]
    if iml_columns and iml_columns == list(range(iml_columns[0], len(header))) and len(iml_columns) >= 2:
        imls = [numeric_header[i] for i in iml_columns]
        return _wide_curve(path, header, rows[1:], iml_columns, imls, site, header_line, None)
    raise CurveError(f"{path}: line {header_line}: expected two columns (PGA g, annual rate of exceedance), "
                     f"OpenQuake's poe-IML columns or nshmp-haz's numeric IML columns; got {len(header)} columns")


def _long_curve(path, body, header_line):
    if not body:
        raise CurveError(f"{path}: line {header_line}: a header and no data")
    pga, rate = [], []
    for number, cells in body:
        if len(cells) != 2:
            raise CurveError(f"{path}: line {number}: expected 2 columns (PGA g, annual rate), got {len(cells)}")
        a, h = _number(cells[0]), _number(cells[1])
        if a is None or h is None:
            raise CurveError(f"{path}: line {number}: not a number: {','.join(cells)}")
        pga.append((number, a))
        rate.append((number, h))
    return _checked(path, pga, rate, "")


def _wide_curve(path, header, body, columns, imls, site, header_line, investigation_time):
    if not body:
        raise CurveError(f"{path}: line {header_line}: a header and no site rows")
    key_columns = [i for i in range(len(header)) if i not in columns]
    names = []
    for number, cells in body:
        if len(cells) != len(header):
            raise CurveError(f"{path}: line {number}: {len(cells)} columns, the header has {len(header)}")
        names.append(",".join(cells[i].strip() for i in key_columns))
    if site is None:
        if len(body) > 1:
            raise CurveError(f"{path}: line {body[1][0]}: {len(body)} sites; choose one with --site (a row's "
                             f"{'/'.join(header[i] for i in key_columns)}, or its 0-based index)")
        chosen = 0
    else:
        lower = [h.strip().lower() for h in header]
        lonlat = None
        if "lon" in lower and "lat" in lower and site.count(",") == 1:
            wanted = [_number(v) for v in site.split(",")]
            if None not in wanted:
                lonlat = (lower.index("lon"), lower.index("lat"), wanted)

        def is_site(i, name):
            if name == site or name.split(",")[0] == site:
                return True
            if lonlat is None:
                return False
            lon, lat = _number(body[i][1][lonlat[0]]), _number(body[i][1][lonlat[1]])
            return lon is not None and lat is not None and abs(lon - lonlat[2][0]) < 1e-9 and abs(lat - lonlat[2][1]) < 1e-9

        matches = [i for i, n in enumerate(names) if is_site(i, n)]
        if matches:
            chosen = matches[0]
        elif site.isdigit() and int(site) < len(body):
            chosen = int(site)
        else:
            raise CurveError(f"{path}: no site {site!r} (sites: {'; '.join(names[:5])}{' ...' if len(names) > 5 else ''})")
    number, cells = body[chosen]
    pga, rate = [], []
    for i, a in zip(columns, imls):
        v = _number(cells[i])
        if v is None:
            raise CurveError(f"{path}: line {number}: column {header[i]}: not a number: {cells[i]!r}")
        if investigation_time is not None:
            if not 0 <= v < 1:
                raise CurveError(f"{path}: line {number}: column {header[i]}: probability of exceedance {v} "
                                 f"outside [0, 1)")
            v = -math.log1p(-v) / investigation_time
        pga.append((number, a))
        rate.append((number, v))
    return _checked(path, pga, rate, names[chosen])


def _checked(path, pga, rate, site):
    for (number, a), (_, h) in zip(pga, rate):
        if not (math.isfinite(a) and a > 0):
            raise CurveError(f"{path}: line {number}: PGA {a} g: must be positive and finite")
        if not math.isfinite(h) or h < 0:
            raise CurveError(f"{path}: line {number}: annual rate {h}: must be >= 0 and finite")
    for (n0, a0), (n1, a1) in zip(pga, pga[1:]):
        if not a1 > a0:
            raise CurveError(f"{path}: line {n1}: PGA {a1} g after {a0} g: PGAs must increase")
    for (n0, h0), (n1, h1) in zip(rate, rate[1:]):
        if h1 > h0:
            raise CurveError(f"{path}: line {n1}: annual rate {h1:g} above {h0:g} at a lower PGA: a hazard curve "
                             f"does not increase")
    if len(pga) < 2:
        raise CurveError(f"{path}: one point; a hazard curve needs at least two")
    if not rate[0][1] > 0:
        raise CurveError(f"{path}: line {rate[0][0]}: the first annual rate is 0: nothing is ever exceeded")
    return HazardCurve([a for _, a in pga], [h for _, h in rate], path, site)


# --------------------------------------------------------------------------------------------
# Rate of toppling

_Z = np.linspace(-8.0, 8.0, 1601)
_DENSITY = np.exp(-0.5 * _Z**2) / math.sqrt(2.0 * math.pi)


def toppling_rate(curve, theta_g, beta):
    """(lambda per year, share of lambda from beyond the curve's PGA range) for a lognormal
    fragility (theta in g, beta); beta 0 is a step at theta (a deterministic threshold): H(theta)."""
    if beta == 0:
        outside = not curve.pga_g[0] <= theta_g <= curve.pga_g[curve.top - 1]
        return float(curve(theta_g)), (1.0 if outside else 0.0)
    z, density = _Z, _DENSITY
    if curve.top < len(curve.rate):
        # H drops to 0 past its last positive PGA: integrate up to that jump, not across it
        z_end = math.log(curve.pga_g[curve.top - 1] / theta_g) / beta
        if z_end <= _Z[0]:
            return 0.0, 0.0
        z = np.linspace(_Z[0], min(z_end, _Z[-1]), len(_Z))
        density = np.exp(-0.5 * z**2) / math.sqrt(2.0 * math.pi)
    a = theta_g * np.exp(beta * z)
    h = curve(np.minimum(a, curve.pga_g[curve.top - 1]) if curve.top < len(curve.rate) else a)
    total = float(integrate.simpson(h * density, x=z))
    outside = (a < curve.pga_g[0]) | (a > curve.pga_g[curve.top - 1])
    extended = float(integrate.simpson(np.where(outside, h, 0.0) * density, x=z))
    return total, (extended / total if total > 0 else 0.0)


def mixture_rate(curve, fragilities):
    """lambda of a fragility that is a weighted mixture of lognormals [(weight, theta, beta)]
    (PGV/PGA distributed independently of PGA)."""
    lam, ext = 0.0, 0.0
    for w, theta, beta in fragilities:
        r, e = toppling_rate(curve, theta, beta)
        lam += w * r
        ext += w * r * e
    return lam, (ext / lam if lam > 0 else 0.0)


def survival(rate, years):
    return math.exp(-rate * years)


def pga_at_rate(pga_g, rate, target):
    """The PGA (g) exceeded at the annual rate `target` on the curve (pga_g, rate), interpolated
    linearly in log-log as HazardCurve is; NaN when the curve's positive rates do not reach it."""
    pga_g, rate = np.asarray(pga_g, float), np.asarray(rate, float)
    positive = rate > 0
    a, h = pga_g[positive], rate[positive]
    if len(a) == 0 or not h[-1] <= target <= h[0]:
        return math.nan
    # rates fall with PGA: interpolate ln a against -ln h, which rises
    return float(math.exp(np.interp(-math.log(target), -np.log(h), np.log(a))))


def ruling_factors(curve, fragilities, years, confidence):
    """How far the curve must be raised before a rock that survived `years` rules it out at
    `confidence` (survival probability below 1 - confidence): the factor on its rates (lambda is
    linear in them) and the factor on its PGAs (solved numerically). A factor below 1 means the
    curve as given is already ruled out."""
    target = -math.log(1.0 - confidence) / years
    lam, _ = mixture_rate(curve, fragilities)
    rate_factor = target / lam if lam > 0 else math.inf

    def excess(ln_f):
        # a curve that ends at rate 0 gives lambda = 0 once scaled far enough down: a floor keeps the
        # log finite for the root finder
        rate = mixture_rate(curve.scaled(pga_factor=math.exp(ln_f)), fragilities)[0]
        return math.log(max(rate, 1e-300)) - math.log(target)

    pga_factor = math.inf
    if lam > 0:
        lo, hi = -6.0, 6.0
        if excess(lo) < 0 < excess(hi):
            pga_factor = math.exp(optimize.brentq(excess, lo, hi, xtol=1e-10))
        elif excess(lo) >= 0:
            pga_factor = 0.0
    return rate_factor, pga_factor


def fragility_probability(a, theta_g, beta):
    if beta == 0:  # a deterministic threshold
        return (np.asarray(a, float) >= theta_g).astype(float)
    return ndtr(np.log(np.asarray(a, float) / theta_g) / beta)


# rigidpy.hazard(...) is fits_data.hazard (callable_module.py says why)
from .callable_module import call_through  # noqa: E402

call_through(__name__, "rigidpy.fits_data", "hazard")
