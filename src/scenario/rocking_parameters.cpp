#include "rigid/scenario/rocking_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rigid::scenario {
namespace {

using P2 = Eigen::Vector2d;

double cross2(const P2& a, const P2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Indices of the counter-clockwise convex hull of the points' (x, y) (monotone chain), collinear
// points dropped.
std::vector<int> hull_xy(const std::vector<Vec3>& p) {
  std::vector<int> order(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return p[a].x() < p[b].x() || (p[a].x() == p[b].x() && p[a].y() < p[b].y());
  });
  if (order.size() < 3) return order;
  const auto turn = [&](int o, int a, int b) {
    return cross2(p[a].head<2>() - p[o].head<2>(), p[b].head<2>() - p[o].head<2>());
  };
  std::vector<int> h(2 * order.size());
  std::size_t k = 0;
  for (int i : order) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], i) <= 1e-15) --k;
    h[k++] = i;
  }
  for (std::size_t i = order.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && turn(h[k - 2], h[k - 1], order[i - 1]) <= 1e-15) --k;
    h[k++] = order[i - 1];
  }
  h.resize(k - 1);
  return h;
}

// Largest signed distance of a world point outside a fixed block's face planes (< 0 inside).
double outside_distance(const dynamics::BodyDef& b, const Vec3& world_point) {
  const Vec3 q = b.orientation.conjugate() * (world_point - b.position);
  double most = -1e300;
  for (const auto& f : b.shape.faces) most = std::max(most, f.normal.dot(q) - f.offset);
  return most;
}

}  // namespace

std::optional<RockingParameters> rocking_parameters(const Scene& scene, double contact_tolerance) {
  const dynamics::BodyDef* block = nullptr;
  for (const auto& b : scene.bodies) {
    if (b.fixed) continue;
    if (block) return std::nullopt;
    block = &b;
  }
  if (!block) return std::nullopt;
  const Mat3 r = block->orientation.toRotationMatrix();
  std::vector<Vec3> support;
  for (const auto& v : block->shape.vertices) {
    const Vec3 w = r * v + block->position;
    for (const auto& b : scene.bodies) {
      if (b.fixed && outside_distance(b, w) <= contact_tolerance) {
        support.push_back(w);
        break;
      }
    }
  }
  // a block can also stand on a smaller pedestal top, whose corners then bound the support
  for (const auto& b : scene.bodies) {
    if (!b.fixed) continue;
    const Mat3 rb = b.orientation.toRotationMatrix();
    for (const auto& v : b.shape.vertices) {
      const Vec3 w = rb * v + b.position;
      if (outside_distance(*block, w) <= contact_tolerance) support.push_back(w);
    }
  }
  const std::vector<int> hull = hull_xy(support);
  if (hull.size() < 3) return std::nullopt;
  const Vec3 c = block->position;
  // inertia about the centroid in world axes
  const Mat3 inertia = r * block->shape.inertia.asDiagonal() * r.transpose();
  const double m = block->shape.mass;
  std::optional<RockingParameters> best;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec3& a = support[hull[i]];
    const Vec3& b = support[hull[(i + 1) % hull.size()]];
    const P2 edge = (b - a).head<2>();
    const double length = edge.norm();
    if (length <= 0) continue;
    // counter-clockwise hull: the centroid is inside when it lies left of every edge
    const double d = cross2(edge, (c - a).head<2>()) / length;
    if (d <= 0) return std::nullopt;
    // height above the edge where the centroid's vertical plane normal to it crosses it
    const double t = std::clamp((c - a).head<2>().dot(edge) / (length * length), 0.0, 1.0);
    const Vec3 foot = a + t * (b - a);
    const double h = c.z() - foot.z();
    if (h <= 0) continue;
    const double alpha = std::atan2(d, h);
    if (best && alpha >= best->alpha) continue;
    const Vec3 axis = (b - a).normalized();
    const Vec3 arm = (c - a) - (c - a).dot(axis) * axis;  // perpendicular from the edge line
    const double radius = arm.norm();
    const double inertia_edge = axis.dot(inertia * axis) + m * radius * radius;  // parallel axes
    RockingParameters out;
    out.alpha = alpha;
    out.radius = radius;
    out.p = std::sqrt(m * kGravity * radius / inertia_edge);
    const P2 outward(edge.y(), -edge.x());  // right of a counter-clockwise edge
    out.azimuth = std::atan2(outward.y(), outward.x());
    best = out;
  }
  return best;
}

}  // namespace rigid::scenario
