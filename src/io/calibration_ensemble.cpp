#include "rigid/io/calibration_ensemble.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "rigid/core/error.hpp"
#include "rigid/io/calibration_document.hpp"
#include "rigid/io/provenance.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

std::string absolute(const std::string& p) { return fs::absolute(p).lexically_normal().string(); }

}  // namespace

double member_number(const Json& j, const char* key, const std::string& file) {
  if (!j.contains(key) || !j[key].is_number() || !std::isfinite(j[key].get<double>()))
    throw InputError(file, 0, std::string("ensemble member without a finite number '") + key + "'");
  return j[key].get<double>();
}

std::vector<double> CalibrationEnsemble::scene_weights() const {
  std::vector<double> w(scenes.size(), 0.0);
  double total = 0;
  for (const Member& m : members) total += m.weight;
  for (const Member& m : members) w[std::size_t(m.variant)] += m.weight / total;
  return w;
}

CalibrationEnsemble read_calibration_ensemble(const std::string& json) {
  const Json j = read_calibration_document(json);
  CalibrationEnsemble e;
  e.json = json;
  e.json_sha256 = file_sha256(json);
  if (j.contains("physics") && j["physics"].is_string()) e.physics = j["physics"].get<std::string>();
  if (!j.contains("ensemble") || !j["ensemble"].is_array() || j["ensemble"].empty())
    throw InputError(json, 0, "has no ensemble");
  std::map<std::string, int> variant_of;
  std::set<double> rotation_set;
  for (const auto& m : j["ensemble"]) {
    if (!m.contains("scene") || !m["scene"].is_string() || !m.contains("rotations_deg") ||
        !m["rotations_deg"].is_array() || m["rotations_deg"].empty())
      throw InputError(json, 0, "ensemble member without scene or rotations_deg");
    CalibrationEnsemble::Member member;
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

Json calibration_summary(const Json& document) {
  Json s = Json::object();
  for (const char* key :
       {"rigid_version", "created", "scene", "physics", "parameters", "in_sample", "cross_validated"}) {
    if (document.contains(key)) s[key] = document[key];
  }
  return s;
}

}  // namespace rigid::io
