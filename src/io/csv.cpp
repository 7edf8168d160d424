// CSV written and read as RFC 4180 says (include/rigid/io/csv.hpp).
#include "rigid/io/csv.hpp"

#include <charconv>
#include <cmath>
#include <limits>

#include "rigid/core/error.hpp"

namespace rigid::io {
namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

}  // namespace

std::string csv_field(std::string_view text) {
  // blanks at an end are quoted too: readers (ours included) trim unquoted fields
  const bool padded = !text.empty() && (blank(text.front()) || blank(text.back()));
  if (!padded && text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

std::string csv_number(double x) {
  if (std::isnan(x)) return {};
  char buf[32];  // the shortest round-trip text of a double is at most 24 characters
  const auto end = std::to_chars(buf, buf + sizeof buf, x).ptr;
  return std::string(buf, end);
}

CsvWriter::CsvWriter(std::ostream& out, std::string line_end) : out_(out), line_end_(std::move(line_end)) {}

void CsvWriter::separate() {
  if (row_started_) out_ << ',';
  row_started_ = true;
}

CsvWriter& CsvWriter::field(std::string_view text) {
  separate();
  out_ << csv_field(text);
  return *this;
}

CsvWriter& CsvWriter::field(long long value) {
  separate();
  out_ << value;
  return *this;
}

CsvWriter& CsvWriter::field(double value) {
  separate();
  out_ << csv_number(value);
  return *this;
}

CsvWriter& CsvWriter::fixed(double value, int decimals) {
  separate();
  if (std::isnan(value)) return *this;
  // sized for the largest double (309 digits) and the decimals asked for
  std::string buf(std::size_t(std::numeric_limits<double>::max_exponent10 + 8 + std::max(decimals, 0)), '\0');
  const auto r =
      std::to_chars(buf.data(), buf.data() + buf.size(), value, std::chars_format::fixed, std::max(decimals, 0));
  out_ << std::string_view(buf.data(), std::size_t(r.ptr - buf.data()));
  return *this;
}

void CsvWriter::end_row() {
  out_ << line_end_;
  row_started_ = false;
}

void CsvWriter::row(const std::vector<std::string>& fields) {
  for (const std::string& f : fields) field(f);
  end_row();
}

std::vector<CsvRow> parse_csv(std::string_view text, const std::string& name, const CsvReadOptions& options) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::vector<CsvRow> rows;
  long line = 1;
  std::size_t i = 0;
  const std::size_t n = text.size();
  while (i < n) {
    // a record: skip comment and blank lines first
    const std::size_t eol = text.find('\n', i);
    const std::string_view first_line = text.substr(i, eol == std::string_view::npos ? n - i : eol - i);
    const bool blank_line = first_line.find_first_not_of(" \t\r") == std::string_view::npos;
    if (blank_line || (options.hash_comments && !first_line.empty() && first_line[0] == '#')) {
      i = eol == std::string_view::npos ? n : eol + 1;
      ++line;
      continue;
    }
    CsvRow row;
    row.line = line;
    while (true) {  // one field per pass
      while (i < n && blank(text[i])) ++i;
      std::string field;
      if (i < n && text[i] == '"') {
        const long opened = line;
        ++i;
        while (true) {
          if (i >= n) throw InputError(name, opened, "a quoted field is never closed (a '\"' is missing)");
          if (text[i] == '"') {
            if (i + 1 < n && text[i + 1] == '"') {
              field += '"';
              i += 2;
              continue;
            }
            ++i;
            break;
          }
          if (text[i] == '\n') ++line;
          field += text[i++];
        }
        while (i < n && (blank(text[i]) || text[i] == '\r')) ++i;
        if (i < n && text[i] != ',' && text[i] != '\n')
          throw InputError(name, line,
                           "text after the closing quote of a field (a quote inside a quoted field is written \"\")");
      } else {
        const std::size_t start = i;
        while (i < n && text[i] != ',' && text[i] != '\n') ++i;
        std::string_view raw = text.substr(start, i - start);
        while (!raw.empty() && (blank(raw.back()) || raw.back() == '\r')) raw.remove_suffix(1);
        field = std::string(raw);
      }
      row.fields.push_back(std::move(field));
      if (i < n && text[i] == ',') {
        ++i;
        continue;
      }
      if (i < n) {  // the line break that ends the record
        ++i;
        ++line;
      }
      break;
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace rigid::io
