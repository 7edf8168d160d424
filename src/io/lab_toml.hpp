#pragma once
// The [lab] table of an already parsed TOML document (job files), for the readers inside rigid_io.
#include <string>

#include <toml++/toml.h>

#include "rigid/io/lab_recording.hpp"

namespace rigid::io {

/// The [lab] table of root (defaults when absent); see lab_format_from_toml.
LabFormat lab_format_from_table(const toml::table& root, const std::string& file);

/// The [lab] table that lab_format_from_table reads back as `format`: the keys whose values
/// differ from the defaults (an empty table for the default format).
toml::table lab_format_table(const LabFormat& format);

}  // namespace rigid::io
