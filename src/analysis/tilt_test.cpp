// The quasi-static tilt test of a settled scene.
#include "rigid/analysis/tilt_test.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "rigid/geometry/polygon2d.hpp"

namespace rigid::analysis {

// scenes, drives and the run are scenario's; this module builds on them
using namespace scenario;
namespace {

// Decides when a free block has gone: tilt, displacement relative to the ground, or the scene's
// failure rule, all measured from the settled state.
class GoneWatch {
 public:
  GoneWatch(const Scene& scene, const TiltTestSettings& s) : scene_(scene), s_(s) {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].fixed && ground_ < 0) ground_ = static_cast<int>(i);
    }
    if (ground_ < 0) throw std::invalid_argument("tilt test: the scene has no fixed block");
  }

  // index of the first free block that has gone, or -1
  int gone(const dynamics::World& w) const {
    const auto& defs = scene_.bodies;
    const Vec3 ground_shift = w.states()[ground_].position - defs[ground_].position;
    double lowest_fixed = std::numeric_limits<double>::infinity();
    if (scene_.failure.kind == FailureRule::Kind::below) {
      for (std::size_t i = 0; i < defs.size(); ++i) {
        if (!defs[i].fixed) continue;
        for (const auto& v : w.world_vertices(static_cast<int>(i))) lowest_fixed = std::min(lowest_fixed, v.z());
      }
    }
    for (std::size_t i = 0; i < defs.size(); ++i) {
      if (defs[i].fixed) continue;
      const auto& st = w.states()[i];
      if (!st.position.allFinite() || !st.orientation.coeffs().allFinite()) {
        throw std::runtime_error("tilt test: non-finite state of block " + defs[i].name);
      }
      const double a = tilt(defs[i].orientation, st.orientation);
      const double moved = (st.position - defs[i].position - ground_shift).norm();
      const bool rule = scene_.failure.kind == FailureRule::Kind::below ? st.position.z() < lowest_fixed
                                                                        : a > scene_.failure.tilt_angle;
      if (a > s_.tilt_threshold || moved > s_.displacement_threshold || rule) return static_cast<int>(i);
    }
    return -1;
  }

 private:
  const Scene& scene_;
  const TiltTestSettings& s_;
  int ground_ = -1;
};

// Ground velocity of a ramp a(t) = rate t up to t_hold, then a constant acceleration rate t_hold.
struct RampHold {
  double rate;    // m/s^3
  double t_hold;  // s (infinity: ramp only)
  Vec3 dir;
  Vec3 at(double t) const {
    if (t <= t_hold) return 0.5 * rate * t * t * dir;
    return (0.5 * rate * t_hold * t_hold + rate * t_hold * (t - t_hold)) * dir;
  }
};

}  // namespace

TiltTestResult tilt_test(const Scene& settled, double azimuth, const TiltTestSettings& s) {
  TiltTestResult out;
  out.azimuth = azimuth;
  const GoneWatch watch(settled, s);
  const Vec3 dir(std::cos(azimuth), std::sin(azimuth), 0);
  const double rate = s.ramp_rate * kGravity;  // m/s^3
  dynamics::World world(settled.bodies, settled.law, s.step);
  const double dt = world.dt();
  const auto level_at = [&](long k) { return s.ramp_rate * double(k) * dt; };  // g

  // 1. the ramp, keeping snapshots every 0.02 g to restart the hold tests from
  struct Snapshot {
    long k;
    dynamics::World world;
  };
  std::vector<Snapshot> snaps;
  const long snap_every = std::max(1L, std::lround(0.02 / s.ramp_rate / dt));
  const RampHold ramp{rate, std::numeric_limits<double>::infinity(), dir};
  snaps.push_back({0, world});
  long k = 0;
  int gone = -1;
  while (gone < 0 && level_at(k) < s.max_acceleration) {
    world.step(dt, ramp.at(double(k) * dt), ramp.at(double(k + 1) * dt));
    ++k;
    gone = watch.gone(world);
    if (gone < 0 && k % snap_every == 0) snaps.push_back({k, world});
  }
  out.steps = k;
  if (gone < 0) {
    out.acceleration = out.bracket_high = out.ramp_detection = std::numeric_limits<double>::infinity();
    out.bracket_low = s.max_acceleration;
    return out;
  }
  out.ramp_detection = level_at(k);
  out.block = settled.bodies[static_cast<std::size_t>(gone)].name;

  // 2. hold tests: does the model stand `level` (g) for hold_time? Returns the block that went.
  const auto hold = [&](double level) {
    ++out.hold_tests;
    const double t_hold = level / s.ramp_rate;
    std::size_t i = 0;
    while (i + 1 < snaps.size() && level_at(snaps[i + 1].k) <= level) ++i;
    dynamics::World w = snaps[i].world;
    const RampHold drive{rate, t_hold, dir};
    const long end = static_cast<long>(std::ceil((t_hold + s.hold_time) / dt));
    for (long j = snaps[i].k; j < end; ++j) {
      w.step(dt, drive.at(double(j) * dt), drive.at(double(j + 1) * dt));
      ++out.steps;
      const int g = watch.gone(w);
      if (g >= 0) return g;
    }
    return -1;
  };
  double hi = out.ramp_detection, lo = -1;
  double step = std::min(0.03, 0.5 * hi);
  while (lo < 0) {
    const double level = hi - step;
    if (level <= 0) {
      lo = 0;
      break;
    }
    const int g = hold(level);
    if (g >= 0) {
      hi = level;
      out.block = settled.bodies[static_cast<std::size_t>(g)].name;
      step *= 2;
    } else {
      lo = level;
    }
  }
  while (hi - lo > s.relative_tolerance * hi) {
    const double mid = 0.5 * (lo + hi);
    const int g = hold(mid);
    if (g >= 0) {
      hi = mid;
      out.block = settled.bodies[static_cast<std::size_t>(g)].name;
    } else {
      lo = mid;
    }
  }
  out.bracket_low = lo;
  out.bracket_high = hi;
  out.acceleration = 0.5 * (lo + hi);
  return out;
}

TiltSurvey tilt_survey(const Scene& settled, int azimuths, const TiltTestSettings& settings) {
  if (azimuths < 1) throw std::invalid_argument("tilt_survey: need at least one azimuth");
  TiltSurvey out;
  out.minimum = std::numeric_limits<double>::infinity();
  for (int j = 0; j < azimuths; ++j) {
    const double az = 2.0 * kPi * double(j) / double(azimuths);
    out.results.push_back(tilt_test(settled, az, settings));
    if (out.results.back().acceleration < out.minimum) {
      out.minimum = out.results.back().acceleration;
      out.azimuth_of_minimum = az;
    }
  }
  return out;
}

}  // namespace rigid::analysis
