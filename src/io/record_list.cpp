// Record lists (study table TSV, Rigid .ABF) and the listed-vs-computed GMRotI comparison.
#include "rigid/io/record_list.hpp"

#include "input_file.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/json.hpp"
#include "rigid/motion/measures.hpp"

namespace rigid::io {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::vector<std::pair<std::string_view, long>> lines_of(std::string_view t) {
  std::vector<std::pair<std::string_view, long>> out;
  std::size_t start = 0;
  long n = 1;
  while (start < t.size()) {
    std::size_t end = t.find('\n', start);
    if (end == std::string_view::npos) end = t.size();
    std::string_view l = t.substr(start, end - start);
    while (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    out.push_back({l, n++});
    start = end + 1;
  }
  return out;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> f;
  std::size_t start = 0;
  while (true) {
    const std::size_t at = s.find(sep, start);
    f.push_back(s.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
    if (at == std::string_view::npos) return f;
    start = at + 1;
  }
}

std::vector<std::string_view> split_blank(std::string_view s, const char* seps) {
  std::vector<std::string_view> f;
  std::size_t i = 0;
  const std::string_view sv(seps);
  while (i < s.size()) {
    while (i < s.size() && sv.find(s[i]) != std::string_view::npos) ++i;
    const std::size_t j0 = i;
    while (i < s.size() && sv.find(s[i]) == std::string_view::npos) ++i;
    if (i > j0) f.push_back(s.substr(j0, i - j0));
  }
  return f;
}

bool to_double(std::string_view s, double& v) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(v);
}

double field(std::string_view s, const std::string& file, long line, const char* what, bool optional) {
  double v = 0.0;
  if (trim(s).empty() && optional) return std::numeric_limits<double>::quiet_NaN();
  if (!to_double(s, v))
    throw InputError(file, line, std::string(what) + " is not a number: '" + std::string(trim(s).substr(0, 40)) + "'");
  return v;
}

void check_window(const RecordEntry& e, const std::string& file) {
  if (!(e.start >= 0.0) || !(e.end > e.start))
    throw InputError(file, e.line, "bad time window: start must be >= 0 and end > start");
}

std::string dir_of(const std::string& path) { return std::filesystem::path(path).parent_path().string(); }

// A record listed twice would be simulated twice and counted twice in every fit: refused at the
// second row, naming the first.
void reject_duplicate_rows(const RecordList& list, const std::string& name) {
  std::map<std::tuple<std::string, double, double>, long> first_line;
  for (const RecordEntry& e : list.records) {
    const auto [at, inserted] = first_line.emplace(std::tuple{e.file, e.start, e.end}, e.line);
    if (!inserted)
      throw InputError(
          name, e.line,
          "duplicate record: " + e.file + " with the same time window as line " + std::to_string(at->second));
  }
}

}  // namespace

RecordList parse_record_table(std::string_view text, const std::string& name) {
  RecordList list;
  list.source = name;
  bool first = true;
  for (const auto& [raw, number] : lines_of(text)) {
    const std::string_view l = trim(raw);
    if (l.empty() || l.front() == '#') continue;
    const auto f = split(raw, '\t');
    double year = 0.0;
    if (first && (f.size() < 2 || !to_double(f[1], year))) {
      first = false;  // header line
      continue;
    }
    first = false;
    if (f.size() < 6)
      throw InputError(name, number,
                       "expected 9 tab-separated columns (earthquake, year, "
                       "magnitude, file, start, end, PGA, PGV, PGV/PGA), got " +
                           std::to_string(f.size()));
    if (f.size() > 10) throw InputError(name, number, "more than 10 tab-separated columns (the 10th, optional: align)");
    RecordEntry e;
    e.line = number;
    e.earthquake = std::string(trim(f[0]));
    const double y = field(f[1], name, number, "year", true);
    e.year = std::isfinite(y) && std::abs(y) < 1e5 ? int(y) : 0;
    e.magnitude = field(f[2], name, number, "magnitude", true);
    e.file = std::string(trim(f[3]));
    if (e.file.empty()) throw InputError(name, number, "empty file column");
    e.start = field(f[4], name, number, "start", false);
    e.end = field(f[5], name, number, "end", false);
    check_window(e, name);
    if (f.size() > 6) e.gmroti_pga_g = field(f[6], name, number, "GMRotI PGA", true);
    if (f.size() > 7) e.gmroti_pgv_cm_s = field(f[7], name, number, "GMRotI PGV", true);
    if (f.size() > 8) e.pgv_pga_s = field(f[8], name, number, "PGV/PGA", true);
    if (f.size() > 9) {
      const std::string_view align = trim(f[9]);
      if (!align.empty() && align != "auto" && align != "resample")
        throw InputError(
            name, number,
            "align must be empty, auto (pad lengths within 1 %) or resample, not \"" + std::string(align) + "\"");
      e.resample = align == "resample";
    }
    list.records.push_back(std::move(e));
  }
  reject_duplicate_rows(list, name);
  return list;
}

RecordList parse_abf(std::string_view text, const std::string& name) {
  RecordList list;
  list.source = name;
  int stage = 0;  // 0: scales, 1: deprecated 0, 2: records
  for (const auto& [raw, number] : lines_of(text)) {
    const std::string_view l = trim(raw);
    if (l.empty() || l.front() == '#') continue;
    if (stage == 0) {
      for (const auto tok : split_blank(l, " \t,;")) {
        const double v = field(tok, name, number, "PGA scale", false);
        if (!(v > 0.0)) throw InputError(name, number, "PGA scales must be positive");
        list.pga_scales_g.push_back(v);
      }
      if (list.pga_scales_g.empty()) throw InputError(name, number, "no PGA scales on line 1");
      stage = 1;
    } else if (stage == 1) {
      double v = 0.0;
      if (!to_double(l, v) || v != 0.0)
        throw InputError(name, number,
                         "line 2 of a batch file is a deprecated field that must "
                         "be 0, got '" +
                             std::string(l.substr(0, 40)) + "'");
      stage = 2;
    } else {
      const auto f = split_blank(l, " \t");
      if (f.size() != 1 && f.size() != 3)
        throw InputError(name, number,
                         "expected 'FILE' or 'FILE START END', got " + std::to_string(f.size()) + " fields");
      RecordEntry e;
      e.line = number;
      e.file = std::string(f[0]);
      if (f.size() == 3) {
        e.start = field(f[1], name, number, "start", false);
        e.end = field(f[2], name, number, "end", false);
        check_window(e, name);
      }
      list.records.push_back(std::move(e));
    }
  }
  if (stage < 2 && !list.pga_scales_g.empty())
    throw InputError(name, 0, "batch file ends before its deprecated line 2");
  if (stage == 0) throw InputError(name, 0, "empty batch file");
  reject_duplicate_rows(list, name);
  return list;
}

RecordList read_record_list(const std::string& path) {
  const std::string text = read_input_file(path, kMaxTextFileBytes);
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  RecordList list = ext == ".abf" ? parse_abf(text, path) : parse_record_table(text, path);
  list.base_dir = dir_of(path);
  return list;
}

RecordCheck check_record(const RecordEntry& entry, const SetReadOptions& options, const std::string& spec_override) {
  RecordCheck c;
  c.entry = entry;
  c.spec = spec_override.empty() ? entry.file : spec_override;
  const motion::GroundMotion full = read_motion_set(c.spec, options);
  if (!full.has_y) throw InputError(c.spec, 0, "GMRotI needs two horizontal components");
  c.npts = full.npts();
  c.dt = full.dt;
  const double g = kGravity;
  const auto hf = motion::horizontal_measures(full);
  c.gmroti_pga_g = hf.gmroti50_pga / g;
  c.gmroti_pgv_cm_s = hf.gmroti50_pgv * 100.0;
  c.gmrotd_pga_g = hf.gmrotd50_pga / g;
  c.gmrotd_pgv_cm_s = hf.gmrotd50_pgv * 100.0;
  c.gmroti_angle_deg = hf.gmroti50_angle_deg;
  const auto gm = motion::gmrot_by_angle(full.x, full.y);
  c.gm_min_pga_g = *std::min_element(gm.begin(), gm.end()) / g;
  c.gm_max_pga_g = *std::max_element(gm.begin(), gm.end()) / g;
  c.rotd0_pga_g = motion::rotd(full.x, full.y, 0.0) / g;
  c.rotd100_pga_g = hf.rotd100_pga / g;
  c.window_clamped = entry.end > full.duration() + 0.5 * full.dt;
  const motion::GroundMotion w =
      (entry.start > 0.0 || std::isfinite(entry.end)) ? motion::windowed(full, entry.start, entry.end) : full;
  const auto hw = motion::horizontal_measures(w);
  c.window_gmroti_pga_g = hw.gmroti50_pga / g;
  c.window_gmroti_pgv_cm_s = hw.gmroti50_pgv * 100.0;
  c.window_gmrotd_pga_g = hw.gmrotd50_pga / g;
  c.window_gmrotd_pgv_cm_s = hw.gmrotd50_pgv * 100.0;
  if (entry.gmroti_pga_g > 0.0) c.pga_rel_diff = c.gmroti_pga_g / entry.gmroti_pga_g - 1.0;
  if (entry.gmroti_pgv_cm_s > 0.0) c.pgv_rel_diff = c.gmroti_pgv_cm_s / entry.gmroti_pgv_cm_s - 1.0;
  return c;
}

std::string to_json(const RecordCheck& c) {
  Json j;
  j["file"] = c.entry.file;
  j["spec"] = c.spec;
  j["npts"] = c.npts;
  j["dt_s"] = c.dt;
  j["start_s"] = c.entry.start;
  j["end_s"] = c.entry.end;
  j["window_clamped"] = c.window_clamped;
  j["listed_gmroti50_pga_g"] = c.entry.gmroti_pga_g;
  j["listed_gmroti50_pgv_cm_s"] = c.entry.gmroti_pgv_cm_s;
  j["gmroti50_pga_g"] = c.gmroti_pga_g;
  j["gmroti50_pgv_cm_s"] = c.gmroti_pgv_cm_s;
  j["gmrotd50_pga_g"] = c.gmrotd_pga_g;
  j["gmrotd50_pgv_cm_s"] = c.gmrotd_pgv_cm_s;
  j["window_gmroti50_pga_g"] = c.window_gmroti_pga_g;
  j["window_gmroti50_pgv_cm_s"] = c.window_gmroti_pgv_cm_s;
  j["pga_rel_diff"] = c.pga_rel_diff;
  j["pgv_rel_diff"] = c.pgv_rel_diff;
  return json_line(j);
}

}  // namespace rigid::io
