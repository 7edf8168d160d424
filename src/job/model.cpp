#include "rigid/job/model.hpp"

#include <sstream>
#include <stdexcept>

#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/at2.hpp"
#include "rigid/io/lab_recording.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/motion/measures.hpp"
#include "rigid/scenario/run_bounds.hpp"

namespace rigid::job {
namespace {

// a scale in six digits, as a message shows it
std::string shortest(double x) {
  std::ostringstream text;
  text << x;
  return text.str();
}

// The record's window, a window error naming where the record is given (job file or list, line).
motion::GroundMotion windowed_record(const JobRecord& r, const motion::GroundMotion& m) {
  try {
    return motion::windowed(m, r.start, r.end);
  } catch (const InputError& e) {
    throw InputError(r.origin_file, r.origin_line, "record " + r.name + ": " + e.problem());
  }
}

// A variant the object cannot take is the job's error, at the line of the [sweep] or [[variant]]
// that asked for it: a centre of mass outside its block or beyond its support polygon (the
// block would tip at once), or values a scene file may not have (scene_value_problem), or
// blocks that start inside each other.
void apply_job_variant(const Job& job, const JobObject& o, scenario::Scene& s) {
  try {
    const bool supported = analysis::rocking_parameters(s).has_value();
    scenario::apply_variant(job.variants, o.variant, s);
    if (const std::string problem = io::scene_value_problem(s); !problem.empty()) throw std::invalid_argument(problem);
    if (supported && !analysis::rocking_parameters(s))
      throw std::invalid_argument("the centre of mass lies outside the support polygon: the block would tip at once");
    try {
      scenario::check_start_overlap(s);
    } catch (const InputError& e) {
      throw std::invalid_argument(e.problem());
    }
  } catch (const std::invalid_argument& e) {
    const std::size_t at = job.variant_lines.size() == 1 ? 0 : std::size_t(o.variant);
    throw InputError(job.path, at < job.variant_lines.size() ? job.variant_lines[at] : 0,
                     "variant " + std::to_string(o.variant) + " of object " + o.name + ": " + e.what());
  }
}

}  // namespace

scenario::Model assemble_model(const Job& job, std::vector<scenario::Scene> scenes,
                               std::vector<motion::GroundMotion> records, std::vector<double> pga_factor_per_g) {
  for (std::size_t o = 0; o < scenes.size() && o < job.objects.size(); ++o) {
    if (job.contact) scenes[o].law.method = *job.contact;
    if (job.objects[o].variant >= 0) apply_job_variant(job, job.objects[o], scenes[o]);
  }
  try {
    return scenario::Model(job.engine, std::move(scenes), std::move(records), job.run, std::move(pga_factor_per_g));
  } catch (const InputError& e) {
    // the run bounds name no file: the job's [run] settings (or its records' lengths) broke them
    if (!e.file().empty() || job.path.empty()) throw;
    throw InputError(job.path, job.run_line, e.what());
  }
}

scenario::Model load_model(const Job& job) {
  std::vector<scenario::Scene> scenes;
  for (const auto& o : job.objects) {
    scenario::Scene s = io::load_scene(o.simulated_scene());
    if (!o.state.empty()) io::apply_state(o.state, s);
    scenes.push_back(std::move(s));
  }
  std::vector<motion::GroundMotion> records;
  std::vector<double> per_g;
  for (const auto& r : job.records) {
    io::SetReadOptions read;
    read.align.resample = r.resample;
    records.push_back(
        windowed_record(r, r.lab ? io::read_lab_motion(r.spec, job.lab_format) : io::read_motion_set(r.spec, read)));
    // once per record: every case scales this record, and the GMRotI50 measure is costly
    per_g.push_back(motion::target_pga_factor(records.back(), 1.0));
    // the largest scale refused now, not as a failed cell: scales rise, so it is the last
    if (!job.as_recorded() && !job.scales_g.empty()) {
      const double top_g = job.drive_scale_g(job.scales_g.size() - 1);
      if (const auto bad = motion::first_bad_drive_sample(records.back(), per_g.back() * top_g)) {
        throw InputError(r.origin_file, r.origin_line,
                         "record " + r.name + " scaled to its largest scale, " + shortest(top_g) +
                             " g (GMRotI50 PGA): its " + bad->axis + " component is " + bad->problem);
      }
    }
  }
  return assemble_model(job, std::move(scenes), std::move(records), std::move(per_g));
}

std::vector<io::RecordMeta> record_metadata(const Job& job, const scenario::Model& model) {
  std::vector<io::RecordMeta> metas;
  for (std::size_t i = 0; i < job.records.size(); ++i) {
    const JobRecord& r = job.records[i];
    const motion::GroundMotion& m = model.record(int(i));
    io::RecordMeta meta;
    meta.name = r.name;
    meta.source = r.spec;
    meta.earthquake = r.earthquake;
    meta.alignment = m.alignment;
    meta.start_s = r.start;
    meta.end_s = r.start + m.duration();
    meta.listed_pga_g = r.listed_pga_g;
    meta.listed_pgv_cm_s = r.listed_pgv_cm_s;
    if (m.has_y) {
      const motion::HorizontalMeasures h = motion::horizontal_measures(m);
      meta.gmroti_pga_g = h.gmroti50_pga / kGravity;
      meta.gmroti_pgv_cm_s = 100.0 * h.gmroti50_pgv;
    } else {
      const motion::Peaks p = motion::peaks(m.x, m.dt);
      meta.gmroti_pga_g = p.pga / kGravity;
      meta.gmroti_pgv_cm_s = 100.0 * p.pgv;
    }
    meta.pgv_pga_s = meta.gmroti_pgv_cm_s / (100.0 * meta.gmroti_pga_g * kGravity);
    metas.push_back(meta);
  }
  return metas;
}

}  // namespace rigid::job
