#pragma once
/// Laboratory (shake-table) recordings as a data acquisition exports them: a delimited text table,
/// optionally gzip-compressed, with header lines, a time column and acceleration and/or
/// displacement columns in the lab's units. One LabFormat says how to read a file and how to turn
/// it into a ground acceleration; it is filled from a TOML `[lab]` table (lab_format_from_toml) or
/// from command-line flags (the app), both checked by check_lab_format. The defaults are the
/// export of the shake-table campaign in ../shared/shaketable (README there).
/// Every error is a rigid::InputError naming the file and line.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rigid/motion/ground_motion.hpp"
#include "rigid/motion/lab_format.hpp"

namespace rigid::io {

// The format itself is plain data in rigid::motion (motion/lab_format.hpp), so a job::Job
// can hold one; these names make it part of io's vocabulary too.
using motion::LabChannel;
using motion::LabColumn;
using motion::LabDelimiter;
using motion::LabFormat;

/// Throws InputError(source, line, problem) if the format is impossible: units unknown, columns
/// not positive or repeated, non-finite or zero scale or factor, a band outside 0 < low < high,
/// an order outside 1..8, a baseline degree outside 0..10. `source`/`line` say where the format
/// came from (a TOML file and its [lab] line, or "" and 0 for flags: the messages then name the
/// option).
void check_lab_format(const LabFormat& f, const std::string& source, long line);

/// Factor from the acceleration unit to m/s^2; 0 for an unknown unit.
double acceleration_unit_to_si(std::string_view unit);
/// Factor from a length unit ("m", "cm", "mm", "in") to m; 0 for an unknown unit.
double length_unit_to_si(std::string_view unit);
/// "tab", "comma", "whitespace"; parse returns false for anything else.
const char* lab_delimiter_name(LabDelimiter d);
bool parse_lab_delimiter(std::string_view text, LabDelimiter& out);
/// "acceleration", "displacement", "combined"; parse returns false for anything else.
const char* lab_channel_name(LabChannel c);
bool parse_lab_channel(std::string_view text, LabChannel& out);
/// "none", "mean", "linear", "polynomial"; false for anything else.
bool parse_lab_baseline(std::string_view text, motion::LabBaseline& out);
/// A column given as text: digits = a 1-based index, anything else = a header name.
LabColumn parse_lab_column(std::string_view text);

/// The `[lab]` table of a TOML document (text, file name for messages); the defaults when it has
/// none. Keys: delimiter, header_lines, time_column, channel, acceleration_column,
/// acceleration_unit, displacement_column, displacement_unit, volts_to_length, volts_length_unit,
/// scale, baseline, baseline_degree, band_hz ([low, high] or "none"), filter_order, crossover_hz. A column is
/// an integer (1-based) or a header name. Unknown keys and bad values: InputError at their line.
LabFormat lab_format_from_toml(std::string_view toml_text, const std::string& file);

/// The [lab] table of a format file (read through the bounded reader of every text input). A file
/// without one is refused: a misspelt table ([labb]) or an empty file must not mean the defaults.
LabFormat read_lab_format(const std::string& path);

/// The raw columns of a recording, in the file's units (time in s).
struct LabTable {
  std::string source;                ///< the file
  std::vector<std::string> header;   ///< header lines (line ends stripped)
  std::vector<double> time;          ///< unit: s
  std::vector<double> acceleration;  ///< the acceleration column in its unit; empty unless read
  std::vector<double> displacement;  ///< the displacement column in its unit; empty unless read
  double dt = 0.0;                   ///< (t_last - t_first) / (n - 1) (unit: s)
  long first_data_line = 0;          ///< 1-based line of the first sample
};

/// Reads the time column and the column(s) f.channel needs from a file (gzip or plain text, detected
/// from the content). Refuses what is not a regular file or is larger than 256 MB (compressed) or
/// decompresses to more than 1 GB. InputError(file, line, ...) for: a corrupt or truncated gzip
/// stream, fewer lines than the header, a header without the named column (or a numeric line
/// where the header should be), a row with fewer cells than the columns read, an empty, non-numeric,
/// NaN or infinite cell, a time that does not increase or strays from uniform sampling by more than
/// half a step, fewer than 64 samples.
LabTable read_lab_table(const std::filesystem::path& path, const LabFormat& f);

/// The single entry point: reads the recording, converts the channel to m/s^2 (displacement: to
/// m, then differentiated twice after the band-pass; combined: both, merged at the crossover),
/// applies the scale, baseline and band-pass,
/// and returns a one-horizontal GroundMotion (x = the table's axis), dt from the time column,
/// name = the file's stem without .txt/.gz, label_x = the channel, sources = {path}.
motion::GroundMotion read_lab_motion(const std::filesystem::path& path, const LabFormat& f);

/// One line saying what read_lab_motion did, e.g. "acceleration channel (column 2, g), mean
/// removed, band-pass 0.1-25 Hz order 4 zero-phase".
std::string describe_lab_processing(const LabFormat& f);

}  // namespace rigid::io
