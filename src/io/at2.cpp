// PEER .AT2 reader and writer, three-component sets (physics.md §6).
#include "rigid/io/at2.hpp"

#include "input_file.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/json.hpp"

namespace rigid::io {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kHeaderSearchLines = 12;
constexpr long long kMaxNpts = 100'000'000;

struct Line {
  std::string_view text;
  long number;  // 1-based
};

// splits at LF; a CR before the LF (also CR CR LF) is dropped by trimming. Files with CR only
// (classic Mac) split at CR.
std::vector<Line> split_lines(std::string_view t) {
  const char sep = t.find('\n') == std::string_view::npos ? '\r' : '\n';
  std::vector<Line> lines;
  std::size_t start = 0;
  long number = 1;
  while (start < t.size()) {
    std::size_t end = t.find(sep, start);
    if (end == std::string_view::npos) end = t.size();
    lines.push_back({t.substr(start, end - start), number++});
    start = end + 1;
  }
  return lines;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && (is_space(s.front()) || s.front() == '\0')) s.remove_prefix(1);
  while (!s.empty() && (is_space(s.back()) || s.back() == '\0')) s.remove_suffix(1);
  return s;
}

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = char(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

std::string printable(std::string_view s) {
  std::string o;
  for (char c : s.substr(0, 40)) o += (c >= 0x20 && c < 0x7f) ? c : '?';
  if (s.size() > 40) o += "...";
  return o;
}

// Parses one number at s[pos]: [sign] digits [. digits] [(E|D)[sign]digits | sign digits].
// The letter-less exponent (Fortran, |exponent| > 99) is taken only when the digits after the
// sign are not followed by '.', otherwise the sign starts the next glued field. Returns false
// if no number starts at pos.
bool scan_number(std::string_view s, std::size_t& pos, double& value) {
  std::size_t i = pos;
  char buf[96];
  std::size_t b = 0;
  auto put = [&](char c) {
    if (b + 1 < sizeof buf) buf[b++] = c;
  };
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) {
    if (s[i] == '-') put('-');
    ++i;
  }
  std::size_t digits = 0;
  while (i < s.size() && is_digit(s[i])) put(s[i++]), ++digits;
  if (i < s.size() && s[i] == '.') {
    put(s[i++]);
    while (i < s.size() && is_digit(s[i])) put(s[i++]), ++digits;
  }
  if (digits == 0 || digits > 60) return false;
  if (i < s.size() && (s[i] == 'E' || s[i] == 'e' || s[i] == 'D' || s[i] == 'd')) {
    std::size_t j = i + 1;
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) ++j;
    std::size_t k = j;
    while (k < s.size() && is_digit(s[k])) ++k;
    if (k == j || k - j > 6) return false;  // a letter without exponent digits: not a number
    put('e');
    if (s[i + 1] == '-') put('-');
    for (std::size_t q = j; q < k; ++q) put(s[q]);
    i = k;
  } else if (i + 1 < s.size() && (s[i] == '+' || s[i] == '-') && is_digit(s[i + 1])) {
    std::size_t k = i + 1;
    while (k < s.size() && is_digit(s[k])) ++k;
    if (!(k < s.size() && s[k] == '.') && k - (i + 1) <= 6) {
      put('e');
      if (s[i] == '-') put('-');
      for (std::size_t q = i + 1; q < k; ++q) put(s[q]);
      i = k;
    }
  }
  const auto r = std::from_chars(buf, buf + b, value);
  if (r.ec == std::errc::result_out_of_range) {
    // underflow to a denormal/zero is harmless; overflow is reported as non-finite
    value = (std::string_view(buf, b).find("e-") != std::string_view::npos) ? 0.0 : HUGE_VAL;
  } else if (r.ec != std::errc() || r.ptr != buf + b) {
    return false;
  }
  pos = i;
  return true;
}

[[noreturn]] void fail(const std::string& file, long line, const std::string& what) {
  throw InputError(file, line, what);
}

// values of a data line, appended to out; throws on anything non-numeric or non-finite
void parse_values(std::string_view line, const std::string& file, long number, std::vector<double>& out,
                  long long limit) {
  std::size_t pos = 0;
  while (true) {
    while (pos < line.size() && (is_space(line[pos]) || line[pos] == ',' || line[pos] == '\0')) ++pos;
    if (pos >= line.size()) return;
    std::size_t tok_end = pos;
    while (tok_end < line.size() && !is_space(line[tok_end]) && line[tok_end] != ',') ++tok_end;
    const std::string_view tok = line.substr(pos, tok_end - pos);
    // one whitespace token may hold several sign-glued fixed-width fields
    std::size_t p = 0;
    while (p < tok.size()) {
      double v = 0.0;
      if (!scan_number(tok, p, v)) {
        const std::string u = upper(tok);
        if (u.find("NAN") != std::string::npos || u.find("INF") != std::string::npos)
          fail(file, number, "NaN or infinite value '" + printable(tok) + "'");
        fail(file, number, "non-numeric value '" + printable(tok) + "'");
      }
      if (!std::isfinite(v)) fail(file, number, "value out of range '" + printable(tok) + "'");
      if ((long long)out.size() >= limit) return;  // the caller reports the excess
      out.push_back(v);
    }
    pos = tok_end;
  }
}

// does the line consist of numbers only (a headerless file's first line)?
bool numeric_line(std::string_view line) {
  std::vector<double> tmp;
  try {
    parse_values(line, "", 0, tmp, 1000);
  } catch (const InputError&) {
    return false;
  }
  return !tmp.empty();
}

// position just after `key` followed by optional blanks and '=', or npos
std::size_t after_key(const std::string& u, const std::string& key, std::size_t from = 0) {
  for (std::size_t at = u.find(key, from); at != std::string::npos; at = u.find(key, at + 1)) {
    // whole word on the left (so "NPTS" does not match inside "XNPTS" and "DT" not in "WIDTH")
    if (at > 0 && std::isalpha(static_cast<unsigned char>(u[at - 1]))) continue;
    std::size_t i = at + key.size();
    while (i < u.size() && is_space(u[i])) ++i;
    if (i < u.size() && u[i] == '=') return i + 1;
  }
  return std::string::npos;
}

bool leading_number(const std::string& u, std::size_t pos, double& v) {
  while (pos < u.size() && is_space(u[pos])) ++pos;
  return pos < u.size() && scan_number(u, pos, v);
}

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

}  // namespace

motion::Component At2Record::component_si() const {
  motion::Component c;
  c.dt = dt;
  c.label = component;
  c.acc.resize(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) c.acc[i] = values[i] * unit_to_si;
  return c;
}

At2Record parse_at2(std::string_view text, const std::string& name, const At2ReadOptions& options) {
  At2Record rec;
  rec.source = name;
  rec.unit_to_si = kGravity;
  const std::vector<Line> lines = split_lines(text);
  if (options.dt < 0.0 || !std::isfinite(options.dt) || (options.dt > 0.0 && options.dt < 1e-6) || options.dt > 10.0)
    fail(name, 0, "the given time step must be in [1e-6, 10] s");

  // find the NPTS/DT line among the first lines (PEER files have it as line 4)
  std::size_t hdr = lines.size();
  for (std::size_t i = 0; i < lines.size() && i < kHeaderSearchLines; ++i) {
    const std::string u = upper(lines[i].text);
    if (u.find("NPTS") != std::string::npos || after_key(u, "DT") != std::string::npos) {
      hdr = i;
      break;
    }
  }
  long long npts = -1;  // -1: count the values
  std::size_t data_from = 0;
  if (hdr == lines.size()) {
    // no header line: a headerless file (numbers from line 1) needs the caller's dt
    std::size_t first = 0;
    while (first < lines.size() && trim(lines[first].text).empty()) ++first;
    if (first == lines.size()) fail(name, 0, "empty file: no header and no values");
    if (!numeric_line(lines[first].text))
      fail(name, 0,
           "missing AT2 header: no NPTS/DT line in the first " + std::to_string(kHeaderSearchLines) + " lines");
    if (!(options.dt > 0.0))
      fail(name, lines[first].number,
           "no header (data from line " + std::to_string(lines[first].number) +
               "): give the time step of a headerless file explicitly");
    rec.header_kind = At2Header::none;
    rec.dt = options.dt;
    data_from = first;
  } else {
    const Line& L = lines[hdr];
    const std::string u = upper(L.text);
    for (std::size_t i = 0; i <= hdr; ++i) rec.header.emplace_back(trim(lines[i].text));
    double dt = 0.0, n = 0.0;
    const std::size_t npos_kw = after_key(u, "NPTS");
    const std::size_t dpos = after_key(u, "DT");
    if (npos_kw != std::string::npos || (dpos != std::string::npos && u.find("NPTS") == std::string::npos)) {
      rec.header_kind = npos_kw != std::string::npos ? At2Header::keyword : At2Header::dt_only;
      if (npos_kw != std::string::npos && !leading_number(u, npos_kw, n))
        fail(name, L.number, "NPTS= is not followed by a number");
      if (dpos == std::string::npos) {
        if (!(options.dt > 0.0)) fail(name, L.number, "header has no DT=");
        dt = options.dt;
      } else if (!leading_number(u, dpos, dt)) {
        fail(name, L.number, "DT= is not followed by a number");
      }
      if (npos_kw != std::string::npos) npts = (long long)std::min(n, 1e18);
      if (npos_kw != std::string::npos && (n != std::floor(n) || n < 0))
        fail(name, L.number, "NPTS must be a non-negative integer, got " + num(n));
    } else {
      // old positional line: "4096   0.0100   NPTS, DT" (values before the labels)
      rec.header_kind = At2Header::positional;
      const std::size_t label = u.find("NPTS");
      std::vector<double> nums;
      std::string_view before = std::string_view(L.text).substr(0, label);
      try {
        parse_values(before, name, L.number, nums, 8);
      } catch (const InputError&) {
        fail(name, L.number, "cannot read 'NPTS, DT' values from the header line");
      }
      if (nums.size() < 2) fail(name, L.number, "header line lacks NPTS and DT values");
      n = nums[0];
      dt = nums[1];
      if (n != std::floor(n) || n < 0) fail(name, L.number, "NPTS must be a non-negative integer, got " + num(n));
      npts = (long long)std::min(n, 1e18);
    }
    if (!(dt > 0.0) || !std::isfinite(dt)) fail(name, L.number, "DT must be positive, got " + num(dt));
    // a time step outside [1 us, 10 s] is a corrupt header, not a record
    if (dt < 1e-6 || dt > 10.0)
      fail(name, L.number, "DT=" + num(dt) + " s is outside the plausible range [1e-6, 10] s");
    if (options.dt > 0.0 && std::abs(options.dt - dt) > 1e-6 * dt)
      fail(name, L.number, "header DT=" + num(dt) + " s disagrees with the given dt " + num(options.dt) + " s");
    if (npts > kMaxNpts) fail(name, L.number, "NPTS=" + std::to_string(npts) + " is too large");
    rec.dt = dt;
    // what the header says about the quantity and its units
    for (std::size_t i = 0; i < hdr; ++i) {
      const std::string h = upper(lines[i].text);
      const std::size_t at = h.find("UNITS");
      if (at == std::string::npos) continue;
      if (h.find("VELOCITY") != std::string::npos || h.find("DISPLACEMENT") != std::string::npos)
        fail(name, lines[i].number, "not an acceleration record (header: " + printable(trim(lines[i].text)) + ")");
      const std::string unit = h.substr(at);
      if (unit.find("CM/S") != std::string::npos || unit.find("GAL") != std::string::npos)
        rec.unit_to_si = 0.01;
      else if (unit.find("M/S") != std::string::npos)
        rec.unit_to_si = 1.0;
    }
    // component label: last comma field of line 2 (PEER: "event, date, station, component")
    if (hdr >= 2) {
      const std::string_view l2 = trim(lines[1].text);
      const std::size_t comma = l2.rfind(',');
      // a long last field is free text (non-PEER headers), not a component label
      if (comma != std::string_view::npos && trim(l2.substr(comma + 1)).size() <= 16)
        rec.component = std::string(trim(l2.substr(comma + 1)));
    }
    data_from = hdr + 1;
  }

  // values: everything after the header, free format
  const long long limit = npts >= 0 ? npts + 1 : kMaxNpts;
  rec.values.reserve(std::size_t(std::min<long long>(npts >= 0 ? npts : 0, (long long)text.size() / 2 + 1)));
  long last_data_line = data_from < lines.size() ? lines[data_from].number : 0;
  for (std::size_t i = data_from; i < lines.size(); ++i) {
    const std::size_t before = rec.values.size();
    parse_values(lines[i].text, name, lines[i].number, rec.values, limit);
    if (rec.values.size() != before) {
      last_data_line = lines[i].number;
      rec.value_lines.emplace_back(before, lines[i].number);
    }
    if (npts >= 0 && (long long)rec.values.size() > npts)
      fail(name, lines[i].number, "more values than NPTS=" + std::to_string(npts) + " in the header");
    if (npts < 0 && (long long)rec.values.size() >= kMaxNpts)
      fail(name, lines[i].number, "more than " + std::to_string(kMaxNpts) + " values");
  }
  if (npts >= 0 && (long long)rec.values.size() != npts)
    fail(name, last_data_line,
         "NPTS=" + std::to_string(npts) + " in the header but " + std::to_string(rec.values.size()) + " values follow");
  if (rec.values.empty()) fail(name, last_data_line, "no acceleration values");
  return rec;
}

At2Record read_at2(const std::string& path, const At2ReadOptions& options) {
  At2Record rec = parse_at2(read_input_file(path, kMaxBulkFileBytes), path, options);
  for (std::size_t k = 0; k < rec.values.size(); ++k) {
    if (const std::string problem = motion::drive_sample_problem(rec.values[k] * rec.unit_to_si); !problem.empty())
      fail(path, rec.line_of_value(k), "acceleration " + num(rec.values[k]) + ": " + problem);
  }
  return rec;
}

long At2Record::line_of_value(std::size_t i) const {
  const auto after = std::upper_bound(value_lines.begin(), value_lines.end(), i,
                                      [](std::size_t v, const std::pair<std::size_t, long>& l) { return v < l.first; });
  return after == value_lines.begin() ? 0 : std::prev(after)->second;
}

std::string format_at2(const motion::Component& c, const At2WriteOptions& options) {
  const int digits = std::clamp(options.digits, 1, 17);
  const int per_line = std::max(options.per_line, 1);
  const int width = digits + 8;  // sign, d, '.', digits-1, 'E+xx', blank(s)
  std::string desc = options.description;
  std::replace(desc.begin(), desc.end(), '\n', ' ');
  std::string label = c.label.empty() ? "X" : c.label;
  std::replace(label.begin(), label.end(), ',', ' ');
  std::string o = options.title + "\n" + (desc.empty() ? std::string("Rigid") : desc) + ", " + label +
                  "\nACCELERATION TIME SERIES IN UNITS OF G\n";
  char buf[128];
  std::snprintf(buf, sizeof buf, "NPTS= %7zu, DT= %.10g SEC\n", c.acc.size(), c.dt);
  o += buf;
  o.reserve(o.size() + c.acc.size() * std::size_t(width) + c.acc.size() / per_line + 2);
  for (std::size_t i = 0; i < c.acc.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%*.*E", width, digits - 1, c.acc[i] / kGravity);
    o += buf;
    if ((i + 1) % std::size_t(per_line) == 0 || i + 1 == c.acc.size()) o += '\n';
  }
  return o;
}

void write_at2(const std::string& path, const motion::Component& c, const At2WriteOptions& options) {
  const std::string text = format_at2(c, options);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) fail(path, 0, "cannot write file");
  out << text;
  out.close();
  if (!out) fail(path, 0, "error while writing file");
}

namespace {

std::string resolve_path(const std::string& p, const std::string& base_dir) {
  if (base_dir.empty() || fs::path(p).is_absolute()) return p;
  return (fs::path(base_dir) / p).string();
}

std::string stem_of(const std::string& p) { return fs::path(p).stem().string(); }

}  // namespace

SetFiles resolve_set(const std::string& spec_in, const std::string& base_dir) {
  const std::string spec(trim(spec_in));
  if (spec.empty()) fail("", 0, "empty motion set");
  SetFiles s;
  // a single role-keyed file (x=FILE) is a one-element list; other '=' belong to the path
  const std::size_t eq0 = spec.find('=');
  const std::string key0 = eq0 == std::string::npos ? "" : upper(trim(std::string_view(spec).substr(0, eq0)));
  const bool single_role = key0 == "X" || key0 == "H1" || key0 == "Y" || key0 == "H2" || key0 == "Z" || key0 == "V";
  if (spec.find(',') != std::string::npos || single_role) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = spec.find(',', start);
      parts.emplace_back(
          trim(std::string_view(spec).substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    if (parts.size() > 3) fail(spec, 0, "a motion set has at most 3 files (H1,H2,V)");
    bool keyed = false, plain = false;
    std::string* slots[3] = {&s.x, &s.y, &s.z};
    for (std::size_t i = 0; i < parts.size(); ++i) {
      std::string& p = parts[i];
      if (p.empty()) fail(spec, 0, "empty file name in the motion set list");
      const std::size_t eq = p.find('=');
      std::string* slot = nullptr;
      if (eq != std::string::npos) {
        const std::string key = upper(trim(std::string_view(p).substr(0, eq)));
        if (key == "X" || key == "H1")
          slot = &s.x;
        else if (key == "Y" || key == "H2")
          slot = &s.y;
        else if (key == "Z" || key == "V")
          slot = &s.z;
        else
          fail(spec, 0, "unknown component role '" + key + "' (use x=, y=, z=)");
        p = std::string(trim(std::string_view(p).substr(eq + 1)));
        if (p.empty()) fail(spec, 0, "empty file name after '" + key + "='");
        keyed = true;
      } else {
        slot = slots[i];
        plain = true;
      }
      if (keyed && plain) fail(spec, 0, "mix of x=/y=/z= roles and positional files");
      if (!slot->empty()) fail(spec, 0, "component given twice");
      *slot = resolve_path(p, base_dir);
    }
    if (s.x.empty()) fail(spec, 0, "the set has no first horizontal (x=) file");
    // name: the common prefix of the horizontal stems, without trailing separators
    const std::string a = stem_of(s.x), b = s.y.empty() ? a : stem_of(s.y);
    std::size_t k = 0;
    while (k < a.size() && k < b.size() && a[k] == b[k]) ++k;
    std::string name = a.substr(0, k);
    while (!name.empty() && (name.back() == '-' || name.back() == '_' || name.back() == '.')) name.pop_back();
    s.name = name.empty() ? a : name;
    return s;
  }
  s.x = resolve_path(spec, base_dir);
  const std::string stem = stem_of(s.x);
  s.name = stem;
  // Rigid naming NAME-X.AT2: the -Y and -Z siblings join when present
  if (stem.size() > 2 && stem[stem.size() - 2] == '-' && (stem.back() == 'X' || stem.back() == 'x')) {
    const bool lower = stem.back() == 'x';
    const fs::path px(s.x);
    const std::string base = stem.substr(0, stem.size() - 1);
    const fs::path py = px.parent_path() / (base + (lower ? "y" : "Y") + px.extension().string());
    const fs::path pz = px.parent_path() / (base + (lower ? "z" : "Z") + px.extension().string());
    std::error_code ec;
    if (fs::is_regular_file(py, ec)) s.y = py.string();
    if (fs::is_regular_file(pz, ec)) s.z = pz.string();
    s.name = stem.substr(0, stem.size() - 2);
  }
  return s;
}

motion::GroundMotion read_motion_set(const std::string& spec, const SetReadOptions& options) {
  const SetFiles f = resolve_set(spec, options.base_dir);
  std::vector<motion::Component> comps;
  std::vector<std::string> sources;
  for (const std::string* p : {&f.x, &f.y, &f.z}) {
    if (p->empty()) {
      comps.emplace_back();  // placeholder for an absent component
      continue;
    }
    comps.push_back(read_at2(*p, options.at2).component_si());
    sources.push_back(*p);
  }
  // an absent H2 with a present V: build from x and z, keep has_y false
  const bool has_y = !f.y.empty(), has_z = !f.z.empty();
  std::vector<motion::Component> present;
  present.push_back(comps[0]);
  if (has_y) present.push_back(comps[1]);
  if (has_z) present.push_back(comps[2]);
  motion::GroundMotion m = motion::make_ground_motion(f.name, std::move(present), options.align);
  if (has_z && !has_y) {
    // make_ground_motion put V in the H2 slot; move it
    m.z = std::move(m.y);
    m.label_z = m.label_y;
    m.y.clear();
    m.label_y.clear();
    m.has_y = false;
    m.has_z = true;
  }
  m.sources = sources;
  return m;
}

std::vector<std::string> write_motion_set(const motion::GroundMotion& m, const std::string& out_prefix,
                                          const At2WriteOptions& options) {
  std::vector<std::string> written;
  struct Part {
    const std::vector<double>* a;
    bool present;
    const char* suffix;
    const std::string* label;
    std::size_t source;
  };
  const Part parts[] = {{&m.x, true, "-X.AT2", &m.label_x, 0},
                        {&m.y, m.has_y, "-Y.AT2", &m.label_y, 1},
                        {&m.z, m.has_z, "-Z.AT2", &m.label_z, 2}};
  for (const Part& p : parts) {
    if (!p.present) continue;
    motion::Component c{*p.a, m.dt, p.label->empty() ? std::string(p.suffix + 1, 1) : *p.label};
    At2WriteOptions o = options;
    if (o.description.empty()) {
      o.description = m.name;
      if (p.source < m.sources.size()) o.description += " " + m.sources[p.source];
      std::replace(o.description.begin(), o.description.end(), ',', ';');
    }
    const std::string path = out_prefix + p.suffix;
    write_at2(path, c, o);
    written.push_back(path);
  }
  return written;
}

std::string motion_info_report(const std::string& spec, const SetReadOptions& read,
                               const motion::MeasureOptions& measures, const std::vector<double>& sa_periods,
                               bool json) {
  const motion::GroundMotion m = read_motion_set(spec, read);
  const motion::MotionInfo info = motion::motion_info(m, measures, sa_periods);
  return json ? motion_info_json(info) : motion::to_text(info);
}

}  // namespace rigid::io
