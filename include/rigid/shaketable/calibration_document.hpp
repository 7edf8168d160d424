#pragma once
/// The calibration document's format is io's (rigid/io/calibration_document.hpp), read by a
/// campaign's job as well as by the shake-table workflow; its names as the workflow spells them.
#include "rigid/io/calibration_document.hpp"

namespace rigid::shaketable {

using io::command_line_text;
using io::kCalibrationFormat;
using io::kCalibrationFormatVersion;
using io::read_calibration_document;
using io::rigid_version;
using io::write_calibration_document;

}  // namespace rigid::shaketable
