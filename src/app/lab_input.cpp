#include "lab_input.hpp"

#include "rigid/core/error.hpp"
#include "rigid/io/lab_recording.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace rigid::app {

void add_lab_options(CLI::App& cmd, LabFlags& o) {
  cmd.add_option("--lab", o.file,
                 "A lab (shake-table) recording instead of an AT2 set: delimited text, gzip or plain; "
                 "its format from --lab-format and the --lab-* flags (defaults: tab, 1 header line, time "
                 "column 1, acceleration column 2 in g, displacement column 3 in V, the combined channel, "
                 "band-pass 0.1-25 Hz)");
  cmd.add_option("--lab-format", o.format, "TOML file whose [lab] table gives the recording's format");
  cmd.add_option("--lab-delimiter", o.delimiter, "tab (default), comma or whitespace");
  cmd.add_option("--lab-header-lines", o.header_lines, "Lines before the data (default 1; the last names the columns)");
  cmd.add_option("--lab-time-column", o.time_column, "Time column, 1-based (default 1; unit: s)");
  cmd.add_option("--lab-channel", o.channel,
                 "acceleration (the accelerometer, band-passed), displacement (band-passed, differentiated "
                 "twice) or combined (displacement below --lab-crossover-hz, accelerometer above)");
  cmd.add_option("--lab-acceleration-column", o.acceleration_column, "Acceleration column: number or header name (default 2)");
  cmd.add_option("--lab-acceleration-unit", o.acceleration_unit, "g (default), m/s^2 or cm/s^2");
  cmd.add_option("--lab-displacement-column", o.displacement_column, "Displacement column: number or header name (default 3)");
  cmd.add_option("--lab-displacement-unit", o.displacement_unit, "m, cm, mm, in, or V (default; times --lab-volts-to-length)");
  cmd.add_option("--lab-volts-to-length", o.volts_to_length, "Length per volt of a V displacement (default 5.9797e-4)");
  cmd.add_option("--lab-volts-length-unit", o.volts_length_unit, "Unit of --lab-volts-to-length's length: m, cm, mm, in (default)");
  cmd.add_option("--lab-scale", o.scale, "Multiply the channel by this after unit conversion (default 1)");
  cmd.add_option("--lab-baseline", o.baseline, "Baseline removed before filtering: none, mean (default), linear, polynomial");
  cmd.add_option("--lab-baseline-degree", o.baseline_degree, "Degree of the polynomial baseline (default 2)");
  cmd.add_option("--lab-band-hz", o.band, "Zero-phase Butterworth band-pass LOW,HIGH in Hz (default 0.1,25) or none");
  cmd.add_option("--lab-filter-order", o.filter_order, "Butterworth order (default 4)");
  cmd.add_option("--lab-crossover-hz", o.crossover_hz, "Crossover of the combined channel (Hz, default 2)");
}

namespace {

[[noreturn]] void bad(const char* flag, const std::string& problem) { throw InputError("", 0, std::string(flag) + ": " + problem); }

}  // namespace

void reject_lab_flags_without_file(const LabFlags& o) {
  if (!o.file.empty()) return;
  const bool any = !o.format.empty() || o.delimiter || o.channel || o.acceleration_column || o.acceleration_unit ||
                   o.displacement_column || o.displacement_unit || o.volts_length_unit || o.baseline || o.band ||
                   o.header_lines || o.time_column || o.baseline_degree || o.filter_order || o.volts_to_length || o.scale || o.crossover_hz;
  if (any) throw InputError("", 0, "the --lab-* options need --lab FILE");
}

io::LabFormat lab_format_from_flags(const LabFlags& o) {
  io::LabFormat f;
  if (!o.format.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(o.format, ec)) throw InputError(o.format, 0, "--lab-format: not a readable file");
    std::ifstream in(o.format);
    std::ostringstream text;
    text << in.rdbuf();
    f = io::lab_format_from_toml(text.str(), o.format);
  }
  if (o.delimiter && !io::parse_lab_delimiter(*o.delimiter, f.delimiter)) bad("--lab-delimiter", "must be tab, comma or whitespace");
  if (o.header_lines) f.header_lines = *o.header_lines;
  if (o.time_column) f.time = {*o.time_column, ""};
  if (o.channel && !io::parse_lab_channel(*o.channel, f.channel)) bad("--lab-channel", "must be acceleration, displacement or combined");
  if (o.acceleration_column) f.acceleration = io::parse_lab_column(*o.acceleration_column);
  if (o.acceleration_unit) f.acceleration_unit = *o.acceleration_unit;
  if (o.displacement_column) f.displacement = io::parse_lab_column(*o.displacement_column);
  if (o.displacement_unit) f.displacement_unit = *o.displacement_unit;
  if (o.volts_to_length) f.volts_to_length = *o.volts_to_length;
  if (o.volts_length_unit) f.volts_length_unit = *o.volts_length_unit;
  if (o.scale) f.scale = *o.scale;
  if (o.baseline && !io::parse_lab_baseline(*o.baseline, f.processing.baseline))
    bad("--lab-baseline", "must be none, mean, linear or polynomial");
  if (o.baseline_degree) f.processing.baseline_degree = *o.baseline_degree;
  if (o.band) {
    if (*o.band == "none") {
      f.processing.band_pass = false;
    } else {
      double lo = 0, hi = 0;
      char extra = 0;
      if (std::sscanf(o.band->c_str(), "%lf,%lf%c", &lo, &hi, &extra) != 2) bad("--lab-band-hz", "must be LOW,HIGH (Hz) or none");
      f.processing.band_pass = true;
      f.processing.low_hz = lo;
      f.processing.high_hz = hi;
    }
  }
  if (o.filter_order) f.processing.order = *o.filter_order;
  if (o.crossover_hz) f.processing.crossover_hz = *o.crossover_hz;
  io::check_lab_format(f, "", 0);
  return f;
}

}  // namespace rigid::app
