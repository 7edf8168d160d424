// Tests of the 2D Housner rocking model against closed forms of physics.md §2 and against an
// independent piecewise-analytic solution of the linearised equation. No expected value below
// comes from the code under test.
#include "rigid/rocking/housner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "rigid/core/types.hpp"

namespace rigid::rocking {
namespace {

constexpr double g = kGravity;

// physics.md §2 worked example: b = 0.5 m, h = 1.5 m.
RockingBlock worked_block() { return RockingBlock::rectangular(0.5, 1.5); }

// physics.md §11 validation block with alpha = 0.1 rad, 1 m tall.
RockingBlock slender_block() { return RockingBlock::rectangular(0.5 * std::tan(0.1), 0.5); }

std::vector<TrajectorySample> of_kind(const RockingResult& r, SampleKind kind) {
  std::vector<TrajectorySample> out;
  for (const auto& s : r.trajectory) {
    if (s.kind == kind) out.push_back(s);
  }
  return out;
}

// ------------------------------------------------------------------------------------------------
// Block parameters.

TEST(RockingBlock, WorkedExampleMatchesPhysicsMd) {
  const RockingBlock b = worked_block();
  EXPECT_NEAR(b.R, 1.581139, 1e-6);
  EXPECT_NEAR(b.alpha, 0.3217506, 1e-7);
  EXPECT_NEAR(std::tan(b.alpha), 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(b.p, 2.156781, 1e-6);
  EXPECT_NEAR(b.restitution, 0.85, 1e-14);
  EXPECT_NEAR(uplift_acceleration(b), g / 3.0, 1e-13);
  EXPECT_NEAR(uplift_acceleration(b, true), g * b.alpha, 1e-13);
}

TEST(RockingBlock, GeneralWithRectangleInertiaEqualsRectangular) {
  const RockingBlock rect = worked_block();
  // I_O of a b x h rectangle about a base corner = (4/3) m R² (physics.md §2).
  const double m = 7.25;
  const RockingBlock gen = RockingBlock::general(rect.alpha, rect.R, m, 4.0 / 3.0 * m * rect.R * rect.R);
  EXPECT_DOUBLE_EQ(gen.alpha, rect.alpha);
  EXPECT_DOUBLE_EQ(gen.R, rect.R);
  EXPECT_NEAR(gen.p, rect.p, 1e-14);
  EXPECT_NEAR(gen.restitution, rect.restitution, 1e-14);
  EXPECT_THROW(RockingBlock::general(0.3, 1.0, 1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(RockingBlock::rectangular(-1.0, 1.0), std::invalid_argument);
}

// ------------------------------------------------------------------------------------------------
// Ground motion.

TEST(RockingGroundAcceleration, SampledInterpolatesLinearlyAndIsZeroOutside) {
  const std::vector<double> v{1.0, 3.0, -1.0};
  const GroundAcceleration gm = GroundAcceleration::sampled(v, 0.5, 2.0, 2.0);
  EXPECT_EQ(gm(1.99), 0.0);
  EXPECT_DOUBLE_EQ(gm(2.0), 2.0);
  EXPECT_DOUBLE_EQ(gm(2.25), 4.0);
  EXPECT_DOUBLE_EQ(gm(2.5), 6.0);
  EXPECT_DOUBLE_EQ(gm(2.75), 2.0);
  EXPECT_DOUBLE_EQ(gm(3.0), -2.0);
  EXPECT_EQ(gm(3.0001), 0.0);
  EXPECT_DOUBLE_EQ(gm.end_time(), 3.0);
  EXPECT_DOUBLE_EQ(gm.next_breakpoint(0.0), 2.0);
  EXPECT_DOUBLE_EQ(gm.next_breakpoint(2.0), 2.5);
  EXPECT_DOUBLE_EQ(gm.next_breakpoint(2.6), 3.0);
  EXPECT_TRUE(std::isinf(gm.next_breakpoint(3.0)));
  const std::vector<double> bad{0.0, std::numeric_limits<double>::quiet_NaN()};
  EXPECT_THROW(GroundAcceleration::sampled(bad, 0.01), std::invalid_argument);
}

TEST(RockingGroundAcceleration, PulsesFollowTheirDefinitions) {
  const double T = 0.8;
  const GroundAcceleration s = make_pulse(PulseShape::one_sine, 2.0, T);
  const GroundAcceleration c = make_pulse(PulseShape::one_cosine, 2.0, T);
  const GroundAcceleration r = make_pulse(PulseShape::rectangular, 2.0, T);
  EXPECT_NEAR(s(T / 4), 2.0, 1e-15);
  EXPECT_NEAR(c(T / 2), -2.0, 1e-15);
  EXPECT_EQ(r(T), 2.0);
  for (const GroundAcceleration* gm : {&s, &c, &r}) {
    EXPECT_EQ((*gm)(-1e-9), 0.0);
    EXPECT_EQ((*gm)(T + 1e-9), 0.0);
    EXPECT_DOUBLE_EQ(gm->end_time(), T);
    EXPECT_DOUBLE_EQ(gm->next_breakpoint(0.1), T);
  }
}

// A record sampled from an analytic pulse gives the response of the pulse: linear interpolation
// at dt = 1 ms misses the sine by at most A (ω dt)²/8 ≈ 5e-6 A. Also checks the start offset.
TEST(RockingGroundAcceleration, SampledPulseMatchesAnalyticPulse) {
  const RockingBlock b = worked_block();
  const double A = 1.2 * uplift_acceleration(b);
  const double T = 1.0;
  const double dt = 1e-3;
  const double offset = 2.0;
  std::vector<double> v;
  for (int k = 0; k <= 1000; ++k) v.push_back(A * std::sin(2.0 * kPi * k * dt / T));
  const RockingResult ra = simulate_rocking(b, make_pulse(PulseShape::one_sine, A, T), 6.0);
  const RockingResult rs = simulate_rocking(b, GroundAcceleration::sampled(v, dt, offset), 6.0 + offset);
  ASSERT_GT(ra.max_abs_theta, 0.0);
  EXPECT_FALSE(ra.overturned);
  EXPECT_EQ(ra.overturned, rs.overturned);
  EXPECT_EQ(ra.impacts, rs.impacts);
  EXPECT_NEAR(rs.max_abs_theta, ra.max_abs_theta, 1e-3 * ra.max_abs_theta);
  EXPECT_NEAR(rs.uplift_time - offset, ra.uplift_time, 1e-4);
}

// ------------------------------------------------------------------------------------------------
// 1. Rectangular pulse: a_min = g α / (1 − e^(−p t1)) for the linearised equation (physics.md §2,
// derived there and re-derived here: θ = (a/g − α)(cosh pt − 1) during the pulse, and after it
// the block overturns iff the growing mode of θ − α is non-negative).

TEST(RockingThreshold, RectangularPulseLinearisedMatchesClosedForm) {
  RockingOptions opt;
  opt.linearised = true;
  ThresholdOptions search;
  search.relative_tolerance = 1e-7;
  for (const RockingBlock& b : {worked_block(), slender_block()}) {
    for (const double t1 : {0.25, 0.5, 1.0}) {
      const double closed = g * b.alpha / (1.0 - std::exp(-b.p * t1));
      const double a = min_overturning_amplitude(b, PulseShape::rectangular, t1, opt, search);
      EXPECT_NEAR(a / closed, 1.0, 1e-6) << "alpha " << b.alpha << ", t1 " << t1;
    }
  }
  // the closed form reproduces the values tabulated in physics.md §2.
  const RockingBlock b = worked_block();
  EXPECT_NEAR(1.0 / (1.0 - std::exp(-b.p * 0.25)), 2.3993, 1e-4);
  EXPECT_NEAR(1.0 / (1.0 - std::exp(-b.p * 0.5)), 1.5155, 1e-4);
  EXPECT_NEAR(1.0 / (1.0 - std::exp(-b.p * 1.0)), 1.1308, 1e-4);
}

// The nonlinear equation differs from the linearised one only through sin x ≈ x (relative error
// ≤ x²/6), cos x ≈ 1 (≤ x²/2) and tan α ≈ α (α²/3), with |x| ≤ α; each shifts the threshold by a
// relative O(α²), so α² (1% for α = 0.1) bounds the difference for a slender block.
TEST(RockingThreshold, RectangularPulseNonlinearSlenderWithinAlphaSquared) {
  const RockingBlock b = slender_block();
  ThresholdOptions search;
  search.relative_tolerance = 1e-6;
  for (const double t1 : {0.25, 0.5, 1.0}) {
    const double closed = g * b.alpha / (1.0 - std::exp(-b.p * t1));
    const double a = min_overturning_amplitude(b, PulseShape::rectangular, t1, {}, search);
    EXPECT_NEAR(a / closed, 1.0, b.alpha * b.alpha) << "t1 " << t1;
  }
}

// ------------------------------------------------------------------------------------------------
// 2. Free rocking (linearised). Released from θ0 at rest: θ = α − (α − θ0) cosh(pt), so θ = 0
// after t = (1/p) cosh⁻¹(1/(1 − θ0/α)), a quarter of the free-rocking period (physics.md §2).
// After an impact at speed ω
// the block leaves θ = 0 and returns after t = (2/p) atanh(ω/(p α)), from
// θ = α (1 − cosh pt) + (ω/p) sinh pt = 0.

TEST(FreeRocking, TimeToFirstImpactMatchesLinearisedSolution) {
  const RockingBlock b = worked_block();
  RockingOptions opt;
  opt.linearised = true;
  opt.record_trajectory = true;
  for (const double f : {0.05, 0.3, 0.6, 0.95}) {
    for (const double sign : {1.0, -1.0}) {
      const double theta0 = sign * f * b.alpha;
      const RockingResult r = simulate_rocking(b, GroundAcceleration(), 5.0, opt, {0.0, theta0, 0.0});
      const auto impacts = of_kind(r, SampleKind::impact_before);
      ASSERT_GE(impacts.size(), 2u);
      const double t_first = std::acosh(1.0 / (1.0 - f)) / b.p;
      EXPECT_NEAR(impacts[0].t / t_first, 1.0, 1e-9) << "theta0/alpha " << theta0 / b.alpha;
      // the impact speed from the same solution: p sqrt(α² − (α − θ0)²).
      const double w1 = b.p * std::sqrt(b.alpha * b.alpha - (b.alpha - f * b.alpha) * (b.alpha - f * b.alpha));
      EXPECT_NEAR(std::abs(impacts[0].theta_dot) / w1, 1.0, 1e-9);
      EXPECT_LT(impacts[0].theta_dot * sign, 0.0);
      const double flight = 2.0 / b.p * std::atanh(b.restitution * w1 / (b.p * b.alpha));
      EXPECT_NEAR((impacts[1].t - impacts[0].t) / flight, 1.0, 1e-9);
    }
  }
}

// ------------------------------------------------------------------------------------------------
// 3. Restitution (nonlinear). Released from θ0, the block hits at |θ̇⁻| = p sqrt(2(cos(α − θ0) −
// cos α)) (energy, physics.md §2); each impact multiplies θ̇ by r = 1 − 1.5 sin²α and the energy
// by r², so successive impact speeds fall by r and successive peaks obey
// cos(α − θ_{k+1}) − cos α = r² (cos(α − θ_k) − cos α).

TEST(Restitution, ImpactsFollowHousnerAngularMomentumRule) {
  const RockingBlock b = worked_block();
  const double r = 1.0 - 1.5 * std::pow(std::sin(b.alpha), 2);
  ASSERT_NEAR(r, 0.85, 1e-14);
  RockingOptions opt;
  opt.record_trajectory = true;
  const double theta0 = 0.6 * b.alpha;
  const RockingResult res = simulate_rocking(b, GroundAcceleration(), 8.0, opt, {0.0, theta0, 0.0});
  const auto before = of_kind(res, SampleKind::impact_before);
  const auto after = of_kind(res, SampleKind::impact_after);
  ASSERT_GE(after.size(), 30u);
  // the ratios are checked over the first 30 impacts (amplitudes down to ~1e-4 α); later ones
  // are so small that round-off in the test's own cos differences exceeds 1e-8.
  constexpr std::size_t kChecked = 30;
  const double w1 = b.p * std::sqrt(2.0 * (std::cos(b.alpha - theta0) - std::cos(b.alpha)));
  EXPECT_NEAR(std::abs(before[0].theta_dot) / w1, 1.0, 1e-9);
  for (std::size_t k = 0; k < kChecked; ++k) {
    EXPECT_EQ(before[k].t, after[k].t);
    EXPECT_NEAR(after[k].theta_dot / before[k].theta_dot, r, 1e-12);
    if (k > 0) {
      EXPECT_NEAR(before[k].theta_dot / before[k - 1].theta_dot, -r, 1e-8) << "impact " << k;
    }
  }
  const auto peaks = of_kind(res, SampleKind::peak);
  ASSERT_GE(peaks.size(), kChecked);
  // first peak, on the other side: cos(α − |θ1|) − cos α = r² (cos(α − θ0) − cos α).
  const double theta1 =
      std::acos(std::cos(b.alpha) + r * r * (std::cos(b.alpha - theta0) - std::cos(b.alpha))) - b.alpha;
  EXPECT_NEAR(peaks[0].theta / theta1, 1.0, 1e-9);
  auto excess = [&](double th) { return std::cos(b.alpha - std::abs(th)) - std::cos(b.alpha); };
  for (std::size_t k = 1; k < kChecked; ++k) {
    EXPECT_LT(peaks[k].theta * peaks[k - 1].theta, 0.0);
    EXPECT_NEAR(excess(peaks[k].theta) / excess(peaks[k - 1].theta), r * r, 1e-8) << "peak " << k;
  }
}

// Zeno: the impact sequence is geometric; the block must come to rest after the ground has ended.
TEST(Restitution, FreeRockingComesToRest) {
  const RockingBlock b = worked_block();
  const RockingResult res = simulate_rocking(b, GroundAcceleration(), 100.0, {}, {0.0, 0.5 * b.alpha, 0.0});
  EXPECT_EQ(res.stop, StopReason::at_rest);
  EXPECT_FALSE(res.overturned);
  EXPECT_LT(res.end_time, 100.0);
  // rest once |θ̇⁺| ≤ 1e-4 of the critical speed: about ln(1e-4 w_c / w1) / ln r impacts.
  EXPECT_GT(res.impacts, 40);
  EXPECT_LT(res.impacts, 80);
}

// ------------------------------------------------------------------------------------------------
// 4. Quasi-static uplift: a slowly ramped acceleration lifts the block when |ü_g| = g tanα
// (g α linearised), toward +θ for ü_g < 0 (header sign convention).

TEST(QuasiStatic, SlowRampLiftsAtUpliftAcceleration) {
  const RockingBlock b = worked_block();
  const double c = 0.05 * g;  // ramp rate (unit: m/s^3)
  for (const bool linear : {false, true}) {
    for (const double sign : {-1.0, 1.0}) {
      RockingOptions opt;
      opt.linearised = linear;
      opt.record_trajectory = true;
      opt.record_interval = 0.01;
      const double expected = linear ? g * b.alpha : g * std::tan(b.alpha);
      const GroundAcceleration ramp = GroundAcceleration::analytic([=](double t) { return sign * c * t; }, 20.0);
      const RockingResult r = simulate_rocking(b, ramp, 20.0, opt);
      ASSERT_FALSE(std::isnan(r.uplift_time));
      EXPECT_NEAR(c * r.uplift_time / expected, 1.0, 1e-6);
      // a sustained excess over the threshold topples the block, away from the acceleration.
      EXPECT_TRUE(r.overturned);
      EXPECT_GT(r.failure_time, r.uplift_time);
      EXPECT_LT(r.trajectory.back().theta * sign, 0.0);
      EXPECT_EQ(r.impacts, 0);
    }
  }
}

TEST(QuasiStatic, BelowThresholdTheBlockNeverLifts) {
  const RockingBlock b = worked_block();
  const double hold = 0.99 * g * std::tan(b.alpha);
  const GroundAcceleration gm =
      GroundAcceleration::analytic([=](double t) { return -std::min(t, 1.0) * hold; }, 6.0, {1.0});
  const RockingResult r = simulate_rocking(b, gm, 10.0);
  EXPECT_EQ(r.max_abs_theta, 0.0);
  EXPECT_EQ(r.impacts, 0);
  EXPECT_TRUE(std::isnan(r.uplift_time));
  EXPECT_EQ(r.stop, StopReason::at_rest);
  EXPECT_DOUBLE_EQ(r.end_time, 6.0);
}

// ------------------------------------------------------------------------------------------------
// 5. Energy (physics.md §2): conserved between impacts with no ground motion, multiplied by r² at
// each impact. RK4 at p h ≈ 2e-4 has a local error ~ (p h)^5, far below 1e-8 over a few seconds.

TEST(Energy, ConservedBetweenImpactsWithoutGroundMotion) {
  for (const bool linear : {false, true}) {
    for (const RockingBlock& b : {worked_block(), slender_block()}) {
      RockingOptions opt;
      opt.linearised = linear;
      opt.record_trajectory = true;
      const RockingResult res = simulate_rocking(b, GroundAcceleration(), 6.0, opt, {0.0, 0.9 * b.alpha, 0.0});
      double e_phase = rocking_energy(b, 0.9 * b.alpha, 0.0, linear);
      int checked = 0;
      for (const auto& s : res.trajectory) {
        if (s.kind == SampleKind::impact_after) e_phase *= b.restitution * b.restitution;
        if (s.kind == SampleKind::rest || s.kind == SampleKind::end) break;
        const double e = rocking_energy(b, s.theta, s.theta_dot, linear);
        ASSERT_NEAR(e / e_phase, 1.0, 1e-8) << "t " << s.t << " linear " << linear;
        ++checked;
      }
      EXPECT_GT(checked, 10000);
    }
  }
}

// ------------------------------------------------------------------------------------------------
// 6. One-sine pulses (Zhang & Makris 2001; physics.md §2): a_min/(g tanα) → 1 as ωp/p → 0 and
// grows without bound for short pulses. For the short-pulse end the linearised equation gives an
// asymptote: when p T → 0 gravity and the block's own motion are negligible during the pulse, the
// ground's second integral ∫∫ A sin = A T/ωp lifts the block by p² (A/g) T²/(2π) with ~zero net
// velocity, and overturning needs that lift to reach α:
//   a_min/(g α) → 2π/(p T)² = (ωp/p)²/(2π),
// with neglected terms of relative order (p T)² = (2π p/ωp)².

TEST(OneSinePulse, ThresholdTrendAndLongPulseLimit) {
  const RockingBlock b = worked_block();
  const double a_up = g * std::tan(b.alpha);
  double previous = 1.0;
  for (const double x : {1.0 / 16, 1.0 / 8, 1.0 / 4, 1.0 / 2, 1.0, 2.0, 4.0, 8.0}) {
    const double T = 2.0 * kPi / (x * b.p);
    RockingOptions opt;
    // long pulses: p h = 1e-3 still leaves RK4 errors ~1e-15 per step.
    opt.time_step = T > 5.0 ? 5e-4 : 1e-4;
    ThresholdOptions search;
    search.relative_tolerance = 1e-5;
    const double ratio = min_overturning_amplitude(b, PulseShape::one_sine, T, opt, search) / a_up;
    EXPECT_GT(ratio, previous) << "omega_p/p " << x;
    if (x < 0.1) {
      EXPECT_LT(ratio, 1.01) << "long-pulse limit";
    }
    previous = ratio;
  }
  EXPECT_GT(previous, 8.0);  // far above the quasi-static value for ωp/p = 8
}

TEST(OneSinePulse, ShortPulseLinearisedAsymptote) {
  const RockingBlock b = worked_block();
  const double x = 64.0;
  const double T = 2.0 * kPi / (x * b.p);
  RockingOptions opt;
  opt.linearised = true;
  opt.time_step = T / 200.0;
  ThresholdOptions search;
  search.relative_tolerance = 1e-5;
  search.max_ratio = 2000.0;
  const double ratio = min_overturning_amplitude(b, PulseShape::one_sine, T, opt, search) / (g * b.alpha);
  const double asymptote = x * x / (2.0 * kPi);
  EXPECT_NEAR(ratio / asymptote, 1.0, std::pow(b.p * T, 2));
}

// ------------------------------------------------------------------------------------------------
// Independent oracle: the linearised equation is linear on each side, so between events its exact
// solution is hyperbolic functions plus a particular solution of the pulse. This propagates that
// solution event by event (uplift from rest, impacts with θ̇⁺ = r θ̇⁻, return to rest below the
// same rest speed, overturn at |θ| = α), locating events by a fine scan and bisection on the
// closed-form θ(t). It shares no integrator with the code under test.

class AnalyticLinearRocker {
 public:
  AnalyticLinearRocker(const RockingBlock& b, PulseShape shape, double A, double T)
      : b_(b), shape_(shape), A_(A), T_(T), w_(2.0 * kPi / T) {}

  double ground(double t) const {
    if (t < 0.0 || t > T_) return 0.0;
    switch (shape_) {
      case PulseShape::one_sine:
        return A_ * std::sin(w_ * t);
      case PulseShape::one_cosine:
        return A_ * std::cos(w_ * t);
      case PulseShape::rectangular:
        return A_;
    }
    return 0.0;
  }

  // true if the block overturns before t_end.
  bool overturns(double t_end) const {
    const double alpha = b_.alpha;
    const double w_rest = 1e-4 * b_.p * alpha;  // linearised critical speed p α
    double t = 0.0;
    double s = 0.0;    // side, 0 = rest
    double eta = 0.0;  // s θ
    double eta_dot = 0.0;
    while (t < t_end) {
      if (s == 0.0) {
        // next instant the ground exceeds g α (uplift), scanning the pulse.
        double tu = -1.0;
        if (std::abs(ground(t)) > g * alpha && t < T_) {
          tu = t;
        } else {
          const double d = T_ / 20000.0;
          for (double a = t; a < T_ && tu < 0.0; a += d) {
            const double bnext = std::min(a + d, T_);
            if (std::abs(ground(bnext)) > g * alpha) {
              double lo = a, hi = bnext;
              for (int i = 0; i < 80; ++i) {
                const double mid = 0.5 * (lo + hi);
                (std::abs(ground(mid)) > g * alpha ? hi : lo) = mid;
              }
              tu = hi;
            }
          }
        }
        if (tu < 0.0) return false;  // the ground never lifts it again
        t = tu;
        s = ground(t) < 0.0 ? 1.0 : -1.0;
        eta = 0.0;
        eta_dot = 0.0;
      }
      // exact phase on side s from (t, eta, eta_dot): phi = eta − α obeys
      // phi'' = p² phi − p² s ü_g/g.
      const double p = b_.p;
      const double t0 = t;
      auto particular = [&](double tt, double* d) {
        if (tt > T_) {
          *d = 0.0;
          return 0.0;
        }
        const double k = (shape_ == PulseShape::rectangular) ? s * A_ / g : p * p * s * A_ / (g * (w_ * w_ + p * p));
        switch (shape_) {
          case PulseShape::one_sine:
            *d = k * w_ * std::cos(w_ * tt);
            return k * std::sin(w_ * tt);
          case PulseShape::one_cosine:
            *d = -k * w_ * std::sin(w_ * tt);
            return k * std::cos(w_ * tt);
          case PulseShape::rectangular:
            *d = 0.0;
            return k;
        }
        return 0.0;
      };
      // the phase ends at the pulse end (the particular solution changes) or at an event.
      const double t_stop = (t0 < T_) ? std::min(T_, t_end) : t_end;
      double dp0 = 0.0;
      const double pp0 = particular(t0 < T_ ? t0 : T_ + 1.0, &dp0);
      const double c1 = (eta - alpha) - pp0;
      const double c2 = (eta_dot - dp0) / p;
      auto phi = [&](double tt, double* dphi) {
        double dpp = 0.0;
        const double pp = particular(t0 < T_ ? std::min(tt, T_) : T_ + 1.0, &dpp);
        const double x = p * (tt - t0);
        *dphi = p * (c1 * std::sinh(x) + c2 * std::cosh(x)) + dpp;
        return c1 * std::cosh(x) + c2 * std::sinh(x) + pp;
      };
      // scan for overturn (phi ≥ 0) or impact (phi ≤ −α); refine near the start for quick
      // returns after an impact or uplift.
      const double d = std::min(1e-3, (t_stop - t0) / 200.0);
      double prev = t0;
      double ta = -1.0;
      bool is_overturn = false;
      for (double step = d; prev < t_stop && ta < 0.0;) {
        const double tb = std::min(prev + step, t_stop);
        double dd = 0.0;
        const double f = phi(tb, &dd);
        if (f >= 0.0 || f <= -alpha) {
          if (prev == t0 && f <= -alpha && step > 1e-14) {
            step *= 0.5;  // the excursion may be shorter than one scan cell
            continue;
          }
          is_overturn = f >= 0.0;
          const double target = is_overturn ? 0.0 : -alpha;
          double lo = prev, hi = tb;
          for (int i = 0; i < 100; ++i) {
            const double mid = 0.5 * (lo + hi);
            double dm = 0.0;
            const double fm = phi(mid, &dm) - target;
            ((is_overturn ? fm >= 0.0 : fm <= 0.0) ? hi : lo) = mid;
          }
          ta = hi;
        }
        prev = tb;
        step = d;
      }
      if (ta < 0.0) {
        // no event before t_stop: continue with the next phase (after the pulse) or stop.
        double dphi = 0.0;
        const double f = phi(t_stop, &dphi);
        t = t_stop;
        eta = f + alpha;
        eta_dot = dphi;
        if (t_stop >= t_end) return false;
        continue;
      }
      if (is_overturn) return true;
      double dphi = 0.0;
      phi(ta, &dphi);
      // impact: θ̇⁺ = r θ̇⁻ about the other corner; in side coordinates eta_dot flips sign.
      t = ta;
      const double w_after = b_.restitution * std::abs(dphi);
      s = -s;
      eta = 0.0;
      eta_dot = w_after;
      if (w_after <= w_rest) s = 0.0;
    }
    return false;
  }

 private:
  RockingBlock b_;
  PulseShape shape_;
  double A_, T_, w_;
};

// scan upward from g α by 2% and bisect, as min_overturning_amplitude() does, so both searches
// bracket the same first overturning amplitude.
double analytic_threshold(const RockingBlock& b, PulseShape shape, double T, double free_time, double rel_tol) {
  const double a_up = g * b.alpha;
  double lo = a_up;
  double hi = a_up * 1.02;
  auto over = [&](double A) { return AnalyticLinearRocker(b, shape, A, T).overturns(T + free_time); };
  while (!over(hi)) {
    lo = hi;
    hi *= 1.02;
    if (hi > 100.0 * a_up) return std::numeric_limits<double>::infinity();
  }
  while (hi - lo > rel_tol * hi) {
    const double mid = 0.5 * (lo + hi);
    (over(mid) ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// Covers both overturning modes: for ωp/p = 2 and 4 a one-sine pulse overturns the block only
// after an impact during the pulse (mode 2), at a far lower amplitude than without one.
TEST(LinearisedPulses, ThresholdsMatchPiecewiseAnalyticSolution) {
  const RockingBlock b = worked_block();
  RockingOptions opt;
  opt.linearised = true;
  ThresholdOptions search;
  search.relative_tolerance = 1e-6;
  search.free_time = 10.0;
  for (const PulseShape shape : {PulseShape::one_sine, PulseShape::one_cosine}) {
    for (const double x : {0.5, 1.0, 2.0, 4.0, 8.0}) {
      const double T = 2.0 * kPi / (x * b.p);
      const double expected = analytic_threshold(b, shape, T, search.free_time, 1e-6);
      const double a = min_overturning_amplitude(b, shape, T, opt, search);
      EXPECT_NEAR(a / expected, 1.0, 1e-4) << "shape " << static_cast<int>(shape) << ", omega_p/p " << x;
    }
  }
}

// ------------------------------------------------------------------------------------------------
// Symmetry and determinism.

// (θ, ü_g) → (−θ, −ü_g) leaves the equation unchanged (header), so a mirrored pulse gives the
// mirrored trajectory.
TEST(RockingSymmetry, MirroredGroundGivesMirroredResponse) {
  const RockingBlock b = worked_block();
  const double A = 1.5 * uplift_acceleration(b);
  RockingOptions opt;
  opt.record_trajectory = true;
  const RockingResult rp = simulate_rocking(b, make_pulse(PulseShape::one_sine, A, 1.5), 6.0, opt);
  const RockingResult rm = simulate_rocking(b, make_pulse(PulseShape::one_sine, -A, 1.5), 6.0, opt);
  ASSERT_EQ(rp.trajectory.size(), rm.trajectory.size());
  ASSERT_GT(rp.impacts, 0);
  EXPECT_EQ(rp.impacts, rm.impacts);
  EXPECT_EQ(rp.overturned, rm.overturned);
  for (std::size_t k = 0; k < rp.trajectory.size(); ++k) {
    EXPECT_EQ(rp.trajectory[k].t, rm.trajectory[k].t);
    EXPECT_NEAR(rp.trajectory[k].theta, -rm.trajectory[k].theta, 1e-14);
  }
}

TEST(RockingDeterminism, SameInputsGiveIdenticalResults) {
  const RockingBlock b = slender_block();
  std::vector<double> v;
  for (int k = 0; k < 2000; ++k) {
    const double t = 0.005 * k;
    v.push_back(0.15 * g * std::sin(2.0 * kPi * 1.7 * t) * std::exp(-0.3 * t) +
                0.08 * g * std::sin(2.0 * kPi * 4.3 * t + 1.0));
  }
  const GroundAcceleration gm = GroundAcceleration::sampled(v, 0.005);
  const RockingResult a = simulate_rocking(b, gm, 15.0);
  const RockingResult c = simulate_rocking(b, gm, 15.0);
  EXPECT_GT(a.impacts, 0);
  EXPECT_EQ(a.overturned, c.overturned);
  EXPECT_EQ(a.impacts, c.impacts);
  EXPECT_EQ(a.max_abs_theta, c.max_abs_theta);
  EXPECT_EQ(a.end_time, c.end_time);
}

TEST(RockingSimulate, RejectsInvalidInput) {
  RockingBlock b = worked_block();
  EXPECT_THROW(simulate_rocking(b, GroundAcceleration(), -1.0), std::invalid_argument);
  RockingOptions opt;
  opt.time_step = 0.0;
  EXPECT_THROW(simulate_rocking(b, GroundAcceleration(), 1.0, opt), std::invalid_argument);
  b.restitution = 1.5;
  EXPECT_THROW(simulate_rocking(b, GroundAcceleration(), 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace rigid::rocking
