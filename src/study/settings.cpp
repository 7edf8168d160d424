// The sweep's settings: the converged reference, the numerical axes (safety factor, rotation
// integrator, at-rest stop, effect selection), the model axis (penalty stiffness, rigid contact)
// and the accuracy presets.
#include <cstdio>
#include <string>
#include <vector>

#include "rigid/scenario/accuracy.hpp"
#include "rigid/study/accuracy_study.hpp"

namespace rigid::study {
namespace {

using dynamics::RotationIntegrator;

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

}  // namespace

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

std::vector<Setting> study_settings(const StudyOptions& o) {
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
  const std::vector<double> safeties =
      o.quick ? std::vector<double>{0.05, 0.2, 0.8} : std::vector<double>{0.05, 0.1, 0.2, 0.4, 0.8};
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
  const std::vector<Tol> tols =
      o.quick ? std::vector<Tol>{{1e-2, 0.25}}
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
  for (const double k : !penalty_axis ? std::vector<double>{}
                        : o.quick     ? std::vector<double>{kStudyStiffness}
                                      : std::vector<double>{kStudyStiffness, 1e9, 1e10}) {
    Setting x;
    x.axis = "stiffness";
    x.contact = contact::ContactMethod::penalty;
    x.stiffness = k;
    x.label = format("stiffness %.0e", k);
    out.push_back(x);
  }
  // the rigid contact model (physics.md §12) at the presets' safety factors and beyond: the other
  // side of the model axis, against the same oracles
  for (const double s : !rigid_axis ? std::vector<double>{}
                        : o.quick   ? std::vector<double>{0.4}
                                    : std::vector<double>{0.05, 0.2, 0.4, 0.8}) {
    Setting x;
    x.axis = "rigid";
    x.contact = contact::ContactMethod::rigid;
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

}  // namespace rigid::study
