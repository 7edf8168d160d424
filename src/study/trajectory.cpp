#include "trajectory.hpp"

#include <algorithm>
#include <cmath>

#include "rigid/scenario/case.hpp"
#include "rigid/study/accuracy_study.hpp"

namespace rigid::study {
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? kNoValue : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

namespace {

// The run of the model's one case (its record as it is); an error inside it is thrown again.
scenario::RunOutcome simulated_run(const scenario::Model& model) {
  scenario::CaseOutcome out = scenario::simulate_case(model, scenario::Case{});
  if (out.error) std::rethrow_exception(out.error);
  return out.run;
}

}  // namespace

Trajectory run_trajectory(const scenario::Scene& scene, const motion::GroundMotion& ground,
                          scenario::RunSettings settings, bool conservative, double interval) {
  Trajectory tr;
  std::vector<int> free, fixed;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) (scene.bodies[i].fixed ? fixed : free).push_back(int(i));
  tr.nfree = int(free.size());
  // energy scale: m g r of the free blocks, or the drop energy of a conservative scene
  double scale = 0;
  double e0 = kNoValue;
  for (int i : free) scale += scene.bodies[i].shape.mass * kGravity * scene.bodies[i].shape.bounding_radius;
  settings.observe_interval = interval;
  settings.observer = [&](const dynamics::World& w) {
    tr.t.push_back(w.time());
    const Vec3 base = fixed.empty() ? Vec3::Zero() : w.states()[fixed[0]].position;
    const Vec3 base0 = fixed.empty() ? Vec3::Zero() : scene.bodies[fixed[0]].position;
    for (int i : free) {
      const auto& s = w.states()[i];
      tr.pos.push_back(s.position - (base - base0));
      tr.tilt.push_back(scenario::tilt(scene.bodies[i].orientation, s.orientation));
      const Quat rel = scene.bodies[i].orientation.conjugate() * s.orientation;
      tr.max_rotation = std::max(tr.max_rotation, 2.0 * std::acos(std::min(1.0, std::abs(rel.w()))));
      if (std::isnan(tr.first_turn) && tr.max_rotation > kPi / 180.0) tr.first_turn = w.time();
    }
    // E - E0 - W: minus the energy dissipated, which can only grow
    const double e = w.kinetic_energy() + w.potential_energy() + w.elastic_energy() - w.pedestal_work();
    if (std::isnan(e0)) {
      e0 = e;
      if (conservative) {
        // the drop energy: m g times the height of the lowest vertex above the fixed blocks' top
        double top = -1e300;
        for (int i : fixed) {
          for (const auto& v : w.world_vertices(i)) top = std::max(top, v.z());
        }
        double drop = 0;
        for (int i : free) {
          double low = 1e300;
          for (const auto& v : w.world_vertices(i)) low = std::min(low, v.z());
          drop += scene.bodies[i].shape.mass * kGravity * std::max(0.0, low - top);
        }
        if (drop > 0) scale = drop;
      }
    }
    const double residual = e - e0;
    tr.energy_err = std::max(tr.energy_err, (conservative ? std::abs(residual) : std::max(0.0, residual)) / scale);
  };
  const scenario::Model model(scenario::Engine::dem3d, {scene}, {ground}, std::move(settings));
  const auto start = Clock::now();
  tr.outcome = simulated_run(model);
  tr.wall = seconds_since(start);
  return tr;
}

TrajectoryError compare(const Trajectory& a, const Trajectory& ref, double interval) {
  TrajectoryError e;
  if (a.t.empty() || ref.t.empty()) return e;
  const double end = std::max(a.t.back(), ref.t.back());
  const int n = ref.nfree;
  auto sample = [n](const Trajectory& tr, double t, std::vector<Vec3>& p, std::vector<double>& th) {
    auto it = std::upper_bound(tr.t.begin(), tr.t.end(), t);
    std::size_t k1 = std::size_t(it - tr.t.begin());
    if (k1 == 0) k1 = 1;
    if (k1 >= tr.t.size()) k1 = tr.t.size() - 1;
    const std::size_t k0 = tr.t.size() > 1 ? k1 - 1 : 0;
    if (tr.t.size() == 1) k1 = 0;
    const double span = tr.t[k1] - tr.t[k0];
    const double f = span > 0 ? std::clamp((t - tr.t[k0]) / span, 0.0, 1.0) : 0.0;
    for (int b = 0; b < n; ++b) {
      p[b] = (1 - f) * tr.pos[k0 * n + b] + f * tr.pos[k1 * n + b];
      th[b] = (1 - f) * tr.tilt[k0 * n + b] + f * tr.tilt[k1 * n + b];
    }
  };
  std::vector<Vec3> pa(n), pr(n);
  std::vector<double> ta(n), trf(n);
  double sum_p = 0, sum_t = 0, sum_ref = 0;
  long count = 0;
  for (double t = 0; t <= end + 1e-12; t += interval) {
    sample(a, t, pa, ta);
    sample(ref, t, pr, trf);
    for (int b = 0; b < n; ++b) {
      sum_p += (pa[b] - pr[b]).squaredNorm();
      sum_t += (ta[b] - trf[b]) * (ta[b] - trf[b]);
      sum_ref += (pr[b] - ref.pos[b]).squaredNorm();
      ++count;
    }
  }
  e.pos_rms_mm = 1e3 * std::sqrt(sum_p / double(count));
  e.tilt_rms_deg = std::sqrt(sum_t / double(count)) * 180.0 / kPi;
  e.rel = sum_ref > 0 ? std::sqrt(sum_p / sum_ref) : 0.0;
  return e;
}

double pulse_threshold(const scenario::Scene& scene, const scenario::RunSettings& settings, double period, double lo,
                       double hi, double rel_tol, double& wall) {
  const auto start = Clock::now();
  scenario::RunSettings s = settings;
  s.duration = period + 10.0;
  auto overturns = [&](double a) {
    return simulated_run(scenario::Model(scenario::Engine::dem3d, {scene}, {one_sine(a, period)}, s)).overturned;
  };
  for (int k = 0; k < 8 && overturns(lo); ++k) lo *= 0.8;
  for (int k = 0; k < 8 && !overturns(hi); ++k) hi *= 1.25;
  while (hi - lo > rel_tol * hi) {
    const double mid = 0.5 * (lo + hi);
    (overturns(mid) ? hi : lo) = mid;
  }
  wall = seconds_since(start);
  return 0.5 * (lo + hi);
}

}  // namespace rigid::study
