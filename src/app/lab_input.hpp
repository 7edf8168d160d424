#pragma once
/// The lab-recording options of `run` and `motion info` (--lab FILE and the --lab-* format flags):
/// one CLI source of io::LabFormat, checked by io::check_lab_format as the TOML [lab] table is.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "rigid/io/lab_recording.hpp"

namespace rigid::app {

/// The flags as given (unset = the format's default, or the --lab-format file's value).
struct LabFlags {
  std::string file;    ///< --lab: the recording
  std::string format;  ///< --lab-format: a TOML file whose [lab] table is the starting format
  std::optional<std::string> delimiter, channel, acceleration_column, acceleration_unit, displacement_column,
      displacement_unit, volts_length_unit, baseline, band;
  std::optional<int> header_lines, time_column, baseline_degree, filter_order;
  std::optional<double> volts_to_length, scale, crossover_hz;
};

void add_lab_options(CLI::App& cmd, LabFlags& o);

/// InputError when a --lab-* flag is given without --lab (it would be ignored).
void reject_lab_flags_without_file(const LabFlags& o);

/// The format the flags describe: --lab-format's [lab] table (or the defaults), each given flag
/// over it, then io::check_lab_format. InputError naming the flag for a bad value.
io::LabFormat lab_format_from_flags(const LabFlags& o);

}  // namespace rigid::app
