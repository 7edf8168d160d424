#pragma once
/// Job files that a command designs rather than a user writes (the campaigns of a shake-table
/// calibration or prediction). They are ordinary job files, so what runs them is an ordinary
/// campaign: resumable, hashed, and open to `rigid campaign` and `rigid inspect` like any other.
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace rigid::io {

struct DesignJob {
  std::string comment;      ///< written as `#` lines at the top
  std::string object_name;  ///< the [[object]]
  std::string scene;        ///< its scene file (absolute path)
  /// [[variant]] tables, each a list of (parameter, value): numbers, or text (contact, scene)
  std::vector<std::vector<std::pair<std::string, std::variant<double, std::string>>>> variants;
  struct Record {
    std::string lab;  ///< the recorded table motion (absolute path)
    double start = 0; ///< window (unit: s)
    double end = 0;
  };
  std::vector<Record> records;
  /// A TOML file whose [lab] table says how to read the recordings; "" for the default format
  std::string lab_format_file;
  std::vector<double> rotation_angles_deg;
  /// The [campaign] scales as the job file states them: "as recorded" (factor 1) or a
  /// "start:stop:step" range of target PGAs (unit: g), read by the job reader like any job's
  std::string scales = "as recorded";
  /// When not empty: the target PGAs as a list (unit: g), in place of `scales`
  std::vector<double> scale_list_g;
  /// The campaign's stop rule: stop raising a record's scale after this many consecutive scales
  /// overturned at every rotation (0: every scale is run)
  int stop_after = 0;
  double free_time_s = 5;
  unsigned long long seed = 1;
};

/// Writes the job through a temporary file renamed into place (a half-written job never stands
/// under the name). Throws InputError naming the path when it cannot be written, or when the
/// lab format file has no [lab] table.
void write_design_job(const std::string& path, const DesignJob& job);

}  // namespace rigid::io
