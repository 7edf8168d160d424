#include "rigid/scenario/run_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
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

std::vector<Vec3> world_vertices(const geometry::ConvexPolyhedron& shape, const Mat3& rotation, const Vec3& position) {
  std::vector<Vec3> out;
  out.reserve(shape.vertices.size());
  for (const Vec3& v : shape.vertices) out.push_back(rotation * v + position);
  return out;
}

// The convex pieces that make a body's contact shape (its shape alone for a plain block).
std::vector<const geometry::ConvexPolyhedron*> contact_pieces(const dynamics::BodyDef& body) {
  std::vector<const geometry::ConvexPolyhedron*> out;
  if (body.pieces.empty()) out.push_back(&body.shape);
  for (const auto& piece : body.pieces) out.push_back(&piece);
  return out;
}

// Penetration depth of two placed blocks (m; <= 0 when apart), by the contact module's overlap
// step: the deepest over their contact pieces (the outline of a compound body is no contact shape:
// a rock in a hollow of its pedestal lies inside the pedestal's hull).
double start_overlap(const dynamics::BodyDef& a, const dynamics::BodyDef& b) {
  const Vec3 between = b.position - a.position;
  if (between.norm() > a.shape.bounding_radius + b.shape.bounding_radius) return 0;
  const Mat3 ra = a.orientation.normalized().toRotationMatrix();
  const Mat3 rb = b.orientation.normalized().toRotationMatrix();
  const Vec3 guess = between.norm() > 0 ? Vec3(between.normalized()) : Vec3::UnitZ();
  double deepest = -std::numeric_limits<double>::infinity();
  for (const auto* pa : contact_pieces(a)) {
    const std::vector<Vec3> va = world_vertices(*pa, ra, a.position);
    for (const auto* pb : contact_pieces(b)) {
      const std::vector<Vec3> vb = world_vertices(*pb, rb, b.position);
      const contact::PlacedHull ha{pa, va.data(), Vec3::Zero(), ra, a.position};
      const contact::PlacedHull hb{pb, vb.data(), Vec3::Zero(), rb, b.position};
      contact::SupportHints hints;
      deepest = std::max(deepest, contact::find_common_plane(ha, hb, guess, hints).overlap);
    }
  }
  return deepest;
}

}  // namespace

double largest_time_step(const std::vector<dynamics::BodyDef>& bodies, const contact::ContactLaw& law) {
  const double rigid = dynamics::rigid_time_step(bodies, 1.0);
  if (law.method == contact::ContactMethod::rigid) return rigid;
  return std::min(rigid, dynamics::critical_time_step(bodies, law));
}

namespace {

// Penalty contact too soft to carry a block: under its own weight on four subcontacts
// (F = K_N d^1.5 each) it would sink deeper than the start-overlap bound.
void check_penalty_stiffness(const Scene& scene) {
  if (scene.law.method != contact::ContactMethod::penalty) return;
  for (const auto& body : scene.bodies) {
    if (body.fixed) continue;
    const double sink = std::pow(body.shape.mass * kGravity / (4.0 * scene.law.normal_stiffness), 2.0 / 3.0);
    if (!(sink <= kMaxStartOverlapFraction * body.shape.bounding_radius)) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.3g m", sink);
      throw InputError("", 0,
                       "normal stiffness of " + scene.source + " too low: block '" + body.name + "' would sink " + buf +
                           " under its own weight");
    }
  }
}

}  // namespace

void check_run_bounds(const Scene& scene, const dynamics::StepSettings& step, double simulated_time) {
  check_penalty_stiffness(scene);
  const double dt = dynamics::time_step(scene.bodies, scene.law, step);
  const double largest = largest_time_step(scene.bodies, scene.law);
  const char* model = contact::contact_method_name(scene.law.method);
  if (!(dt <= largest)) {
    throw InputError("", 0,
                     "time step " + seconds(dt) + " of " + scene.source + " exceeds the largest the " + model +
                         " contact model allows (" + seconds(largest) +
                         ", its automatic step at safety 1): lower dt or safety");
  }
  const double steps = simulated_time / dt;
  if (!(steps <= kMaxStepsPerRun)) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g steps of %.3g s", steps, dt);
    throw InputError("", 0,
                     std::string("a run of ") + scene.source + " would take " + buf + " for " +
                         seconds(simulated_time) +
                         " (more than 1e9): the duration, dt, block size, "
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
