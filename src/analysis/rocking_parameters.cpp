#include "rigid/analysis/rocking_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "rigid/geometry/polygon2d.hpp"

namespace rigid::analysis {

// scenes, drives and the run are scenario's; this module builds on them
using namespace scenario;
namespace {

using P2 = geometry::Point2;

// The convex pieces of a body's contact shape (its shape for a plain block).
std::vector<const geometry::ConvexPolyhedron*> contact_pieces(const dynamics::BodyDef& b) {
  std::vector<const geometry::ConvexPolyhedron*> out;
  if (b.pieces.empty()) out.push_back(&b.shape);
  for (const auto& piece : b.pieces) out.push_back(&piece);
  return out;
}

// Signed distance of a world point outside a block's contact shape, by face planes (< 0 inside):
// the smallest over its pieces of the largest over each piece's faces.
double outside_distance(const dynamics::BodyDef& b, const Vec3& world_point) {
  const Vec3 q = b.orientation.conjugate() * (world_point - b.position);
  double least = 1e300;
  for (const auto* piece : contact_pieces(b)) {
    double most = -1e300;
    for (const auto& f : piece->faces) most = std::max(most, f.normal.dot(q) - f.offset);
    least = std::min(least, most);
  }
  return least;
}

// World positions of the vertices of a block's contact pieces.
std::vector<Vec3> contact_vertices(const dynamics::BodyDef& b) {
  const Mat3 r = b.orientation.toRotationMatrix();
  std::vector<Vec3> out;
  for (const auto* piece : contact_pieces(b)) {
    for (const auto& v : piece->vertices) out.push_back(r * v + b.position);
  }
  return out;
}

// Height of the support polygon's boundary at `offset` from the centroid's projection: linear
// along the hull edge that contains it (the corners' heights differ on an uneven pedestal).
double support_height(const std::vector<Vec3>& support, const std::vector<int>& hull, const Vec3& c, const P2& offset) {
  const P2 x = c.head<2>() + offset;
  double best_distance = std::numeric_limits<double>::infinity(), z = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec3& a = support[hull[i]];
    const Vec3& b = support[hull[(i + 1) % hull.size()]];
    const P2 edge = (b - a).head<2>();
    const double t = std::clamp((x - a.head<2>()).dot(edge) / std::max(edge.squaredNorm(), 1e-300), 0.0, 1.0);
    const double distance = (a.head<2>() + t * edge - x).norm();
    if (distance < best_distance) {
      best_distance = distance;
      z = a.z() + t * (b.z() - a.z());
    }
  }
  return z;
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
  for (const Vec3& w : contact_vertices(*block)) {
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
    for (const Vec3& w : contact_vertices(b)) {
      if (outside_distance(*block, w) <= contact_tolerance) support.push_back(w);
    }
  }
  std::vector<geometry::Point2> support_xy;
  for (const auto& w : support) support_xy.push_back(w.head<2>());
  const std::vector<int> hull = geometry::convex_hull_2d_indices(support_xy);
  if (hull.size() < 3) return std::nullopt;
  const Vec3 c = block->position;
  // inertia about the centroid in world axes
  const Mat3 inertia = r * block->shape.inertia.asDiagonal() * r.transpose();
  const double m = block->shape.mass;
  std::optional<RockingParameters> best;
  geometry::Polygon2 polygon;
  for (int i : hull) polygon.push_back((support[i] - c).head<2>());
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec3& a = support[hull[i]];
    const Vec3& b = support[hull[(i + 1) % hull.size()]];
    const P2 edge = (b - a).head<2>();
    const double length = edge.norm();
    if (length <= 0) continue;
    // counter-clockwise hull: the centroid is inside when it lies left of every edge
    const double d = geometry::cross(edge, (c - a).head<2>()) / length;
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
  if (!best) return best;
  best->support_polygon = polygon;
  for (int k = 0; k < kRockingAzimuths; ++k) {
    const double azimuth = 2.0 * kPi * k / kRockingAzimuths;
    const P2 lean(-std::cos(azimuth), -std::sin(azimuth));
    const double s = geometry::ray_to_boundary(polygon, P2::Zero(), lean);
    best->alpha_by_azimuth.push_back(std::atan2(s, c.z() - support_height(support, hull, c, s * lean)));
  }
  return best;
}

}  // namespace rigid::analysis
