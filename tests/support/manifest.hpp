#pragma once
// Reads the shared waveforms' manifest.csv (quoted fields may hold commas) into one map per row,
// keyed by the header's column names.
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace rigid::test {

inline std::vector<std::map<std::string, std::string>> read_manifest(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::vector<std::map<std::string, std::string>> rows;
  std::vector<std::string> header;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> f(1);
    bool quoted = false;
    for (char c : line) {
      if (c == '"')
        quoted = !quoted;
      else if (c == ',' && !quoted)
        f.emplace_back();
      else
        f.back() += c;
    }
    if (header.empty()) {
      header = f;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

}  // namespace rigid::test
