#include "rigid/io/job_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "input_file.hpp"
#include "job_record_names.hpp"
#include "job_variants.hpp"
#include "lab_toml.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/at2.hpp"
#include "rigid/io/calibration_document.hpp"
#include "rigid/io/calibration_ensemble.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/record_list.hpp"
#include "toml_values.hpp"

namespace rigid::io {
namespace fs = std::filesystem;

namespace {

double number(const toml::node& n, const std::string& src, const std::string& what) {
  const auto v = n.value<double>();
  if (!v || !std::isfinite(*v)) throw InputError(src, line_of(n), what + " must be a finite number");
  return *v;
}

constexpr long kMaxScales = 100000;

// A decimal number as digits x 10^-places ("0.25" -> 25, 2; "1e-1" -> 1, 1), when it is one
// that a double holds exactly as an integer (at most 15 significant digits, 0-22 places).
struct Decimal {
  long long digits = 0;
  int places = 0;
};

std::optional<Decimal> decimal_of(const std::string& text) {
  static const std::regex form(R"(\s*\+?([0-9]*)(?:\.([0-9]*))?(?:[eE]([+-]?[0-9]{1,3}))?\s*)");
  std::smatch m;
  if (!std::regex_match(text, m, form) || (m[1].length() == 0 && m[2].length() == 0)) return std::nullopt;
  std::string digits = m[1].str() + m[2].str();
  int places = int(m[2].length()) - (m[3].matched ? std::stoi(m[3].str()) : 0);
  for (; places < 0; ++places) digits += '0';
  digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size()));
  if (digits.size() > 15 || places > 22) return std::nullopt;
  return Decimal{digits.empty() ? 0 : std::stoll(digits), places};
}

// "start:stop:step" (g), stop included when it falls on the grid. Each scale is the double nearest
// the decimal start + i * step, as if the user had written it out ("0.1:1.0:0.1" gives 0.3, not the
// float sum 0.30000000000000004), so a reader selects it by the number the job states.
std::optional<std::vector<double>> decimal_range(const std::string& text) {
  std::vector<std::optional<Decimal>> part;
  std::size_t from = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t to = k < 2 ? text.find(':', from) : text.size();
    if (to == std::string::npos) return std::nullopt;
    part.push_back(decimal_of(text.substr(from, to - from)));
    from = to + 1;
  }
  if (!part[0] || !part[1] || !part[2]) return std::nullopt;
  const int places = std::max({part[0]->places, part[1]->places, part[2]->places});
  long long scaled[3];
  for (int k = 0; k < 3; ++k) {
    long long v = part[std::size_t(k)]->digits;
    for (int p = part[std::size_t(k)]->places; p < places; ++p) {
      if (v > (1LL << 53) / 10) return std::nullopt;
      v *= 10;
    }
    scaled[k] = v;
  }
  const auto [start, stop, step] = scaled;
  if (step <= 0 || stop < start) return std::nullopt;  // the caller names the problem
  const long long count = (stop - start) / step + 1;
  if (count > kMaxScales) return std::vector<double>(std::size_t(kMaxScales) + 1, 0.0);  // "too many"
  double power = 1;  // 10^places is exact in a double up to 10^22
  for (int p = 0; p < places; ++p) power *= 10;
  std::vector<double> out;
  // both operands exact, so the one rounding of the division gives the nearest double
  for (long long i = 0; i < count; ++i) out.push_back(double(start + i * step) / power);
  return out;
}

/// The stated scales (g); a range also fills `drive` with its float sums (Job::drive_scales_g).
std::vector<double> parse_scales(const toml::node& n, const std::string& src, std::vector<double>& drive) {
  std::vector<double> out;
  if (n.value<std::string>() && *n.value<std::string>() == "as recorded") return {kAsRecordedScale};
  if (const auto* arr = n.as_array()) {
    for (const auto& v : *arr) out.push_back(number(v, src, "each scale (g)"));
  } else if (const auto s = n.value<std::string>()) {
    double a, b, c;
    char extra;
    if (std::sscanf(s->c_str(), "%lf:%lf:%lf%c", &a, &b, &c, &extra) != 3) {
      throw InputError(src, line_of(n),
                       "scales must be a list, \"start:stop:step\" (g) or \"as recorded\", not \"" + *s + "\"");
    }
    if (!(c > 0) || !(b >= a) || !std::isfinite(a) || !std::isfinite(b)) {
      throw InputError(src, line_of(n), "scales \"start:stop:step\" needs step > 0 and stop >= start");
    }
    const std::optional<std::vector<double>> exact = decimal_range(*s);
    const long count = exact ? long(exact->size()) : std::lround(std::floor((b - a) / c + 1e-9)) + 1;
    if (count > kMaxScales) throw InputError(src, line_of(n), "too many scales");
    for (long i = 0; i < count; ++i) drive.push_back(a + double(i) * c);
    out = exact ? *exact : drive;  // more digits than a decimal grid holds: the float sums
  } else {
    throw InputError(src, line_of(n), "scales must be a list, \"start:stop:step\" (g) or \"as recorded\"");
  }
  if (out.empty()) throw InputError(src, line_of(n), "the scale list is empty");
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!(out[i] > 0)) throw InputError(src, line_of(n), "scales must be positive (g)");
    if (i > 0 && !(out[i] > out[i - 1])) throw InputError(src, line_of(n), "scales must be strictly increasing");
  }
  return out;
}

// Makes every file of a set spec absolute against base (keeping roles such as x=).
std::string resolve_spec(const std::string& spec, const fs::path& base) {
  std::string out;
  std::stringstream in(spec);
  std::string part;
  while (std::getline(in, part, ',')) {
    std::string role;
    const auto eq = part.find('=');
    if (eq != std::string::npos) {
      role = part.substr(0, eq + 1);
      part = part.substr(eq + 1);
    }
    const fs::path p = fs::path(part).is_absolute() ? fs::path(part) : base / part;
    out += (out.empty() ? "" : ",") + role + p.lexically_normal().string();
  }
  return out;
}

// An object's name is the name of its HDF5 group in the cube: "." and ".." are no group, '/'
// separates groups, and a NUL or other control character cuts or garbles the name in every file
// and table that shows it.
std::string object_name_problem(const std::string& name) {
  if (name.empty() || name == "." || name == "..") return "object name must not be empty, \".\" or \"..\"";
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '/' || u < 0x20 || u == 0x7f)
      return "object name must contain no '/' and no control character (NUL, tab, newline, ...)";
  }
  return "";
}

void read_campaign(const toml::table& root, JobFile& job) {
  const std::string& path = job.path;
  const auto* c = root["campaign"].as_table();
  if (!c) throw InputError(path, 0, "missing [campaign] table");
  job.campaign_line = line_of(*c);
  reject_unknown(*c,
                 {"name", "seed", "output", "scales", "rotations", "rotation_angles_deg", "stop_after",
                  "checkpoint_interval_s", "grace_s"},
                 path, "[campaign]");
  optional_string(*c, "name", "", path);  // a label for people: type-checked, not used
  if (const auto* o = c->get("output")) {
    const auto s = o->value<std::string>();
    if (!s || s->empty()) throw InputError(path, line_of(*o), "output must be a file name");
    job.output = *s;
  } else {
    job.output = fs::path(path).stem().string() + ".h5";
  }
  if (const auto* s = c->get("seed")) {
    const auto v = s->value<std::int64_t>();
    if (!v || *v < 0) throw InputError(path, line_of(*s), "seed must be a non-negative integer");
    job.seed = static_cast<std::uint64_t>(*v);
  }
  const toml::node* scales = c->get("scales");
  if (!scales)
    throw InputError(path, line_of(*c), "[campaign] needs scales (list or \"start:stop:step\", g, or \"as recorded\")");
  job.scales_g = parse_scales(*scales, path, job.drive_scales_g);
  if (const auto* r = c->get("rotations")) {
    const auto v = r->value<std::int64_t>();
    if (!v || *v < 1 || *v > 1000) throw InputError(path, line_of(*r), "rotations must be an integer from 1 to 1000");
    job.rotations = static_cast<int>(*v);
  }
  if (const auto* r = c->get("rotation_angles_deg")) {
    const auto* list = r->as_array();
    if (!list || list->empty() || list->size() > 1000) {
      throw InputError(path, line_of(*r), "rotation_angles_deg must be a list of 1 to 1000 angles (deg)");
    }
    for (const auto& node : *list) {
      const auto v = node.value<double>();
      if (!v || !std::isfinite(*v))
        throw InputError(path, line_of(node), "rotation_angles_deg: angles must be finite numbers (deg)");
      job.rotation_angles_deg.push_back(*v);
    }
    if (c->contains("rotations") && job.rotations != int(list->size())) {
      throw InputError(path, line_of(*r), "rotations and rotation_angles_deg disagree: give one of them");
    }
    job.rotations = int(list->size());
  }
  if (const auto* s = c->get("stop_after")) {
    const auto v = s->value<std::int64_t>();
    if (!v || *v < 0) throw InputError(path, line_of(*s), "stop_after must be a non-negative integer (0 = off)");
    job.stop_after = static_cast<int>(*v);
  }
  job.checkpoint_interval_s = optional_number(*c, "checkpoint_interval_s", job.checkpoint_interval_s, path);
  job.grace_s = optional_number(*c, "grace_s", job.grace_s, path);
}

// The calibration of an [[object]] (calibration = "FILE", relative to the job file) read into
// job.calibration; returns the scene the object simulates (its `scene`, which must be the
// calibration's own, else the calibration's scene beside the file) and fills `member_scenes`.
std::string read_object_calibration(const std::string& calibration, const std::string& scene, long line,
                                    const fs::path& base, JobFile& job, std::vector<std::string>& member_scenes) {
  const std::string& path = job.path;
  if (job.calibration)
    throw InputError(path, line,
                     "a job takes one calibrated [[object]] (another is at line " +
                         std::to_string(job.calibration->line) +
                         "): run each calibrated rock as a campaign of its own");
  const std::string file = (base / calibration).lexically_normal().string();
  std::error_code ec;
  if (!fs::exists(file, ec)) throw InputError(path, line, "calibration file not found: " + file);
  CalibrationEnsemble ensemble;
  Json document;
  try {
    ensemble = read_calibration_ensemble(file);
    document = read_calibration_document(file);
  } catch (const InputError& e) {  // name the [[object]] that takes it as well as the file
    throw InputError(path, line, std::string("calibration ") + e.what());
  }
  if (!document.contains("scene") || !document["scene"].is_string())
    throw InputError(path, line, "calibration " + file + " names no scene (\"scene\": the calibrated scene beside it)");
  const std::string own =
      (fs::path(file).parent_path() / document["scene"].get<std::string>()).lexically_normal().string();
  if (!scene.empty()) {
    const std::string given = (base / scene).lexically_normal().string();
    if (fs::weakly_canonical(given, ec) != fs::weakly_canonical(own, ec))
      throw InputError(path, line,
                       "scene " + given + " is not the calibration's scene " + own +
                           ": leave scene out, or calibrate (or transfer) this scene");
  }
  JobCalibration c;
  c.path = file;
  c.sha256 = ensemble.json_sha256;
  c.weights = ensemble.scene_weights();
  c.summary_json = json_line(calibration_summary(document));
  c.line = line;
  job.calibration = c;
  member_scenes = ensemble.scenes;
  return own;
}

// A calibrated object's members are the job's variant axis (key `scene`, method "calibration"):
// the object must be the job's only one, and the job has no [sweep] or [[variant]] of its own.
void calibration_variants(const std::vector<std::string>& member_scenes, JobFile& job) {
  const long line = job.calibration->line;
  if (job.objects.size() != 1)
    throw InputError(job.path, line,
                     "a calibrated [[object]] must be the job's only object (its calibration's members are the "
                     "job's variants): run the other objects as a campaign of their own");
  if (job.variants.count() > 0)
    throw InputError(job.path, job.variant_lines.empty() ? line : job.variant_lines.front(),
                     "[sweep] and [[variant]] do not combine with a calibrated [[object]] (line " +
                         std::to_string(line) + "): its calibration's members are the job's variants");
  scenario::VariantSpace space;
  space.method = "calibration";
  space.keys = {scenario::VariantKey::scene};
  for (const std::string& s : member_scenes) {
    scenario::VariantValue v;
    v.text = s;
    space.variants.push_back({v});
  }
  job.variants = space;
  job.variant_lines = {line};
}

void read_objects(const toml::table& root, const fs::path& base, JobFile& job,
                  std::vector<std::string>& member_scenes) {
  const std::string& path = job.path;
  const auto* objects = root["object"].as_array();
  if (!objects || objects->empty()) throw InputError(path, 0, "the job needs at least one [[object]]");
  std::set<std::string> object_names;
  for (const auto& node : *objects) {
    const auto* t = node.as_table();
    if (!t) throw InputError(path, line_of(node), "each [[object]] must be a table");
    reject_unknown(*t, {"name", "scene", "state", "optional", "calibration"}, path, "[[object]]");
    JobFileObject o;
    std::string scene = optional_string(*t, "scene", "", path);
    const std::string calibration = optional_string(*t, "calibration", "", path);
    if (!calibration.empty()) {
      if (optional_bool(*t, "optional", false, path) && !fs::exists(base / calibration)) {
        const std::string left_out =
            "[[object]] at line " + std::to_string(line_of(node)) + " left out: its calibration ";
        job.notes.push_back(left_out + (base / calibration).lexically_normal().string() +
                            " does not exist (optional = true)");
        job.text +=
            "\n# " + left_out + "\"" + calibration + "\" (relative to the job file) does not exist (optional = true)\n";
        continue;
      }
      const std::string own = read_object_calibration(calibration, scene, line_of(node), base, job, member_scenes);
      if (scene.empty()) scene = fs::relative(own, base.empty() ? fs::path(".") : base).string();
    }
    if (scene.empty())
      throw InputError(path, line_of(node), "[[object]] needs scene = \"FILE\" (or calibration = \"FILE\")");
    o.scene = (base / scene).lexically_normal().string();
    // an optional object is a generated scene (e.g. a scan imported from data outside the
    // repository): left out with a note when absent; the note enters the job's text, so a resume
    // after it appeared is refused instead of mixing two sets of objects. The text (and so the job's
    // hash) names the scene as the job writes it: the same job reached by another path is the same job.
    const bool optional = optional_bool(*t, "optional", false, path);
    if (optional && !fs::exists(o.scene)) {
      const std::string left_out = "[[object]] at line " + std::to_string(line_of(node)) + " left out: its scene ";
      job.notes.push_back(left_out + o.scene + " does not exist (optional = true)");
      job.text += "\n# " + left_out + "\"" + scene + "\" (relative to the job file) does not exist (optional = true)\n";
      continue;
    }
    if (!fs::exists(o.scene)) throw InputError(path, line_of(node), "scene file not found: " + o.scene);
    const std::string state = optional_string(*t, "state", "", path);
    if (!state.empty()) {
      o.state = (base / state).lexically_normal().string();
      if (!fs::exists(o.state)) throw InputError(path, line_of(node), "state file not found: " + o.state);
    }
    o.name = optional_string(*t, "name", fs::path(scene).stem().string(), path);
    if (const std::string problem = object_name_problem(o.name); !problem.empty()) {
      throw InputError(path, line_of(t->contains("name") ? *t->get("name") : node), problem);
    }
    if (!object_names.insert(o.name).second)
      throw InputError(path, line_of(node), "duplicate object name '" + o.name + "'");
    job.objects.push_back(o);
  }
  if (job.objects.empty()) throw InputError(path, 0, "every [[object]] of the job is optional and absent");
}

void read_listed_records(const toml::node& list, const fs::path& base, JobFile& job) {
  const auto name = list.value<std::string>();
  if (!name) throw InputError(job.path, line_of(list), "records must be a record-list file name");
  const fs::path list_path = base / *name;
  if (!fs::exists(list_path)) throw InputError(job.path, line_of(list), "record list not found: " + list_path.string());
  const RecordList rl = read_record_list(list_path.string());
  job.record_list = list_path.lexically_normal().string();
  for (const auto& e : rl.records) {
    JobRecord r;
    r.spec = resolve_spec(e.file, fs::path(rl.base_dir));
    r.name = record_name(e.file);
    r.origin_file = job.record_list;
    r.origin_line = e.line;
    r.start = e.start;
    r.end = e.end;
    r.earthquake = e.earthquake;
    r.listed_pga_g = std::isfinite(e.gmroti_pga_g) ? e.gmroti_pga_g : 0.0;
    r.listed_pgv_cm_s = std::isfinite(e.gmroti_pgv_cm_s) ? e.gmroti_pgv_cm_s : 0.0;
    r.resample = e.resample;
    job.records.push_back(r);
  }
}

void read_record_tables(const toml::table& root, const fs::path& base, JobFile& job) {
  const std::string& path = job.path;
  const auto* arr = root["record"].as_array();
  if (!arr) throw InputError(path, 0, "record must be an array of tables ([[record]])");
  for (const auto& node : *arr) {
    const auto* t = node.as_table();
    if (!t) throw InputError(path, line_of(node), "each [[record]] must be a table");
    reject_unknown(*t, {"name", "motion", "lab", "start", "end", "earthquake", "align"}, path, "[[record]]");
    JobRecord r;
    const std::string motion = optional_string(*t, "motion", "", path);
    const std::string lab = optional_string(*t, "lab", "", path);
    if (motion.empty() == lab.empty())
      throw InputError(
          path, line_of(node),
          "[[record]] needs motion = \"NAME-X.AT2\" (or \"H1.AT2,H2.AT2\") or lab = \"FILE\", one of them");
    r.lab = !lab.empty();
    r.spec = r.lab ? (fs::path(lab).is_absolute() ? fs::path(lab) : base / lab).lexically_normal().string()
                   : resolve_spec(motion, base);
    r.name = optional_string(*t, "name", r.lab ? lab_record_name(lab) : record_name(motion), path);
    if (r.lab && t->contains("align"))
      throw InputError(path, line_of(*t->get("align")),
                       "[[record]] align applies to AT2 sets, not to lab = recordings");
    r.origin_file = path;
    r.origin_line = line_of(node);
    r.start = optional_number(*t, "start", 0.0, path);
    r.end = optional_number(*t, "end", std::numeric_limits<double>::infinity(), path);
    r.earthquake = optional_string(*t, "earthquake", "", path);
    if (const auto* align = t->get("align")) {
      const auto value = align->value<std::string>();
      if (!value || (*value != "resample" && *value != "auto"))
        throw InputError(path, line_of(*align),
                         "[[record]] align must be \"auto\" (pad lengths within 1 %) or \"resample\"");
      r.resample = *value == "resample";
    }
    job.records.push_back(r);
  }
}

// Every file of every record must exist now, not at the first task; names are made unique.
void check_records(JobFile& job) {
  std::set<std::string> record_names;
  for (auto& r : job.records) {
    if (const std::string problem = r.lab ? input_file_problem(r.spec) : ""; !problem.empty()) {
      throw InputError(r.origin_file, r.origin_line, "record " + r.name + ": lab recording " + problem + ": " + r.spec);
    }
    std::stringstream parts(r.lab ? std::string() : r.spec);
    std::string part;
    while (std::getline(parts, part, ',')) {
      const auto eq = part.find('=');
      const std::string file = eq == std::string::npos ? part : part.substr(eq + 1);
      if (const std::string problem = input_file_problem(file); !problem.empty()) {
        throw InputError(r.origin_file, r.origin_line, "record " + r.name + ": motion file " + problem + ": " + file);
      }
    }
    if (!(r.start >= 0) || !(r.end > r.start)) {
      throw InputError(r.origin_file, r.origin_line, "record " + r.name + ": window needs 0 <= start < end");
    }
    std::string unique = r.name;
    for (int k = 2; !record_names.insert(unique).second; ++k) unique = r.name + "_" + std::to_string(k);
    r.name = unique;
  }
}

// Records: a list file or [[record]] tables, and the [lab] table their lab recordings are read with.
void read_records(const toml::table& root, const fs::path& base, JobFile& job) {
  const std::string& path = job.path;
  if (root.contains("records") == root.contains("record")) {
    throw InputError(path, 0, "give the records either as records = \"LIST\" or as [[record]] tables");
  }
  if (const auto* list = root.get("records")) {
    read_listed_records(*list, base, job);
  } else {
    read_record_tables(root, base, job);
  }
  if (job.records.empty()) throw InputError(path, 0, "the job has no records");
  // the [lab] table: read here, so a bad format stops the job before any work
  job.lab_format = lab_format_from_table(root, path);
  if (const auto* lab = root.get("lab")) {
    const bool used = std::any_of(job.records.begin(), job.records.end(), [](const auto& r) { return r.lab; });
    if (!used) throw InputError(path, line_of(*lab), "[lab] is given but no [[record]] has lab = \"FILE\"");
  }
  check_records(job);
}

// [run] as written: keys and types; what the values mean is the job module's (job::RunOverrides).
RunTable read_run(const toml::table& root, const std::string& path) {
  RunTable out;
  const auto* run = root["run"].as_table();
  if (!run) return out;
  reject_unknown(*run,
                 {"model", "duration_s", "free_time_s", "dt_s", "safety", "integrator", "accuracy", "effects",
                  "contact", "solver_tolerance", "solver_max_sweeps"},
                 path, "[run]");
  out.line = line_of(*run);
  const auto text = [&](const char* key) -> std::optional<RunText> {
    const toml::node* n = run->get(key);
    if (!n) return std::nullopt;
    return RunText{n->value<std::string>(), line_of(*n)};
  };
  out.contact = text("contact");
  // model and integrator must be strings; their value errors point at [run]
  if (run->contains("model")) out.model = RunText{optional_string(*run, "model", "", path), out.line};
  const auto number = [&](const char* key) -> std::optional<double> {
    if (!run->contains(key)) return std::nullopt;
    return optional_number(*run, key, 0.0, path);
  };
  out.duration_s = number("duration_s");
  out.free_time_s = number("free_time_s");
  out.dt_s = number("dt_s");
  out.safety = number("safety");
  if (run->contains("integrator")) out.integrator = RunText{optional_string(*run, "integrator", "", path), out.line};
  out.accuracy = text("accuracy");
  out.effects = text("effects");
  const toml::node* step_key = run->contains("dt_s") ? run->get("dt_s") : run->get("safety");
  out.step_line = line_of(step_key ? *step_key : *run);
  out.solver_tolerance = number("solver_tolerance");
  out.solver_max_sweeps = number("solver_max_sweeps");
  const toml::node* solver_key =
      run->contains("solver_tolerance") ? run->get("solver_tolerance") : run->get("solver_max_sweeps");
  out.solver_line = line_of(solver_key ? *solver_key : *run);
  return out;
}

}  // namespace

std::string record_name(const std::string& spec) {
  std::string first = spec.substr(0, spec.find(','));
  const auto eq = first.find('=');
  if (eq != std::string::npos) first = first.substr(eq + 1);
  std::string stem = fs::path(first).stem().string();
  if (stem.size() > 2 && stem[stem.size() - 2] == '-' && (stem.back() == 'X' || stem.back() == 'x')) {
    stem.resize(stem.size() - 2);
  }
  return stem;
}

// A lab recording's name: its file name without .gz and the text extension (Test013.txt.gz -> Test013).
std::string lab_record_name(const std::string& file) {
  std::string name = fs::path(file).filename().string();
  for (const std::string ext : {".gz", ".txt", ".csv", ".tsv", ".dat"}) {
    if (name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0)
      name.resize(name.size() - ext.size());
  }
  return name;
}

JobFile read_job_file(const std::string& path) {
  JobFile job;
  job.path = path;
  if (!fs::exists(path)) throw InputError(path, 0, "job file not found");
  job.text = read_input_file(path, kMaxTextFileBytes);
  const toml::table root = parse_toml(job.text, path);
  const fs::path base = fs::path(path).parent_path();
  reject_unknown(root, {"campaign", "lab", "object", "record", "records", "run", "sweep", "variant"}, path, "the job");
  read_campaign(root, job);
  std::vector<std::string> member_scenes;
  read_objects(root, base, job, member_scenes);
  job.variants = read_variants(root, path, base, job.seed, job.objects.size(), job.variant_lines);
  if (job.calibration) calibration_variants(member_scenes, job);
  read_records(root, base, job);
  job.run = read_run(root, path);
  return job;
}

}  // namespace rigid::io
