// `rigid study accuracy`: what accuracy costs in time (issue 6; docs/accuracy.md). Reference
// scenes built in code are run with the settings that trade accuracy for time (time-step safety
// factor, rotation integrator, the at-rest stop tolerances) with the default contact model, and
// with both contact models (penalty at three stiffnesses, rigid at four time steps: a model axis,
// not a numerical one: it changes the physics), and each run is measured against a converged
// reference run of the same scene (default model) (outcome, failure time, max tilt, trajectory) and
// against the analytic oracles where they exist (Housner one-sine thresholds, g tan(alpha),
// rigid-statics toppling of a stack, Newmark rigid-plastic sliding, energy conservation and
// passivity). Writes DIR/accuracy.csv, then DIR/accuracy_pareto.png and DIR/accuracy_table.md
// with src/plot/accuracy_plot.py.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "python_script.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/at2.hpp"
#include "rigid/motion/synth.hpp"
#include "rigid/rocking/housner.hpp"
#include "rigid/rocking/newmark.hpp"
#include "rigid/scenario/accuracy.hpp"
#include "rigid/scenario/builders.hpp"
#include "rigid/scenario/rock_library.hpp"
#include "rigid/scenario/rocking2d.hpp"
#include "rigid/scenario/tilt_test.hpp"

namespace rigid::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using dynamics::RotationIntegrator;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kStudyStiffness = 1e8;  // the study's K_N = K_S (physics.md §11)

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? kNaN : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// ------------------------------------------------------------------------------------------
// Settings

struct Setting {
  std::string axis;    // converged | safety | tolerance | effects | stiffness | preset | rigid
  std::string label;   // unique within a case
  std::string preset;  // preset name (axis == preset)
  double safety = 0.2;
  RotationIntegrator rotation = RotationIntegrator::splitting;
  double stiffness = kStudyStiffness;
  // the default model on the numerical axes; the model axis sets it explicitly, with stiffness
  contact::ContactModel contact = contact::ContactLaw{}.model;
  double rest_speed = 1e-3;          // unit: m/s
  double rest_angular_speed = 1e-3;  // unit: rad/s
  double rest_time = 0.5;            // unit: s
  bool select_effects = true;        // RunSettings::select_effects (false: every effect simulated)
};

scenario::RunSettings run_settings(const Setting& s) {
  scenario::RunSettings r;
  r.step.safety = s.safety;
  r.step.rotation = s.rotation;
  r.rest_speed = s.rest_speed;
  r.rest_angular_speed = s.rest_angular_speed;
  r.rest_time = s.rest_time;
  r.select_effects = s.select_effects;
  return r;
}

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

struct StudyOptions {
  std::string out = "out/accuracy";
  bool quick = false;
  int repeat = 3;
  double reference_safety = 0.025;
  std::string record;
  bool plot = true;
  std::vector<std::string> only;
  std::string contact = "both";  // which contact models the model axis runs: rigid, penalty or both
};

std::vector<Setting> settings_to_study(const StudyOptions& o) {
  std::vector<Setting> out;
  // the converged reference: half the smallest safety of the sweep, tight at-rest stop, every
  // effect simulated (no sleeping, no culling)
  Setting ref;
  ref.axis = "converged";
  ref.label = "converged reference";
  ref.safety = o.reference_safety;
  ref.rest_speed = ref.rest_angular_speed = 1e-5;
  ref.rest_time = 2.0;
  ref.select_effects = false;
  out.push_back(ref);
  const std::vector<double> safeties = o.quick ? std::vector<double>{0.05, 0.2, 0.8}
                                               : std::vector<double>{0.05, 0.1, 0.2, 0.4, 0.8};
  const std::vector<RotationIntegrator> rotations =
      o.quick ? std::vector<RotationIntegrator>{RotationIntegrator::splitting}
              : std::vector<RotationIntegrator>{RotationIntegrator::splitting, RotationIntegrator::rk4};
  for (const auto rot : rotations) {
    for (const double s : safeties) {
      Setting x;
      x.axis = "safety";
      x.safety = s;
      x.rotation = rot;
      x.label = format("safety %g", s) + " " + scenario::integrator_name(rot);
      out.push_back(x);
    }
  }
  // the at-rest stop (speed and time), around the defaults, at safety 0.2
  struct Tol {
    double speed, time;
  };
  const std::vector<Tol> tols = o.quick ? std::vector<Tol>{{1e-2, 0.25}}
                                        : std::vector<Tol>{{1e-4, 1.0}, {1e-4, 0.5}, {1e-2, 0.5}, {1e-3, 0.25}, {1e-2, 0.25}};
  for (const auto& t : tols) {
    Setting x;
    x.axis = "tolerance";
    x.rest_speed = x.rest_angular_speed = t.speed;
    x.rest_time = t.time;
    x.label = format("rest %g", t.speed) + format(" for %g s", t.time);
    out.push_back(x);
  }
  // effect selection off (sleeping etc.; RunSettings::select_effects), at safety 0.2
  {
    Setting x;
    x.axis = "effects";
    x.select_effects = false;
    x.label = "effects all";
    out.push_back(x);
  }
  // contact stiffness: the model axis, against the rigid-block oracles
  const bool penalty_axis = o.contact != "rigid", rigid_axis = o.contact != "penalty";
  for (const double k : !penalty_axis ? std::vector<double>{} : o.quick ? std::vector<double>{kStudyStiffness}
                                                                       : std::vector<double>{kStudyStiffness, 1e9, 1e10}) {
    Setting x;
    x.axis = "stiffness";
    x.contact = contact::ContactModel::penalty;
    x.stiffness = k;
    x.label = format("stiffness %.0e", k);
    out.push_back(x);
  }
  // the rigid contact model (physics.md §12) at the presets' safety factors and beyond: the other
  // side of the model axis, against the same oracles
  for (const double s : !rigid_axis ? std::vector<double>{} : o.quick ? std::vector<double>{0.4}
                                                                       : std::vector<double>{0.05, 0.2, 0.4, 0.8}) {
    Setting x;
    x.axis = "rigid";
    x.contact = contact::ContactModel::rigid;
    x.safety = s;
    x.label = format("rigid safety %g", s);
    out.push_back(x);
  }
  for (const auto& p : scenario::accuracy_presets()) {
    Setting x;
    x.axis = "preset";
    x.preset = p.name;
    x.label = "preset " + p.name;
    x.safety = p.safety;
    x.rotation = p.rotation;
    x.rest_speed = p.rest_speed;
    x.rest_angular_speed = p.rest_angular_speed;
    x.rest_time = p.rest_time;
    out.push_back(x);
  }
  return out;
}

// ------------------------------------------------------------------------------------------
// Cases: a scene, a motion, the oracle that applies

enum class Oracle { none, housner_pulse, g_tan_alpha, rigid_statics, newmark_slide, energy_conservation };

const char* oracle_name(Oracle o) {
  switch (o) {
    case Oracle::housner_pulse: return "housner_one_sine_threshold_g";
    case Oracle::g_tan_alpha: return "g_tan_alpha_g";
    case Oracle::rigid_statics: return "rigid_statics_toppling_g";
    case Oracle::newmark_slide: return "newmark_sliding_displacement_m";
    case Oracle::energy_conservation: return "energy_conservation";
    case Oracle::none: break;
  }
  return "";
}

struct Case {
  std::string scene;   // slender | stocky | stack | sliding | geode
  std::string motion;  // pulse | record | quasi-static | drop
  bool quasi_static = false;
  /// The unsettled scene for a contact law (stiffness set by the setting).
  std::function<scenario::Scene(const contact::ContactLaw&)> build;
  contact::ContactLaw law;
  bool settle = true;
  bool conservative = false;  // no friction, no damping: energy must be conserved
  motion::GroundMotion ground;  // x component only; empty: no ground motion
  double pulse_period = 0;      // > 0: one-sine pulse, amplitude from the threshold search
  double duration = 0;          // 0: motion + free time
  double free_time = 5.0;
  Oracle oracle = Oracle::none;
  double oracle_value = kNaN;
  std::string model_quantity;   // what model_value is
  std::optional<scenario::LibraryModel> library;  // for the rigid-statics oracle
};

// The study's validation blocks (models/library block_a0N: 1 m tall, 0.5 m deep, alpha 0.1-0.4).
scenario::LibraryModel library_model(const std::string& name) {
  for (auto& m : scenario::rock_library()) {
    if (m.name == name) return m;
  }
  throw std::logic_error("rock library has no " + name);
}

// Two boxes stacked on a pedestal: a stocky lower block and a slender upper one.
scenario::LibraryModel two_block_stack() {
  scenario::LibraryModel m;
  m.name = "two_block_stack";
  m.description = "two boxes on a pedestal";
  m.pieces.push_back({"pedestal", geometry::box_soup(Vec3(-0.27, -0.27, -0.2), Vec3(0.27, 0.27, 0)), true});
  m.pieces.push_back({"lower", geometry::box_soup(Vec3(-0.25, -0.25, 0), Vec3(0.25, 0.25, 0.4)), false});
  m.pieces.push_back({"upper", geometry::box_soup(Vec3(-0.1, -0.15, 0.4), Vec3(0.1, 0.15, 1.0)), false});
  m.simple_stack = true;
  return m;
}

motion::GroundMotion one_sine(double amplitude_g, double period, double dt = 1e-3) {
  motion::PulseParams p;
  p.kind = motion::PulseKind::one_sine;
  p.amplitude_g = amplitude_g;
  p.period = period;
  p.dt = dt;
  p.duration = period + dt;
  return motion::pulse_motion("one_sine", p);
}

motion::GroundMotion x_only_scaled(const motion::GroundMotion& m, double pga_g) {
  motion::GroundMotion x = m;
  x.y.clear();
  x.z.clear();
  x.has_y = x.has_z = false;
  return motion::scaled(x, motion::target_pga_factor(x, pga_g));
}

// ------------------------------------------------------------------------------------------
// One trajectory run, sampled by the observer

struct Trajectory {
  std::vector<double> t;
  int nfree = 0;
  std::vector<Vec3> pos;      // centroid relative to the first fixed body, per free block
  std::vector<double> tilt;   // per free block (unit: rad)
  double energy_err = 0;      // largest energy gained from nothing (or drift, if conservative) / scale
  double max_rotation = 0;    // largest rotation of any free block from its start (unit: rad)
  double first_turn = kNaN;   // first time a free block has turned more than 1 degree (unit: s)
  scenario::RunOutcome outcome;
  double wall = 0;
};

Trajectory run_trajectory(const scenario::Scene& scene, const scenario::GroundDrive& drive,
                          scenario::RunSettings settings, bool conservative, double interval) {
  Trajectory tr;
  std::vector<int> free, fixed;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) (scene.bodies[i].fixed ? fixed : free).push_back(int(i));
  tr.nfree = int(free.size());
  // energy scale: m g r of the free blocks, or the drop energy of a conservative scene
  double scale = 0;
  double e0 = kNaN;
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
  const auto start = Clock::now();
  tr.outcome = scenario::run(scene, drive, settings);
  tr.wall = seconds_since(start);
  return tr;
}

struct TrajectoryError {
  double tilt_rms_deg = 0, pos_rms_mm = 0, rel = 0;
};

// Both trajectories on one grid from 0 to the later end; a run that stopped (overturned or at
// rest) holds its last state.
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

// Smallest one-sine amplitude (unit: g) that overturns the scene, by bisection between lo and hi
// (widened when they do not bracket); stops when the bracket is narrower than rel_tol * hi.
double pulse_threshold(const scenario::Scene& scene, const scenario::RunSettings& settings, double period,
                       double lo, double hi, double rel_tol, double& wall) {
  const auto start = Clock::now();
  scenario::RunSettings s = settings;
  s.duration = period + 10.0;
  auto overturns = [&](double a) { return scenario::run(scene, scenario::ground_drive(one_sine(a, period)), s).overturned; };
  for (int k = 0; k < 8 && overturns(lo); ++k) lo *= 0.8;
  for (int k = 0; k < 8 && !overturns(hi); ++k) hi *= 1.25;
  while (hi - lo > rel_tol * hi) {
    const double mid = 0.5 * (lo + hi);
    (overturns(mid) ? hi : lo) = mid;
  }
  wall = seconds_since(start);
  return 0.5 * (lo + hi);
}

// ------------------------------------------------------------------------------------------
// The study

struct Row {
  const Case* c = nullptr;
  const Setting* s = nullptr;
  double dt = kNaN;
  long steps = 0;
  double simulated = kNaN;
  std::optional<bool> overturned;
  double failure_time = kNaN, max_tilt_deg = kNaN;
  std::optional<bool> outcome_match;
  double failure_time_err = kNaN, max_tilt_err = kNaN;
  double tilt_rms = kNaN, pos_rms = kNaN, traj_rel = kNaN, error = kNaN, energy_err = kNaN;
  double model_value = kNaN, model_ref_err = kNaN, oracle_err = kNaN;
  double wall = kNaN, search_wall = kNaN;
  int repeats = 0;
};

std::string csv_number(double v) {
  if (!std::isfinite(v)) return "";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string csv_bool(const std::optional<bool>& b) { return b ? (*b ? "1" : "0") : ""; }

void write_csv(const std::string& path, const std::vector<Row>& rows) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw InputError(path, 0, "cannot write");
  std::fprintf(f,
               "scene,motion,axis,setting,contact,preset,safety,integrator,stiffness_n_m,rest_speed,rest_time_s,effects,dt_s,steps,"
               "simulated_s,overturned,failure_time_s,max_tilt_deg,outcome_match,failure_time_err_s,max_tilt_err_deg,"
               "traj_tilt_rms_deg,traj_pos_rms_mm,traj_rel_err,error,energy_err,model_quantity,model_value,"
               "model_ref_err,oracle,oracle_value,oracle_err,wall_s,search_wall_s,repeats\n");
  for (const Row& r : rows) {
    const Case& c = *r.c;
    const Setting& s = *r.s;
    std::fprintf(f, "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%ld,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%d\n",
                 c.scene.c_str(), c.motion.c_str(), s.axis.c_str(), s.label.c_str(), contact::contact_model_name(s.contact),
                 s.preset.c_str(),
                 csv_number(s.safety).c_str(), scenario::integrator_name(s.rotation), csv_number(s.stiffness).c_str(),
                 csv_number(s.rest_speed).c_str(), csv_number(s.rest_time).c_str(), s.select_effects ? "auto" : "all",
                 csv_number(r.dt).c_str(), r.steps,
                 csv_number(r.simulated).c_str(), csv_bool(r.overturned).c_str(), csv_number(r.failure_time).c_str(),
                 csv_number(r.max_tilt_deg).c_str(), csv_bool(r.outcome_match).c_str(),
                 csv_number(r.failure_time_err).c_str(), csv_number(r.max_tilt_err).c_str(),
                 csv_number(r.tilt_rms).c_str(), csv_number(r.pos_rms).c_str(), csv_number(r.traj_rel).c_str(),
                 csv_number(r.error).c_str(), csv_number(r.energy_err).c_str(), c.model_quantity.c_str(),
                 csv_number(r.model_value).c_str(), csv_number(r.model_ref_err).c_str(), oracle_name(c.oracle),
                 csv_number(c.oracle_value).c_str(), csv_number(r.oracle_err).c_str(), csv_number(r.wall).c_str(),
                 csv_number(r.search_wall).c_str(), r.repeats);
  }
  std::fclose(f);
}

// The real record: the Rinaldi Receiving Station fault-normal component (Northridge 1994) from
// ../shared beside the checkout, else the bundled synthetic record (a fresh clone has no ../shared).
std::string find_record(const std::string& given) {
  if (!given.empty()) return given;
  const fs::path source = fs::path(__FILE__).parent_path().parent_path().parent_path();
  std::vector<fs::path> roots{source};
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) roots.push_back(exe.parent_path().parent_path().parent_path());
  roots.push_back(fs::current_path());
  for (const auto& root : roots) {
    const fs::path p = root / ".." / "shared" / "waveforms" / "peer" / "NORTHR" / "Rinaldi228.AT2";
    if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  }
  for (const auto& root : roots) {
    const fs::path p = root / "waveforms" / "demo" / "stochastic_s1-X.AT2";
    if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  }
  throw InputError("", 0, "no record found (../shared/waveforms/peer/NORTHR/Rinaldi228.AT2 or waveforms/demo); give --record");
}

std::vector<Case> build_cases(const StudyOptions& o, const std::string& record_path) {
  std::vector<Case> cases;
  const motion::GroundMotion record = motion::windowed(io::read_motion_set("x=" + record_path), 0.0, 20.0);
  const contact::ContactLaw study_law;  // physics.md §11

  auto block_case = [&](const std::string& scene, const std::string& model_name) {
    Case c;
    c.scene = scene;
    c.law = study_law;
    const scenario::LibraryModel model = library_model(model_name);
    c.build = [model](const contact::ContactLaw& law) { return scenario::library_scene(model, law); };
    c.library = model;
    return c;
  };
  struct BlockSpec {
    const char* scene;
    const char* model;
    double pulse_period, record_pga_g;
  };
  // slender alpha 0.1 and stocky alpha 0.4: the ends of the validation set
  for (const BlockSpec& b : {BlockSpec{"slender", "block_a01", 0.5, 0.2}, BlockSpec{"stocky", "block_a04", 1.0, 0.6}}) {
    Case pulse = block_case(b.scene, b.model);
    pulse.motion = "pulse";
    pulse.pulse_period = b.pulse_period;
    pulse.oracle = Oracle::housner_pulse;
    pulse.model_quantity = "one_sine_threshold_g";
    cases.push_back(pulse);
    if (o.quick) continue;
    Case rec = block_case(b.scene, b.model);
    rec.motion = "record";
    rec.ground = x_only_scaled(record, b.record_pga_g);
    cases.push_back(rec);
    Case qs = block_case(b.scene, b.model);
    qs.motion = "quasi-static";
    qs.quasi_static = true;
    qs.oracle = Oracle::g_tan_alpha;
    qs.model_quantity = "tilt_test_g";
    cases.push_back(qs);
  }
  if (!o.quick) {
    const scenario::LibraryModel stack = two_block_stack();
    Case rec;
    rec.scene = "stack";
    rec.motion = "record";
    rec.law = study_law;
    rec.build = [stack](const contact::ContactLaw& law) { return scenario::library_scene(stack, law); };
    rec.library = stack;
    rec.ground = x_only_scaled(record, 0.5);
    cases.push_back(rec);
    Case qs = rec;
    qs.motion = "quasi-static";
    qs.quasi_static = true;
    qs.ground = {};
    qs.oracle = Oracle::rigid_statics;
    qs.model_quantity = "tilt_test_g";
    cases.push_back(qs);
  }
  // a wide block (tan alpha = 2) with mu = 0.2 slides and does not rock; the pedestal is wide
  // enough that it stays on it
  {
    Case c;
    c.scene = "sliding";
    c.law = study_law;
    c.law.friction = 0.2;
    c.build = [](const contact::ContactLaw& law) { return scenario::block_on_pedestal(0.4, 0.2, 0.4, law, 2600, 1.0); };
    c.oracle = Oracle::newmark_slide;
    c.model_quantity = "sliding_displacement_m";
    c.motion = "pulse";
    c.ground = one_sine(0.6, 0.5);
    cases.push_back(c);
    if (!o.quick) {
      c.motion = "record";
      c.ground = x_only_scaled(record, 0.5);
      cases.push_back(c);
    }
  }
  // the geode (rock library) dropped 0.5 m vertex-down, no friction, no damping
  {
    Case c;
    c.scene = "geode";
    c.motion = "drop";
    c.law = study_law;
    c.law.friction = 0;
    c.law.damping = 0;
    c.settle = false;
    c.conservative = true;
    c.duration = o.quick ? 2.0 : 10.0;
    // oracles: energy is conserved (relative drift, energy_err); a symmetric vertex-down drop
    // gives no torque, so the time before the geode first turns by 1 degree tells how long the
    // numerical symmetry lasts (README: 14 bounces here, 9 in the study's code, 3 in 3DEC)
    c.oracle = Oracle::energy_conservation;
    c.oracle_value = 0;
    c.model_quantity = "first_1deg_turn_s";
    const scenario::LibraryModel model = library_model("geode");
    c.build = [model](const contact::ContactLaw& law) {
      scenario::Scene s = scenario::library_scene(model, law);
      for (auto& b : s.bodies) {
        if (b.fixed) continue;
        const Vec3 lowest = b.shape.vertices[0];  // body frame: any vertex, pointed straight down
        b.orientation = Quat::FromTwoVectors(lowest, -Vec3::UnitZ());
        b.position = Vec3(0, 0, 0.5 + lowest.norm());
      }
      return s;
    };
    cases.push_back(c);
  }
  if (!o.only.empty()) {
    std::vector<Case> kept;
    for (auto& c : cases) {
      if (std::find(o.only.begin(), o.only.end(), c.scene) != o.only.end() ||
          std::find(o.only.begin(), o.only.end(), c.scene + "/" + c.motion) != o.only.end()) {
        kept.push_back(std::move(c));
      }
    }
    cases = std::move(kept);
  }
  return cases;
}

void study_accuracy(const StudyOptions& o) {
  if (o.repeat < 1) throw InputError("", 0, "--repeat must be at least 1");
  if (o.contact != "rigid" && o.contact != "penalty" && o.contact != "both") {
    throw InputError("", 0, "--contact must be rigid, penalty or both");
  }
  if (!(o.reference_safety > 0)) throw InputError("", 0, "--reference-safety must be positive");
  const auto study_start = Clock::now();
  const std::string record_path = find_record(o.record);
  std::vector<Case> cases = build_cases(o, record_path);
  if (cases.empty()) throw InputError("", 0, "--only selects no case");
  const std::vector<Setting> settings = settings_to_study(o);
  const double interval = o.quick ? 0.002 : 0.001;  // trajectory sampling (unit: s)
  const double search_tol = o.quick ? 0.02 : 0.005;
  const int repeat = o.quick ? 1 : o.repeat;
  fs::create_directories(o.out);
  std::printf("rigid study accuracy: %zu cases x %zu settings; record %s\n", cases.size(), settings.size(),
              record_path.c_str());
  std::vector<Row> rows;

  for (Case& c : cases) {
    const auto case_start = Clock::now();
    std::map<std::pair<int, double>, scenario::Scene> settled;  // per contact model and stiffness
    auto scene_for = [&](const Setting& s) -> const scenario::Scene& {
      const std::pair<int, double> key(int(s.contact), s.stiffness);
      auto it = settled.find(key);
      if (it != settled.end()) return it->second;
      contact::ContactLaw law = c.law;
      law.model = s.contact;
      // no damping in a conservative case: the rigid model's counterpart is an elastic impact
      if (c.conservative && s.contact == contact::ContactModel::rigid) law.restitution = 1;
      law.normal_stiffness = law.shear_stiffness = s.stiffness;
      scenario::Scene scene = c.build(law);
      if (c.settle) scene = scenario::equilibrate(scene, dynamics::StepSettings{});
      return settled.emplace(key, std::move(scene)).first->second;
    };
    // the oracle value, from the scene at build time
    if (c.oracle == Oracle::housner_pulse) {
      const auto block = scenario::rocking_block_of(c.build(c.law));
      rocking::RockingOptions ro;
      ro.overturn_angle = scenario::kRocking2dOverturnAngle;
      c.oracle_value = rocking::min_overturning_amplitude(block, rocking::PulseShape::one_sine, c.pulse_period, ro) / kGravity;
    } else if (c.oracle == Oracle::g_tan_alpha) {
      c.oracle_value = std::tan(scenario::rocking_block_of(c.build(c.law)).alpha);
    } else if (c.oracle == Oracle::rigid_statics) {
      c.oracle_value = scenario::static_toppling(*c.library, 0.0);
    } else if (c.oracle == Oracle::newmark_slide) {
      c.oracle_value = rocking::newmark_displacement(c.ground.x, c.ground.dt, c.law.friction);
    }
    const Setting& ref_setting = settings.front();
    std::optional<Trajectory> ref;
    double ref_model = kNaN;
    for (const Setting& s : settings) {
      // the tilt test has no at-rest stop and no effect selection; the drop has no at-rest stop
      if ((c.quasi_static || c.motion == "drop") && s.axis == "tolerance") continue;
      if (c.quasi_static && s.axis == "effects") continue;
      Row row;
      row.c = &c;
      row.s = &s;
      const scenario::Scene& scene = scene_for(s);
      scenario::RunSettings rs = run_settings(s);
      rs.duration = c.duration;
      rs.free_time = c.free_time;
      row.dt = s.contact == contact::ContactModel::rigid ? dynamics::rigid_time_step(scene.bodies, s.safety)
                                                          : s.safety * dynamics::critical_time_step(scene.bodies, scene.law);
      if (c.quasi_static) {
        scenario::TiltTestSettings tts;
        tts.step = rs.step;
        if (o.quick) tts.relative_tolerance = 0.01;
        std::vector<double> walls;
        scenario::TiltTestResult r;
        for (int k = 0; k < repeat; ++k) {
          const auto start = Clock::now();
          r = scenario::tilt_test(scene, 0.0, tts);
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
        const scenario::GroundDrive drive = c.ground.x.empty() ? scenario::GroundDrive{} : scenario::ground_drive(c.ground);
        std::vector<double> walls;
        Trajectory tr;
        for (int k = 0; k < repeat; ++k) {
          Trajectory t = run_trajectory(scene, drive, rs, c.conservative, interval);
          walls.push_back(t.wall);
          if (k == 0) tr = std::move(t);
        }
        row.wall = median(walls);
        row.repeats = repeat;
        const auto& out = tr.outcome;
        row.steps = out.steps;
        row.dt = out.dt;
        row.simulated = out.simulated;
        row.overturned = out.overturned;
        row.failure_time = out.failure_time ? *out.failure_time : kNaN;
        row.max_tilt_deg = out.max_tilt * 180.0 / kPi;
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
        if (out.failure_time && r0.outcome.failure_time) row.failure_time_err = std::abs(*out.failure_time - *r0.outcome.failure_time);
        row.max_tilt_err = std::abs(out.max_tilt - r0.outcome.max_tilt) * 180.0 / kPi;
      }
      if (&s == &ref_setting) ref_model = row.model_value;
      if (std::isfinite(row.model_value) && std::isfinite(ref_model) && ref_model != 0) {
        row.model_ref_err = row.model_value / ref_model - 1.0;
        if (c.quasi_static) row.error = std::abs(row.model_ref_err);
      }
      if (c.oracle == Oracle::energy_conservation) {
        row.oracle_err = row.energy_err;
      } else if (std::isfinite(row.model_value) && std::isfinite(c.oracle_value)) {
        row.oracle_err = c.oracle_value != 0 ? row.model_value / c.oracle_value - 1.0 : row.model_value - c.oracle_value;
      }
      rows.push_back(row);
    }
    std::printf("  %-8s %-12s %5.1f s  (oracle %s = %s)\n", c.scene.c_str(), c.motion.c_str(), seconds_since(case_start),
                c.oracle == Oracle::none ? "-" : oracle_name(c.oracle), csv_number(c.oracle_value).c_str());
    std::fflush(stdout);
  }

  const std::string csv = (fs::path(o.out) / "accuracy.csv").string();
  write_csv(csv, rows);
  std::printf("wrote %s (%zu rows) in %.1f s\n", csv.c_str(), rows.size(), seconds_since(study_start));
  if (!o.plot) return;
  const std::string script = find_plot_helper("accuracy_plot.py");
  if (script.empty()) {
    std::fprintf(stderr, "rigid study: warning: src/plot/accuracy_plot.py not found; no plot\n");
    return;
  }
  const std::string png = (fs::path(o.out) / "accuracy_pareto.png").string();
  const std::string md = (fs::path(o.out) / "accuracy_table.md").string();
  const int status = run_python(script, {csv, "--png", png, "--table", md});
  if (status != 0) {
    std::fprintf(stderr, "rigid study: warning: %s %s failed (status %d); the CSV is complete\n",
                 python_interpreter().c_str(), script.c_str(), status);
  }
}

}  // namespace

void register_study_command(CLI::App& app) {
  CLI::App* study = app.add_subcommand("study", "Studies of the engine itself: `rigid study accuracy`");
  study->require_subcommand(1);
  auto o = std::make_shared<StudyOptions>();
  CLI::App* acc = study->add_subcommand(
      "accuracy",
      "What accuracy costs in time: reference scenes (slender and stocky blocks under a one-sine pulse, a real "
      "record and a quasi-static ramp; a two-block stack; a sliding block; the geode drop) run with every "
      "time-step safety factor, rotation integrator, at-rest tolerance, contact stiffness and accuracy preset, "
      "measured against a converged reference run and the analytic oracles. Writes DIR/accuracy.csv, "
      "DIR/accuracy_pareto.png and DIR/accuracy_table.md (docs/accuracy.md)");
  acc->add_option("--out", o->out, "Output directory")->capture_default_str();
  acc->add_flag("--quick", o->quick, "A small subset (CI smoke test, well under a minute)");
  acc->add_option("--repeat", o->repeat, "Runs per timing; the median wall time is reported (1 with --quick)")
      ->capture_default_str();
  acc->add_option("--reference-safety", o->reference_safety, "Safety factor of the converged reference run")
      ->capture_default_str();
  acc->add_option("--record", o->record,
                  "AT2 file of the real record (x component); default ../shared/waveforms/peer/NORTHR/Rinaldi228.AT2 "
                  "beside the checkout, else waveforms/demo/stochastic_s1-X.AT2");
  acc->add_option("--only", o->only, "Only these scenes (slender, stocky, stack, sliding, geode) or SCENE/MOTION cases");
  acc->add_flag("!--no-plot", o->plot, "Write the CSV only");
  acc->add_option("--contact", o->contact,
                  "Contact models on the model axis: rigid (at safety 0.05-0.8), penalty (stiffness 1e8-1e10) or both")
      ->capture_default_str();
  acc->callback([o] { study_accuracy(*o); });
}

}  // namespace rigid::app
