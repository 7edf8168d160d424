// Lab (shake-table) recordings: the LabFormat checks and its TOML source, the bounded gzip/text
// reader and read_lab_motion (include/rigid/io/lab_recording.hpp).
#include "rigid/io/lab_recording.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <zlib.h>

#include "input_file.hpp"
#include "lab_toml.hpp"
#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "toml_values.hpp"

namespace rigid::io {

namespace {

// a gzip file decompressing to more than this is refused (a 73 s test is ~2 MB of text)
constexpr std::size_t kMaxDecompressedBytes = std::size_t(1) << 30;
constexpr std::size_t kMinSamples = 64;

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string printable(std::string_view s) {
  std::string o;
  for (char c : s.substr(0, 40)) o += (c >= 0x20 && c < 0x7f) ? c : '?';
  if (s.size() > 40) o += "...";
  return o;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string o(s);
  for (char& c : o) c = char(std::tolower(static_cast<unsigned char>(c)));
  return o;
}

// Inflates a gzip stream (concatenated members allowed) chunk by chunk, handing each chunk to
// `take`; refuses a corrupt or truncated stream, and more than kMaxDecompressedBytes, naming the
// number of complete lines reached.
template <typename Take>
void inflate_gzip(std::string& raw, const std::string& path, Take take) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 16) != Z_OK) throw InputError(path, 0, "cannot start gzip decompression");
  z.next_in = reinterpret_cast<Bytef*>(raw.data());
  z.avail_in = uInt(raw.size());
  std::vector<char> buf(std::size_t(1) << 16);
  std::size_t total = 0;
  long lines = 0;
  const auto fail = [&](const std::string& what) {
    inflateEnd(&z);
    throw InputError(path, lines + 1, what + " (after " + std::to_string(lines) + " complete lines)");
  };
  while (true) {
    z.next_out = reinterpret_cast<Bytef*>(buf.data());
    z.avail_out = uInt(buf.size());
    const int rc = inflate(&z, Z_NO_FLUSH);
    const std::size_t got = buf.size() - z.avail_out;
    total += got;
    if (total > kMaxDecompressedBytes) fail("decompresses to more than 1 GB");
    lines += long(std::count(buf.data(), buf.data() + got, '\n'));
    take(buf.data(), got);
    if (rc == Z_STREAM_END) {
      if (z.avail_in == 0) break;
      if (inflateReset(&z) != Z_OK) fail("corrupt gzip stream");  // another member follows
      continue;
    }
    if (rc == Z_BUF_ERROR || (rc == Z_OK && z.avail_in == 0 && z.avail_out != 0)) fail("gzip stream truncated");
    if (rc != Z_OK) fail(std::string("corrupt gzip stream: ") + (z.msg ? z.msg : "inflate failed"));
  }
  inflateEnd(&z);
}

// The file's text, gzip streams (magic 1f 8b) inflated. The limit costs what it says: a first pass
// measures the inflated size (and refuses a bomb) without keeping it, so the text is allocated
// once at its exact size, never by doubling a growing buffer past the limit.
std::string file_text(const std::string& path) {
  std::string raw = read_input_file(path, kMaxBulkFileBytes);
  if (raw.size() < 2 || static_cast<unsigned char>(raw[0]) != 0x1f || static_cast<unsigned char>(raw[1]) != 0x8b)
    return raw;
  std::size_t size = 0;
  inflate_gzip(raw, path, [&](const char*, std::size_t n) { size += n; });
  std::string out;
  out.reserve(size);
  inflate_gzip(raw, path, [&](const char* data, std::size_t n) { out.append(data, n); });
  return out;
}

// the cells of a line by the delimiter, each trimmed of blanks
std::vector<std::string_view> split_cells(std::string_view line, LabDelimiter d) {
  std::vector<std::string_view> cells;
  if (d == LabDelimiter::whitespace) {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      if (i >= line.size()) break;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
      cells.push_back(line.substr(i, j - i));
      i = j;
    }
    return cells;
  }
  const char sep = d == LabDelimiter::tab ? '\t' : ',';
  std::size_t start = 0;
  while (true) {
    const std::size_t at = line.find(sep, start);
    cells.push_back(trim(line.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start)));
    if (at == std::string_view::npos) break;
    start = at + 1;
  }
  return cells;
}

bool parse_number(std::string_view cell, double& v) {
  if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
  if (cell.empty()) return false;
  const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), v);
  return r.ec == std::errc() && r.ptr == cell.data() + cell.size();
}

// the unit written in a header cell: the text in [] or () at its end, "" when none
std::string header_unit(std::string_view cell) {
  cell = trim(cell);
  if (cell.empty()) return "";
  const char close = cell.back();
  const char open = close == ']' ? '[' : close == ')' ? '(' : 0;
  if (!open) return "";
  const std::size_t at = cell.rfind(open);
  if (at == std::string_view::npos) return "";
  return std::string(trim(cell.substr(at + 1, cell.size() - at - 2)));
}

// canonical spelling of a unit, for comparing a header's unit with the format's
std::string canonical_unit(std::string_view u) {
  std::string s = lower(trim(u));
  s.erase(std::remove(s.begin(), s.end(), ' '), s.end());
  if (s == "m/s2" || s == "m/s/s" || s == "m/s^2" || s == "ms-2") return "m/s^2";
  if (s == "cm/s2" || s == "cm/s/s" || s == "cm/s^2" || s == "gal" || s == "cms-2") return "cm/s^2";
  if (s == "inch" || s == "inches" || s == "in") return "in";
  if (s == "v" || s == "volt" || s == "volts") return "v";
  return s;
}

[[noreturn]] void format_error(const std::string& source, long line, const std::string& key,
                               const std::string& problem) {
  // flags name themselves; a TOML [lab] table names its key
  throw InputError(source, line, (source.empty() ? "--lab-" : "[lab] ") + key + ": " + problem);
}

std::string flag_key(std::string key, const std::string& source) {
  if (source.empty()) std::replace(key.begin(), key.end(), '_', '-');
  return key;
}

// The index of a column in the header's cells (1-based index checked against the row later).
std::size_t column_position(const LabColumn& c, const std::vector<std::string_view>& header, bool have_header,
                            const std::string& path, long header_line, const char* what) {
  if (c.index > 0) return std::size_t(c.index - 1);
  if (!have_header)
    throw InputError(path, 0,
                     std::string("the ") + what + " column is named '" + c.name +
                         "' but the format has no header line (header_lines = 0)");
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == c.name) return i;
  throw InputError(path, header_line, std::string("the header has no ") + what + " column '" + c.name + "'");
}

}  // namespace

double acceleration_unit_to_si(std::string_view unit) {
  const std::string u = canonical_unit(unit);
  if (u == "g") return kGravity;
  if (u == "m/s^2") return 1.0;
  if (u == "cm/s^2") return 0.01;
  return 0.0;
}

double length_unit_to_si(std::string_view unit) {
  const std::string u = canonical_unit(unit);
  if (u == "m") return 1.0;
  if (u == "cm") return 0.01;
  if (u == "mm") return 0.001;
  if (u == "in") return 0.0254;
  return 0.0;
}

const char* lab_delimiter_name(LabDelimiter d) {
  return d == LabDelimiter::tab ? "tab" : d == LabDelimiter::comma ? "comma" : "whitespace";
}

bool parse_lab_delimiter(std::string_view text, LabDelimiter& out) {
  if (text == "tab")
    out = LabDelimiter::tab;
  else if (text == "comma")
    out = LabDelimiter::comma;
  else if (text == "whitespace")
    out = LabDelimiter::whitespace;
  else
    return false;
  return true;
}

const char* lab_channel_name(LabChannel c) {
  return c == LabChannel::acceleration ? "acceleration" : c == LabChannel::displacement ? "displacement" : "combined";
}

bool parse_lab_channel(std::string_view text, LabChannel& out) {
  if (text == "acceleration")
    out = LabChannel::acceleration;
  else if (text == "displacement")
    out = LabChannel::displacement;
  else if (text == "combined")
    out = LabChannel::combined;
  else
    return false;
  return true;
}

bool parse_lab_baseline(std::string_view text, motion::LabBaseline& out) {
  if (text == "none")
    out = motion::LabBaseline::none;
  else if (text == "mean")
    out = motion::LabBaseline::mean;
  else if (text == "linear")
    out = motion::LabBaseline::linear;
  else if (text == "polynomial")
    out = motion::LabBaseline::polynomial;
  else
    return false;
  return true;
}

LabColumn parse_lab_column(std::string_view text) {
  const std::string_view t = trim(text);
  const bool digits =
      !t.empty() && t.size() <= 6 && std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (digits) return {std::stoi(std::string(t)), ""};
  return {0, std::string(t)};
}

void check_lab_format(const LabFormat& f, const std::string& source, long line) {
  const auto bad = [&](const char* key, const std::string& problem) {
    format_error(source, line, flag_key(key, source), problem);
  };
  if (f.header_lines < 0 || f.header_lines > 100) bad("header_lines", "must be 0 to 100");
  const std::pair<const char*, const LabColumn*> columns[] = {
      {"time_column", &f.time}, {"acceleration_column", &f.acceleration}, {"displacement_column", &f.displacement}};
  for (const auto& [key, c] : columns) {
    if (c->index < 0 || (c->index == 0 && c->name.empty()) || c->index > 1000)
      bad(key, "must be a column number from 1 to 1000 or a header name");
  }
  if (f.channel != LabChannel::displacement && f.acceleration.index > 0 && f.acceleration.index == f.time.index)
    bad("acceleration_column", "is the time column (" + std::to_string(f.time.index) + ")");
  if (f.channel != LabChannel::acceleration && f.displacement.index > 0 && f.displacement.index == f.time.index)
    bad("displacement_column", "is the time column (" + std::to_string(f.time.index) + ")");
  if (acceleration_unit_to_si(f.acceleration_unit) == 0.0)
    bad("acceleration_unit", "must be g, m/s^2 or cm/s^2, not '" + f.acceleration_unit + "'");
  if (canonical_unit(f.displacement_unit) != "v" && length_unit_to_si(f.displacement_unit) == 0.0)
    bad("displacement_unit", "must be m, cm, mm, in or V, not '" + f.displacement_unit + "'");
  if (length_unit_to_si(f.volts_length_unit) == 0.0)
    bad("volts_length_unit", "must be m, cm, mm or in, not '" + f.volts_length_unit + "'");
  if (!std::isfinite(f.volts_to_length) || f.volts_to_length == 0.0)
    bad("volts_to_length", "must be a finite non-zero number (length per volt)");
  if (!std::isfinite(f.scale) || f.scale == 0.0) bad("scale", "must be a finite non-zero number");
  const motion::LabProcessing& p = f.processing;
  if (p.baseline_degree < 0 || p.baseline_degree > 10) bad("baseline_degree", "must be 0 to 10");
  if (p.band_pass) {
    if (!(p.low_hz > 0) || !(p.high_hz > p.low_hz) || !std::isfinite(p.high_hz))
      bad("band_hz", "needs 0 < low < high (Hz), got " + num(p.low_hz) + "-" + num(p.high_hz));
    if (p.order < 1 || p.order > 8) bad("filter_order", "must be 1 to 8");
  }
  if (f.channel == LabChannel::combined) {
    if (!p.band_pass) bad("band_hz", "the combined channel needs a band-pass");
    if (!(p.crossover_hz > p.low_hz) || !(p.crossover_hz < p.high_hz))
      bad("crossover_hz", "must lie inside the band (" + num(p.low_hz) + "-" + num(p.high_hz) + " Hz)");
  }
}

LabFormat lab_format_from_toml(std::string_view toml_text, const std::string& file) {
  return lab_format_from_table(parse_toml(std::string(toml_text), file), file);
}

LabFormat lab_format_from_table(const toml::table& root, const std::string& file) {
  LabFormat f;
  const toml::node* node = root.get("lab");
  if (!node) return f;
  const toml::table* t = node->as_table();
  if (!t) throw InputError(file, line_of(*node), "lab must be a table ([lab])");
  reject_unknown(*t,
                 {"delimiter", "header_lines", "time_column", "channel", "acceleration_column", "acceleration_unit",
                  "displacement_column", "displacement_unit", "volts_to_length", "volts_length_unit", "scale",
                  "baseline", "baseline_degree", "band_hz", "filter_order", "crossover_hz"},
                 file, "[lab]");
  const auto integer = [&](const char* key, int fallback) {
    const toml::node* n = t->get(key);
    if (!n) return fallback;
    const auto v = n->value_exact<std::int64_t>();
    if (!v || *v < -1000000 || *v > 1000000)
      throw InputError(file, line_of(*n), std::string("[lab] ") + key + " must be an integer");
    return int(*v);
  };
  const auto column = [&](const char* key, LabColumn fallback) {
    const toml::node* n = t->get(key);
    if (!n) return fallback;
    if (const auto v = n->value_exact<std::int64_t>()) {
      if (*v < 1 || *v > 1000)
        throw InputError(file, line_of(*n), std::string("[lab] ") + key + " must be from 1 to 1000");
      return LabColumn{int(*v), ""};
    }
    const auto s = n->value_exact<std::string>();
    if (!s || trim(*s).empty())
      throw InputError(file, line_of(*n),
                       std::string("[lab] ") + key + " must be a column number (1-based) or a header name");
    return LabColumn{0, std::string(trim(*s))};
  };
  const auto keyword = [&](const char* key, auto parse, auto& out, const char* choices) {
    const toml::node* n = t->get(key);
    if (!n) return;
    const auto s = n->value_exact<std::string>();
    if (!s || !parse(*s, out)) throw InputError(file, line_of(*n), std::string("[lab] ") + key + " must be " + choices);
  };
  keyword("delimiter", parse_lab_delimiter, f.delimiter, "\"tab\", \"comma\" or \"whitespace\"");
  f.header_lines = integer("header_lines", f.header_lines);
  f.time = column("time_column", f.time);
  keyword("channel", parse_lab_channel, f.channel, "\"acceleration\", \"displacement\" or \"combined\"");
  f.acceleration = column("acceleration_column", f.acceleration);
  f.acceleration_unit = optional_string(*t, "acceleration_unit", f.acceleration_unit, file);
  f.displacement = column("displacement_column", f.displacement);
  f.displacement_unit = optional_string(*t, "displacement_unit", f.displacement_unit, file);
  f.volts_to_length = optional_number(*t, "volts_to_length", f.volts_to_length, file);
  f.volts_length_unit = optional_string(*t, "volts_length_unit", f.volts_length_unit, file);
  f.scale = optional_number(*t, "scale", f.scale, file);
  keyword("baseline", parse_lab_baseline, f.processing.baseline, "\"none\", \"mean\", \"linear\" or \"polynomial\"");
  f.processing.baseline_degree = integer("baseline_degree", f.processing.baseline_degree);
  if (const toml::node* n = t->get("band_hz")) {
    const auto s = n->value_exact<std::string>();
    const toml::array* a = n->as_array();
    if (s && *s == "none") {
      f.processing.band_pass = false;
    } else if (a && a->size() == 2 && (*a)[0].value<double>() && (*a)[1].value<double>()) {
      f.processing.low_hz = *(*a)[0].value<double>();
      f.processing.high_hz = *(*a)[1].value<double>();
    } else {
      throw InputError(file, line_of(*n), "[lab] band_hz must be [low, high] (Hz) or \"none\"");
    }
  }
  f.processing.order = integer("filter_order", f.processing.order);
  f.processing.crossover_hz = optional_number(*t, "crossover_hz", f.processing.crossover_hz, file);
  check_lab_format(f, file, line_of(*node));
  return f;
}

toml::table lab_format_table(const LabFormat& f) {
  const LabFormat d;
  toml::table t;
  const auto column = [&](const char* key, const LabColumn& c, const LabColumn& fallback) {
    if (c.index == fallback.index && c.name == fallback.name) return;
    if (c.index > 0) {
      t.insert(key, c.index);
    } else {
      t.insert(key, c.name);
    }
  };
  const auto value = [&](const char* key, const auto& v, const auto& fallback) {
    if (v != fallback) t.insert(key, v);
  };
  if (f.delimiter != d.delimiter) t.insert("delimiter", lab_delimiter_name(f.delimiter));
  value("header_lines", f.header_lines, d.header_lines);
  column("time_column", f.time, d.time);
  if (f.channel != d.channel) t.insert("channel", lab_channel_name(f.channel));
  column("acceleration_column", f.acceleration, d.acceleration);
  value("acceleration_unit", f.acceleration_unit, d.acceleration_unit);
  column("displacement_column", f.displacement, d.displacement);
  value("displacement_unit", f.displacement_unit, d.displacement_unit);
  value("volts_to_length", f.volts_to_length, d.volts_to_length);
  value("volts_length_unit", f.volts_length_unit, d.volts_length_unit);
  value("scale", f.scale, d.scale);
  const motion::LabProcessing &p = f.processing, &dp = d.processing;
  if (p.baseline != dp.baseline) t.insert("baseline", motion::lab_baseline_name(p.baseline));
  value("baseline_degree", p.baseline_degree, dp.baseline_degree);
  if (!p.band_pass) {
    t.insert("band_hz", "none");
  } else if (p.low_hz != dp.low_hz || p.high_hz != dp.high_hz) {
    t.insert("band_hz", toml::array{p.low_hz, p.high_hz});
  }
  value("filter_order", p.order, dp.order);
  value("crossover_hz", p.crossover_hz, dp.crossover_hz);
  return t;
}

LabTable read_lab_table(const std::filesystem::path& path_in, const LabFormat& f) {
  const std::string path = path_in.string();
  const std::string text = file_text(path);
  LabTable table;
  table.source = path;
  const bool want_acc = f.channel != LabChannel::displacement, want_disp = f.channel != LabChannel::acceleration;

  std::size_t pos = 0;
  long line_no = 0;
  const auto next_line = [&](std::string_view& line) {
    if (pos >= text.size()) return false;
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    line = std::string_view(text).substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = end + 1;
    ++line_no;
    return true;
  };

  std::string_view line;
  std::vector<std::string_view> header_cells;
  for (int h = 0; h < f.header_lines; ++h) {
    if (!next_line(line))
      throw InputError(path, line_no, "the file ends within its " + std::to_string(f.header_lines) + " header line(s)");
    table.header.emplace_back(line);
  }
  const long header_line = line_no;
  if (f.header_lines > 0) {
    header_cells = split_cells(table.header.back(), f.delimiter);
    // a header made of numbers is a data line: the file has fewer header lines than the format says
    double v;
    const bool numeric =
        std::all_of(header_cells.begin(), header_cells.end(), [&](std::string_view c) { return parse_number(c, v); });
    if (numeric && !header_cells.empty())
      throw InputError(path, header_line, "expected a header line, found numbers (set header_lines)");
  }
  const std::size_t time_at = column_position(f.time, header_cells, f.header_lines > 0, path, header_line, "time");
  const std::size_t none = std::size_t(-1);
  const std::size_t acc_at =
      want_acc ? column_position(f.acceleration, header_cells, f.header_lines > 0, path, header_line, "acceleration")
               : none;
  const std::size_t disp_at =
      want_disp ? column_position(f.displacement, header_cells, f.header_lines > 0, path, header_line, "displacement")
                : none;
  std::size_t need = time_at + 1;
  if (want_acc) need = std::max(need, acc_at + 1);
  if (want_disp) need = std::max(need, disp_at + 1);
  if (f.header_lines > 0) {
    if (header_cells.size() < need)
      throw InputError(path, header_line,
                       "the header has " + std::to_string(header_cells.size()) + " columns, the format reads column " +
                           std::to_string(need));
    // a unit in the header must be the one the format converts from
    const auto check_unit = [&](std::size_t at, const std::string& unit, const char* what) {
      const std::string said = header_unit(header_cells[at]);
      if (!said.empty() && canonical_unit(said) != canonical_unit(unit))
        throw InputError(path, header_line,
                         std::string("the ") + what + " column's header '" + printable(header_cells[at]) + "' says " +
                             said + ", the format says " + unit);
    };
    if (want_acc) check_unit(acc_at, f.acceleration_unit, "acceleration");
    if (want_disp) check_unit(disp_at, f.displacement_unit, "displacement");
  }

  while (next_line(line)) {
    if (trim(line).empty()) {
      // blank lines may end the file, not interrupt it
      const std::size_t mark = pos;
      const long mark_line = line_no;
      std::string_view rest;
      bool more = false;
      while (next_line(rest))
        if (!trim(rest).empty()) {
          more = true;
          break;
        }
      if (more) throw InputError(path, mark_line, "blank line inside the data");
      pos = mark;
      break;
    }
    if (table.first_data_line == 0) table.first_data_line = line_no;
    const std::vector<std::string_view> cells = split_cells(line, f.delimiter);
    if (cells.size() < need)
      throw InputError(path, line_no,
                       "short row: " + std::to_string(cells.size()) + " cells, column " + std::to_string(need) +
                           " is read (truncated file?)");
    const auto cell = [&](std::size_t at, const char* what) {
      double v = 0.0;
      const std::string_view c = cells[at];
      if (c.empty())
        throw InputError(path, line_no, std::string("empty ") + what + " cell (column " + std::to_string(at + 1) + ")");
      if (!parse_number(c, v)) {
        const std::string l = lower(c);
        if (l.find("nan") != std::string::npos || l.find("inf") != std::string::npos)
          throw InputError(path, line_no, std::string("NaN or infinite ") + what + " '" + printable(c) + "'");
        throw InputError(path, line_no, std::string("non-numeric ") + what + " '" + printable(c) + "'");
      }
      if (!std::isfinite(v))
        throw InputError(path, line_no, std::string("NaN or infinite ") + what + " '" + printable(c) + "'");
      return v;
    };
    const double t = cell(time_at, "time");
    if (!table.time.empty() && !(t > table.time.back()))
      throw InputError(path, line_no,
                       "time " + num(t) + " s does not increase (previous " + num(table.time.back()) + " s)");
    table.time.push_back(t);
    if (want_acc) table.acceleration.push_back(cell(acc_at, "acceleration"));
    if (want_disp) table.displacement.push_back(cell(disp_at, "displacement"));
  }
  if (table.time.size() < kMinSamples)
    throw InputError(
        path, line_no,
        "only " + std::to_string(table.time.size()) + " samples, at least " + std::to_string(kMinSamples) + " needed");
  const std::size_t n = table.time.size();
  table.dt = (table.time.back() - table.time.front()) / double(n - 1);
  // printed times carry round-off (6 digits: 1e-4 s at 30 s, 8 % of 1/800 s); a dropped or
  // repeated sample moves every later time by a whole step
  for (std::size_t i = 1; i < n; ++i) {
    const double expected = table.time.front() + double(i) * table.dt;
    if (std::abs(table.time[i] - expected) > 0.5 * table.dt)
      throw InputError(path, table.first_data_line + long(i),
                       "non-uniform sampling: time " + num(table.time[i]) + " s, expected " + num(expected) +
                           " s for a step of " + num(table.dt) + " s");
  }
  return table;
}

motion::GroundMotion read_lab_motion(const std::filesystem::path& path, const LabFormat& f) {
  check_lab_format(f, "", 0);
  const LabTable table = read_lab_table(path, f);
  std::vector<double> acc = table.acceleration, disp = table.displacement;
  const double acc_to_si = acceleration_unit_to_si(f.acceleration_unit) * f.scale;
  const bool volts = canonical_unit(f.displacement_unit) == "v";
  const double disp_to_si =
      (volts ? f.volts_to_length * length_unit_to_si(f.volts_length_unit) : length_unit_to_si(f.displacement_unit)) *
      f.scale;
  // each sample in SI checked where its line is known: a 1e308 cell or a 1e308 V-to-length
  // factor would otherwise turn the whole filtered motion into NaN
  const std::string scaled = f.scale != 1.0 ? " scaled by " + num(f.scale) : "";
  for (std::size_t i = 0; i < acc.size(); ++i) {
    const double raw = acc[i];
    acc[i] *= acc_to_si;
    if (const std::string problem = motion::drive_sample_problem(acc[i]); !problem.empty())
      throw InputError(path.string(), table.first_data_line + long(i),
                       "acceleration " + num(raw) + " " + f.acceleration_unit + scaled + ": " + problem);
  }
  for (std::size_t i = 0; i < disp.size(); ++i) {
    const double raw = disp[i];
    disp[i] *= disp_to_si;
    if (!std::isfinite(disp[i]))
      throw InputError(path.string(), table.first_data_line + long(i),
                       "displacement " + num(raw) + " " + f.displacement_unit + scaled +
                           " is not a finite number of metres (volts_to_length?)");
  }
  motion::GroundMotion m;
  const motion::LabProcessing& p = f.processing;
  try {
    switch (f.channel) {
      case LabChannel::acceleration:
        m.x = motion::process_acceleration(acc, table.dt, p);
        break;
      case LabChannel::displacement:
        m.x = motion::acceleration_from_displacement(disp, table.dt, p);
        break;
      case LabChannel::combined:
        m.x = motion::merge_complementary(motion::acceleration_from_displacement(disp, table.dt, p),
                                          motion::process_acceleration(acc, table.dt, p), p.crossover_hz, p.order,
                                          table.dt);
        break;
    }
  } catch (const std::invalid_argument& e) {
    throw InputError(table.source, 0, e.what());
  }
  // the processed drive under the same rule (a displacement differentiated twice can break it): a
  // filter spreads one bad sample over the record, so the line named is the raw channel's peak,
  // the sample that made it (a displacement weighed as the acceleration at the crossover)
  if (const auto bad = motion::first_bad_drive_sample(m)) {
    const auto peak = [](const std::vector<double>& v) {
      const auto larger = [](double a, double b) { return std::abs(a) < std::abs(b); };
      return std::size_t(std::max_element(v.begin(), v.end(), larger) - v.begin());
    };
    const double omega = 2.0 * kPi * p.crossover_hz;
    const bool from_disp =
        f.channel == LabChannel::displacement ||
        (f.channel == LabChannel::combined && std::abs(disp[peak(disp)]) * omega * omega > std::abs(acc[peak(acc)]));
    const std::size_t at = from_disp ? peak(disp) : peak(acc);
    const double value = from_disp ? table.displacement[at] : table.acceleration[at];
    const double processed = m.x[bad->index];
    throw InputError(table.source, table.first_data_line + long(at),
                     "the processed acceleration (" + std::string(lab_channel_name(f.channel)) +
                         " channel) at t = " + num(double(bad->index) * table.dt) + " s is " +
                         (std::isfinite(processed) ? num(processed / kGravity) + " g: " : "") + bad->problem +
                         "; the largest " + (from_disp ? "displacement" : "acceleration") + " sample, " + num(value) +
                         " " + (from_disp ? f.displacement_unit : f.acceleration_unit) + ", is on this line");
  }
  std::string name = path.filename().string();
  for (const char* ext : {".gz", ".txt", ".csv", ".tsv", ".dat"}) {
    const std::string e(ext);
    if (name.size() > e.size() && lower(name.substr(name.size() - e.size())) == e) name.resize(name.size() - e.size());
  }
  m.name = name;
  m.dt = table.dt;
  m.label_x = lab_channel_name(f.channel);
  m.sources = {table.source};
  return m;
}

std::string describe_lab_processing(const LabFormat& f) {
  const std::string acc = "acceleration column " + f.acceleration.describe() + " in " + f.acceleration_unit;
  const std::string disp =
      "displacement column " + f.displacement.describe() + " in " +
      (canonical_unit(f.displacement_unit) == "v" ? "V x " + num(f.volts_to_length) + " " + f.volts_length_unit
                                                  : f.displacement_unit);
  std::string s =
      f.channel == LabChannel::acceleration ? acc
      : f.channel == LabChannel::displacement
          ? disp + " (differentiated twice)"
          : disp + " (differentiated twice) below " + num(f.processing.crossover_hz) + " Hz, " + acc + " above";
  if (f.scale != 1.0) s += ", scaled by " + num(f.scale);
  const motion::LabProcessing& p = f.processing;
  if (p.baseline == motion::LabBaseline::polynomial)
    s += ", polynomial baseline of degree " + std::to_string(p.baseline_degree) + " removed";
  else if (p.baseline != motion::LabBaseline::none)
    s += std::string(", ") + motion::lab_baseline_name(p.baseline) + " removed";
  if (p.band_pass)
    s += ", band-pass " + num(p.low_hz) + "-" + num(p.high_hz) + " Hz order " + std::to_string(p.order) + " zero-phase";
  else
    s += ", not filtered";
  return s;
}

LabFormat read_lab_format(const std::string& path) {
  const toml::table root = parse_toml(read_input_file(path, kMaxTextFileBytes), path);
  if (!root.contains("lab")) throw InputError(path, 1, "has no [lab] table (the recordings' format)");
  return lab_format_from_table(root, path);
}

}  // namespace rigid::io
