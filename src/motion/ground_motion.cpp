// Ground-motion operations: alignment, window, scale, rotation, resampling, integration.
#include "rigid/motion/ground_motion.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/motion/measures.hpp"

namespace rigid::motion {

namespace {

std::string num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

// every stored component, in x, y, z order
template <class F>
void for_each_component(GroundMotion& m, F f) {
  f(m.x);
  if (m.has_y) f(m.y);
  if (m.has_z) f(m.z);
}

}  // namespace

GroundMotion make_ground_motion(std::string name, std::vector<Component> components, const AlignOptions& options) {
  if (components.empty() || components.size() > 3)
    throw InputError(name, 0, "a motion needs 1 to 3 components (H1, H2, V), got " + std::to_string(components.size()));
  for (const auto& c : components) {
    if (!(c.dt > 0.0) || !std::isfinite(c.dt))
      throw InputError(name, 0, "component " + c.label + ": time step must be positive");
    if (c.acc.size() < 2) throw InputError(name, 0, "component " + c.label + ": needs at least 2 samples");
  }
  const double dt0 = components[0].dt;
  const std::size_t n0 = components[0].acc.size();
  bool same_dt = true, same_n = true;
  for (const auto& c : components) {
    same_dt = same_dt && std::abs(c.dt - dt0) <= 1e-9 * dt0;
    same_n = same_n && c.acc.size() == n0;
  }
  std::size_t longest = 0, shortest = n0;
  for (const auto& c : components) {
    longest = std::max(longest, c.acc.size());
    shortest = std::min(shortest, c.acc.size());
  }
  std::string alignment;
  if (!options.resample && same_dt && !same_n && double(longest - shortest) <= kAutoPadFraction * double(longest)) {
    // a few samples' difference at equal dt: pad the shorter with the quiet they end in
    for (std::size_t i = 0; i < components.size(); ++i) {
      auto& c = components[i];
      if (c.acc.size() == longest) continue;
      if (!alignment.empty()) alignment += ", ";
      const std::size_t added = longest - c.acc.size();
      alignment += "component " + (c.label.empty() ? "#" + std::to_string(i + 1) : c.label) + " zero-padded by " +
                   std::to_string(added) + " samples (" + num(double(added) * c.dt) + " s)";
      c.acc.resize(longest, 0.0);
    }
    same_n = true;
  }
  if (!options.resample && (!same_dt || !same_n)) {
    std::string what = "components differ in ";
    what += !same_dt ? "time step" : "length";
    what += " (";
    for (std::size_t i = 0; i < components.size(); ++i) {
      if (i) what += ", ";
      if (components[i].label.empty()) {
        what += '#';
        what += std::to_string(i + 1);
      } else {
        what += components[i].label;
      }
      what += ": npts " + std::to_string(components[i].acc.size()) + " dt " + num(components[i].dt);
    }
    what +=
        "); lengths within 1 % at equal dt are padded automatically; otherwise ask for resampling to "
        "a common dt, zero-padded to the longest (--resample, or align = \"resample\" in a job's [[record]])";
    throw InputError(name, 0, what);
  }
  double dt = dt0;
  if (options.resample) {
    dt = options.dt;
    if (dt <= 0.0) {
      dt = dt0;
      for (const auto& c : components) dt = std::min(dt, c.dt);
    }
    if (!std::isfinite(dt)) throw InputError(name, 0, "resampling time step must be positive");
    std::size_t n = 0;
    for (auto& c : components) {
      if (std::abs(c.dt - dt) > 1e-9 * dt) c.acc = resample_linear(c.acc, c.dt, dt);
      c.dt = dt;
      n = std::max(n, c.acc.size());
    }
    // zero-pad at the end: records end in quiet, so this keeps all data of the longest one
    for (auto& c : components) c.acc.resize(n, 0.0);
    if (!same_dt)
      alignment = "resampled to dt " + num(dt) + " s, zero-padded to " + std::to_string(n) + " samples";
    else if (!same_n)
      alignment = "zero-padded to " + std::to_string(n) + " samples (resampling asked for)";
  }
  GroundMotion m;
  m.name = std::move(name);
  m.alignment = std::move(alignment);
  m.dt = dt;
  m.x = std::move(components[0].acc);
  m.label_x = components[0].label;
  if (components.size() > 1) {
    m.y = std::move(components[1].acc);
    m.label_y = components[1].label;
    m.has_y = true;
  }
  if (components.size() > 2) {
    m.z = std::move(components[2].acc);
    m.label_z = components[2].label;
    m.has_z = true;
  }
  return m;
}

std::vector<double> resample_linear(const std::vector<double>& a, double dt_in, double dt_out) {
  if (a.empty() || !(dt_in > 0.0) || !(dt_out > 0.0)) return {};
  const double t_end = double(a.size() - 1) * dt_in;
  const double steps = std::floor(t_end / dt_out * (1.0 + 1e-12) + 1e-9);
  if (!(steps < 1e9)) throw InputError("", 0, "resampling would create too many samples");
  const std::size_t n = std::size_t(steps) + 1;
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = double(i) * dt_out / dt_in;
    std::size_t k = std::size_t(std::floor(s));
    if (k >= a.size() - 1) {
      out[i] = a.back();
      continue;
    }
    const double w = s - double(k);
    out[i] = (1.0 - w) * a[k] + w * a[k + 1];
  }
  return out;
}

GroundMotion resampled(const GroundMotion& m, double dt_out) {
  if (!(dt_out > 0.0)) throw InputError(m.name, 0, "resampling time step must be positive");
  GroundMotion r = m;
  for_each_component(r, [&](std::vector<double>& a) { a = resample_linear(a, m.dt, dt_out); });
  r.dt = dt_out;
  return r;
}

GroundMotion windowed(const GroundMotion& m, double start, double end) {
  if (!(start >= 0.0) || !(end > start))
    throw InputError(m.name, 0, "bad time window [" + num(start) + ", " + num(end) + "] s");
  const double tol = 1e-6;
  const double first = std::ceil(start / m.dt - tol);
  const double last_t = std::floor(end / m.dt + tol);
  const double n = double(m.npts());
  if (first >= n - 1)
    throw InputError(m.name, 0,
                     "time window starts at " + num(start) + " s, after the record (" + num(m.duration()) + " s)");
  const std::size_t i0 = std::size_t(first);
  const std::size_t i1 = last_t >= n - 1 ? m.npts() - 1 : std::size_t(last_t);
  if (i1 < i0 + 1)
    throw InputError(m.name, 0, "time window [" + num(start) + ", " + num(end) + "] s holds fewer than 2 samples");
  GroundMotion r = m;
  for_each_component(r, [&](std::vector<double>& a) {
    a = std::vector<double>(a.begin() + std::ptrdiff_t(i0), a.begin() + std::ptrdiff_t(i1) + 1);
  });
  return r;
}

GroundMotion scaled(const GroundMotion& m, double factor) {
  GroundMotion r = m;
  for_each_component(r, [&](std::vector<double>& a) {
    for (double& v : a) v *= factor;
  });
  return r;
}

GroundMotion rotated(const GroundMotion& m, double angle) {
  GroundMotion r = m;
  if (!r.has_y) {
    r.y.assign(r.x.size(), 0.0);
    r.has_y = true;
    r.label_y = r.label_x.empty() ? "rotated" : r.label_x + " (rotated)";
  }
  const double c = std::cos(angle), s = std::sin(angle);
  for (std::size_t i = 0; i < r.x.size(); ++i) {
    const double x = r.x[i], y = r.y[i];
    r.x[i] = x * c - y * s;
    r.y[i] = x * s + y * c;
  }
  return r;
}

std::vector<double> integrate_trapezoid(const std::vector<double>& f, double dt) {
  std::vector<double> out(f.size(), 0.0);
  for (std::size_t i = 1; i < f.size(); ++i) out[i] = out[i - 1] + 0.5 * dt * (f[i - 1] + f[i]);
  return out;
}

Kinematics integrate(const std::vector<double>& acc, double dt, Baseline baseline) {
  Kinematics k;
  k.acc = acc;
  k.vel = integrate_trapezoid(acc, dt);
  if (baseline != Baseline::none && acc.size() > 2) {
    // least squares of v(t) on {t} or {t, t^2} (no constant: v(0) = 0 stays), by normal
    // equations in the scaled time s = t/T for conditioning (Boore 2001 style velocity fit)
    const double T = double(acc.size() - 1) * dt;
    double s11 = 0, s12 = 0, s22 = 0, b1 = 0, b2 = 0;
    for (std::size_t i = 0; i < acc.size(); ++i) {
      const double s = double(i) * dt / T;
      s11 += s * s;
      s12 += s * s * s;
      s22 += s * s * s * s;
      b1 += s * k.vel[i];
      b2 += s * s * k.vel[i];
    }
    double c1 = 0, c2 = 0;  // coefficients in s
    if (baseline == Baseline::velocity_linear) {
      c1 = b1 / s11;
    } else {
      const double det = s11 * s22 - s12 * s12;
      c1 = (b1 * s22 - b2 * s12) / det;
      c2 = (s11 * b2 - s12 * b1) / det;
    }
    for (std::size_t i = 0; i < acc.size(); ++i) {
      const double s = double(i) * dt / T;
      k.vel[i] -= c1 * s + c2 * s * s;
      k.acc[i] -= (c1 + 2.0 * c2 * s) / T;
    }
  }
  k.disp = integrate_trapezoid(k.vel, dt);
  return k;
}

double peak_abs(const std::vector<double>& a) {
  double p = 0.0;
  for (double v : a) p = std::max(p, std::abs(v));
  return p;
}

Peaks peaks(const std::vector<double>& acc, double dt, Baseline baseline) {
  const Kinematics k = integrate(acc, dt, baseline);
  return {peak_abs(k.acc), peak_abs(k.vel), peak_abs(k.disp)};
}

GroundVelocity ground_velocity(const GroundMotion& m, Baseline baseline) {
  GroundVelocity g;
  g.dt = m.dt;
  g.vx = integrate(m.x, m.dt, baseline).vel;
  g.vy = m.has_y ? integrate(m.y, m.dt, baseline).vel : std::vector<double>(m.npts(), 0.0);
  g.vz = m.has_z ? integrate(m.z, m.dt, baseline).vel : std::vector<double>(m.npts(), 0.0);
  return g;
}

double target_pga_factor(const GroundMotion& m, double target_pga_g) {
  if (!(target_pga_g > 0.0) || !std::isfinite(target_pga_g))
    throw InputError(m.name, 0, "target PGA must be positive, got " + num(target_pga_g) + " g");
  double measure = 0.0;
  if (m.has_y) {
    // GMRotI50 PGA over the PGA and PGV measures (physics.md §5); the angle from both.
    measure = horizontal_measures(m).gmroti50_pga;
  } else {
    measure = peak_abs(m.x);
  }
  if (!(measure > 0.0)) throw InputError(m.name, 0, "cannot scale to a target PGA: horizontal acceleration is zero");
  return target_pga_g * kGravity / measure;
}

GroundMotion scaled_to_pga(const GroundMotion& m, double target_pga_g) {
  return scaled(m, target_pga_factor(m, target_pga_g));
}

GroundMotion transformed(const GroundMotion& m, const MotionTransform& t) {
  GroundMotion r = (t.start > 0.0 || std::isfinite(t.end)) ? windowed(m, t.start, t.end) : m;
  // the target sets the level; factor multiplies on top of it (1 = no change)
  double f = t.factor;
  if (t.target_pga_g > 0.0) {
    const double per_g = t.pga_factor_per_g > 0.0 ? t.pga_factor_per_g : target_pga_factor(r, 1.0);
    f *= per_g * t.target_pga_g;
  }
  if (f != 1.0) r = scaled(r, f);
  if (t.rotation != 0.0) r = rotated(r, t.rotation);
  if (const auto bad = first_bad_drive_sample(r)) {
    std::ostringstream what;
    const std::vector<double>& c = bad->axis == 'x' ? r.x : bad->axis == 'y' ? r.y : r.z;
    what.precision(3);
    what << "the motion " << r.name << " scaled by " << f << ": " << bad->axis
         << " at t = " << double(bad->index) * r.dt << " s is " << c[bad->index] / kGravity << " g: " << bad->problem;
    throw InputError("", 0, what.str());
  }
  return r;
}

std::string drive_sample_problem(double a) {
  if (!std::isfinite(a)) return "not a finite number";
  if (std::abs(a) <= kMaxDriveAccelerationG * kGravity) return "";
  std::ostringstream what;
  what << "beyond " << kMaxDriveAccelerationG << " g, more than any ground motion (a unit or scale mistake?)";
  return what.str();
}

std::optional<BadDriveSample> first_bad_drive_sample(const GroundMotion& m, double factor) {
  const std::pair<char, const std::vector<double>*> components[] = {{'x', &m.x}, {'y', &m.y}, {'z', &m.z}};
  const std::size_t n = std::max({m.x.size(), m.y.size(), m.z.size()});
  for (std::size_t i = 0; i < n; ++i) {
    for (const auto& [axis, samples] : components) {
      if (i >= samples->size()) continue;
      if (std::string problem = drive_sample_problem((*samples)[i] * factor); !problem.empty())
        return BadDriveSample{axis, i, std::move(problem)};
    }
  }
  return std::nullopt;
}

}  // namespace rigid::motion
