#pragma once
/// The recorded table motions of a test list as a designed campaign runs them: the recordings'
/// format, the strong-motion window of each and the level that sets it, and the outcome grid
/// read back from a designed campaign's cube.
#include <string>
#include <vector>

#include "rigid/calibration/outcome_model.hpp"
#include "rigid/io/cube.hpp"
#include "rigid/io/job_file.hpp"
#include "rigid/io/lab_tests.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/motion/ground_motion.hpp"
#include "rigid/motion/lab_format.hpp"

namespace rigid::shaketable {

/// The recordings' format: a TOML file's [lab] table, or the default (this lab's export).
struct LabInput {
  std::string format_file;  ///< "" for the default
  motion::LabFormat format;
};
LabInput lab_input(const std::string& format_file);

/// Every file a shake-table command reads: the test list and each test's recording, the lab
/// format file, each scene with every file it is built from, and `others` (a scan, a calibration
/// file). No output of the command may be one of them (io::InputFiles).
io::InputFiles command_inputs(const std::string& tests_csv, const io::LabTestList& tests, const LabInput& lab,
                              const std::vector<std::string>& scenes, const std::vector<std::string>& others);

/// One recording as a designed job's [[record]] (lab = FILE), windowed.
io::JobRecord lab_record(const std::string& file, double start_s, double end_s);

/// Each test's recording, windowed to its strong motion at `level_g` (motion::strong_motion_window).
std::vector<io::JobRecord> strong_motion_records(const io::LabTestList& tests, const LabInput& lab, double level_g);

/// The smallest quasi-static toppling acceleration of a scene's free block (unit: g).
double static_toppling_g(const std::string& scene);

/// The level of the strong-motion windows for these scenes (unit: g): half the weakest static
/// toppling acceleration when every scene has rigid contact (a rock at rest on a rigid support
/// cannot start to move below it); a tenth of it when one has penalty contact, whose compliant
/// support lets the rock rock below that acceleration: the window then only drops the table's
/// quiet lead-in and tail (docs/validation-shaketable.md measures what it changes).
double window_level_g(bool rigid_contact_only, double weakest_static_toppling_g);
/// window_level_g of these scenes' contact laws and their weakest static toppling.
double window_level_g(const std::vector<std::string>& scenes);

/// The outcome grid of a designed campaign's cube: variant v, test t (record t), heading h
/// (rotation index h). Throws InputError if a cell is not simulated or failed.
calibration::OutcomeGrid outcome_grid(const io::Cube& cube, const std::vector<double>& headings_deg);

}  // namespace rigid::shaketable
