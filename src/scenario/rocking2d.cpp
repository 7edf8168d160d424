#include "rigid/scenario/rocking2d.hpp"

#include <algorithm>
#include <cmath>

#include "rigid/core/error.hpp"

namespace rigid::scenario {
namespace {

// World-frame extent of a body along each axis, if it is a box with faces normal to the axes.
bool axis_aligned_box(const dynamics::BodyDef& b, Vec3& lo, Vec3& hi) {
  const auto& s = b.shape;
  if (s.vertices.size() != 8 || s.faces.size() != 6) return false;
  const Mat3 r = b.orientation.toRotationMatrix();
  for (const auto& f : s.faces) {
    const Vec3 n = r * f.normal;
    const double largest = n.cwiseAbs().maxCoeff();
    if (largest < 1.0 - 1e-9) return false;
  }
  lo = Vec3::Constant(1e300);
  hi = Vec3::Constant(-1e300);
  for (const auto& v : s.vertices) {
    const Vec3 w = r * v + b.position;
    lo = lo.cwiseMin(w);
    hi = hi.cwiseMax(w);
  }
  return true;
}

}  // namespace

rocking::RockingBlock rocking_block_of(const Scene& scene) {
  const dynamics::BodyDef* block = nullptr;
  for (const auto& b : scene.bodies) {
    if (b.fixed) continue;
    if (block) throw InputError(scene.source, 0, "the 2D rocking model needs exactly one free block");
    block = &b;
  }
  if (!block) throw InputError(scene.source, 0, "the 2D rocking model needs a free block");
  Vec3 lo, hi;
  if (!axis_aligned_box(*block, lo, hi)) {
    throw InputError(scene.source, 0,
                     "the 2D rocking model needs a rectangular box block with faces normal to x, y, z");
  }
  // a fixed box whose top face carries the block
  const double size = (hi - lo).norm();
  bool supported = false;
  for (const auto& b : scene.bodies) {
    Vec3 plo, phi;
    if (!b.fixed || !axis_aligned_box(b, plo, phi)) continue;
    supported |= std::abs(phi.z() - lo.z()) < 1e-3 * size && plo.x() <= lo.x() + 1e-9 && phi.x() >= hi.x() - 1e-9;
  }
  if (!supported) {
    throw InputError(scene.source, 0,
                     "the 2D rocking model needs the block standing on a box pedestal at least as wide in x");
  }
  const double b = 0.5 * (hi.x() - lo.x());
  const double h = 0.5 * (hi.z() - lo.z());
  return rocking::RockingBlock::rectangular(b, h);
}

RunOutcome run_rocking2d(const rocking::RockingBlock& block, const std::vector<double>& ax, double dt,
                         const RunSettings& settings) {
  const double motion_end = ax.size() < 2 ? 0.0 : dt * double(ax.size() - 1);
  const double end = settings.duration > 0 ? settings.duration : motion_end + settings.free_time;
  rocking::RockingOptions options;
  options.overturn_angle = kRocking2dOverturnAngle;
  const auto ground = rocking::GroundAcceleration::sampled(ax, dt);
  const rocking::RockingResult r = rocking::simulate_rocking(block, ground, end, options);
  RunOutcome out;
  out.overturned = r.overturned;
  if (r.overturned) out.failure_time_s = r.failure_time;
  out.failed_block = r.overturned ? "block" : "";
  out.dt_s = options.time_step;
  out.simulated_s = r.end_time;
  out.steps = std::lround(r.end_time / options.time_step);
  out.max_tilt_rad = r.max_abs_theta;
  out.ended_at_rest = r.stop == rocking::StopReason::at_rest;
  return out;
}

}  // namespace rigid::scenario
