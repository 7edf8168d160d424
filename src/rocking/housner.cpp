// Housner rocking block, physics.md §2. See include/rigid/rocking/housner.hpp for the model, the
// sign convention and the contract of every function.
#include "rigid/rocking/housner.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "rigid/core/types.hpp"

namespace rigid::rocking {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("rocking: ") + what);
}

// (θ, θ̇) of the block.
struct Phase {
  double theta;
  double omega;
};

// The right-hand side and the ground, bound together for the stepper. The pivot side s is a
// parameter, not sgn θ: within one step the equation of the current pivot is continued across
// θ = 0, so the crossing can be located on a smooth function before the pivot switches.
class Rhs {
 public:
  Rhs(const RockingBlock& block, const GroundAcceleration& ground, bool linearised)
      : ground_(ground), p2_(block.p * block.p), alpha_(block.alpha), linear_(linearised) {}

  // θ̈ for pivot side s (±1) and ground acceleration ug, physics.md §2.
  double accel(double theta, double s, double ug) const {
    const double x = s * alpha_ - theta;
    if (linear_) return -p2_ * (x + ug / kGravity);
    return -p2_ * (std::sin(x) + (ug / kGravity) * std::cos(x));
  }

  // side toward which the ground lifts a block at rest: the moment at θ = 0± must push the heel
  // up (θ̈ away from zero); 0 when the block stays on its base.
  int uplift_side(double ug) const {
    if (accel(0.0, +1.0, ug) > 0.0) return +1;
    if (accel(0.0, -1.0, ug) < 0.0) return -1;
    return 0;
  }

  // one-sided ground values: a step starting at t sees the motion just after t, a step ending at
  // t the motion just before it, so jumps at breakpoints are honoured.
  double ground_after(double t) const { return ground_(std::nextafter(t, kInf)); }
  double ground_before(double t) const { return ground_(std::nextafter(t, -kInf)); }
  double ground_at(double t) const { return ground_(t); }

  // one classic RK4 step of length tau from (t, y) on pivot s; a0 is the ground just after t.
  Phase step(double t, Phase y, double s, double tau, double a0) const {
    const double am = ground_(t + 0.5 * tau);
    const double a1 = ground_before(t + tau);
    const double k1t = y.omega;
    const double k1w = accel(y.theta, s, a0);
    const double k2t = y.omega + 0.5 * tau * k1w;
    const double k2w = accel(y.theta + 0.5 * tau * k1t, s, am);
    const double k3t = y.omega + 0.5 * tau * k2w;
    const double k3w = accel(y.theta + 0.5 * tau * k2t, s, am);
    const double k4t = y.omega + tau * k3w;
    const double k4w = accel(y.theta + tau * k3t, s, a1);
    return {y.theta + tau / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t),
            y.omega + tau / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w)};
  }

 private:
  const GroundAcceleration& ground_;
  double p2_;
  double alpha_;
  bool linear_;
};

// First root of f on [lo, hi] with f(lo) > 0 ≥ f(hi): safeguarded Newton (f returns the value and
// its derivative). Returns the abscissa of the last evaluation, whose residual is ≤ ftol unless the
// bracket collapsed first.
template <class F>
double find_root(F f, double lo, double f_lo, double hi, double f_hi, double ftol, double ttol) {
  double x = (f_lo - f_hi > 0.0) ? lo + (hi - lo) * f_lo / (f_lo - f_hi) : 0.5 * (lo + hi);
  if (!(x > lo && x <= hi)) x = 0.5 * (lo + hi);
  double last = hi;
  for (int it = 0; it < 100; ++it) {
    const auto [v, d] = f(x);
    last = x;
    if (v > 0.0) {
      lo = x;
    } else {
      hi = x;
    }
    if (std::abs(v) <= ftol || hi - lo <= ttol) break;
    double next = (d != 0.0) ? x - v / d : kNaN;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    x = next;
  }
  return last;
}

// kinetic + potential energy per unit I_O at θ = α (the barrier), physics.md §2.
double barrier_energy(const RockingBlock& b, bool linearised) {
  const double p2 = b.p * b.p;
  return linearised ? 0.5 * p2 * b.alpha * b.alpha : p2 * (1.0 - std::cos(b.alpha));
}

void validate_block(const RockingBlock& b) {
  require(std::isfinite(b.alpha) && b.alpha > 0.0 && b.alpha < 0.5 * kPi, "block alpha must be in (0, pi/2)");
  require(std::isfinite(b.p) && b.p > 0.0, "block p must be finite and positive");
  require(std::isfinite(b.restitution) && b.restitution >= 0.0 && b.restitution <= 1.0,
          "block restitution must be in [0, 1]");
}

}  // namespace

RockingBlock RockingBlock::rectangular(double half_width, double half_height) {
  require(std::isfinite(half_width) && half_width > 0.0, "half_width must be finite and positive");
  require(std::isfinite(half_height) && half_height > 0.0, "half_height must be finite and positive");
  RockingBlock b;
  b.alpha = std::atan2(half_width, half_height);
  b.R = std::hypot(half_width, half_height);
  // I_O = (4/3) m R² about a base corner, so p² = m g R / I_O = 3g/(4R) (physics.md §2).
  b.p = std::sqrt(3.0 * kGravity / (4.0 * b.R));
  const double s = std::sin(b.alpha);
  b.restitution = 1.0 - 1.5 * s * s;
  return b;
}

RockingBlock RockingBlock::general(double alpha, double R, double mass, double inertia_pivot) {
  require(std::isfinite(alpha) && alpha > 0.0 && alpha < 0.5 * kPi, "alpha must be in (0, pi/2)");
  require(std::isfinite(R) && R > 0.0, "R must be finite and positive");
  require(std::isfinite(mass) && mass > 0.0, "mass must be finite and positive");
  require(std::isfinite(inertia_pivot) && inertia_pivot >= mass * R * R * (1.0 - 1e-12),
          "inertia about the pivot must be at least m R^2 (parallel-axis theorem)");
  RockingBlock b;
  b.alpha = alpha;
  b.R = R;
  b.p = std::sqrt(mass * kGravity * R / inertia_pivot);
  // angular momentum about the new pivot is conserved through the impact (physics.md §2).
  const double s = std::sin(alpha);
  b.restitution = 1.0 - 2.0 * mass * R * R / inertia_pivot * s * s;
  return b;
}

GroundAcceleration GroundAcceleration::sampled(std::span<const double> accel, double dt, double start_time,
                                               double scale) {
  require(std::isfinite(dt) && dt > 0.0, "sampling interval dt must be finite and positive");
  require(std::isfinite(start_time), "start_time must be finite");
  require(std::isfinite(scale), "scale must be finite");
  GroundAcceleration g;
  g.samples_.reserve(accel.size());
  for (const double a : accel) {
    require(std::isfinite(a), "ground acceleration samples must be finite");
    g.samples_.push_back(scale * a);
  }
  g.dt_ = dt;
  g.start_ = start_time;
  // the same expression as the last breakpoint, so the jump to zero sits exactly on it.
  g.end_ = g.samples_.empty() ? 0.0 : start_time + static_cast<double>(g.samples_.size() - 1) * dt;
  return g;
}

GroundAcceleration GroundAcceleration::analytic(std::function<double(double)> accel, double end_time,
                                                std::vector<double> breakpoints) {
  require(static_cast<bool>(accel), "analytic ground motion needs a function");
  require(std::isfinite(end_time), "end_time must be finite");
  for (const double t : breakpoints) require(std::isfinite(t), "breakpoints must be finite");
  GroundAcceleration g;
  g.fn_ = std::move(accel);
  g.end_ = end_time;
  g.breaks_ = std::move(breakpoints);
  g.breaks_.push_back(end_time);
  std::sort(g.breaks_.begin(), g.breaks_.end());
  g.breaks_.erase(std::unique(g.breaks_.begin(), g.breaks_.end()), g.breaks_.end());
  return g;
}

double GroundAcceleration::operator()(double t) const {
  if (fn_) return t <= end_ ? fn_(t) : 0.0;
  if (samples_.empty() || t < start_ || t > end_) return 0.0;
  const double x = (t - start_) / dt_;
  const auto k = static_cast<std::size_t>(x);
  if (k + 1 >= samples_.size()) return samples_.back();
  const double f = x - static_cast<double>(k);
  return samples_[k] + f * (samples_[k + 1] - samples_[k]);
}

double GroundAcceleration::next_breakpoint(double t) const {
  if (fn_) {
    const auto it = std::upper_bound(breaks_.begin(), breaks_.end(), t);
    return it == breaks_.end() ? kInf : *it;
  }
  if (samples_.empty()) return kInf;
  if (t < start_) return start_;
  const double last = static_cast<double>(samples_.size() - 1);
  double k = std::floor((t - start_) / dt_) + 1.0;
  for (; k <= last; k += 1.0) {
    const double b = start_ + k * dt_;
    if (b > t) return b;
  }
  return kInf;
}

double uplift_acceleration(const RockingBlock& block, bool linearised) {
  return kGravity * (linearised ? block.alpha : std::tan(block.alpha));
}

double rocking_energy(const RockingBlock& block, double theta, double theta_dot, bool linearised) {
  const double p2 = block.p * block.p;
  const double a = std::abs(theta);
  const double potential =
      linearised ? p2 * (block.alpha * a - 0.5 * a * a) : p2 * (std::cos(block.alpha - a) - std::cos(block.alpha));
  return 0.5 * theta_dot * theta_dot + potential;
}

namespace {

void validate_run(const RockingOptions& options, const InitialState& initial, double end_time) {
  require(std::isfinite(options.time_step) && options.time_step > 0.0, "time_step must be finite and positive");
  require(std::isfinite(options.overturn_angle) && options.overturn_angle >= 0.0 && options.overturn_angle <= 0.5 * kPi,
          "overturn_angle must be in [0, pi/2] (0 selects alpha)");
  require(std::isfinite(options.rest_velocity_ratio) && options.rest_velocity_ratio >= 0.0,
          "rest_velocity_ratio must be finite and non-negative");
  require(std::isfinite(options.record_interval) && options.record_interval >= 0.0,
          "record_interval must be finite and non-negative");
  require(std::isfinite(initial.time) && std::isfinite(initial.theta) && std::isfinite(initial.theta_dot),
          "initial state must be finite");
  require(std::isfinite(end_time) && end_time >= initial.time,
          "end_time must be finite and not before the initial time");
}

// time tolerance for bisection and root brackets (unit: s).
double ttol(double at) { return 1e-15 * std::max(1.0, std::abs(at)); }

// One run of the event-driven integration: the state (t, θ, θ̇, pivot s) and the result, with one
// method per kind of step. Each step either advances t or changes the state at the same t.
class Integration {
 public:
  Integration(const RockingBlock& block, const GroundAcceleration& ground, const RockingOptions& options,
              const InitialState& initial)
      : ground_(ground),
        options_(options),
        rhs_(block, ground, options.linearised),
        theta_ov_(options.overturn_angle > 0.0 ? options.overturn_angle : block.alpha),
        r_(block.restitution),
        w_rest_(options.rest_velocity_ratio * std::sqrt(2.0 * barrier_energy(block, options.linearised))),
        // residuals for root finding: θ to near round-off, θ̇ loosely (θ is flat at a peak).
        theta_tol_(1e-15 * std::max(1.0, theta_ov_)),
        omega_tol_(1e-12 * block.p),
        t_(initial.time),
        th_(initial.theta),
        w_(initial.theta_dot),
        // active pivot: +1 / −1 while rocking, 0 at rest.
        s_(th_ > 0.0   ? 1.0
           : th_ < 0.0 ? -1.0
           : w_ > 0.0  ? 1.0
           : w_ < 0.0  ? -1.0
                       : 0.0) {
    res_.max_abs_theta = std::abs(th_);
  }

  RockingResult run(double end_time) {
    record(SampleKind::start);
    if (std::abs(th_) >= theta_ov_) {
      res_.overturned = true;
      res_.failure_time = t_;
      res_.stop = StopReason::overturned;
      res_.end_time = t_;
      record(SampleKind::overturn);
      return res_;
    }
    StopReason stop = StopReason::end_time;
    // a long run of passes without progress would be a bug, not physics.
    int stalled = 0;
    double t_prev = t_;
    while (t_ < end_time) {
      stalled = (t_ > t_prev) ? 0 : stalled + 1;
      t_prev = t_;
      if (stalled > 1000) throw std::logic_error("rocking: simulation time does not advance");
      const double t1 = step_end(end_time);
      if (s_ == 0.0) {
        if (t_ >= ground_.end_time()) {
          stop = StopReason::at_rest;
          break;
        }
        rest_step(t1);
        continue;
      }
      const double h = t1 - t_;
      const double a0 = rhs_.ground_after(t_);
      const Phase y0{th_, w_};
      const Phase y1 = rhs_.step(t_, y0, s_, h, a0);
      if (overturn_within(y0, y1, a0, h, t1)) {
        stop = StopReason::overturned;
        break;
      }
      if (impact_within(y0, y1, a0, h, t1)) continue;
      ordinary_step(t1, y1);
    }
    res_.stop = stop;
    res_.end_time = t_;
    record(SampleKind::end);
    return res_;
  }

 private:
  void record(SampleKind kind) {
    if (!options_.record_trajectory) return;
    res_.trajectory.push_back({t_, th_, w_, kind});
  }
  void record_step() {
    if (options_.record_trajectory && t_ - last_step_record_ >= options_.record_interval) {
      record(SampleKind::step);
      last_step_record_ = t_;
    }
  }

  // the end of a step that lands exactly on the next breakpoint (or on end_time).
  double step_end(double end_time) const {
    double seg_end = std::min(ground_.next_breakpoint(t_), end_time);
    if (seg_end - t_ <= ttol(t_) && seg_end < end_time) {
      seg_end = std::min(ground_.next_breakpoint(seg_end), end_time);
    }
    const double remaining = seg_end - t_;
    const double n = std::max(1.0, std::ceil(remaining / options_.time_step * (1.0 - 1e-12)));
    return n <= 1.0 ? seg_end : t_ + remaining / n;
  }

  // state at t0 + tau on pivot s, re-integrated by one RK4 step from the step start (t0, y0).
  Phase state_at(double t0, Phase y0, double a0, double tau) const {
    return tau > 0.0 ? rhs_.step(t0, y0, s_, tau, a0) : y0;
  }

  // at rest the block moves with the ground: nothing to integrate until the ground lifts it.
  void rest_step(double t1) {
    int side = rhs_.uplift_side(rhs_.ground_after(t_));
    if (side == 0) {
      side = rhs_.uplift_side(rhs_.ground_before(t1));
      if (side == 0) {
        t_ = t1;
        record_step();
        return;
      }
      // bisect the first instant in (t, t1] at which the ground exceeds the threshold.
      double lo = t_;
      double hi = t1;
      while (hi - lo > ttol(hi)) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        const int side_mid = rhs_.uplift_side(rhs_.ground_at(mid));
        if (side_mid != 0) {
          hi = mid;
          side = side_mid;
        } else {
          lo = mid;
        }
      }
      t_ = hi;
    }
    s_ = static_cast<double>(side);
    th_ = 0.0;
    w_ = 0.0;
    if (std::isnan(res_.uplift_time)) res_.uplift_time = t_;
    record(SampleKind::uplift);
  }

  // locate a peak of |θ| (θ̇ = 0) in (0, tau_end] of the step from (t0, y0), where s θ̇ goes from
  // positive to non-positive; update max|θ| and record it.
  std::pair<double, Phase> locate_peak(double t0, Phase y0, double a0, Phase y_end, double tau_end) {
    const double s = s_;
    const auto f = [&](double tau) {
      const Phase y = state_at(t0, y0, a0, tau);
      return std::pair{s * y.omega, s * rhs_.accel(y.theta, s, rhs_.ground_at(t0 + tau))};
    };
    const double tau = find_root(f, 0.0, s * y0.omega, tau_end, s * y_end.omega, omega_tol_, ttol(t0 + tau_end));
    const Phase y = state_at(t0, y0, a0, tau);
    // a peak beyond the overturn angle is an overturn, handled (and recorded) by the caller.
    if (s * y.theta < theta_ov_) {
      res_.max_abs_theta = std::max(res_.max_abs_theta, std::abs(y.theta));
      if (options_.record_trajectory) res_.trajectory.push_back({t0 + tau, y.theta, y.omega, SampleKind::peak});
    }
    return std::pair{tau, y};
  }

  // overturning: s θ reaches the overturn angle within the step, either at its end or at a
  // peak inside it (the ground can push the block past the angle and back within one step).
  bool overturn_within(Phase y0, Phase y1, double a0, double h, double t1) {
    const double s = s_;
    const double t = t_;
    double tau_ov = (s * y1.theta >= theta_ov_) ? h : -1.0;
    if (tau_ov < 0.0 && s * w_ > 0.0 && s * y1.omega <= 0.0) {
      const auto [tau_pk, y_pk] = locate_peak(t, y0, a0, y1, h);
      if (s * y_pk.theta >= theta_ov_) tau_ov = tau_pk;
    }
    if (!(tau_ov > 0.0)) return false;
    const Phase y_ov = state_at(t, y0, a0, tau_ov);
    const auto f = [&](double tau) {
      const Phase y = state_at(t, y0, a0, tau);
      return std::pair{theta_ov_ - s * y.theta, -s * y.omega};
    };
    const double tau = find_root(f, 0.0, theta_ov_ - s * th_, tau_ov, theta_ov_ - s * y_ov.theta, theta_tol_, ttol(t1));
    const Phase y = state_at(t, y0, a0, tau);
    t_ += tau;
    th_ = y.theta;
    w_ = y.omega;
    res_.overturned = true;
    res_.failure_time = t_;
    res_.max_abs_theta = std::max(res_.max_abs_theta, theta_ov_);
    record(SampleKind::overturn);
    return true;
  }

  // impact: s θ reaches zero within the step, either at its end or by dipping through zero
  // and back inside it (a grazing return, caught where the linearly interpolated θ̇ vanishes).
  bool impact_within(Phase y0, Phase y1, double a0, double h, double t1) {
    const double s = s_;
    const double t = t_;
    const double g0 = s * th_;
    double tau_hi = -1.0;
    if (s * y1.theta <= 0.0) {
      tau_hi = h;
    } else if (s * w_ < 0.0 && s * y1.omega > 0.0) {
      const double tau_m = h * (s * w_) / (s * w_ - s * y1.omega);
      if (s * state_at(t, y0, a0, tau_m).theta <= 0.0) tau_hi = tau_m;
    }
    if (!(tau_hi > 0.0)) return false;
    const Phase y_hi = state_at(t, y0, a0, tau_hi);
    // a step starting on θ = 0 (after an impact or uplift) needs an interior point with
    // s θ > 0 to bracket the return to zero: try the apex of the local parabola, then halve.
    double tau_lo = 0.0;
    double f_lo = g0;
    if (!(g0 > 0.0)) {
      const double acc0 = s * rhs_.accel(th_, s, a0);
      double tau = (s * w_ > 0.0 && acc0 < 0.0) ? std::min(-s * w_ / acc0, 0.5 * tau_hi) : 0.5 * tau_hi;
      f_lo = 0.0;
      for (int i = 0; i < 64 && !(f_lo > 0.0); ++i, tau *= 0.5) {
        f_lo = s * state_at(t, y0, a0, tau).theta;
        tau_lo = tau;
      }
    }
    if (!(f_lo > 0.0)) {
      // the excursion off the base is below resolution (the ground barely reached the uplift
      // threshold): the block is back at rest; resume from the step end so time advances.
      t_ = t1;
      th_ = 0.0;
      w_ = 0.0;
      s_ = 0.0;
      record(SampleKind::rest);
      return true;
    }
    const auto f = [&](double tau) {
      const Phase y = state_at(t, y0, a0, tau);
      return std::pair{s * y.theta, s * y.omega};
    };
    const double tau = find_root(f, tau_lo, f_lo, tau_hi, s * y_hi.theta, theta_tol_, ttol(t1));
    const double w_minus = state_at(t, y0, a0, tau).omega;
    t_ += tau;
    th_ = 0.0;
    w_ = w_minus;
    record(SampleKind::impact_before);
    ++res_.impacts;
    // Housner impact: angular momentum about the new pivot, θ̇⁺ = r θ̇⁻ (physics.md §2).
    w_ = r_ * w_minus;
    s_ = -s_;
    if (std::abs(w_) <= w_rest_) {
      // a rebound this small would start a Zeno sequence of impacts; the rest state lifts the
      // block again at once if the ground is strong enough.
      w_ = 0.0;
      s_ = 0.0;
      record(SampleKind::rest);
    } else {
      record(SampleKind::impact_after);
    }
    return true;
  }

  void ordinary_step(double t1, Phase y1) {
    t_ = t1;
    th_ = y1.theta;
    w_ = y1.omega;
    res_.max_abs_theta = std::max(res_.max_abs_theta, std::abs(th_));
    record_step();
  }

  const GroundAcceleration& ground_;
  const RockingOptions& options_;
  const Rhs rhs_;
  const double theta_ov_;
  const double r_;
  const double w_rest_;
  const double theta_tol_;
  const double omega_tol_;
  RockingResult res_;
  double t_;
  double th_;
  double w_;
  double s_;
  double last_step_record_ = -kInf;
};

}  // namespace

RockingResult simulate_rocking(const RockingBlock& block, const GroundAcceleration& ground, double end_time,
                               const RockingOptions& options, const InitialState& initial) {
  validate_block(block);
  validate_run(options, initial, end_time);
  return Integration(block, ground, options, initial).run(end_time);
}

GroundAcceleration make_pulse(PulseShape shape, double amplitude, double duration) {
  require(std::isfinite(duration) && duration > 0.0, "pulse duration must be finite and positive");
  require(std::isfinite(amplitude), "pulse amplitude must be finite");
  const double w = 2.0 * kPi / duration;
  std::function<double(double)> f;
  switch (shape) {
    case PulseShape::one_sine:
      f = [=](double t) { return (t >= 0.0 && t <= duration) ? amplitude * std::sin(w * t) : 0.0; };
      break;
    case PulseShape::one_cosine:
      f = [=](double t) { return (t >= 0.0 && t <= duration) ? amplitude * std::cos(w * t) : 0.0; };
      break;
    case PulseShape::rectangular:
      f = [=](double t) { return (t >= 0.0 && t <= duration) ? amplitude : 0.0; };
      break;
  }
  require(static_cast<bool>(f), "unknown pulse shape");
  return GroundAcceleration::analytic(std::move(f), duration, {0.0});
}

double min_overturning_amplitude(const RockingBlock& block, PulseShape shape, double duration,
                                 const RockingOptions& options, const ThresholdOptions& search) {
  validate_block(block);
  require(std::isfinite(duration) && duration > 0.0, "pulse duration must be finite and positive");
  require(std::isfinite(search.free_time) && search.free_time >= 0.0, "free_time must be finite and non-negative");
  require(std::isfinite(search.relative_tolerance) && search.relative_tolerance > 0.0,
          "relative_tolerance must be finite and positive");
  require(std::isfinite(search.scan_ratio) && search.scan_ratio > 1.0, "scan_ratio must be > 1");
  require(std::isfinite(search.max_ratio) && search.max_ratio > 1.0, "max_ratio must be > 1");

  RockingOptions opt = options;
  opt.record_trajectory = false;
  const double end = duration + search.free_time;
  auto overturns = [&](double amplitude) {
    return simulate_rocking(block, make_pulse(shape, amplitude, duration), end, opt).overturned;
  };

  // below the uplift acceleration the block never leaves its base, so it is a safe lower bound.
  const double a_up = uplift_acceleration(block, options.linearised);
  double lo = a_up;
  double hi = a_up * search.scan_ratio;
  while (!overturns(hi)) {
    lo = hi;
    hi *= search.scan_ratio;
    if (hi > search.max_ratio * a_up) return kInf;
  }
  while (hi - lo > search.relative_tolerance * hi) {
    const double mid = 0.5 * (lo + hi);
    if (overturns(mid)) {
      hi = mid;
    } else {
      lo = mid;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace rigid::rocking
