#include "rigid/shaketable/transfer.hpp"
#include "text.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/campaign/output_lock.hpp"
#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/calibration_ensemble.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/io/provenance.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/io/scene_writer.hpp"
#include "rigid/shaketable/calibration_document.hpp"
#include "rigid/shaketable/settle.hpp"

namespace rigid::shaketable {
namespace {

namespace fs = std::filesystem;

// What makes two members' physics the same: every value the law uses, to the last bit.
std::string physics_key(const Physics& p) {
  return format("%.17g %s %.17g %.17g %.17g %.17g", p.flatten_m, contact::contact_method_name(p.law.method),
                p.penalty() ? p.law.normal_stiffness : 0.0, p.penalty() ? p.law.damping : 0.0,
                p.penalty() ? 0.0 : p.law.restitution, p.law.friction);
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// What the work folder was started with: the inputs its imports and settled scenes depend on.
// The headings only shape the written files, which every run writes whole.
std::string transfer_manifest(const TransferSettings& s) {
  const CalibrationSettings& i = s.scan_import;
  std::ostringstream m;
  m.precision(17);
  m << "calibration: " << io::file_sha256(s.calibration) << "\nscan: " << io::file_sha256(s.scan)
    << "\nscale: " << i.scale << "\nup: " << i.up << "\nmax vertices: " << i.max_vertices
    << "\npedestal margin (m): " << i.pedestal_margin << "\ntilt rule (deg): " << i.tilt_deg << "\n";
  return m.str();
}

// Resumes OUT.transfer/ only over the same inputs (or starts it anew with --restart).
void claim_work_folder(const TransferSettings& s, const std::string& work, const std::string& manifest) {
  const fs::path manifest_file = fs::path(work) / "transfer.manifest";
  std::error_code ec;
  if (s.restart) fs::remove_all(work, ec);
  if (fs::exists(manifest_file)) {
    const std::string then = read_text(manifest_file);
    if (then == manifest) return;  // the same transfer: what it finished is reused
    std::istringstream a(then), b(manifest);
    std::string was, now;
    while (std::getline(a, was) && std::getline(b, now) && was == now) {
    }
    throw InputError(work, 0,
                     "holds a transfer of other inputs (then '" + was + "', now '" + now +
                         "'): choose another --out, or --restart to start over");
  }
  if (fs::exists(work) && !fs::is_empty(work, ec))
    throw InputError(work, 0,
                     "exists and is not a transfer's work folder (no transfer.manifest): choose another --out, or "
                     "--restart to start over");
  fs::create_directories(work, ec);
  if (ec) throw InputError(work, 0, "cannot create the transfer's folder: " + ec.message());
  io::write_output_file(manifest_file.string(), [&](std::ostream& out) { out << manifest; });
}

void mark_done(const fs::path& marker) {
  io::write_output_file(marker.string(), [](std::ostream& out) { out << "done\n"; });
}

// The scan imported once per base model and settled once per base model and contact law, in the
// work folder; a step an earlier run finished (its marker file) is reused.
struct ImportedScenes {
  std::map<double, std::string> base;          ///< flatten depth -> imported scene
  std::map<std::string, std::string> settled;  ///< settled_name -> settled scene
};
ImportedScenes import_and_settle(const TransferSettings& s, const std::string& work,
                                 const std::vector<CarriedMember>& members, const Callbacks& callbacks) {
  ImportedScenes out;
  std::map<double, std::string>& base_scene = out.base;
  std::map<std::string, std::string>& settled = out.settled;
  std::error_code ec;
  for (const CarriedMember& m : members) {
    const Physics& p = m.physics;
    if (!base_scene.count(p.flatten_m)) {
      const fs::path folder = fs::path(work) / p.base;
      const std::string scene = fs::absolute(folder / (p.base + ".toml")).lexically_normal().string();
      if (fs::exists(folder / "imported")) {
        callbacks.tell(format("shaketable: base model %s: imported by an earlier run", p.base.c_str()));
      } else {
        const scan::ImportOptions in =
            base_model_import(s.scan_import, s.scan, p.flatten_m, (folder / p.base).string());
        callbacks.tell(format("shaketable: base model %s (--flatten-base %g m)", p.base.c_str(), p.flatten_m));
        fs::create_directories(folder, ec);
        callbacks.import_scan(in);
        mark_done(folder / "imported");
      }
      base_scene[p.flatten_m] = scene;
    }
    const std::string name = settled_name(p);
    if (!settled.count(name)) {
      const fs::path folder = fs::path(work) / name;
      if (fs::exists(folder / "settled")) {
        settled[name] = fs::absolute(folder / (name + ".toml")).lexically_normal().string();
      } else {
        callbacks.tell(format("shaketable: settling %s under %s contact", s.scan.c_str(), name.c_str()));
        settled[name] = settled_scene(s.scan, base_scene[p.flatten_m], p, work);
        mark_done(folder / "settled");
      }
    }
  }

  return out;
}

}  // namespace

void check_transfer_settings(const TransferSettings& s) {
  CalibrationSettings import = s.scan_import;
  import.out = s.out;
  check_settings(import);
  if (s.headings < 4 || s.headings > 72) throw InputError("", 0, "--headings must be 4 to 72");
  if (s.heading_deg && !(*s.heading_deg >= -360 && *s.heading_deg <= 360))
    throw InputError("", 0, "--heading must be an angle in [-360, 360] deg");
  if (!(s.heading_spread_deg >= 0 && s.heading_spread_deg <= 180))
    throw InputError("", 0, "--heading-spread must be in [0, 180] deg");
  if (!s.heading_deg && !s.heading_weakest && s.heading_spread_deg > 0)
    throw InputError("", 0, "--heading-spread needs --heading (without it every heading of the ring counts)");
  if (s.heading_deg && s.heading_weakest) throw InputError("", 0, "--heading is an angle or weakest, not both");
  if (s.heading_weakest && !(s.heading_spread_deg < 90))
    throw InputError("", 0,
                     "--heading-spread must be below 90 deg with --heading weakest (the axis is taken both ways)");
}

std::vector<CarriedMember> carried_members(const io::Json& calibration, const std::string& file) {
  if (!calibration.contains("ensemble") || !calibration["ensemble"].is_array() || calibration["ensemble"].empty())
    throw InputError(file, 0, "has no ensemble");
  std::vector<CarriedMember> out;
  std::map<std::pair<std::string, double>, std::size_t> index;
  for (const io::Json& m : calibration["ensemble"]) {
    if (!m.is_object()) throw InputError(file, 0, "ensemble member that is not an object");
    const Physics p = physics_from_json(m, file);
    const double weight = io::member_number(m, "weight", file), lapse = io::member_number(m, "lapse", file);
    if (!(weight > 0) || !(lapse >= 0 && lapse <= 1))
      throw InputError(file, 0, "ensemble member with a weight <= 0 or a lapse outside [0, 1]");
    const auto [it, added] = index.emplace(std::make_pair(physics_key(p), lapse), out.size());
    if (added) out.push_back({p, 0.0, lapse, 0});
    out[it->second].weight += weight;
    out[it->second].source_members += 1;
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const CarriedMember& a, const CarriedMember& b) { return a.weight > b.weight; });
  return out;
}

std::vector<double> transfer_rotations(const TransferSettings& s) {
  const std::vector<double> ring = heading_ring(s.headings);
  if (!s.heading_deg && !s.heading_weakest) return ring;
  std::vector<double> window;
  for (double h : ring) {
    const double offset = std::remainder(h, 360.0);
    const double from_heading = std::abs(s.heading_weakest ? std::remainder(h, 180.0) : offset);
    if (from_heading <= s.heading_spread_deg + 1e-9) window.push_back(offset == -180.0 ? 180.0 : offset);
  }
  std::sort(window.begin(), window.end());
  return window;
}

double weakest_heading_deg(const std::string& scene) {
  const auto rocking = analysis::rocking_parameters(io::load_scene(scene));
  if (!rocking)
    throw InputError(scene, 0, "--heading weakest: the rock does not rest on its base, so it has no weakest direction");
  double h = std::fmod(rocking->azimuth * 180.0 / kPi, 180.0);
  if (h < 0) h += 180.0;
  return std::round(h * 10.0) / 10.0;  // the job and the document state it exactly
}

TransferSummary transfer_calibration(const TransferSettings& given_settings, const Callbacks& given) {
  TransferSettings s = given_settings;
  const auto start = std::chrono::steady_clock::now();
  Callbacks callbacks = given;
  if (!callbacks.import_scan) callbacks.import_scan = [](const scan::ImportOptions& o) { scan::import_scan(o); };
  check_transfer_settings(s);
  const io::Json source = read_calibration_document(s.calibration);
  const std::vector<CarriedMember> members = carried_members(source, s.calibration);
  const std::string work = s.out + ".transfer";
  {  // every output checked against every input before the first write
    io::InputFiles inputs;
    inputs.add({s.calibration, s.scan});
    for (const io::Json& m : source["ensemble"]) {
      if (m.contains("scene") && m["scene"].is_string())
        inputs.add((fs::path(s.calibration).parent_path() / m["scene"].get<std::string>()).string());
    }
    for (const char* ending : {".toml", ".state.toml", ".calibration.json"}) inputs.refuse_as_output(s.out + ending);
    inputs.refuse_folder(work);
  }
  const std::string manifest = transfer_manifest(s);  // hashes the scan: a missing one is named here
  std::error_code ec;
  fs::create_directories(fs::absolute(s.out).parent_path(), ec);
  const campaign::OutputLock lock(s.out, "--out");
  claim_work_folder(s, work, manifest);

  std::size_t source_count = 0;
  for (const CarriedMember& m : members) source_count += std::size_t(m.source_members);
  callbacks.tell(
      format("shaketable: transfer: the %zu members of %s merge into %zu of the same physics and lapse "
             "(the source rock's headings say nothing about this one)",
             source_count, s.calibration.c_str(), members.size()));
  // the scan once per base model, settled once per base model and contact law
  const ImportedScenes scenes = import_and_settle(s, work, members, callbacks);
  const std::map<double, std::string>& base_scene = scenes.base;
  const std::map<std::string, std::string>& settled = scenes.settled;
  if (s.heading_weakest) {
    // the heaviest member's base model, imported and settled on the rigid pedestal: the geometry's
    // weakest direction, not one law's lean
    s.heading_deg = weakest_heading_deg(base_scene.at(members.front().physics.flatten_m));
    callbacks.tell(
        format("shaketable: transfer: the rock's weakest rocking direction is a heading of %g deg (either "
               "way along the table's axis, within %g deg)",
               *s.heading_deg, s.heading_spread_deg));
  }
  // each physics' scene (the heaviest's is OUT.toml), turned to the known heading
  const fs::path out(s.out);
  const std::string out_name = out.filename().string();
  const std::vector<double> rotations = transfer_rotations(s);
  std::map<std::string, std::string> scene_of;  // physics_key -> file relative to OUT's folder
  io::Json ensemble = io::Json::array();
  for (const CarriedMember& m : members) {
    const Physics& p = m.physics;
    const std::string key = physics_key(p);
    if (!scene_of.count(key)) {
      const std::string file = scene_of.empty()
                                   ? out_name + ".toml"
                                   : out_name + ".transfer/member_" + std::to_string(scene_of.size()) + ".toml";
      io::SceneChanges changes;
      changes.physics = p.physics_table();
      changes.turn_free_blocks_deg = s.heading_deg ? -*s.heading_deg : 0.0;
      changes.comment =
          out_name + ": " + s.scan + " with the physics of " + s.calibration + " (" + p.label() +
          (s.heading_deg ? format(", the table's axis along x: heading %g deg in the scan's frame)", *s.heading_deg)
                         : std::string(", heading unknown)")) +
          " by rigid shaketable transfer";
      io::write_derived_scene(settled.at(settled_name(p)), (out.parent_path() / file).string(), changes);
      scene_of[key] = file;
    }
    io::Json j = physics_json(p);
    j["scene"] = scene_of[key];
    j["weight"] = m.weight;
    j["lapse"] = m.lapse;
    j["rotations_deg"] = rotations;
    j["source_members"] = m.source_members;
    ensemble.push_back(j);
  }

  io::Json body;
  body["scan"] = s.scan;
  body["scene"] = out_name + ".toml";
  body["source_calibration"] = {{"path", s.calibration},
                                {"sha256", io::file_sha256(s.calibration)},
                                {"scan", source.value("scan", "")},
                                {"tests", source.value("tests", "")}};
  io::Json t;
  t["scan"] = s.scan;
  t["scan_sha256"] = io::file_sha256(s.scan);
  t["headings"] = s.headings;
  t["heading_known"] = bool(s.heading_deg) && !s.heading_weakest;
  t["heading_rule"] = s.heading_weakest ? "weakest rocking direction, either way along the axis"
                      : s.heading_deg   ? "given"
                                        : "unknown: the whole ring";
  t["heading_deg"] = io::json_or_null(s.heading_deg);
  t["heading_spread_deg"] = s.heading_deg ? io::Json(s.heading_spread_deg) : io::Json(nullptr);
  t["rotations_deg"] = rotations;
  t["source_members"] = long(source_count);
  t["members"] = long(members.size());
  const CalibrationSettings& how = s.scan_import;
  t["scan_import"] = {{"scale", how.scale},
                      {"up", how.up},
                      {"max_vertices", how.max_vertices},
                      {"pedestal_margin_m", how.pedestal_margin},
                      {"tilt_rule_deg", how.tilt_deg}};
  t["method"] =
      "each source member's physics (base model, contact law, impact law, friction) on this scan, settled under its "
      "law; members of the same physics and lapse merged, their weights added; each member seen over the same "
      "headings: the whole ring when the heading is unknown, else the ring's headings within the spread of the "
      "given one (or, for the weakest direction, of its axis either way); the lapse is the lab's and kept; no outcome "
      "of this rock was read, so there are no scores";
  body["transfer"] = t;
  body["ensemble"] = ensemble;
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  body["wall_s"] = wall_s;
  const std::string json_path = s.out + ".calibration.json";
  write_calibration_document(json_path, body, s.command_line);

  TransferSummary summary;
  summary.scene = s.out + ".toml";
  summary.json = json_path;
  summary.source_members = source_count;
  summary.members = members.size();
  summary.physics = scene_of.size();
  summary.rotations = rotations.size();
  summary.heaviest = members.front().physics.label();
  summary.heaviest_weight = members.front().weight;
  summary.wall_s = wall_s;
  return summary;
}

}  // namespace rigid::shaketable
