#pragma once
/// Campaign job files (TOML). Every problem is reported before any work starts, naming the file
/// and line: unknown keys, missing files, an empty or non-increasing scale list, impossible
/// values.
#include <string>

#include "rigid/scenario/job.hpp"

namespace rigid::io {

/// Reads and checks a job file. Scene, state and record-list paths are relative to the job file;
/// the output path is relative to the current directory.
scenario::Job load_job(const std::string& path);

/// Stable 64-bit FNV-1a hash of a text, as 16 hex digits.
std::string text_hash(const std::string& text);

/// The hash that identifies a job's results (Job::hash): text_hash of its text, with the accuracy
/// preset appended unless it is "balanced" (the settings of every cube written before the presets
/// existed, whose hashes therefore stay valid). A resume with another preset is refused.
std::string job_hash(const scenario::Job& job);

/// What job_hash hashes: the job text (with the command-line overrides the driver appends) and
/// the accuracy preset, i.e. every physics-relevant setting that is not in an input file.
std::string job_settings_text(const scenario::Job& job);

}  // namespace rigid::io
