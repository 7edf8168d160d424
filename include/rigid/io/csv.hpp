#pragma once
/// CSV as RFC 4180 says it, written and read in one place: every table the project writes with
/// names in it (record names, scene names, messages) goes through CsvWriter, and every table it
/// reads back through parse_csv, so a name with a comma, a quote or a line break, of any length,
/// stays one field.
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace rigid::io {

/// The field as RFC 4180 writes it: as it is, unless it holds a comma, a double quote or a line
/// break, or starts or ends with a blank; then in double quotes, its quotes doubled.
std::string csv_field(std::string_view text);

/// The shortest text that reads back as the same double; NaN (nothing known) as an empty field.
std::string csv_number(double x);

/// Writes a table row by row: fields are separated by commas and quoted by csv_field; rows end in
/// `line_end` ("\n" by default; "\r\n" as RFC 4180 has it).
///
///   io::CsvWriter csv(out);
///   csv.row({"test_no", "record", "pga_g"});
///   csv.field(test.test_no).field(test.record).fixed(pga_g, 5).end_row();
class CsvWriter {
 public:
  explicit CsvWriter(std::ostream& out, std::string line_end = "\n");

  /// A text field (quoted when it needs to be).
  CsvWriter& field(std::string_view text);
  CsvWriter& field(const std::string& text) { return field(std::string_view(text)); }
  CsvWriter& field(const char* text) { return field(std::string_view(text)); }
  /// A whole number.
  CsvWriter& field(long long value);
  CsvWriter& field(long value) { return field(static_cast<long long>(value)); }
  CsvWriter& field(int value) { return field(static_cast<long long>(value)); }
  /// A number as csv_number writes it (shortest exact text; NaN empty).
  CsvWriter& field(double value);
  /// A number with `decimals` digits after the point (as printf's %.Nf; NaN empty), of any size.
  CsvWriter& fixed(double value, int decimals);
  /// Ends the row.
  void end_row();
  /// The given text fields as one row.
  void row(const std::vector<std::string>& fields);

 private:
  void separate();
  std::ostream& out_;
  std::string line_end_;
  bool row_started_ = false;
};

/// One record of a CSV text and the line it starts on (1-based).
struct CsvRow {
  long line = 0;
  std::vector<std::string> fields;
};

struct CsvReadOptions {
  /// A line whose first character is '#' is a comment (outside a quoted field).
  bool hash_comments = false;
};

/// Splits a CSV text into its records (RFC 4180): fields separated by commas, records by LF or
/// CRLF; a field in double quotes may hold commas, doubled quotes and line breaks. A UTF-8
/// byte-order mark at the start (Excel writes one) is skipped; blanks around a field are
/// trimmed; blank lines are skipped. Throws rigid::InputError(name, line, ...) for a quote left
/// open at the end of the text or text after a field's closing quote.
std::vector<CsvRow> parse_csv(std::string_view text, const std::string& name, const CsvReadOptions& options = {});

}  // namespace rigid::io
