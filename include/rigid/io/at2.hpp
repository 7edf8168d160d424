#pragma once
/// PEER .AT2 acceleration records (physics.md §6): a robust reader for both header generations
/// (the old positional `NPTS, DT` line and the NGA `NPTS=..., DT=... SEC` line), headerless
/// files with an explicit dt, a writer, three-component sets and the `rigid motion info` report.
/// Every error in a file is a rigid::InputError naming the file and line.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rigid/motion/ground_motion.hpp"
#include "rigid/motion/measures.hpp"

namespace rigid::io {

/// Which header a record had.
enum class At2Header {
  keyword,     ///< `NPTS=  N, DT= dt SEC` (NGA and most PEER files; also `dt=`, no comma)
  positional,  ///< `N  dt  NPTS, DT` (old PEER files)
  dt_only,     ///< a `DT=` line without NPTS: the values are counted
  none         ///< no header: dt given by the caller
};

/// Options for reading one AT2 file.
struct At2ReadOptions {
  /// Time step (unit: s) for headerless files; 0 = none given (a headerless file is then an
  /// error). For a file with a header it must agree with the header's DT (relative 1e-6).
  double dt = 0.0;
};

/// One parsed AT2 file.
struct At2Record {
  std::string source;               ///< file name used in messages
  std::vector<std::string> header;  ///< header lines (line ends stripped), NPTS line last
  At2Header header_kind = At2Header::keyword;
  std::string component;       ///< component label (last comma field of header line 2)
  double dt = 0.0;             ///< time step (unit: s)
  double unit_to_si = 0.0;     ///< factor from file units to m/s^2 (g -> 9.80665)
  std::vector<double> values;  ///< samples in the file's units (usually g)
  /// (index of its first value, line number) of every line that holds values, in order
  std::vector<std::pair<std::size_t, long>> value_lines;

  /// The samples in SI (m/s^2) with dt and label.
  motion::Component component_si() const;
  /// The line holding values[i] (0 if none).
  long line_of_value(std::size_t i) const;
};

/// Parses AT2 text held in memory; `name` is used in error messages. Accepts LF, CRLF and
/// CR CR LF line ends, any number of values per line, a short last line, Fortran exponents
/// (1.0E-03, 1.0D-03, 1.0-103) and fields glued by their signs (-.1E-02-.2E-02).
/// Throws InputError(name, line, ...) for: a missing header (no NPTS/DT line in the first 12
/// lines and no dt given), DT not positive (or outside [1e-6, 10] s), NPTS disagreeing with the values present,
/// non-numeric, NaN or infinite values, no values, a velocity or displacement file.
At2Record parse_at2(std::string_view text, const std::string& name, const At2ReadOptions& options = {});

/// Reads and parses one file as a ground drive: InputError if it cannot be opened or is larger
/// than 256 MB, or at the line of the first value motion::drive_sample_problem refuses (beyond
/// 50 g). parse_at2 reads any finite number (the format itself).
At2Record read_at2(const std::string& path, const At2ReadOptions& options = {});

/// Options for writing AT2 files.
struct At2WriteOptions {
  int digits = 7;    ///< significant digits (E format: d.ddddddE+xx), 1..17
  int per_line = 5;  ///< values per line
  std::string title = "RIGID GROUND MOTION (PEER NGA AT2 FORMAT)";  ///< header line 1
  std::string description;                                          ///< header line 2 text before the component label
};

/// AT2 text of one component: 4 header lines (title; description, label; units; NPTS/DT) and
/// the samples in g. Reading it back gives each value to the printed precision.
std::string format_at2(const motion::Component& c, const At2WriteOptions& options = {});

/// Writes format_at2 to path (InputError if the file cannot be written).
void write_at2(const std::string& path, const motion::Component& c, const At2WriteOptions& options = {});

/// The files of a three-component set, in the order H1 (x), H2 (y), V (z); empty = absent.
struct SetFiles {
  std::string name;  ///< set name
  std::string x, y, z;
};

/// Resolves a set spec: `NAME-X.AT2` (with NAME-Y.AT2 and NAME-Z.AT2 joining when they exist,
/// same extension case), a comma-joined list `H1.AT2,H2.AT2[,V.AT2]`, optionally with explicit
/// roles `x=...,y=...,z=...` (also h1=, h2=, v=), or a single file (one horizontal). Relative
/// paths are taken from base_dir when it is not empty. Throws InputError for malformed specs.
SetFiles resolve_set(const std::string& spec, const std::string& base_dir = "");

/// Options for reading a set.
struct SetReadOptions {
  At2ReadOptions at2;          ///< per-file options (dt of headerless files)
  motion::AlignOptions align;  ///< unequal dt/npts: error or resample
  std::string base_dir;        ///< directory for relative paths
};

/// Reads a set (see resolve_set) into a GroundMotion in SI units, with sources = the files.
motion::GroundMotion read_motion_set(const std::string& spec, const SetReadOptions& options = {});

/// Writes the motion as PREFIX-X.AT2 (+ -Y, -Z when present), PREFIX = out_prefix
/// (`DIR/NAME`); returns the paths written. The directory must exist.
std::vector<std::string> write_motion_set(const motion::GroundMotion& m, const std::string& out_prefix,
                                          const At2WriteOptions& options = {});

/// The `rigid motion info` report of one set: one JSON line (json = true, no newline) or text.
std::string motion_info_report(const std::string& spec, const SetReadOptions& read,
                               const motion::MeasureOptions& measures, const std::vector<double>& sa_periods,
                               bool json);

}  // namespace rigid::io
