#pragma once
/// NAME.calibration.json as a document (io owns the format: the shake-table workflow writes it, a
/// campaign's job reads it): which kind of file it is, the version of its format,
/// which Rigid wrote it, when and by which command line, and a SHA-256 over everything else, so
/// that a file edited by hand, cut short or written by another format version is refused in one
/// line instead of being read as a calibration (docs/validation-shaketable.md lists its fields).
#include <string>

#include "rigid/io/json.hpp"

namespace rigid::io {

inline constexpr const char* kCalibrationFormat = "rigid calibration";
/// 1: the files written before the format carried a version (read by no Rigid since); 2: this one.
inline constexpr int kCalibrationFormatVersion = 2;

/// The program's version as the documents state it ("0.1.0 (GITHASH)").
std::string rigid_version();

/// Writes `body` (a JSON object) to `path` (io::write_output_file: whole or not at all) after the
/// envelope keys format, format_version, rigid_version, created (UTC, ISO 8601; the time of
/// SOURCE_DATE_EPOCH when that is set, so that outputs can be made reproducible) and
/// command_line, and followed by sha256: the SHA-256 of the compact dump (io::json_line) of the
/// document without it.
void write_calibration_document(const std::string& path, const Json& body, const std::string& command_line);

/// Reads `path` and proves it is a whole, unedited calibration of this format version: throws
/// InputError naming the file for a missing file, text that is not JSON (a truncated file), a
/// document of another kind, another format version, or a checksum that does not match.
Json read_calibration_document(const std::string& path);

/// "'a b' c": a command line as one line, each argument quoted when it holds a space or quote.
std::string command_line_text(int argc, const char* const* argv);

}  // namespace rigid::io
