#include "rigid/campaign/session.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/campaign/journal.hpp"
#include "rigid/campaign/log.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/at2.hpp"
#include "rigid/io/json.hpp"

#if !defined(RIGID_VERSION) || !defined(RIGID_GIT_HASH)
#error "the build defines RIGID_VERSION and RIGID_GIT_HASH"
#endif

namespace rigid::campaign {
namespace {

namespace fs = std::filesystem;

InputError changed_file(const std::string& file, const OutputRemedies& remedies) {
  const std::string anew = remedies.start_anew.empty() ? "" : "; " + remedies.start_anew + " starts anew";
  return InputError(file, 0, "changed since the campaign started (resume refused" + anew + ")");
}

// What to do about an output written by another job, in the caller's words.
std::string other_job_remedy(const OutputRemedies& remedies) {
  const bool anew = !remedies.start_anew.empty(), elsewhere = !remedies.other_output.empty();
  if (!anew && !elsewhere) return "";
  return "; use " + (anew ? remedies.start_anew + " to start a new campaign over it" : std::string()) +
         (anew && elsewhere ? ", or " : "") + (elsewhere ? "another " + remedies.other_output : std::string());
}

// Why the cube's results must not be resumed with these inputs, or nothing when they may.
std::optional<InputError> input_change(const io::Cube& old, const job::Job& job, const Inputs& now,
                                       const OutputRemedies& remedies) {
  const io::Digests old_job = io::parse_digests(old.job_inputs);
  if (old.job_hash != job.hash && old.job_hash != job::legacy_job_hash(job)) {
    // the same job file edited is named; another job file or other command-line settings name the output
    if (old_job.size() >= 2 && old_job[1].path == now.job[1].path && old_job[1].sha256 != now.job[1].sha256) {
      return changed_file(job.path, remedies);
    }
    return InputError(job.output, 0,
                      "was written by a different job file, accuracy preset or command-line settings (hash " +
                          old.job_hash + ", now " + job.hash + ")" + other_job_remedy(remedies));
  }
  if (old.inputs_sha256.empty()) {
    log_warning(job.output +
                " was written before input hashes were stored; its scenes and records are not checked for changes");
    return std::nullopt;
  }
  if (old.inputs_sha256 == now.combined) return std::nullopt;
  if (auto f = io::first_changed(old_job, now.job)) return changed_file(*f, remedies);
  for (std::size_t o = 0; o < now.objects.size() && o < old.objects.size(); ++o) {
    if (auto f = io::first_changed(io::parse_digests(old.objects[o].inputs), now.objects[o]))
      return changed_file(*f, remedies);
  }
  for (std::size_t r = 0; r < now.records.size() && r < old.records.size(); ++r) {
    if (auto f = io::first_changed(io::parse_digests(old.records[r].inputs), now.records[r]))
      return changed_file(*f, remedies);
  }
  return changed_file(job.output, remedies);  // a digest that matches no file list: the cube itself was altered
}

}  // namespace

Inputs collect_inputs(const job::Job& job, const scenario::Model& model) {
  Inputs in;
  in.job.push_back({"(settings)", io::sha256_hex(job::job_settings_text(job))});
  in.job.push_back({job.path, io::file_sha256(job.path)});
  if (!job.record_list.empty()) in.job.push_back({job.record_list, io::file_sha256(job.record_list)});
  // the calibration's weights and members are not in the job's text: a replaced or recalibrated
  // file must not be resumed into the same cube
  if (job.calibration) in.job.push_back({job.calibration->path, io::file_sha256(job.calibration->path)});
  for (std::size_t o = 0; o < job.objects.size(); ++o)
    in.objects.push_back(io::digest_files(model.scene(int(o)).files));
  for (const auto& r : job.records) {
    // a lab recording is one file (its format is in the job text, hashed above)
    if (r.lab) {
      in.records.push_back(io::digest_files({r.spec}));
      continue;
    }
    const io::SetFiles set = io::resolve_set(r.spec);
    std::vector<std::string> files;
    for (const std::string* f : {&set.x, &set.y, &set.z}) {
      if (!f->empty()) files.push_back(*f);
    }
    in.records.push_back(io::digest_files(files));
  }
  std::string all;
  const auto add = [&all](const char* what, const io::Digests& d) {
    all += std::string(what) + " " + std::to_string(d.size()) + "\n";
    for (const auto& f : d) all += f.sha256 + "\n";
  };
  add("job", in.job);
  for (const auto& d : in.objects) add("object", d);
  for (const auto& d : in.records) add("record", d);
  in.combined = io::sha256_hex(all);
  return in;
}

namespace {

// The job's variants as the cube's table: one column per parameter, a value per variant.
io::VariantTable variant_table(const scenario::VariantSpace& space) {
  io::VariantTable table;
  table.method = space.method;
  table.seed = space.seed;
  table.count = space.count();
  for (std::size_t j = 0; j < space.keys.size(); ++j) {
    const scenario::VariantParameterInfo& info = scenario::variant_parameter(space.keys[j]);
    io::VariantParameter p{info.name, info.units, info.description, {}, {}};
    for (const auto& row : space.variants) {
      if (info.text) {
        p.labels.push_back(row[j].text);
      } else {
        p.values.push_back(row[j].number);
      }
    }
    table.parameters.push_back(std::move(p));
  }
  return table;
}

}  // namespace

io::Cube make_cube(const CampaignContext& context, const Plan& plan) {
  const job::Job& job = context.job;
  const scenario::Model& model = context.model;
  const Inputs& inputs = context.inputs;
  io::Cube cube;
  cube.records = context.records;
  for (std::size_t r = 0; r < cube.records.size(); ++r) cube.records[r].inputs = io::format_digests(inputs.records[r]);
  cube.job_inputs = io::format_digests(inputs.job);
  cube.inputs_sha256 = inputs.combined;
  cube.scales_g = job.scales_g;
  cube.rotations = job.rotations;
  cube.job_text = job.text;
  cube.job_hash = job.hash;
  cube.software_version = RIGID_VERSION " (" RIGID_GIT_HASH ")";
  cube.seed = job.seed;
  cube.variants = variant_table(job.variants);
  if (job.calibration) {
    const io::JobCalibration& c = *job.calibration;
    cube.calibration = io::CubeCalibration{c.path, c.sha256, c.weights, c.summary_json};
  }
  cube.physics_json = io::physics_json(model.scene(0), job.run, job.accuracy,
                                       job.stop_after);  // object 0's, as before per-object records
  const std::vector<std::int8_t> outcome = plan.final_outcomes();
  const std::vector<bool> kept = plan.kept_mask();
  const long per_object = job.cells().per_object();
  const double nan = std::nan("");
  for (std::size_t o = 0; o < job.objects.size(); ++o) {
    io::ObjectCube oc;
    oc.name = job.objects[o].name;
    oc.variant = job.objects[o].variant;
    oc.scene = job.objects[o].scene;
    oc.inputs = io::format_digests(inputs.objects[o]);
    oc.physics_json = io::physics_json(model.scene(int(o)), job.run, job.accuracy, job.stop_after);
    if (const auto rocking = analysis::rocking_parameters(model.scene(int(o)))) {
      oc.alpha_rad = rocking->alpha;
      oc.p_rad_s = rocking->p;
      oc.rocking_radius_m = rocking->radius;
      oc.weakest_azimuth_deg = rocking->azimuth * 180.0 / kPi;
      oc.alpha_by_azimuth_rad = rocking->alpha_by_azimuth;
      for (const auto& corner : rocking->support_polygon) {
        oc.support_polygon_m.push_back(corner.x());
        oc.support_polygon_m.push_back(corner.y());
      }
    }
    for (long i = 0; i < per_object; ++i) {
      const long t = long(o) * per_object + i;
      const TaskResult& r = plan.results()[t];
      oc.outcome.push_back(outcome[t]);
      oc.rotation_deg.push_back(cell_rotation_deg(job, plan.cell(t)));
      oc.failure_time_s.push_back(kept[t] ? r.failure_time_s : nan);
      oc.max_tilt_deg.push_back(kept[t] ? r.max_tilt_deg : nan);
      oc.max_slip_m.push_back(kept[t] ? r.max_slip_m : nan);
      oc.wall_s.push_back(kept[t] ? r.wall_s : nan);
      oc.failure_reason.push_back(kept[t] ? r.reason : 0);
      oc.failure_message.push_back(kept[t] ? message_of(r) : std::string());
      oc.unconverged_steps.push_back(
          kept[t] ? std::int32_t(std::clamp<std::int64_t>(r.unconverged_steps, -1, INT32_MAX)) : -1);
    }
    cube.objects.push_back(std::move(oc));
  }
  return cube;
}

std::vector<TaskResult> restore(const std::string& output, const job::Job& job, const Inputs& inputs, Plan& plan,
                                bool force, const OutputRemedies& remedies) {
  const std::string journal = output + ".journal";
  const bool have_cube = fs::exists(output);
  if (have_cube) {
    const io::Cube old = io::read_cube(output);
    if (const std::string w = io::old_cube_warning(output, old); !w.empty()) log_warning(w);
    if (std::optional<InputError> change = input_change(old, job, inputs, remedies)) {
      if (!force) throw *change;
      fs::remove(output);
      fs::remove(journal);
      return {};
    }
    const long per_object = job.cells().per_object();
    for (std::size_t o = 0; o < old.objects.size() && o < job.objects.size(); ++o) {
      const auto& oc = old.objects[o];
      for (long i = 0; i < per_object && i < long(oc.outcome.size()); ++i) {
        const auto v = static_cast<scenario::CellOutcome>(oc.outcome[i]);
        if (v != scenario::CellOutcome::survived && v != scenario::CellOutcome::overturned &&
            v != scenario::CellOutcome::failed)
          continue;
        TaskResult r;
        r.task = long(o) * per_object + i;
        r.outcome = oc.outcome[i];
        r.reason = oc.failure_reason[i];
        if (i < long(oc.failure_message.size())) set_message(r, oc.failure_message[i]);
        r.failure_time_s = oc.failure_time_s[i];
        r.max_tilt_deg = oc.max_tilt_deg[i];
        r.max_slip_m = oc.max_slip_m[i];
        r.wall_s = oc.wall_s[i];
        if (i < long(oc.unconverged_steps.size())) r.unconverged_steps = oc.unconverged_steps[i];
        plan.restore(r);
      }
    }
  } else if (force) {
    fs::remove(journal);
  }
  JournalContents kept = read_journal(journal, inputs.combined, plan.size());
  if (kept.foreign) {
    // without a cube to name the changed file, the journal itself is the evidence
    if (!have_cube) throw changed_file(journal, remedies);
    kept.problems.push_back(journal + ": written for other inputs; ignored");
  }
  for (const std::string& p : kept.problems) log_warning(p);
  for (const TaskResult& r : kept.results) plan.restore(r);
  return std::move(kept.results);
}

}  // namespace rigid::campaign
