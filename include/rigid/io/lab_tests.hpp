#pragma once
/// The list of shake-table tests a calibration or prediction runs: one CSV row per test, in the
/// layout a lab's test sheet has (docs/validation-shaketable.md): a header line naming the
/// columns, then `test_no`, `record`, `pgv_over_pga_s`, `pga_g`, `file` and, for calibration,
/// `overturned` (0/1). Extra columns (a date, notes) are kept out of the way, not refused.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rigid::io {

/// One test: which recorded table motion drove the specimen and, when known, what happened.
struct LabTest {
  long line = 0;                ///< line in the CSV (for messages)
  long test_no = 0;             ///< the lab's test number, unique in the list
  std::string record;           ///< the ground motion the table reproduced (groups tests for cross-validation)
  std::string file;             ///< the table's recorded motion, resolved against the CSV's folder
  double sheet_pga_g = 0;       ///< PGA from the lab's sheet (unit: g), 0 when absent; reporting only
  double sheet_pgv_pga_s = 0;   ///< PGV/PGA from the lab's sheet (unit: s), 0 when absent; reporting only
  std::optional<int> overturned;  ///< 1 overturned, 0 stood; absent when the CSV has no such column
};

struct LabTestList {
  std::string source;   ///< the CSV's path
  bool has_outcomes = false;  ///< the CSV has an `overturned` column
  std::vector<LabTest> tests;
};

/// Parses the CSV text; `base_dir` resolves relative `file` entries. InputError(name, line) for a
/// missing required column (test_no, file), a malformed number, an `overturned` other than 0/1, a
/// duplicate test number, a row with too few fields, or no test at all. Files are not opened.
LabTestList parse_lab_tests(std::string_view text, const std::string& name, const std::string& base_dir);

/// Reads and parses a test list, then checks that every motion file exists (InputError at the
/// row naming the missing file).
LabTestList read_lab_tests(const std::string& path);

}  // namespace rigid::io
