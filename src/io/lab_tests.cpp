#include "rigid/io/lab_tests.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "input_file.hpp"
#include "rigid/core/error.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

std::string trim(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && (s[a] == ' ' || s[a] == '\t' || s[a] == '\r')) ++a;
  while (b > a && (s[b - 1] == ' ' || s[b - 1] == '\t' || s[b - 1] == '\r')) --b;
  std::string out(s.substr(a, b - a));
  if (out.size() >= 2 && out.front() == '"' && out.back() == '"') out = out.substr(1, out.size() - 2);
  return out;
}

std::vector<std::string> split_csv(std::string_view line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  bool quoted = false;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i < line.size() && line[i] == '"') quoted = !quoted;
    if (i == line.size() || (line[i] == ',' && !quoted)) {
      fields.push_back(trim(line.substr(start, i - start)));
      start = i + 1;
    }
  }
  return fields;
}

double number(const std::string& text, const std::string& column, const std::string& name, long line) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    throw InputError(name, line, "column " + column + ": '" + text + "' is not a finite number");
  return v;
}

}  // namespace

LabTestList parse_lab_tests(std::string_view text, const std::string& name, const std::string& base_dir) {
  LabTestList list;
  list.source = name;
  std::map<std::string, std::size_t> column;
  long line_no = 0;
  std::set<long> seen;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view raw = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    const std::string line = trim(raw);
    if (line.empty() || line[0] == '#') {
      if (pos > text.size()) break;
      continue;
    }
    const std::vector<std::string> fields = split_csv(raw);
    if (column.empty()) {
      for (std::size_t k = 0; k < fields.size(); ++k) {
        if (fields[k].empty()) continue;
        if (!column.emplace(fields[k], k).second)
          throw InputError(name, line_no, "column '" + fields[k] + "' named twice in the header");
      }
      for (const char* required : {"test_no", "file"}) {
        if (!column.count(required))
          throw InputError(name, line_no, std::string("header has no '") + required +
                                              "' column (expected test_no,record,pgv_over_pga_s,pga_g,file[,overturned])");
      }
      list.has_outcomes = column.count("overturned") > 0;
      continue;
    }
    std::size_t needed = 0;
    for (const auto& [_, k] : column) needed = std::max(needed, k + 1);
    if (fields.size() < needed)
      throw InputError(name, line_no, std::to_string(fields.size()) + " fields where the header has " +
                                          std::to_string(needed));
    auto field = [&](const char* c) -> const std::string* {
      const auto it = column.find(c);
      return it == column.end() ? nullptr : &fields[it->second];
    };
    LabTest t;
    t.line = line_no;
    const double test_no = number(*field("test_no"), "test_no", name, line_no);
    if (test_no != std::floor(test_no) || std::abs(test_no) > 1e15)
      throw InputError(name, line_no, "column test_no: '" + *field("test_no") + "' is not a whole number");
    t.test_no = long(test_no);
    if (!seen.insert(t.test_no).second)
      throw InputError(name, line_no, "test " + std::to_string(t.test_no) + " listed twice");
    const std::string& file = *field("file");
    if (file.empty()) throw InputError(name, line_no, "column file is empty");
    t.file = fs::path(file).is_absolute() ? file : (fs::path(base_dir) / file).lexically_normal().string();
    const std::string* record = field("record");
    t.record = record && !record->empty() ? *record : fs::path(file).stem().string();
    if (const std::string* s = field("pga_g"); s && !s->empty()) t.sheet_pga_g = number(*s, "pga_g", name, line_no);
    if (const std::string* s = field("pgv_over_pga_s"); s && !s->empty())
      t.sheet_pgv_pga_s = number(*s, "pgv_over_pga_s", name, line_no);
    if (const std::string* s = field("overturned")) {
      if (*s != "0" && *s != "1")
        throw InputError(name, line_no, "column overturned: '" + *s + "' is not 0 or 1");
      t.overturned = *s == "1" ? 1 : 0;
    }
    list.tests.push_back(std::move(t));
    if (pos > text.size()) break;
  }
  if (column.empty()) throw InputError(name, 0, "empty test list (no header, no test)");
  if (list.tests.empty()) throw InputError(name, 0, "no test listed below the header");
  return list;
}

LabTestList read_lab_tests(const std::string& path) {
  const std::string text = read_input_file(path, kMaxTextFileBytes);
  LabTestList list = parse_lab_tests(text, path, fs::path(path).parent_path().string());
  for (const LabTest& t : list.tests) {
    std::error_code ec;
    if (!fs::is_regular_file(t.file, ec))
      throw InputError(path, t.line, "test " + std::to_string(t.test_no) + ": motion file " + t.file + " not found");
  }
  return list;
}

}  // namespace rigid::io
