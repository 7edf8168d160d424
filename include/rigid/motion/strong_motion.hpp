#pragma once
/// The part of a motion that can move a rock at rest: what a designed campaign runs of a long
/// recording (the shake table's quiet lead-in and tail cost time and decide nothing).
#include "rigid/motion/ground_motion.hpp"

namespace rigid::motion {

struct TimeWindow {
  double start_s = 0;
  double end_s = 0;
};

/// From 1 s before the first sample whose horizontal (x) acceleration exceeds `level_g` to 1 s
/// after the last, within the motion (the first 2 s when none does; the whole motion for a level
/// <= 0). A rock at rest on its base cannot start to rock or slide below its quasi-static toppling
/// acceleration, so with a level under it nothing is cut that could decide the outcome, and the
/// run's free time after the window lets a rocking rock settle or fall.
TimeWindow strong_motion_window(const GroundMotion& motion, double level_g);

}  // namespace rigid::motion
