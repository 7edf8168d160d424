#pragma once
// The [lab] table of an already parsed TOML document (job files), for the readers inside rigid_io.
#include <string>

#include <toml++/toml.h>

#include "rigid/io/lab_recording.hpp"

namespace rigid::io {

/// The [lab] table of root (defaults when absent); see lab_format_from_toml.
LabFormat lab_format_from_table(const toml::table& root, const std::string& file);

}  // namespace rigid::io
