// The sweep: every case with every setting that applies to it, measured against the converged
// reference run of the same case and against the case's oracle.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include "rigid/analysis/tilt_test.hpp"
#include "rigid/study/accuracy_study.hpp"
#include "trajectory.hpp"

namespace rigid::study {
StudyResult run_study(const StudyOptions& o, std::vector<Case> cases_in, std::vector<Setting> settings_in,
                      const std::function<void(const Case&, double)>& case_done) {
  StudyResult result;
  result.cases = std::move(cases_in);
  result.settings = std::move(settings_in);
  const std::vector<Setting>& settings = result.settings;
  std::vector<Row>& rows = result.rows;
  const double interval = o.quick ? 0.002 : 0.001;  // trajectory sampling (unit: s)
  const double search_tol = o.quick ? 0.02 : 0.005;
  const int repeat = o.quick ? 1 : o.repeat;
  for (std::size_t ci = 0; ci < result.cases.size(); ++ci) {
    Case& c = result.cases[ci];
    const auto case_start = Clock::now();
    std::map<std::pair<int, double>, scenario::Scene> settled;  // per contact model and stiffness
    auto scene_for = [&](const Setting& s) -> const scenario::Scene& {
      const std::pair<int, double> key(int(s.contact), s.stiffness);
      auto it = settled.find(key);
      if (it != settled.end()) return it->second;
      contact::ContactLaw law = c.law;
      law.method = s.contact;
      // no damping in a conservative case: the rigid model's counterpart is an elastic impact
      if (c.conservative && s.contact == contact::ContactMethod::rigid) law.restitution = 1;
      law.normal_stiffness = law.shear_stiffness = s.stiffness;
      scenario::Scene scene = c.build(law);
      if (c.settle) scene = scenario::equilibrate(scene, dynamics::StepSettings{});
      return settled.emplace(key, std::move(scene)).first->second;
    };
    c.oracle_value = oracle_value(c);  // from the scene at build time
    const Setting& ref_setting = settings.front();
    std::optional<Trajectory> ref;
    double ref_model = kNoValue;
    for (std::size_t si = 0; si < settings.size(); ++si) {
      const Setting& s = settings[si];
      // the tilt test has no at-rest stop and no effect selection; the drop has no at-rest stop
      if ((c.quasi_static || c.motion == "drop") && s.axis == "tolerance") continue;
      if (c.quasi_static && s.axis == "effects") continue;
      Row row;
      row.case_index = ci;
      row.setting_index = si;
      const scenario::Scene& scene = scene_for(s);
      scenario::RunSettings rs = run_settings(s);
      rs.duration = c.duration;
      rs.free_time = c.free_time;
      row.dt = dynamics::time_step(scene.bodies, scene.law, rs.step);
      if (c.quasi_static) {
        analysis::TiltTestSettings tts;
        tts.step = rs.step;
        if (o.quick) tts.relative_tolerance = 0.01;
        std::vector<double> walls;
        analysis::TiltTestResult r;
        for (int k = 0; k < repeat; ++k) {
          const auto start = Clock::now();
          r = analysis::tilt_test(scene, 0.0, tts);
          walls.push_back(seconds_since(start));
        }
        row.wall = median(walls);
        row.repeats = repeat;
        row.steps = r.steps;
        row.model_value = r.acceleration;
      } else {
        if (c.pulse_period > 0 && o.quick) {
          // no threshold search: the trajectory runs at 70 % of the Housner threshold
          if (&s == &ref_setting) c.ground = one_sine(0.7 * c.oracle_value, c.pulse_period);
        } else if (c.pulse_period > 0) {
          // threshold first: the trajectory runs at 90 % of the converged threshold
          const double h = c.oracle_value;
          double wall = 0;
          row.model_value = pulse_threshold(scene, rs, c.pulse_period, 0.6 * h, 1.2 * h, search_tol, wall);
          row.search_wall = wall;
          if (&s == &ref_setting) c.ground = one_sine(0.9 * row.model_value, c.pulse_period);
        }
        std::vector<double> walls;
        Trajectory tr;
        for (int k = 0; k < repeat; ++k) {
          Trajectory t = run_trajectory(scene, c.ground, rs, c.conservative, interval);
          walls.push_back(t.wall);
          if (k == 0) tr = std::move(t);
        }
        row.wall = median(walls);
        row.repeats = repeat;
        const auto& out = tr.outcome;
        row.steps = out.steps;
        row.dt = out.dt_s;
        row.simulated = out.simulated_s;
        row.overturned = out.overturned;
        row.failure_time = out.failure_time_s ? *out.failure_time_s : kNoValue;
        row.max_tilt_deg = out.max_tilt_rad * 180.0 / kPi;
        row.energy_err = tr.energy_err;
        if (c.oracle == Oracle::newmark_slide) {
          // final relative displacement of the block along x (pedestal frame)
          const int n = tr.nfree;
          row.model_value = tr.pos[tr.pos.size() - std::size_t(n)].x() - tr.pos[0].x();
        } else if (c.oracle == Oracle::energy_conservation) {
          row.model_value = tr.first_turn;
        }
        if (&s == &ref_setting) ref = tr;
        const Trajectory& r0 = *ref;
        const TrajectoryError e = compare(tr, r0, interval);
        row.tilt_rms = e.tilt_rms_deg;
        row.pos_rms = e.pos_rms_mm;
        row.traj_rel = e.rel;
        row.error = e.rel;
        row.outcome_match = out.overturned == r0.outcome.overturned;
        if (out.failure_time_s && r0.outcome.failure_time_s)
          row.failure_time_err = std::abs(*out.failure_time_s - *r0.outcome.failure_time_s);
        row.max_tilt_err = std::abs(out.max_tilt_rad - r0.outcome.max_tilt_rad) * 180.0 / kPi;
      }
      if (&s == &ref_setting) ref_model = row.model_value;
      if (std::isfinite(row.model_value) && std::isfinite(ref_model) && ref_model != 0) {
        row.model_ref_err = row.model_value / ref_model - 1.0;
        if (c.quasi_static) row.error = std::abs(row.model_ref_err);
      }
      if (c.oracle == Oracle::energy_conservation) {
        row.oracle_err = row.energy_err;
      } else if (std::isfinite(row.model_value) && std::isfinite(c.oracle_value)) {
        row.oracle_err =
            c.oracle_value != 0 ? row.model_value / c.oracle_value - 1.0 : row.model_value - c.oracle_value;
      }
      rows.push_back(row);
    }
    if (case_done) case_done(c, seconds_since(case_start));
  }

  return result;
}

}  // namespace rigid::study
