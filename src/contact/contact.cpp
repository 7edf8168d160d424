#include "rigid/contact/contact.hpp"

#include <algorithm>
#include <cmath>

namespace rigid::contact {
namespace {

constexpr int kMaxOverlapSteps = 8;

double support_value(const PlacedHull& h, const Vec3& dir, int& hint) {
  return dir.dot(h.world_vertices[support_vertex(h, dir, hint)] + h.offset);
}

// Overlap of A and B measured along n (A -> B): max_A n.x - min_B n.x.
double overlap_along(const PlacedHull& a, const PlacedHull& b, const Vec3& n, SupportHints& hints) {
  return support_value(a, n, hints.a) + support_value(b, -n, hints.b);
}

bool inside(const geometry::ConvexPolyhedron& shape, const Mat3& rotation, const Vec3& position,
            const Vec3& world_point, double tolerance) {
  const Vec3 p = rotation.transpose() * (world_point - position);
  for (const auto& f : shape.faces) {
    if (f.normal.dot(p) - f.offset > tolerance) return false;
  }
  return true;
}

// The face of `h` whose world normal is closest to `dir`, by a walk over the face adjacency
// from `hint` (temporal coherence makes it one or two moves).
int best_aligned_face(const PlacedHull& h, const Vec3& dir, int& hint) {
  const auto& faces = h.shape->faces;
  const Vec3 local = h.rotation.transpose() * dir;
  int current = hint < static_cast<int>(faces.size()) ? hint : 0;
  double best = faces[current].normal.dot(local);
  for (;;) {
    int next = current;
    for (int f : h.shape->face_neighbors[current]) {
      const double d = faces[f].normal.dot(local);
      if (d > best) {
        best = d;
        next = f;
      }
    }
    if (next == current) break;
    current = next;
  }
  hint = current;
  return current;
}

// Vertex-face, edge-face and face-face contacts have the face's normal as their common-plane
// normal. Snapping to it removes the ~1e-13 rad direction noise of the distance iteration, which
// an unstable contact (a rock balanced on a vertex) would otherwise amplify.
Vec3 snap_to_face(const PlacedHull& a, const PlacedHull& b, const Vec3& n, SupportHints& hints) {
  constexpr double kAligned = 1e-16;  // squared angle: 1e-8 rad
  const int fa = best_aligned_face(a, n, hints.face_a);
  const Vec3 na = a.rotation * a.shape->faces[fa].normal;
  if ((na - n).squaredNorm() < kAligned) return na;
  const int fb = best_aligned_face(b, -n, hints.face_b);
  const Vec3 nb = -(b.rotation * b.shape->faces[fb].normal);
  if ((nb - n).squaredNorm() < kAligned) return nb;
  return n;
}

}  // namespace

CommonPlane find_common_plane(const PlacedHull& a, const PlacedHull& b, const Vec3& previous_normal,
                              SupportHints& hints) {
  CommonPlane cp;
  LinkResult link = shortest_link(a, b, previous_normal, hints);
  if (!link.overlapping) {
    cp.normal = link.direction;
    cp.overlap = -link.distance;
    cp.point_a = link.point_a;
    cp.point_b = link.point_b;
    return cp;
  }
  // overlap step: separate virtually along the estimate, take the shortest link's direction
  const double margin = 1e-3 * (a.shape->bounding_radius + b.shape->bounding_radius);
  Vec3 n = previous_normal.normalized();
  PlacedHull shifted = b;
  double shift = 0;
  for (int iter = 0; iter < kMaxOverlapSteps; ++iter) {
    shift = overlap_along(a, b, n, hints) + margin;
    shifted.offset = b.offset + shift * n;
    link = shortest_link(a, shifted, n, hints);
    if (link.overlapping) break;  // round-off at a degenerate configuration: keep n
    const Vec3 next = link.direction;
    const bool settled = (next - n).squaredNorm() < 1e-20;
    n = next;
    if (settled) break;
  }
  n = snap_to_face(a, b, n, hints);
  cp.normal = n;
  cp.overlap = overlap_along(a, b, n, hints);
  if (!link.overlapping) {
    cp.point_a = link.point_a;
    cp.point_b = link.point_b - shift * n;
  } else {
    cp.point_a = a.position;
    cp.point_b = b.position;
  }
  return cp;
}

void collect_subcontacts(const PlacedHull& a, const PlacedHull& b, const CommonPlane& plane,
                         std::vector<SubcontactPoint>& out) {
  const Vec3& n = plane.normal;
  const double scale = a.shape->bounding_radius + b.shape->bounding_radius;
  const double tolerance = 1e-9 * scale;
  const std::size_t first = out.size();
  // supporting planes: B's lowest point and A's highest point along n
  double min_b = std::numeric_limits<double>::infinity();
  double max_a = -std::numeric_limits<double>::infinity();
  const std::size_t na = a.shape->vertices.size(), nb = b.shape->vertices.size();
  for (std::size_t i = 0; i < na; ++i) max_a = std::max(max_a, n.dot(a.world_vertices[i] + a.offset));
  for (std::size_t j = 0; j < nb; ++j) min_b = std::min(min_b, n.dot(b.world_vertices[j] + b.offset));

  for (std::size_t i = 0; i < na; ++i) {
    const Vec3 p = a.world_vertices[i] + a.offset;
    const double depth = n.dot(p) - min_b;
    if (depth <= 0) continue;
    if (!inside(*b.shape, b.rotation, b.position + b.offset, p, tolerance)) continue;
    out.push_back({subcontact_key(0, static_cast<int>(i)), p - 0.5 * depth * n, depth});
  }
  const std::size_t from_a = out.size();
  for (std::size_t j = 0; j < nb; ++j) {
    const Vec3 p = b.world_vertices[j] + b.offset;
    const double depth = max_a - n.dot(p);
    if (depth <= 0) continue;
    if (!inside(*a.shape, a.rotation, a.position + a.offset, p, tolerance)) continue;
    // a vertex of B sitting on a vertex of A is one contact, not two
    bool duplicate = false;
    for (std::size_t k = first; k < from_a; ++k) {
      duplicate |= (out[k].point - (p + 0.5 * depth * n)).squaredNorm() < 1e-6 * scale * scale;
    }
    if (duplicate) continue;
    out.push_back({subcontact_key(1, static_cast<int>(j)), p + 0.5 * depth * n, depth});
  }
  if (out.size() == first && plane.overlap > 0) {
    out.push_back({kEdgeSubcontact, 0.5 * (plane.point_a + plane.point_b), plane.overlap});
  }
}

Vec3 subcontact_force(const ContactLaw& law, const Vec3& normal, double overlap, double overlap_rate,
                      const Vec3& tangential_step, Vec3& shear_force, double& slip) {
  slip = 0;
  // normal: Hertz-type spring with hysteretic damping, never pulling (physics.md §3)
  const double elastic = law.normal_stiffness * overlap * std::sqrt(overlap);
  const double fn = std::max(0.0, elastic * (1.0 + law.damping * overlap_rate));
  // shear: carry the old force into the current tangent plane, keeping its magnitude
  const double old_magnitude = shear_force.norm();
  shear_force -= normal.dot(shear_force) * normal;
  const double projected = shear_force.norm();
  if (projected > 0) shear_force *= old_magnitude / projected;
  shear_force -= law.shear_stiffness * tangential_step;
  const double cap = law.friction * fn;
  const double magnitude = shear_force.norm();
  if (magnitude > cap) {
    slip = (magnitude - cap) / law.shear_stiffness;
    shear_force *= (magnitude > 0 ? cap / magnitude : 0.0);
  }
  return fn * normal + shear_force;
}

}  // namespace rigid::contact
