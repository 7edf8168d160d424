#pragma once
/// The list of shake-table tests a calibration or prediction runs: one CSV row per test, in the
/// layout a lab's test sheet has (docs/validation-shaketable.md): a header line naming the
/// columns, then `test_no`, `record`, `pgv_over_pga_s`, `pga_g`, `file` and, for calibration,
/// `overturned` (0/1; blank or `?` where not known, as in a hold-out list). Extra columns (a date,
/// notes) are kept out of the way, not refused. Read as RFC 4180 CSV (io/csv.hpp): quoted fields
/// may hold commas, quotes and line breaks; a UTF-8 byte-order mark (Excel) is skipped.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rigid::io {

/// One test: which recorded table motion drove the specimen and, when known, what happened.
struct LabTest {
  long line = 0;                  ///< line in the CSV (for messages)
  long test_no = 0;               ///< the lab's test number, unique in the list
  std::string record;             ///< the ground motion the table reproduced (groups tests for cross-validation)
  std::string file;               ///< the table's recorded motion, resolved against the CSV's folder
  double sheet_pga_g = 0;         ///< PGA from the lab's sheet (unit: g), 0 when absent; reporting only
  double sheet_pgv_pga_s = 0;     ///< PGV/PGA from the lab's sheet (unit: s), 0 when absent; reporting only
  std::optional<int> overturned;  ///< 1 overturned, 0 stood; absent when not known (no such column, blank or ?)
};

struct LabTestList {
  std::string source;           ///< the CSV's path
  long header_line = 0;         ///< line of the header (for messages)
  bool outcome_column = false;  ///< the CSV has an `overturned` column
  bool has_outcomes = false;    ///< every test's outcome is known (0 or 1)
  std::vector<LabTest> tests;
};

/// Parses the CSV text; `base_dir` resolves relative `file` entries. InputError(name, line) for a
/// missing required column (test_no, file), a malformed number, an `overturned` other than 0, 1,
/// blank or ?, a quote left open, a
/// duplicate test number, a row with too few fields, or no test at all. Files are not opened.
LabTestList parse_lab_tests(std::string_view text, const std::string& name, const std::string& base_dir);

/// Reads and parses a test list, then checks that every motion file is a regular file
/// (InputError at the row naming the file and what it is: not found, a directory, a FIFO...).
LabTestList read_lab_tests(const std::string& path);

/// For the commands that fit the outcomes (calibrate, fragility): throws InputError naming the
/// list and the header line when it has no `overturned` column, or the line of the first test
/// whose outcome is not known (blank or ?); `why` ends the message ("calibration fits the
/// observed outcomes"). A list that passes has has_outcomes true and every `overturned` set.
void require_outcomes(const LabTestList& list, std::string_view why);

}  // namespace rigid::io
