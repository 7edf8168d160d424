#include "motion_input.hpp"

#include <cmath>

#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/at2.hpp"
#include "rigid/motion/ground_motion.hpp"

namespace rigid::app {

void add_motion_options(CLI::App& cmd, MotionOptions& o) {
  cmd.add_option("--motion", o.path,
                 "Ground motion: NAME-X.AT2 (NAME-Y.AT2 and NAME-Z.AT2 join when present) or "
                 "H1.AT2,H2.AT2[,V.AT2]; PEER AT2 files in g");
  cmd.add_option("--factor", o.factor, "Multiply every component by this (unit: 1)")->capture_default_str();
  cmd.add_option("--target-pga", o.target_pga_g,
                 "Scale so the GMRotI50 PGA equals this (unit: g; with one horizontal, its PGA)");
  cmd.add_option("--start", o.start, "Start of the time window (s)")->capture_default_str();
  cmd.add_option("--end", o.end, "End of the time window (s); default: end of the record");
  cmd.add_option("--rotation", o.rotation_deg,
                 "Rotate the horizontal components about z, counter-clockwise from above (deg)")
      ->capture_default_str();
}

motion::GroundMotion load_motion(const MotionOptions& o) {
  if (!std::isfinite(o.factor)) throw InputError("", 0, "--factor must be finite");
  if (!std::isfinite(o.rotation_deg)) throw InputError("", 0, "--rotation must be finite");
  if (o.target_pga_g < 0 || !std::isfinite(o.target_pga_g)) {
    throw InputError("", 0, "--target-pga must be positive (g)");
  }
  const motion::GroundMotion record = io::read_motion_set(o.path);
  motion::MotionTransform t;
  t.start = o.start;
  t.end = o.end;
  t.factor = o.factor;
  t.target_pga_g = o.target_pga_g;
  t.rotation = o.rotation_deg * kPi / 180.0;
  return motion::transformed(record, t);
}

}  // namespace rigid::app
