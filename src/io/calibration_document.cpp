#include "rigid/io/calibration_document.hpp"

#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rigid/core/error.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/io/provenance.hpp"

#ifndef RIGID_VERSION
#define RIGID_VERSION "unknown"
#endif
#ifndef RIGID_GIT_HASH
#define RIGID_GIT_HASH "unknown"
#endif

namespace rigid::io {
namespace {

// SOURCE_DATE_EPOCH (reproducible-builds.org) fixes the date when set; else now.
std::string created_utc() {
  std::time_t t = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) {
    char* end = nullptr;
    const long long v = std::strtoll(epoch, &end, 10);
    if (end != epoch && *end == '\0' && v >= 0) t = static_cast<std::time_t>(v);
  }
  std::tm utc{};
  gmtime_r(&t, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string checksum_of(Json document) {
  document.erase("sha256");
  return sha256_hex(json_line(document));
}

}  // namespace

std::string rigid_version() { return RIGID_VERSION " (" RIGID_GIT_HASH ")"; }

void write_calibration_document(const std::string& path, const Json& body, const std::string& command_line) {
  Json doc;
  doc["format"] = kCalibrationFormat;
  doc["format_version"] = kCalibrationFormatVersion;
  doc["rigid_version"] = rigid_version();
  doc["created"] = created_utc();
  doc["command_line"] = command_line;
  for (const auto& [key, value] : body.items()) doc[key] = value;
  doc["sha256"] = checksum_of(doc);
  write_output_file(path, [&](std::ostream& out) { out << doc.dump(2) << "\n"; });
}

Json read_calibration_document(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path, 0, std::filesystem::exists(path, ec) ? "is not a regular file" : "no such calibration file");
  Json doc;
  try {
    std::ifstream in(path);
    doc = Json::parse(in);
  } catch (const Json::parse_error& e) {
    throw InputError(path, 0, std::string("is not a whole calibration file (truncated or not JSON): ") + e.what());
  }
  if (!doc.is_object() || !doc.contains("format") || doc["format"] != kCalibrationFormat)
    throw InputError(path, 0, "is not a calibration file (no \"format\": \"rigid calibration\")");
  if (!doc.contains("format_version") || !doc["format_version"].is_number_integer() ||
      doc["format_version"].get<long long>() != kCalibrationFormatVersion) {
    const std::string was = doc.contains("format_version") ? doc["format_version"].dump() : "none";
    throw InputError(path, 0,
                     "calibration format version " + was + " is not the one this Rigid reads (" +
                         std::to_string(kCalibrationFormatVersion) + "): calibrate again with this version");
  }
  if (!doc.contains("sha256") || !doc["sha256"].is_string() || doc["sha256"] != checksum_of(doc))
    throw InputError(path, 0,
                     "its checksum (sha256) does not match its contents: the file was edited or damaged after it "
                     "was written; calibrate or transfer again");
  return doc;
}

std::string command_line_text(int argc, const char* const* argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i] ? argv[i] : "";
    if (i) line += ' ';
    if (a.empty() || a.find_first_of(" \t'\"\\$") != std::string::npos) {
      line += '\'';
      for (char c : a) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
      line += '\'';
    } else {
      line += a;
    }
  }
  return line;
}

}  // namespace rigid::io
