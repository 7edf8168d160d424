#include "motion_input.hpp"

#include <cmath>

#include "number_checks.hpp"
#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/at2.hpp"
#include "rigid/motion/ground_motion.hpp"

namespace rigid::app {

void add_motion_options(CLI::App& cmd, MotionOptions& o) {
  cmd.add_option("--motion", o.path,
                 "Ground motion: NAME-X.AT2 (NAME-Y.AT2 and NAME-Z.AT2 join when present) or "
                 "H1.AT2,H2.AT2[,V.AT2]; PEER AT2 files in g");
  cmd.add_option("--factor", o.factor, "Multiply every component by this (unit: 1)")
      ->capture_default_str()
      ->check(finite_number());
  cmd.add_option("--target-pga", o.target_pga_g,
                 "Scale so the GMRotI50 PGA equals this (unit: g; with one horizontal, its PGA)")
      ->check(positive_number());
  cmd.add_option("--start", o.start, "Start of the time window (s)")
      ->capture_default_str()
      ->check(non_negative_number());
  cmd.add_option("--end", o.end, "End of the time window (s); default: end of the record")->check(positive_number());
  cmd.add_option("--rotation", o.rotation_deg,
                 "Rotate the horizontal components about z, counter-clockwise from above (deg; |angle| <= 1e6)")
      ->capture_default_str()
      ->check(angle_deg());
  add_lab_options(cmd, o.lab);
}

namespace {

// The --start/--end window of the record; a window outside it is an error of those options.
motion::GroundMotion windowed_record(const motion::GroundMotion& record, double start, double end) {
  if (start == 0 && !std::isfinite(end)) return record;  // no window asked for
  try {
    return motion::windowed(record, start, end);
  } catch (const InputError& e) {
    throw InputError("", 0, "--start/--end: " + e.problem() + " (" + record.name + ")");
  }
}

}  // namespace

motion::GroundMotion load_motion(const MotionOptions& o) {
  // the options' validators have refused non-finite and out-of-range values
  reject_lab_flags_without_file(o.lab);
  if (!o.path.empty() && !o.lab.file.empty()) throw InputError("", 0, "give --motion or --lab, not both");
  const motion::GroundMotion read =
      o.lab.file.empty() ? io::read_motion_set(o.path) : io::read_lab_motion(o.lab.file, lab_format_from_flags(o.lab));
  const motion::GroundMotion record = windowed_record(read, o.start, o.end);
  motion::MotionTransform t;
  t.factor = o.factor;
  t.target_pga_g = o.target_pga_g;
  t.rotation = o.rotation_deg * kPi / 180.0;
  return motion::transformed(record, t);
}

}  // namespace rigid::app
