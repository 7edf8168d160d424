#pragma once
/// The quasi-static tilt test that gives each model of the rock library (or any settled scene) its
/// toppling acceleration, and the rigid-statics estimate of a simple stack it is checked against.
/// No I/O.
#include <string>
#include <vector>

#include "rigid/scenario/scene.hpp"

namespace rigid::analysis {

/// Settings of the quasi-static tilt test.
struct TiltTestSettings {
  /// Rate of the ground-acceleration ramp (unit: g/s). It only finds a bracket: the answer comes
  /// from hold tests, so it does not depend on this rate.
  double ramp_rate = 0.05;
  /// Highest ground acceleration tried (unit: g); a model standing there is reported as +inf.
  double max_acceleration = 1.0;
  /// How long a level is held before the model counts as standing (unit: s).
  double hold_time = 2.5;
  /// A free block has gone when it tilts more than this from its settled attitude (unit: rad)...
  double tilt_threshold = 2.0 * kPi / 180.0;
  /// ...or its centroid moves more than this relative to the ground (unit: m)...
  double displacement_threshold = 0.02;
  // ...or the scene's failure rule triggers.
  /// Bisection stops when the bracket is narrower than this fraction of its top (unit: 1).
  double relative_tolerance = 0.003;
  dynamics::StepSettings step;  ///< time step etc. (automatic step by default)
};

/// Result of the tilt test in one azimuth.
struct TiltTestResult {
  double azimuth = 0;  ///< direction of the ground acceleration, from +x towards +y (unit: rad)
  /// Quasi-static toppling acceleration (unit: g): the middle of the final bracket between the
  /// highest held level the model stood and the lowest at which it went. +inf if it stood at
  /// max_acceleration during the ramp.
  double acceleration = 0;
  double bracket_low = 0;     ///< highest level it stood for the hold time (unit: g)
  double bracket_high = 0;    ///< lowest level at which a block went (unit: g)
  double ramp_detection = 0;  ///< level at which the ramp alone first saw a block go (unit: g)
  std::string block;          ///< the block that went at bracket_high
  int hold_tests = 0;
  long steps = 0;  ///< time steps simulated in total
};

/// Quasi-static tilt test of a settled scene: the smallest constant horizontal ground acceleration
/// in direction `azimuth` (unit: rad) that the model cannot stand. The fixed blocks take the
/// ground velocity of a ramp a(t) = ramp_rate g t (as the tipping tests do); when a free block goes
/// (tilt, displacement or failure rule, see TiltTestSettings), the level is refined by hold tests:
/// from a snapshot of the ramp just below the level, ramp on to it and hold it for hold_time. The
/// ramp alone lags the onset of toppling (the rock needs time to rotate that far), the hold tests
/// do not. For a rigid rectangular block of slenderness alpha the answer is g tan(alpha); the
/// study's soft Hertz contacts lower it by 1-3 % (docs/validation.md, "What contact compliance does").
TiltTestResult tilt_test(const scenario::Scene& settled, double azimuth, const TiltTestSettings& settings = {});

/// Tilt tests in `azimuths` directions evenly spaced from +x (8: every 45 degrees).
struct TiltSurvey {
  std::vector<TiltTestResult> results;
  double minimum = 0;             ///< smallest toppling acceleration (unit: g)
  double azimuth_of_minimum = 0;  ///< unit: rad
};
TiltSurvey tilt_survey(const scenario::Scene& settled, int azimuths = 8, const TiltTestSettings& settings = {});

}  // namespace rigid::analysis
