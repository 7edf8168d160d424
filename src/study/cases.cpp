// The study's cases (a scene, a motion, the oracle that applies) and the oracles' values.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "rigid/analysis/tilt_test.hpp"
#include "rigid/library/builders.hpp"
#include "rigid/motion/synth.hpp"
#include "rigid/rocking/housner.hpp"
#include "rigid/rocking/newmark.hpp"
#include "rigid/scenario/rocking2d.hpp"
#include "rigid/study/accuracy_study.hpp"

namespace rigid::study {
namespace {

// The study's validation blocks (models/library block_a0N: 1 m tall, 0.5 m deep, alpha 0.1-0.4).
library::LibraryModel library_model(const std::string& name) {
  for (auto& m : library::rock_library()) {
    if (m.name == name) return m;
  }
  throw std::logic_error("rock library has no " + name);
}

// Two boxes stacked on a pedestal: a stocky lower block and a slender upper one.
library::LibraryModel two_block_stack() {
  library::LibraryModel m;
  m.name = "two_block_stack";
  m.description = "two boxes on a pedestal";
  m.pieces.push_back({"pedestal", geometry::box_soup(Vec3(-0.27, -0.27, -0.2), Vec3(0.27, 0.27, 0)), true});
  m.pieces.push_back({"lower", geometry::box_soup(Vec3(-0.25, -0.25, 0), Vec3(0.25, 0.25, 0.4)), false});
  m.pieces.push_back({"upper", geometry::box_soup(Vec3(-0.1, -0.15, 0.4), Vec3(0.1, 0.15, 1.0)), false});
  m.simple_stack = true;
  return m;
}

motion::GroundMotion x_only_scaled(const motion::GroundMotion& m, double pga_g) {
  motion::GroundMotion x = m;
  x.y.clear();
  x.z.clear();
  x.has_y = x.has_z = false;
  return motion::scaled(x, motion::target_pga_factor(x, pga_g));
}

}  // namespace

const char* oracle_name(Oracle o) {
  switch (o) {
    case Oracle::housner_pulse:
      return "housner_one_sine_threshold_g";
    case Oracle::g_tan_alpha:
      return "g_tan_alpha_g";
    case Oracle::rigid_statics:
      return "rigid_statics_toppling_g";
    case Oracle::newmark_slide:
      return "newmark_sliding_displacement_m";
    case Oracle::energy_conservation:
      return "energy_conservation";
    case Oracle::none:
      break;
  }
  return "";
}

motion::GroundMotion one_sine(double amplitude_g, double period, double dt) {
  motion::PulseParams p;
  p.kind = motion::PulseKind::one_sine;
  p.amplitude_g = amplitude_g;
  p.period = period;
  p.dt = dt;
  p.duration = period + dt;
  return motion::pulse_motion("one_sine", p);
}

std::vector<Case> study_cases(const StudyOptions& o, const motion::GroundMotion& record) {
  std::vector<Case> cases;
  const contact::ContactLaw study_law;  // physics.md §11

  auto block_case = [&](const std::string& scene, const std::string& model_name) {
    Case c;
    c.scene = scene;
    c.law = study_law;
    const library::LibraryModel model = library_model(model_name);
    c.build = [model](const contact::ContactLaw& law) { return library::library_scene(model, law); };
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
    const library::LibraryModel stack = two_block_stack();
    Case rec;
    rec.scene = "stack";
    rec.motion = "record";
    rec.law = study_law;
    rec.build = [stack](const contact::ContactLaw& law) { return library::library_scene(stack, law); };
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
    c.build = [](const contact::ContactLaw& law) { return library::block_on_pedestal(0.4, 0.2, 0.4, law, 2600, 1.0); };
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
    // numerical symmetry lasts (docs/validation.md: 14 bounces here, 9 in the study's code, 3 in 3DEC)
    c.oracle = Oracle::energy_conservation;
    c.oracle_value = 0;
    c.model_quantity = "first_1deg_turn_s";
    const library::LibraryModel model = library_model("geode");
    c.build = [model](const contact::ContactLaw& law) {
      scenario::Scene s = library::library_scene(model, law);
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

double oracle_value(const Case& c) {
  switch (c.oracle) {
    case Oracle::housner_pulse: {
      const auto block = scenario::rocking_block_of(c.build(c.law));
      rocking::RockingOptions ro;
      ro.overturn_angle = scenario::kRocking2dOverturnAngle;
      return rocking::min_overturning_amplitude(block, rocking::PulseShape::one_sine, c.pulse_period, ro) / kGravity;
    }
    case Oracle::g_tan_alpha:
      return std::tan(scenario::rocking_block_of(c.build(c.law)).alpha);
    case Oracle::rigid_statics:
      return library::static_toppling(*c.library, 0.0);
    case Oracle::newmark_slide:
      return rocking::newmark_displacement(c.ground.x, c.ground.dt, c.law.friction);
    case Oracle::energy_conservation:
    case Oracle::none:
      break;
  }
  return c.oracle_value;
}

}  // namespace rigid::study
