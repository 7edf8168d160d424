#pragma once
/// The format of a laboratory (shake-table) recording and what to make of it: which columns hold
/// time and the channels, their units, and the processing (motion/lab_processing.hpp). Plain
/// data; rigid::io reads recordings with it and fills it from a TOML [lab] table or the CLI's
/// --lab-* flags (io/lab_recording.hpp). The defaults are the export of the shake-table campaign
/// in ../shared/shaketable (its README).
#include <string>

#include "rigid/motion/lab_processing.hpp"

namespace rigid::motion {

/// How the cells of a line are separated.
enum class LabDelimiter {
  tab,        ///< one tab between cells (an empty cell is an error)
  comma,      ///< one comma between cells
  whitespace  ///< any run of blanks and tabs
};

/// Which channel becomes the ground acceleration.
enum class LabChannel {
  acceleration,  ///< the accelerometer column, band-passed
  displacement,  ///< the displacement column, band-passed and differentiated twice
  /// both: the differentiated displacement below LabProcessing::crossover_hz, the accelerometer
  /// above it (motion::merge_complementary), each band-passed first
  combined
};

/// A column, by its 1-based index or by its name in the (last) header line.
struct LabColumn {
  int index = 0;     ///< 1-based; 0 when given by name
  std::string name;  ///< the header cell (trimmed, exact match); used when index == 0
  /// "3" or "Displacement [V]"
  std::string describe() const { return index > 0 ? std::to_string(index) : "'" + name + "'"; }
};

/// How to read a lab recording and what to make of it. Defaults: this lab's export.
struct LabFormat {
  LabDelimiter delimiter = LabDelimiter::tab;
  int header_lines = 1;   ///< lines before the data, 0..100; the last one names the columns
  LabColumn time{1, ""};  ///< time (unit: s), uniformly sampled and increasing
  /// which channel drives the ground: combined by default, because the pedestal is driven by the
  /// integrated velocity, which needs the displacement transducer's low frequencies (the
  /// accelerometer's content below 0.6 Hz is 2-6 times the transducer's on the shake-table
  /// campaign: noise and tilt, integrating to metres), and the rock feels the accelerometer's
  /// high frequencies (the differentiated transducer is noise above 18 Hz); the two agree within
  /// 2 % between 0.6 and 5 Hz (tests/bench/lab_channels.py)
  LabChannel channel = LabChannel::combined;
  LabColumn acceleration{2, ""};  ///< acceleration column
  /// "g", "m/s^2" or "cm/s^2" (also "gal")
  std::string acceleration_unit = "g";
  LabColumn displacement{3, ""};  ///< displacement column
  /// "m", "cm", "mm", "in", or "V" (a transducer voltage, times volts_to_length gives
  /// volts_length_unit)
  std::string displacement_unit = "V";
  double volts_to_length = 5.9797e-4;    ///< length per volt (unit: volts_length_unit / V)
  std::string volts_length_unit = "in";  ///< "m", "cm", "mm" or "in"
  double scale = 1.0;                    ///< multiplies the channel after unit conversion (unit: 1), != 0
  motion::LabProcessing processing;      ///< baseline, band-pass (0.1-25 Hz, order 4)
};

}  // namespace rigid::motion
