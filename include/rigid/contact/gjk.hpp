#pragma once
/// Shortest link between two convex polyhedra (Gilbert-Johnson-Keerthi distance on the Minkowski
/// difference). Its perpendicular bisector is a valid common plane (Nezami et al. 2006; physics.md
/// §4). Supports are found by hill-climbing over the vertex adjacency from the previous step's
/// support vertex, so a pair in persistent contact costs a few dot products.
#include <vector>

#include "rigid/core/types.hpp"
#include "rigid/geometry/polyhedron.hpp"

namespace rigid::contact {

/// A convex block placed in the world: its shape and the current world positions of its vertices,
/// shifted by `offset` (used by the overlap step to pull penetrating blocks apart virtually).
struct PlacedHull {
  const geometry::ConvexPolyhedron* shape = nullptr;
  const Vec3* world_vertices = nullptr;  ///< shape->vertices.size() points (unit: m)
  Vec3 offset{0, 0, 0};                  ///< added to every vertex (unit: m)
  Mat3 rotation = Mat3::Identity();      ///< body-to-world rotation of the block
  Vec3 position{0, 0, 0};                ///< world position of the body origin (centroid)
};

/// Index of a vertex maximising dir . x. `hint` is where the walk starts (warm start); it is
/// updated to the answer. Ties resolve to the vertex found first, so the result is deterministic.
int support_vertex(const PlacedHull& hull, const Vec3& dir, int& hint);

/// Outcome of a distance query.
struct LinkResult {
  bool overlapping = false;  ///< the hulls intersect (no separating link exists)
  double distance = 0;       ///< length of the shortest link (unit: m); 0 when overlapping
  Vec3 point_a{0, 0, 0};     ///< end of the link on A (unit: m)
  Vec3 point_b{0, 0, 0};     ///< end of the link on B (unit: m)
  Vec3 direction{0, 0, 1};   ///< unit vector from A to B along the link (valid when separated)
};

/// Warm-start hints for the support walks of one pair (kept per pair across steps).
struct SupportHints {
  int a = 0;       ///< support vertex of A
  int b = 0;       ///< support vertex of B
  int face_a = 0;  ///< face of A last aligned with the normal
  int face_b = 0;  ///< face of B last aligned with the normal
};

/// Shortest link between A and B. `guess` is any direction from A towards B (e.g. the last
/// common-plane normal); it only affects speed.
LinkResult shortest_link(const PlacedHull& a, const PlacedHull& b, const Vec3& guess, SupportHints& hints);

}  // namespace rigid::contact
