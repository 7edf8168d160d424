#include "rigid/io/lab_tests.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "input_file.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/csv.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

double number(const std::string& text, const std::string& column, const std::string& name, long line) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    throw InputError(name, line, "column " + column + ": '" + text + "' is not a finite number");
  return v;
}

// An outcome cell: 1 overturned, 0 stood, blank or '?' not known (a hold-out list may leave it out)
std::optional<int> outcome(const std::string& text, const std::string& name, long line) {
  if (text == "1") return 1;
  if (text == "0") return 0;
  if (text.empty() || text == "?") return std::nullopt;
  throw InputError(name, line, "column overturned: '" + text + "' is not 0, 1, blank or ? (not known)");
}

}  // namespace

LabTestList parse_lab_tests(std::string_view text, const std::string& name, const std::string& base_dir) {
  LabTestList list;
  list.source = name;
  std::map<std::string, std::size_t> column;
  std::set<long> seen;
  for (const CsvRow& row : parse_csv(text, name, {.hash_comments = true})) {
    const std::vector<std::string>& fields = row.fields;
    const long line_no = row.line;
    if (column.empty()) {
      list.header_line = line_no;
      for (std::size_t k = 0; k < fields.size(); ++k) {
        if (fields[k].empty()) continue;
        if (!column.emplace(fields[k], k).second)
          throw InputError(name, line_no, "column '" + fields[k] + "' named twice in the header");
      }
      for (const char* required : {"test_no", "file"}) {
        if (!column.count(required))
          throw InputError(name, line_no,
                           std::string("header has no '") + required +
                               "' column (expected test_no,record,pgv_over_pga_s,pga_g,file[,overturned])");
      }
      list.outcome_column = column.count("overturned") > 0;
      continue;
    }
    std::size_t needed = 0;
    for (const auto& [_, k] : column) needed = std::max(needed, k + 1);
    if (fields.size() < needed)
      throw InputError(name, line_no,
                       std::to_string(fields.size()) + " fields where the header has " + std::to_string(needed));
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
    if (const std::string* s = field("overturned")) t.overturned = outcome(*s, name, line_no);
    list.tests.push_back(std::move(t));
  }
  if (column.empty()) throw InputError(name, 0, "empty test list (no header, no test)");
  if (list.tests.empty()) throw InputError(name, 0, "no test listed below the header");
  list.has_outcomes = list.outcome_column &&
                      std::all_of(list.tests.begin(), list.tests.end(), [](const LabTest& t) { return t.overturned; });
  return list;
}

void require_outcomes(const LabTestList& list, std::string_view why) {
  if (!list.outcome_column)
    throw InputError(list.source, list.header_line, "the header has no 'overturned' column: " + std::string(why));
  for (const LabTest& t : list.tests) {
    if (!t.overturned)
      throw InputError(
          list.source, t.line,
          "test " + std::to_string(t.test_no) + ": the outcome (column overturned) is not known: " + std::string(why));
  }
}

LabTestList read_lab_tests(const std::string& path) {
  const std::string text = read_input_file(path, kMaxTextFileBytes);
  LabTestList list = parse_lab_tests(text, path, fs::path(path).parent_path().string());
  for (const LabTest& t : list.tests) {
    if (const std::string problem = input_file_problem(t.file); !problem.empty())
      throw InputError(path, t.line, "test " + std::to_string(t.test_no) + ": motion file " + problem + ": " + t.file);
  }
  return list;
}

}  // namespace rigid::io
