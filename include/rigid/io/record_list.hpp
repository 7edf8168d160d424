#pragma once
/// Record lists: the study's table format (tab-separated, as the study's ../shared/docs/table3_6_records.tsv) and the
/// original Rigid batch file (.ABF), plus the comparison of listed GMRotI values with the values
/// computed from the files.
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "rigid/io/at2.hpp"

namespace rigid::io {

/// One record of a list. `file` is a motion-set spec (see resolve_set): a Rigid name
/// NAME-X.AT2, or an explicit comma-joined mapping of arbitrarily named files
/// (`x=RSN1_E.AT2,y=RSN1_N.AT2,z=RSN1_V.AT2` or `H1.AT2,H2.AT2[,V.AT2]`).
struct RecordEntry {
  long line = 0;           ///< line in the list file
  std::string earthquake;  ///< may be empty
  int year = 0;            ///< 0 if not given
  double magnitude = std::numeric_limits<double>::quiet_NaN();
  std::string file;                                                   ///< motion-set spec as written
  double start = 0.0;                                                 ///< window start (unit: s)
  double end = std::numeric_limits<double>::infinity();               ///< window end (unit: s)
  double gmroti_pga_g = std::numeric_limits<double>::quiet_NaN();     ///< listed (unit: g)
  double gmroti_pgv_cm_s = std::numeric_limits<double>::quiet_NaN();  ///< listed (unit: cm/s)
  double pgv_pga_s = std::numeric_limits<double>::quiet_NaN();        ///< listed (unit: s)
  /// align column "resample": components of unequal dt or length resampled and padded (as a job's
  /// [[record]] align = "resample"); empty or "auto": only lengths within 1 % padded
  bool resample = false;
};

/// A parsed list.
struct RecordList {
  std::string source;                ///< list file name
  std::string base_dir;              ///< directory of the list (relative record paths)
  std::vector<double> pga_scales_g;  ///< .ABF line 1: PGA levels (unit: g); empty for tables
  std::vector<RecordEntry> records;
};

/// Parses the table format: one record per line, 9 tab-separated columns: earthquake, year,
/// magnitude, file, start s, end s, GMRotI PGA g, GMRotI PGV cm/s, PGV/PGA s (the last three
/// may be empty; earthquake may be empty), and an optional 10th, align (empty, auto or resample). Blank lines, `#`
/// comments and a header line (second column not a number) are skipped. InputError(name, line) for malformed lines.
RecordList parse_record_table(std::string_view text, const std::string& name);

/// Parses a Rigid batch file: line 1 the PGA scales (unit: g, separated by blanks, commas or
/// tabs), line 2 a deprecated field that must be 0, then one record per line:
/// `FILE [START END]` (set spec, optional window in s, blank- or tab-separated). Blank lines and
/// `#` comments are skipped. InputError(name, line) for malformed lines.
RecordList parse_abf(std::string_view text, const std::string& name);

/// Reads a list file: `.abf` (any case) as a batch file, anything else as a table; base_dir is
/// the file's directory.
RecordList read_record_list(const std::string& path);

/// Listed vs computed GMRotI50 values of one record. The study's listed values behave as
/// whole-record values (docs/ground-motions.md), so the relative differences use the whole
/// record; the values on the listed window are reported beside them.
struct RecordCheck {
  RecordEntry entry;
  std::string spec;  ///< set spec that was read
  std::size_t npts = 0;
  double dt = 0.0;              ///< unit: s
  bool window_clamped = false;  ///< the listed end lies past the record
  // whole record
  double gmroti_pga_g = 0.0, gmroti_pgv_cm_s = 0.0;
  double gmrotd_pga_g = 0.0, gmrotd_pgv_cm_s = 0.0;
  double gm_min_pga_g = 0.0, gm_max_pga_g = 0.0;  ///< range of GM(theta) over 0..89 deg
  double rotd0_pga_g = 0.0, rotd100_pga_g = 0.0;  ///< min and max single-direction PGA
  double gmroti_angle_deg = 0.0;
  // the listed window [start, end], integrated from rest at its start
  double window_gmroti_pga_g = 0.0, window_gmroti_pgv_cm_s = 0.0;
  double window_gmrotd_pga_g = 0.0, window_gmrotd_pgv_cm_s = 0.0;
  /// relative differences computed (whole record) / listed - 1; NaN if not listed
  double pga_rel_diff = std::numeric_limits<double>::quiet_NaN();
  double pgv_rel_diff = std::numeric_limits<double>::quiet_NaN();
};

/// Reads the record's set (spec = entry.file unless spec_override is given), computes GMRotI50
/// and GMRotD50 PGA/PGV on the listed window and on the whole record, and compares with the
/// listed values. Throws InputError if the set has fewer than two horizontals.
RecordCheck check_record(const RecordEntry& entry, const SetReadOptions& options,
                         const std::string& spec_override = "");

/// One JSON line per check (no newline): keys as in RecordCheck.
std::string to_json(const RecordCheck& c);

}  // namespace rigid::io
