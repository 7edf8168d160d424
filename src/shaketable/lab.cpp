#include "rigid/shaketable/lab.hpp"

#include <algorithm>
#include <string>

#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/lab_recording.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/motion/strong_motion.hpp"

namespace rigid::shaketable {

LabInput lab_input(const std::string& format_file) {
  LabInput in;
  in.format_file = format_file;
  if (!format_file.empty()) in.format = io::read_lab_format(format_file);
  return in;
}

io::InputFiles command_inputs(const std::string& tests_csv, const io::LabTestList& tests, const LabInput& lab,
                              const std::vector<std::string>& scenes, const std::vector<std::string>& others) {
  io::InputFiles in;
  in.add(tests_csv);
  for (const io::LabTest& t : tests.tests) in.add(t.file);
  if (!lab.format_file.empty()) in.add(lab.format_file);
  for (const std::string& scene : scenes) {
    in.add(scene);
    in.add(io::load_scene(scene).files);
  }
  in.add(others);
  return in;
}

io::JobRecord lab_record(const std::string& file, double start_s, double end_s) {
  io::JobRecord r;
  r.spec = file;
  r.lab = true;
  r.start = start_s;
  r.end = end_s;
  return r;
}

std::vector<io::JobRecord> strong_motion_records(const io::LabTestList& tests, const LabInput& lab, double level_g) {
  std::vector<io::JobRecord> out;
  for (const io::LabTest& t : tests.tests) {
    const motion::TimeWindow w = motion::strong_motion_window(io::read_lab_motion(t.file, lab.format), level_g);
    out.push_back(lab_record(t.file, w.start_s, w.end_s));
  }
  return out;
}

double static_toppling_g(const std::string& scene) {
  const auto rocking = analysis::rocking_parameters(io::load_scene(scene));
  if (!rocking) throw InputError(scene, 0, "has no single free block standing on its pedestal (no rocking parameters)");
  return analysis::static_toppling_g(*rocking);
}

double window_level_g(bool rigid_contact_only, double weakest_static_toppling_g) {
  return (rigid_contact_only ? 0.5 : 0.1) * weakest_static_toppling_g;
}

double window_level_g(const std::vector<std::string>& scenes) {
  double weakest = 1e300;
  bool rigid = true;
  for (const std::string& s : scenes) {
    rigid = rigid && io::load_scene(s).law.method == contact::ContactMethod::rigid;
    weakest = std::min(weakest, static_toppling_g(s));
  }
  return window_level_g(rigid, weakest);
}

calibration::OutcomeGrid outcome_grid(const io::Cube& cube, const std::vector<double>& headings_deg) {
  const int variants = int(cube.objects.size());
  const int tests = int(cube.records.size());
  const int headings = cube.rotations;
  if (headings != int(headings_deg.size()) || cube.scales_g.size() != 1)
    throw InputError("", 0, "a designed campaign's cube has an unexpected shape");
  calibration::OutcomeGrid grid(variants, tests, headings_deg);
  for (int v = 0; v < variants; ++v) {
    const io::ObjectCube& o = cube.objects[std::size_t(v)];
    for (int t = 0; t < tests; ++t) {
      for (int h = 0; h < headings; ++h) {
        const auto code = static_cast<io::CellOutcome>(o.outcome[std::size_t(t * headings + h)]);
        if (code != io::CellOutcome::survived && code != io::CellOutcome::overturned) {
          throw InputError("", 0,
                           "cell (" + io::object_label(o) + ", record " + cube.records[std::size_t(t)].name +
                               ", heading " + std::to_string(headings_deg[std::size_t(h)]) + ") was not simulated (" +
                               io::outcome_name(std::int8_t(code)) + ")");
        }
        grid.set(v, t, h, code == io::CellOutcome::overturned);
      }
    }
  }
  return grid;
}

}  // namespace rigid::shaketable
