#include "shaketable.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "commands.hpp"
#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/lab_recording.hpp"
#include "rigid/io/scene_file.hpp"

namespace rigid::app::shaketable {

std::string Physics::label() const {
  char text[160];
  if (contact == "penalty") {
    std::snprintf(text, sizeof text, "%s penalty K=%.3g D=%g mu=%.2f", base.c_str(), normal_stiffness, damping,
                  friction);
  } else {
    std::snprintf(text, sizeof text, "%s rigid e=%.2f mu=%.2f", base.c_str(), restitution, friction);
  }
  return text;
}

std::vector<std::pair<std::string, std::variant<double, std::string>>> Physics::contact_law_table() const {
  std::vector<std::pair<std::string, std::variant<double, std::string>>> t;
  t.emplace_back("contact", contact);
  if (contact == "penalty") {
    t.emplace_back("normal_stiffness", normal_stiffness);
    t.emplace_back("shear_stiffness", normal_stiffness);
    t.emplace_back("damping", damping);
  }
  return t;
}

std::vector<std::pair<std::string, std::variant<double, std::string>>> Physics::physics_table() const {
  auto t = contact_law_table();
  t.emplace_back("friction", friction);
  if (contact != "penalty") t.emplace_back("restitution", restitution);
  return t;
}

std::vector<std::pair<std::string, std::variant<double, std::string>>> Physics::variant_table() const {
  std::vector<std::pair<std::string, std::variant<double, std::string>>> t;
  // every variant of a job sets the same parameters: each law ignores the other's
  t.emplace_back("scene", base_scene);
  t.emplace_back("friction", friction);
  t.emplace_back("damping", damping);
  t.emplace_back("restitution", restitution);
  return t;
}

namespace {

double member_number(const io::Json& j, const char* key, const std::string& file) {
  if (!j.contains(key) || !j[key].is_number())
    throw InputError(file, 0, std::string("ensemble member without a number '") + key + "'");
  return j[key].get<double>();
}

}  // namespace

Ensemble load_ensemble(const std::string& scene_file) {
  namespace fs = std::filesystem;
  Ensemble e;
  const std::string scene = fs::absolute(scene_file).lexically_normal().string();
  std::string json = scene_file;
  if (json.size() > 5 && json.ends_with(".toml")) json = json.substr(0, json.size() - 5);
  json += ".calibration.json";
  if (!fs::exists(json)) {
    e.scenes = {scene};
    e.rotations_deg = {0.0};
    e.members.push_back({0, {0}, 1.0, 0.0});
    return e;
  }
  e.json = json;
  io::Json j;
  try {
    std::ifstream in(json);
    j = io::Json::parse(in);
  } catch (const std::exception& ex) {
    throw InputError(json, 0, std::string("not a calibration file: ") + ex.what());
  }
  if (!j.contains("ensemble") || !j["ensemble"].is_array() || j["ensemble"].empty())
    throw InputError(json, 0, "has no ensemble");
  std::map<std::string, int> variant_of;
  std::set<double> rotation_set;
  for (const auto& m : j["ensemble"]) {
    if (!m.contains("scene") || !m["scene"].is_string() || !m.contains("rotations_deg") ||
        !m["rotations_deg"].is_array() || m["rotations_deg"].empty())
      throw InputError(json, 0, "ensemble member without scene or rotations_deg");
    Ensemble::Member member;
    member.weight = member_number(m, "weight", json);
    member.lapse = member_number(m, "lapse", json);
    if (!(member.weight > 0) || !(member.lapse >= 0 && member.lapse <= 1))
      throw InputError(json, 0, "ensemble member with a weight <= 0 or a lapse outside [0, 1]");
    const std::string file =
        fs::absolute(fs::path(json).parent_path() / m["scene"].get<std::string>()).lexically_normal().string();
    const auto [it, added] = variant_of.emplace(file, int(variant_of.size()));
    if (added) e.scenes.push_back(file);
    member.variant = it->second;
    for (const auto& r : m["rotations_deg"]) {
      if (!r.is_number()) throw InputError(json, 0, "rotations_deg must be numbers");
      rotation_set.insert(r.get<double>());
    }
    e.members.push_back(member);
  }
  e.rotations_deg.assign(rotation_set.begin(), rotation_set.end());
  std::size_t k = 0;
  for (const auto& m : j["ensemble"]) {
    for (const auto& r : m["rotations_deg"]) {
      const auto at = std::find(e.rotations_deg.begin(), e.rotations_deg.end(), r.get<double>());
      e.members[k].rotations.push_back(int(at - e.rotations_deg.begin()));
    }
    ++k;
  }
  return e;
}

io::DesignJob ensemble_job(const std::string& scene, const Ensemble& e, const std::string& lab_format_file) {
  namespace fs = std::filesystem;
  io::DesignJob job;
  job.object_name = "rock";
  job.scene = fs::absolute(scene).lexically_normal().string();
  if (!e.json.empty()) {
    for (const std::string& s : e.scenes) job.variants.push_back({{"scene", s}});
  }
  job.lab_format_file = lab_format_file.empty() ? "" : fs::absolute(lab_format_file).string();
  job.rotation_angles_deg = e.rotations_deg;
  return job;
}

double Ensemble::probability(const std::function<bool(int, int)>& overturned, bool with_lapse) const {
  double total = 0, p = 0;
  for (const Member& m : members) total += m.weight;
  for (const Member& m : members) {
    int over = 0;
    for (int r : m.rotations) over += overturned(m.variant, r) ? 1 : 0;
    const double share = double(over) / double(m.rotations.size());
    const double lapse = with_lapse ? m.lapse : 0.0;
    p += m.weight / total * (0.5 * lapse + (1 - lapse) * share);
  }
  return p;
}

void add_recording_options(CLI::App& cmd, std::string& lab_format, std::string& progress) {
  cmd.add_option("--lab-format", lab_format,
                 "TOML file whose [lab] table says how to read the recordings (default: the lab export of "
                 "docs/ground-motions.md: tab-separated, time, acceleration in g, displacement in V)");
  cmd.add_option("--progress", progress, "auto, bar, log or none")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "bar", "log", "none"}));
}

LabInput lab_input(const std::string& format_file) {
  LabInput in;
  in.format_file = format_file;
  if (!format_file.empty()) {
    in.format = io::read_lab_format(format_file);
  }
  return in;
}

io::DesignJob::Record strong_motion_window(const motion::GroundMotion& m, const std::string& file, double level_g) {
  io::DesignJob::Record r;
  r.lab = file;
  r.end = m.duration();
  if (!(level_g > 0)) return r;  // the whole recording
  const double level = level_g * kGravity;
  long first = -1, last = -1;
  for (std::size_t i = 0; i < m.x.size(); ++i) {
    if (std::abs(m.x[i]) > level) {
      if (first < 0) first = long(i);
      last = long(i);
    }
  }
  if (first < 0) {
    r.start = 0;
    r.end = std::min(2.0, m.duration());
  } else {
    r.start = std::max(0.0, double(first) * m.dt - 1.0);
    r.end = std::min(m.duration(), double(last) * m.dt + 1.0);
  }
  return r;
}

std::vector<io::DesignJob::Record> strong_motion_windows(const io::LabTestList& tests, const LabInput& lab,
                                                         double level_g) {
  std::vector<io::DesignJob::Record> out;
  for (const io::LabTest& t : tests.tests)
    out.push_back(strong_motion_window(io::read_lab_motion(t.file, lab.format), t.file, level_g));
  return out;
}

double static_toppling_g(const std::string& scene) {
  const auto rocking = analysis::rocking_parameters(io::load_scene(scene));
  if (!rocking) throw InputError(scene, 0, "has no single free block standing on its pedestal (no rocking parameters)");
  return std::tan(rocking->alpha);
}

double window_level_g(bool rigid_contact_only, double weakest_static_toppling_g) {
  return (rigid_contact_only ? 0.5 : 0.1) * weakest_static_toppling_g;
}

double window_level_g(const std::vector<std::string>& scenes) {
  double weakest = 1e300;
  bool rigid = true;
  for (const std::string& s : scenes) {
    rigid = rigid && io::load_scene(s).law.method == contact::ContactMethod::rigid;
    weakest = std::min(weakest, static_toppling_g(s));
  }
  return window_level_g(rigid, weakest);
}

calibration::OutcomeGrid outcome_grid(const io::Cube& cube, const std::vector<double>& headings_deg) {
  const int variants = int(cube.objects.size());
  const int tests = int(cube.records.size());
  const int headings = cube.rotations;
  if (headings != int(headings_deg.size()) || cube.scales_g.size() != 1)
    throw InputError("", 0, "a designed campaign's cube has an unexpected shape");
  calibration::OutcomeGrid grid(variants, tests, headings_deg);
  for (int v = 0; v < variants; ++v) {
    const io::ObjectCube& o = cube.objects[std::size_t(v)];
    for (int t = 0; t < tests; ++t) {
      for (int h = 0; h < headings; ++h) {
        const auto code = static_cast<io::CellOutcome>(o.outcome[std::size_t(t * headings + h)]);
        if (code != io::CellOutcome::survived && code != io::CellOutcome::overturned) {
          throw InputError("", 0,
                           "cell (" + io::object_label(o) + ", record " + cube.records[std::size_t(t)].name +
                               ", heading " + std::to_string(headings_deg[std::size_t(h)]) + ") was not simulated (" +
                               io::outcome_name(std::int8_t(code)) + ")");
        }
        grid.set(v, t, h, code == io::CellOutcome::overturned);
      }
    }
  }
  return grid;
}

void run_designed_campaigns(
    const std::function<std::optional<campaign::CampaignOptions>(const campaign::CampaignResult*)>& next,
    const std::function<void(const campaign::CampaignResult&)>& finish) {
  int status = 0;
  {
    const campaign::MpiSession session(campaign_argc(), campaign_argv());
    const campaign::CampaignResult result = campaign::run_campaign_sequence(session, next);
    if (session.rank() == 0 && result.status == 0) finish(result);
    status = result.status;
  }  // MPI ends with the session, before the exit status is set
  if (status != 0) std::exit(status);
}

}  // namespace rigid::app::shaketable
