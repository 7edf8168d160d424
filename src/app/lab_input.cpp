#include "lab_input.hpp"

#include "rigid/core/error.hpp"
#include "rigid/io/lab_recording.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rigid::app {

void add_lab_options(CLI::App& cmd, LabFlags& o) {
  // the defaults shown are the format's own (io::LabFormat), which a --lab-format file replaces
  const io::LabFormat d;
  const auto number = [](double v) {
    std::ostringstream text;
    text << v;
    return text.str();
  };
  const motion::LabProcessing& p = d.processing;
  cmd.add_option("--lab", o.file,
                 "A lab (shake-table) recording instead of an AT2 set: delimited text, gzip or plain; "
                 "its format from --lab-format and the --lab-* flags (defaults below)");
  cmd.add_option("--lab-format", o.format, "TOML file whose [lab] table gives the recording's format");
  cmd.add_option("--lab-delimiter", o.delimiter, "tab, comma or whitespace")
      ->default_str(io::lab_delimiter_name(d.delimiter));
  cmd.add_option("--lab-header-lines", o.header_lines, "Lines before the data (the last names the columns)")
      ->default_str(std::to_string(d.header_lines));
  cmd.add_option("--lab-time-column", o.time_column, "Time column, 1-based (unit: s)")
      ->default_str(std::to_string(d.time.index));
  cmd.add_option("--lab-channel", o.channel,
                 "acceleration (the accelerometer, band-passed), displacement (band-passed, differentiated "
                 "twice) or combined (displacement below --lab-crossover-hz, accelerometer above)")
      ->default_str(io::lab_channel_name(d.channel));
  cmd.add_option("--lab-acceleration-column", o.acceleration_column, "Acceleration column: number or header name")
      ->default_str(std::to_string(d.acceleration.index));
  cmd.add_option("--lab-acceleration-unit", o.acceleration_unit, "g, m/s^2 or cm/s^2")
      ->default_str(d.acceleration_unit);
  cmd.add_option("--lab-displacement-column", o.displacement_column, "Displacement column: number or header name")
      ->default_str(std::to_string(d.displacement.index));
  cmd.add_option("--lab-displacement-unit", o.displacement_unit, "m, cm, mm, in, or V (times --lab-volts-to-length)")
      ->default_str(d.displacement_unit);
  cmd.add_option("--lab-volts-to-length", o.volts_to_length, "Length per volt of a V displacement")
      ->default_str(number(d.volts_to_length));
  cmd.add_option("--lab-volts-length-unit", o.volts_length_unit,
                 "Unit of --lab-volts-to-length's length: m, cm, mm, in")
      ->default_str(d.volts_length_unit);
  cmd.add_option("--lab-scale", o.scale, "Multiply the channel by this after unit conversion")
      ->default_str(number(d.scale));
  cmd.add_option("--lab-baseline", o.baseline, "Baseline removed before filtering: none, mean, linear, polynomial")
      ->default_str(motion::lab_baseline_name(p.baseline));
  cmd.add_option("--lab-baseline-degree", o.baseline_degree, "Degree of the polynomial baseline")
      ->default_str(std::to_string(p.baseline_degree));
  cmd.add_option("--lab-band-hz", o.band, "Zero-phase Butterworth band-pass LOW,HIGH in Hz, or none")
      ->default_str(number(p.low_hz) + "," + number(p.high_hz));
  cmd.add_option("--lab-filter-order", o.filter_order, "Butterworth order")->default_str(std::to_string(p.order));
  cmd.add_option("--lab-crossover-hz", o.crossover_hz, "Crossover of the combined channel (Hz)")
      ->default_str(number(p.crossover_hz));
}

namespace {

[[noreturn]] void bad(const char* flag, const std::string& problem) {
  throw InputError("", 0, std::string(flag) + ": " + problem);
}

}  // namespace

void reject_lab_flags_without_file(const LabFlags& o) {
  if (!o.file.empty()) return;
  const bool any = !o.format.empty() || o.delimiter || o.channel || o.acceleration_column || o.acceleration_unit ||
                   o.displacement_column || o.displacement_unit || o.volts_length_unit || o.baseline || o.band ||
                   o.header_lines || o.time_column || o.baseline_degree || o.filter_order || o.volts_to_length ||
                   o.scale || o.crossover_hz;
  if (any) throw InputError("", 0, "the --lab-* options need --lab FILE");
}

io::LabFormat lab_format_from_flags(const LabFlags& o) {
  io::LabFormat f;
  if (!o.format.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(o.format, ec))
      throw InputError(o.format, 0, "--lab-format: not a readable file");
    std::ifstream in(o.format);
    std::ostringstream text;
    text << in.rdbuf();
    f = io::lab_format_from_toml(text.str(), o.format);
  }
  if (o.delimiter && !io::parse_lab_delimiter(*o.delimiter, f.delimiter))
    bad("--lab-delimiter", "must be tab, comma or whitespace");
  if (o.header_lines) f.header_lines = *o.header_lines;
  if (o.time_column) f.time = {*o.time_column, ""};
  if (o.channel && !io::parse_lab_channel(*o.channel, f.channel))
    bad("--lab-channel", "must be acceleration, displacement or combined");
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
      if (std::sscanf(o.band->c_str(), "%lf,%lf%c", &lo, &hi, &extra) != 2)
        bad("--lab-band-hz", "must be LOW,HIGH (Hz) or none");
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
