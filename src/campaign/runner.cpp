#include "rigid/campaign/runner.hpp"

#include <chrono>
#include <cmath>
#include <exception>

#include "rigid/io/at2.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/motion/measures.hpp"

namespace rigid::campaign {

TaskRunner::TaskRunner(const scenario::Job& job) : job_(job) {
  for (const auto& o : job.objects) {
    scenario::Scene s = io::load_scene(o.scene);
    if (!o.state.empty()) io::apply_state(o.state, s);
    if (!job.contact.empty()) contact::parse_contact_model(job.contact, s.law.model);
    if (job.model == "rocking2d") rocking_.push_back(scenario::rocking_block_of(s));
    scenes_.push_back(std::move(s));
  }
  for (const auto& r : job.records) {
    io::SetReadOptions read;
    read.align.resample = r.resample;
    const motion::GroundMotion m = motion::windowed(io::read_motion_set(r.spec, read), r.start, r.end);
    const double unit = motion::target_pga_factor(m, 1.0);
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
    meta_.push_back(meta);
    windowed_.push_back(m);
    unit_factor_.push_back(unit);
  }
}

double TaskRunner::simulated_time(int r) const {
  return job_.run.duration > 0 ? job_.run.duration : windowed_[r].duration() + job_.run.free_time;
}

TaskResult TaskRunner::run(long task, const Cell& cell, bool noop) const {
  TaskResult out;
  out.task = task;
  out.failure_time_s = std::nan("");
  out.max_tilt_deg = std::nan("");
  out.max_slip_m = std::nan("");
  const auto start = std::chrono::steady_clock::now();
  if (noop) {
    out.outcome = static_cast<std::int32_t>(io::CellOutcome::survived);
    out.wall_s = 0;
    return out;
  }
  try {
    const double angle = cell_rotation_deg(job_, cell) * kPi / 180.0;
    const motion::GroundMotion scaled =
        motion::scaled(windowed_[cell.record], unit_factor_[cell.record] * job_.scales_g[cell.scale]);
    // The 2D reference takes the record's x component as scaled, whatever the rotation: a 2D
    // fragility (Purvance et al. 2008, the study's reference, physics.md §11) is a function of the
    // record's PGA and PGV alone. Projecting the rotated motion on x instead would weaken the
    // shaking by |cos| of a random angle that the 2D block cannot feel.
    const scenario::RunOutcome r = job_.model == "rocking2d"
        ? scenario::run_rocking2d(rocking_[cell.object], scaled.x, scaled.dt, job_.run)
        : scenario::run(scenes_[cell.object], scenario::ground_drive(motion::rotated(scaled, angle)), job_.run);
    if (!r.finite) {
      out.outcome = static_cast<std::int32_t>(io::CellOutcome::failed);
      out.reason = static_cast<std::int32_t>(FailureReason::non_finite);
    } else {
      out.outcome = static_cast<std::int32_t>(r.overturned ? io::CellOutcome::overturned : io::CellOutcome::survived);
      if (r.failure_time) out.failure_time_s = *r.failure_time;
      out.max_tilt_deg = r.max_tilt * 180.0 / kPi;
      out.max_slip_m = r.max_slip;
    }
  } catch (const std::exception&) {
    out.outcome = static_cast<std::int32_t>(io::CellOutcome::failed);
    out.reason = static_cast<std::int32_t>(FailureReason::exception);
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rigid::campaign
