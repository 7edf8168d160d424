// Orientation-independent measures (physics.md §5) and response spectra (Nigam & Jennings 1969).
#include "rigid/motion/measures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"

namespace rigid::motion {

double percentile(std::vector<double> values, double pp) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const double rank = std::clamp(pp, 0.0, 100.0) / 100.0 * double(values.size() - 1);
  const std::size_t lo = std::size_t(std::floor(rank));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  const double w = rank - double(lo);
  return values[lo] + w * (values[hi] - values[lo]);
}

std::vector<double> rotated_peaks(const std::vector<double>& a1, const std::vector<double>& a2, int n_angles) {
  const std::size_t n = std::min(a1.size(), a2.size());
  std::vector<double> out(std::size_t(std::max(n_angles, 0)), 0.0);
  for (int k = 0; k < n_angles; ++k) {
    const double th = kPi * double(k) / double(n_angles);
    const double c = std::cos(th), s = std::sin(th);
    double p = 0.0;
    for (std::size_t i = 0; i < n; ++i) p = std::max(p, std::abs(a1[i] * c + a2[i] * s));
    out[std::size_t(k)] = p;
  }
  return out;
}

namespace {

// GM(theta) for theta = 0..89 deg from the single-component peaks at 0..179 deg: the second
// rotated component at theta is the first one at theta + 90 deg (up to sign).
std::vector<double> gm_from_peaks(const std::vector<double>& p180) {
  std::vector<double> gm(90);
  for (std::size_t k = 0; k < 90; ++k) gm[k] = std::sqrt(p180[k] * p180[k + 90]);
  return gm;
}

}  // namespace

std::vector<double> gmrot_by_angle(const std::vector<double>& a1, const std::vector<double>& a2) {
  return gm_from_peaks(rotated_peaks(a1, a2, 180));
}

double gmrotd(const std::vector<double>& a1, const std::vector<double>& a2, double pp) {
  return percentile(gmrot_by_angle(a1, a2), pp);
}

double rotd(const std::vector<double>& a1, const std::vector<double>& a2, double pp) {
  return percentile(rotated_peaks(a1, a2, 180), pp);
}

GmRotI gmroti(const std::vector<std::pair<const std::vector<double>*, const std::vector<double>*>>& measures,
              double pp) {
  GmRotI r;
  if (measures.empty()) return r;
  std::vector<std::vector<double>> gm;
  for (const auto& [a1, a2] : measures) {
    gm.push_back(gmrot_by_angle(*a1, *a2));
    r.gmrotd.push_back(percentile(gm.back(), pp));
  }
  // penalty of Boore et al. (2006) eq. (physics.md §5 item 5); measures with a zero GMRotD
  // carry no information and are skipped
  std::size_t best = 0;
  double best_pen = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < 90; ++k) {
    double pen = 0.0;
    std::size_t used = 0;
    for (std::size_t m = 0; m < gm.size(); ++m) {
      if (!(r.gmrotd[m] > 0.0)) continue;
      const double d = gm[m][k] / r.gmrotd[m] - 1.0;
      pen += d * d;
      ++used;
    }
    if (used) pen /= double(used);
    if (pen < best_pen) {
      best_pen = pen;
      best = k;
    }
  }
  r.angle_deg = double(best);
  r.penalty = best_pen;
  for (const auto& g : gm) r.values.push_back(g[best]);
  return r;
}

SdofResponse sdof_response(const std::vector<double>& acc, double dt, double period, double zeta) {
  SdofResponse r;
  const std::size_t n = acc.size();
  r.u.assign(n, 0.0);
  r.v.assign(n, 0.0);
  if (n == 0 || !(period > 0.0) || !(dt > 0.0)) return r;
  if (!(zeta >= 0.0 && zeta < 1.0)) throw InputError("", 0, "oscillator damping ratio must be in [0, 1)");
  // exact recurrence for piecewise-linear excitation p = -acc (unit mass), Nigam & Jennings
  // (1969) in the form of Chopra, Dynamics of Structures, Table 5.2.1
  const double w = 2.0 * kPi / period;
  const double k = w * w;
  const double sq = std::sqrt(1.0 - zeta * zeta);
  const double wd = w * sq;
  const double e = std::exp(-zeta * w * dt);
  const double sn = std::sin(wd * dt), cs = std::cos(wd * dt);
  const double A = e * (zeta / sq * sn + cs);
  const double B = e * (sn / wd);
  const double C = (2.0 * zeta / (w * dt) + e * (((1.0 - 2.0 * zeta * zeta) / (wd * dt) - zeta / sq) * sn -
                                                 (1.0 + 2.0 * zeta / (w * dt)) * cs)) /
                   k;
  const double D =
      (1.0 - 2.0 * zeta / (w * dt) + e * ((2.0 * zeta * zeta - 1.0) / (wd * dt) * sn + 2.0 * zeta / (w * dt) * cs)) / k;
  const double A1 = -e * (w / sq * sn);
  const double B1 = e * (cs - zeta / sq * sn);
  const double C1 = (-1.0 / dt + e * ((w / sq + zeta / (dt * sq)) * sn + cs / dt)) / k;
  const double D1 = (1.0 - e * (zeta / sq * sn + cs)) / (k * dt);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double p0 = -acc[i], p1 = -acc[i + 1];
    r.u[i + 1] = A * r.u[i] + B * r.v[i] + C * p0 + D * p1;
    r.v[i + 1] = A1 * r.u[i] + B1 * r.v[i] + C1 * p0 + D1 * p1;
  }
  return r;
}

std::vector<double> response_spectrum(const std::vector<double>& acc, double dt, const std::vector<double>& periods,
                                      double zeta) {
  std::vector<double> sa;
  sa.reserve(periods.size());
  for (double T : periods) {
    if (!(T > 0.0)) {
      sa.push_back(peak_abs(acc));
      continue;
    }
    const double w = 2.0 * kPi / T;
    sa.push_back(w * w * peak_abs(sdof_response(acc, dt, T, zeta).u));
  }
  return sa;
}

HorizontalMeasures horizontal_measures(const GroundMotion& m, const MeasureOptions& options) {
  if (!m.has_y) throw InputError(m.name, 0, "orientation-independent measures need two horizontal components");
  HorizontalMeasures h;
  const std::vector<double> v1 = integrate(m.x, m.dt, options.baseline).vel;
  const std::vector<double> v2 = integrate(m.y, m.dt, options.baseline).vel;
  const auto pa = rotated_peaks(m.x, m.y, 180);
  const auto pv = rotated_peaks(v1, v2, 180);
  const auto ga = gm_from_peaks(pa), gv = gm_from_peaks(pv);
  h.gmrotd50_pga = percentile(ga, 50.0);
  h.gmrotd50_pgv = percentile(gv, 50.0);
  h.rotd50_pga = percentile(pa, 50.0);
  h.rotd100_pga = percentile(pa, 100.0);
  h.rotd50_pgv = percentile(pv, 50.0);
  h.rotd100_pgv = percentile(pv, 100.0);

  // GMRotI: PGA and PGV, plus oscillator responses if asked (pseudo-acceleration w^2 u)
  std::vector<std::vector<double>> osc;
  osc.reserve(2 * options.gmroti_periods.size());
  for (double T : options.gmroti_periods) {
    if (!(T > 0.0)) continue;
    const double w2 = std::pow(2.0 * kPi / T, 2);
    for (const auto* a : {&m.x, &m.y}) {
      auto u = sdof_response(*a, m.dt, T, options.zeta).u;
      for (double& x : u) x *= w2;
      osc.push_back(std::move(u));
    }
  }
  std::vector<std::pair<const std::vector<double>*, const std::vector<double>*>> measures;
  if (options.gmroti_use_peaks || osc.empty()) measures = {{&m.x, &m.y}, {&v1, &v2}};
  for (std::size_t i = 0; i + 1 < osc.size(); i += 2) measures.push_back({&osc[i], &osc[i + 1]});
  const GmRotI gi = gmroti(measures, 50.0);
  // PGA and PGV at the chosen angle (the "I" of GMRotI: one rotation for every measure)
  const std::size_t k = std::size_t(gi.angle_deg);
  h.gmroti50_pga = ga[k];
  h.gmroti50_pgv = gv[k];
  h.gmroti50_angle_deg = gi.angle_deg;
  return h;
}

MotionInfo motion_info(const GroundMotion& m, const MeasureOptions& options, const std::vector<double>& sa_periods) {
  MotionInfo info;
  info.name = m.name;
  info.sources = m.sources;
  info.alignment = m.alignment;
  info.npts = m.npts();
  info.dt = m.dt;
  info.duration = m.duration();
  const std::vector<std::pair<char, const std::vector<double>*>> comps = [&] {
    std::vector<std::pair<char, const std::vector<double>*>> c = {{'x', &m.x}};
    if (m.has_y) c.push_back({'y', &m.y});
    if (m.has_z) c.push_back({'z', &m.z});
    return c;
  }();
  for (const auto& [axis, a] : comps) {
    MotionInfo::Axis ax;
    ax.axis = axis;
    ax.label = axis == 'x' ? m.label_x : axis == 'y' ? m.label_y : m.label_z;
    ax.peaks = peaks(*a, m.dt, options.baseline);
    info.axes.push_back(ax);
  }
  info.two_horizontals = m.has_y;
  if (m.has_y) {
    info.horizontal = horizontal_measures(m, options);
    info.pgv_pga =
        info.horizontal.gmroti50_pga > 0.0 ? info.horizontal.gmroti50_pgv / info.horizontal.gmroti50_pga : 0.0;
  } else {
    info.pgv_pga = info.axes[0].peaks.pga > 0.0 ? info.axes[0].peaks.pgv / info.axes[0].peaks.pga : 0.0;
  }
  for (double T : sa_periods) {
    MotionInfo::SpectralValue sv;
    sv.period = T;
    std::vector<std::vector<double>> resp;
    for (const auto& [axis, a] : comps) {
      (void)axis;
      if (T > 0.0) {
        const double w2 = std::pow(2.0 * kPi / T, 2);
        auto u = sdof_response(*a, m.dt, T, options.zeta).u;
        for (double& x : u) x *= w2;
        sv.per_axis.push_back(peak_abs(u));
        resp.push_back(std::move(u));
      } else {
        sv.per_axis.push_back(peak_abs(*a));
        resp.push_back(*a);
      }
    }
    if (m.has_y) {
      sv.gmrotd50 = gmrotd(resp[0], resp[1], 50.0);
      sv.rotd50 = rotd(resp[0], resp[1], 50.0);
    }
    info.spectrum.push_back(sv);
  }
  return info;
}

namespace {

constexpr double kCm = 100.0;

}  // namespace

std::string to_text(const MotionInfo& info) {
  const double g = kGravity;
  char buf[256];
  std::string o = info.name + "\n";
  for (const auto& s : info.sources) o += "  source " + s + "\n";
  if (!info.alignment.empty()) o += "  aligned: " + info.alignment + "\n";
  std::snprintf(buf, sizeof buf, "  npts %zu  dt %.6g s  duration %.6g s\n", info.npts, info.dt, info.duration);
  o += buf;
  for (const auto& a : info.axes) {
    std::snprintf(buf, sizeof buf, "  %c %-12s PGA %.5g g  PGV %.5g cm/s  PGD %.5g cm\n", a.axis, a.label.c_str(),
                  a.peaks.pga / g, a.peaks.pgv * kCm, a.peaks.pgd * kCm);
    o += buf;
  }
  if (info.two_horizontals) {
    const auto& h = info.horizontal;
    std::snprintf(buf, sizeof buf, "  GMRotD50  PGA %.5g g  PGV %.5g cm/s\n", h.gmrotd50_pga / g, h.gmrotd50_pgv * kCm);
    o += buf;
    std::snprintf(buf, sizeof buf, "  GMRotI50  PGA %.5g g  PGV %.5g cm/s  (angle %.0f deg)\n", h.gmroti50_pga / g,
                  h.gmroti50_pgv * kCm, h.gmroti50_angle_deg);
    o += buf;
    std::snprintf(buf, sizeof buf, "  RotD50 PGA %.5g g  RotD100 PGA %.5g g\n", h.rotd50_pga / g, h.rotd100_pga / g);
    o += buf;
  }
  std::snprintf(buf, sizeof buf, "  PGV/PGA %.5g s\n", info.pgv_pga);
  o += buf;
  for (const auto& s : info.spectrum) {
    std::snprintf(buf, sizeof buf, "  Sa(%.4g s)", s.period);
    o += buf;
    for (std::size_t k = 0; k < s.per_axis.size() && k < info.axes.size(); ++k) {
      std::snprintf(buf, sizeof buf, "  %c %.5g g", info.axes[k].axis, s.per_axis[k] / g);
      o += buf;
    }
    if (info.two_horizontals) {
      std::snprintf(buf, sizeof buf, "  GMRotD50 %.5g g  RotD50 %.5g g", s.gmrotd50 / g, s.rotd50 / g);
      o += buf;
    }
    o += "\n";
  }
  return o;
}

}  // namespace rigid::motion
