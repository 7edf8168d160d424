#include "rigid/shaketable/ensemble.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "rigid/calibration/outcome_model.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/provenance.hpp"
#include "rigid/shaketable/calibration_document.hpp"

namespace rigid::shaketable {
namespace {

namespace fs = std::filesystem;

std::string absolute(const std::string& p) { return fs::absolute(p).lexically_normal().string(); }

double member_number(const io::Json& j, const char* key, const std::string& file) {
  if (!j.contains(key) || !j[key].is_number())
    throw InputError(file, 0, std::string("ensemble member without a number '") + key + "'");
  return j[key].get<double>();
}

}  // namespace

double Ensemble::probability(const std::function<bool(int, int)>& overturned, bool with_lapse) const {
  double total = 0, p = 0;
  for (const Member& m : members) total += m.weight;
  for (const Member& m : members) {
    int over = 0;
    for (int r : m.rotations) over += overturned(m.variant, r) ? 1 : 0;
    const double share = double(over) / double(m.rotations.size());
    p += m.weight * calibration::member_probability(share, with_lapse ? m.lapse : 0.0);
  }
  // normalised once at the end: members that all say 1 give exactly 1 (the same sum over the same
  // weights), which per-member shares w / total need not
  return p / total;
}

std::vector<double> Ensemble::scene_weights() const {
  std::vector<double> w(scenes.size(), 0.0);
  double total = 0;
  for (const Member& m : members) total += m.weight;
  for (const Member& m : members) w[std::size_t(m.variant)] += m.weight / total;
  return w;
}

Ensemble load_calibration(const std::string& json) {
  const io::Json j = read_calibration_document(json);
  Ensemble e;
  e.json = json;
  e.json_sha256 = io::file_sha256(json);
  if (j.contains("physics") && j["physics"].is_string()) e.physics = j["physics"].get<std::string>();
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
    const std::string file = absolute((fs::path(json).parent_path() / m["scene"].get<std::string>()).string());
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
      throw InputError(json, 0, "ensemble member's scene " + file + " does not exist");
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

Ensemble load_ensemble(const std::string& scene_file) {
  std::string json = scene_file;
  if (json.size() > 5 && json.ends_with(".toml")) json = json.substr(0, json.size() - 5);
  json += ".calibration.json";
  if (fs::exists(json)) return load_calibration(json);
  Ensemble e;
  e.scenes = {absolute(scene_file)};
  e.rotations_deg = {0.0};
  e.members.push_back({0, {0}, 1.0, 0.0});
  return e;
}

io::JobFile designed_job(const std::string& scene, const LabInput& lab) {
  io::JobFile job;
  job.seed = 1;
  job.stop_after = 0;
  job.output.clear();  // the caller's CampaignOptions name the cube
  job.scales_g = {io::kAsRecordedScale};
  job.objects.push_back({"rock", absolute(scene), ""});
  job.lab_format = lab.format;
  job.run.free_time_s = 5.0;
  return job;
}

io::JobFile ensemble_job(const std::string& scene, const Ensemble& e, const LabInput& lab) {
  io::JobFile job = designed_job(scene, lab);
  if (!e.json.empty()) {
    job.variants.method = "list";
    job.variants.keys = {scenario::VariantKey::scene};
    for (const std::string& s : e.scenes) {
      scenario::VariantValue v;
      v.text = s;
      job.variants.variants.push_back({v});
    }
  }
  job.rotation_angles_deg = e.rotations_deg;
  return job;
}

}  // namespace rigid::shaketable
