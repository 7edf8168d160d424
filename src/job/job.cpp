#include "rigid/job/job.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <stdexcept>

#include "rigid/io/provenance.hpp"

namespace rigid::job {

void apply_overrides(Job& job) {
  job.run = run_settings(job.overrides);
  job.accuracy = accuracy_name(job.overrides);
  job.engine = job.overrides.engine.value_or(scenario::Engine::dem3d);
  job.contact = job.overrides.contact;
}

std::string checkpoint_interval_problem(double interval_s) {
  return std::isfinite(interval_s) && interval_s > 0 ? "" : "must be a positive number of seconds";
}

std::string grace_problem(double grace_s) {
  return std::isfinite(grace_s) && grace_s >= 0 ? "" : "must be a number of seconds >= 0";
}

Job one_cell_job(const RunOverrides& overrides) {
  Job job;
  job.objects.resize(1);
  job.records.resize(1);
  job.scales_g = {kAsRecordedScale};
  job.rotations = 1;
  job.rotation_angles_deg = {0.0};
  job.stop_after = 0;
  job.overrides = overrides;
  apply_overrides(job);
  return job;
}

scenario::RunOutcome simulate_one_cell(const Job& job, const scenario::Model& model) {
  const scenario::CaseOutcome outcome = scenario::simulate_case(model, case_of(job, Cell{}));
  if (outcome.error) std::rethrow_exception(outcome.error);
  if (!outcome.run.finite) throw std::runtime_error("the simulation produced a non-finite state");
  return outcome.run;
}

double cell_rotation_deg(const Job& job, const Cell& c) {
  if (!job.rotation_angles_deg.empty()) return job.rotation_angles_deg[std::size_t(c.rotation)];
  // every variant of an object shakes at the same angles (common random numbers): a difference
  // between variants is then the parameters', not the rotations' sampling noise
  Cell keyed = c;
  if (std::size_t(c.object) < job.objects.size() && job.objects[std::size_t(c.object)].base >= 0) {
    keyed.object = job.objects[std::size_t(c.object)].base;
  }
  return rotation_angle_deg(job.seed, keyed);
}

scenario::Case case_of(const Job& job, const Cell& cell) {
  return {cell.object, cell.record, job.drive_scale_g(std::size_t(cell.scale)), cell_rotation_deg(job, cell)};
}

std::string job_settings_text(const Job& job) {
  // cubes from before the presets were computed with balanced's settings and hash the text alone
  if (job.accuracy == "balanced") return job.text;
  return job.text + "\n# accuracy: " + job.accuracy + "\n";
}

std::string job_hash(const Job& job) { return io::sha256_hex(job_settings_text(job)); }

std::string legacy_job_hash(const Job& job) {
  // FNV-1a, 64 bits, of the same text
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const unsigned char c : job_settings_text(job)) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

}  // namespace rigid::job
