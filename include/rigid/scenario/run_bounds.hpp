#pragma once
/// Bounds that refuse a run as bad input before any work (docs/robustness.md): a step above what
/// the contact model allows gives a wrong answer with exit 0, a step count beyond any budget is a
/// hang, and blocks that start deep inside each other explode. Each check throws
/// rigid::InputError without a file; the caller (io, app) adds the file or the option.
#include <vector>

#include "rigid/scenario/scene.hpp"

namespace rigid::scenario {

/// Most steps one run may take (unit: 1): about an hour of wall time at the cheapest step.
inline constexpr double kMaxStepsPerRun = 1e9;
/// Deepest overlap of two blocks at the start, as a fraction of the smaller block's bounding
/// radius (unit: 1). Settled states overlap by 1e-5 of the size or less.
inline constexpr double kMaxStartOverlapFraction = 0.1;

/// The largest time step the scene's contact model allows (unit: s): its automatic step at safety
/// 1. Rigid contact: sqrt(r/g)/50 (dynamics::rigid_time_step), 1/50 of the rocking time scale;
/// penalty contact: the damped critical step (dynamics::critical_time_step), the stability limit,
/// and never above the rigid bound (a very soft contact does not make coarse steps right).
double largest_time_step(const std::vector<dynamics::BodyDef>& bodies, const contact::ContactLaw& law);

/// Refuses a run of `simulated_time` seconds of the scene whose step (given or automatic) exceeds
/// largest_time_step, or which would take more than kMaxStepsPerRun steps.
void check_run_bounds(const Scene& scene, const dynamics::StepSettings& step, double simulated_time);

/// Refuses two blocks (not both fixed) that overlap at the start by more than
/// kMaxStartOverlapFraction of the smaller one's bounding radius.
void check_start_overlap(const Scene& scene);

}  // namespace rigid::scenario
