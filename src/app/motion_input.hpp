#pragma once
/// Ground-motion options shared by `run` (and later `campaign`): which record, which window, how
/// scaled and rotated; and the conversion into the velocity that drives the pedestals.
#include <limits>
#include <string>

#include <CLI/CLI.hpp>

#include "lab_input.hpp"
#include "rigid/motion/ground_motion.hpp"

namespace rigid::app {

struct MotionOptions {
  std::string path;                                      ///< NAME-X.AT2 (siblings -Y, -Z join) or H1.AT2,H2.AT2[,V.AT2]
  double factor = 1.0;                                   ///< multiplies every component as it is
  double target_pga_g = 0;                               ///< > 0: scale so the GMRotI50 PGA equals this (unit: g)
  double start = 0;                                      ///< window start (unit: s)
  double end = std::numeric_limits<double>::infinity();  ///< window end (unit: s)
  double rotation_deg = 0;                               ///< rotation of the horizontals about z (unit: deg)
  LabFlags lab;  ///< --lab FILE: a lab recording instead of `path` (its axis is x)
  /// Whether a motion was asked for (--motion or --lab).
  bool given() const { return !path.empty() || !lab.file.empty(); }
};

void add_motion_options(CLI::App& cmd, MotionOptions& o);

/// Reads (an AT2 set, or a lab recording), windows, scales and rotates the record.
motion::GroundMotion load_motion(const MotionOptions& o);

}  // namespace rigid::app
