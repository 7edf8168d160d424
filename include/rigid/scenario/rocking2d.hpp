#pragma once
/// The 2D Housner rocking reference applied to a scene: a box block standing on a box pedestal
/// rocks in the x-z plane, driven by the x component of the ground acceleration (physics.md §2,
/// the model the study's validation compares with).
#include <vector>

#include "rigid/rocking/housner.hpp"
#include "rigid/scenario/scene.hpp"

namespace rigid::scenario {

/// The rocking block of a scene: one free block that is a rectangular box with faces normal to
/// the world axes, standing on a fixed box with a horizontal top face. Half-width b = half the
/// block's extent along x, half-height h; restitution r = 1 - 1.5 sin^2(alpha) (Housner).
/// Throws rigid::InputError(scene.source, 0, reason) for any other scene.
rocking::RockingBlock rocking_block_of(const Scene& scene);

/// Overturning angle of the 2D model in runs and campaigns: the block lies on its side (pi/2),
/// which matches the 3D failure rules (falling off the pedestal, or a large tilt) better than
/// the static instability angle alpha; short pulses can carry a block past alpha and back.
inline constexpr double kRocking2dOverturnAngle = kPi / 2;

/// Runs the 2D model on the x acceleration `ax` (unit: m/s^2, sampled every dt s from t = 0) for
/// the duration the settings give (motion plus free time, or `duration`). The outcome uses the
/// 3D fields: max_tilt_rad = max |theta|, max_slip_m = 0, steps = integration steps.
RunOutcome run_rocking2d(const rocking::RockingBlock& block, const std::vector<double>& ax, double dt,
                         const RunSettings& settings);

}  // namespace rigid::scenario
