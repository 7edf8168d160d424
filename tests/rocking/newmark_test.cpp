// Newmark (1965) rigid-plastic sliding against closed forms: a block sticks while the base
// acceleration stays within mu g, and otherwise slides against the base with relative acceleration
// -(a_g - mu g) (lagging it), then decelerates at mu g once the base is quiet.
#include "rigid/rocking/newmark.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rigid/core/types.hpp"

namespace rigid::rocking {
namespace {

constexpr double g = kGravity;

// a constant for `duration`, sampled every dt (the samples end at `duration`)
std::vector<double> constant_pulse(double a, double duration, double dt) {
  return std::vector<double>(static_cast<std::size_t>(std::lround(duration / dt)) + 1, a);
}

TEST(Newmark, ConstantPulseAboveTheFrictionLimit) {
  // a > mu g for T: v(T) = -(a - mu g) T, u(T) = -(a - mu g) T^2 / 2, then the block decelerates
  // at mu g and stops after a further v(T)^2 / (2 mu g):
  // u = -(a - mu g) T^2 / 2 (1 + (a - mu g) / (mu g)) = -a (a - mu g) T^2 / (2 mu g)
  const double mu = 0.2, a = 0.5 * g, T = 0.5;
  const double expected = -a * (a - mu * g) * T * T / (2 * mu * g);  // -0.919 m
  EXPECT_NEAR(newmark_displacement(constant_pulse(a, T, 0.01), 0.01, mu), expected, 1e-4 * std::abs(expected));
  // the mirror pulse slides the other way by as much
  EXPECT_NEAR(newmark_displacement(constant_pulse(-a, T, 0.01), 0.01, mu), -expected, 1e-4 * std::abs(expected));
}

TEST(Newmark, StaysPutWithinTheFrictionLimit) {
  EXPECT_EQ(newmark_displacement(constant_pulse(0.19 * g, 1.0, 0.01), 0.01, 0.2), 0.0);
  EXPECT_EQ(newmark_displacement(constant_pulse(-0.199 * g, 1.0, 0.01), 0.01, 0.2), 0.0);
}

TEST(Newmark, LinearRampThenRelease) {
  // two samples, 0 and A, dt = T: a(t) = A t / T up to T (linear between samples), 0 after.
  // Sliding starts at t1 = mu g T / A; while it lasts v' = -(A / T)(t - t1), so
  // v(T) = -(A / 2T)(T - t1)^2 and u(T) = -(A / 6T)(T - t1)^3; then it decelerates at mu g
  // over a further v(T)^2 / (2 mu g).
  const double mu = 0.2, A = 0.6 * g, T = 0.4;
  const double t1 = mu * g * T / A;
  const double vT = -(A / (2 * T)) * (T - t1) * (T - t1);
  const double expected = -(A / (6 * T)) * std::pow(T - t1, 3) - vT * vT / (2 * mu * g);
  EXPECT_NEAR(newmark_displacement({0.0, A}, T, mu), expected, 1e-4 * std::abs(expected));
}

}  // namespace
}  // namespace rigid::rocking
