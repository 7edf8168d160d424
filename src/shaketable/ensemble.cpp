#include "rigid/shaketable/ensemble.hpp"

#include <algorithm>
#include <filesystem>

#include "rigid/calibration/outcome_model.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/json.hpp"

namespace rigid::shaketable {
namespace {

namespace fs = std::filesystem;

std::string absolute(const std::string& p) { return fs::absolute(p).lexically_normal().string(); }

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

Ensemble load_calibration(const std::string& json) {
  Ensemble e;
  static_cast<io::CalibrationEnsemble&>(e) = io::read_calibration_ensemble(json);
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
