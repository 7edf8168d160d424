#include "rigid/scenario/run_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "rigid/contact/gjk.hpp"
#include "rigid/core/error.hpp"

namespace rigid::scenario {
namespace {

std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g s", s);
  return buf;
}

std::vector<Vec3> world_vertices(const dynamics::BodyDef& body, const Mat3& rotation) {
  std::vector<Vec3> out;
  out.reserve(body.shape.vertices.size());
  for (const Vec3& v : body.shape.vertices) out.push_back(rotation * v + body.position);
  return out;
}

// Penetration depth of two placed blocks (m; <= 0 when apart), by the contact module's overlap step.
double start_overlap(const dynamics::BodyDef& a, const dynamics::BodyDef& b) {
  const Vec3 between = b.position - a.position;
  if (between.norm() > a.shape.bounding_radius + b.shape.bounding_radius) return 0;
  const Mat3 ra = a.orientation.normalized().toRotationMatrix();
  const Mat3 rb = b.orientation.normalized().toRotationMatrix();
  const std::vector<Vec3> va = world_vertices(a, ra), vb = world_vertices(b, rb);
  const contact::PlacedHull ha{&a.shape, va.data(), Vec3::Zero(), ra, a.position};
  const contact::PlacedHull hb{&b.shape, vb.data(), Vec3::Zero(), rb, b.position};
  contact::SupportHints hints;
  const Vec3 guess = between.norm() > 0 ? Vec3(between.normalized()) : Vec3::UnitZ();
  return contact::find_common_plane(ha, hb, guess, hints).overlap;
}

}  // namespace

double largest_time_step(const std::vector<dynamics::BodyDef>& bodies, const contact::ContactLaw& law) {
  const double rigid = dynamics::rigid_time_step(bodies, 1.0);
  if (law.model == contact::ContactModel::rigid) return rigid;
  return std::min(rigid, dynamics::critical_time_step(bodies, law));
}

namespace {

// Penalty contact too soft to carry a block: under its own weight on four subcontacts
// (F = K_N d^1.5 each) it would sink deeper than the start-overlap bound.
void check_penalty_stiffness(const Scene& scene) {
  if (scene.law.model != contact::ContactModel::penalty) return;
  for (const auto& body : scene.bodies) {
    if (body.fixed) continue;
    const double sink = std::pow(body.shape.mass * kGravity / (4.0 * scene.law.normal_stiffness), 2.0 / 3.0);
    if (!(sink <= kMaxStartOverlapFraction * body.shape.bounding_radius)) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.3g m", sink);
      throw InputError("", 0, "normal stiffness of " + scene.source + " too low: block '" + body.name +
                                  "' would sink " + buf + " under its own weight");
    }
  }
}

}  // namespace

void check_run_bounds(const Scene& scene, const dynamics::StepSettings& step, double simulated_time) {
  check_penalty_stiffness(scene);
  const double dt = dynamics::time_step(scene.bodies, scene.law, step);
  const double largest = largest_time_step(scene.bodies, scene.law);
  const char* model = contact::contact_model_name(scene.law.model);
  if (!(dt <= largest)) {
    throw InputError("", 0, "time step " + seconds(dt) + " of " + scene.source + " exceeds the largest the " + model +
                                " contact model allows (" + seconds(largest) +
                                ", its automatic step at safety 1): lower dt or safety" +
                                (step.dt > 0 ? "" : ", or raise the contact stiffness"));
  }
  const double steps = simulated_time / dt;
  if (!(steps <= kMaxStepsPerRun)) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g steps of %.3g s", steps, dt);
    throw InputError("", 0, std::string("a run of ") + scene.source + " would take " + buf + " for " +
                                seconds(simulated_time) + " (more than 1e9): the duration, dt, block size, "
                                "density or stiffness is out of range");
  }
}

void check_start_overlap(const Scene& scene) {
  const auto& bodies = scene.bodies;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < bodies.size(); ++j) {
      if (bodies[i].fixed && bodies[j].fixed) continue;  // pedestals never interact
      const double depth = start_overlap(bodies[i], bodies[j]);
      const double limit =
          kMaxStartOverlapFraction * std::min(bodies[i].shape.bounding_radius, bodies[j].shape.bounding_radius);
      if (depth > limit) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "%.3g m at the start (more than %.3g m, a tenth of the smaller block's radius)",
                      depth, limit);
        throw InputError("", 0, "blocks '" + bodies[i].name + "' and '" + bodies[j].name + "' overlap by " + buf);
      }
    }
  }
}

}  // namespace rigid::scenario
