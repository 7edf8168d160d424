#pragma once
/// Convex polyhedral blocks built from triangle meshes: welding, adjacency, checks, mass
/// properties (physics.md §7). No I/O: readers live in rigid::io and hand over a TriangleSoup.
#include <array>
#include <string>
#include <vector>

#include "rigid/core/types.hpp"

namespace rigid::geometry {

/// One facet as read from a mesh file, vertices in file order (unit: m).
struct Triangle {
  Vec3 a, b, c;
};
using TriangleSoup = std::vector<Triangle>;

/// Tolerances for turning a triangle soup into a checked convex block.
struct MeshOptions {
  /// Vertices closer than this fraction of the bounding-box diagonal are welded (unit: 1).
  double weld_tolerance = 1e-9;
  /// A vertex may lie at most this fraction of the bounding-box diagonal outside any facet plane
  /// before the mesh is called non-convex (unit: 1). Photogrammetry hulls are convex only to
  /// rounding; real concavities are far larger.
  double convexity_tolerance = 1e-6;
  /// Adjacent triangles whose normals differ by less than this angle are merged into one planar
  /// face for contact (unit: rad).
  double coplanar_angle = 1e-6;
  /// Refuse a mesh that is not convex (a block's contact shape). false: any closed, manifold,
  /// oriented mesh is accepted (a scanned rock, whose mass properties come from its true surface).
  bool require_convex = true;
};

/// A closed, consistently outward-oriented triangle mesh with welded vertices, in the file's frame.
struct ClosedMesh {
  std::vector<Vec3> vertices;                 ///< unit: m
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
  std::vector<std::string> warnings;          ///< e.g. "orientation was inward; flipped"
};

/// Welds vertices, builds adjacency and checks the mesh: non-empty, no degenerate (zero-area)
/// triangles, closed (every edge shared by exactly two triangles), consistently oriented,
/// outward (fixes an inward mesh and records a warning), and, when options.require_convex, a
/// topological sphere that is convex within tolerance.
/// Throws rigid::InputError(source, 0, "facet N: <problem>") when a check fails.
ClosedMesh make_closed_mesh(const TriangleSoup& soup, const MeshOptions& options, const std::string& source);

/// Removes the facets that have two corners at exactly the same point (a scanner's duplicated
/// vertex: the facet has no area, and welding would make it a degenerate triangle) and returns
/// their indices in the soup as given.
std::vector<std::size_t> drop_collapsed_facets(TriangleSoup& soup);

/// Triangle adjacency of a mesh: entry [t][i] is the triangle across the edge from vertex i to
/// vertex (i+1)%3 of triangle t, or -1 when that edge is not shared by exactly two triangles
/// running it in opposite directions. Throws std::invalid_argument for an out-of-range index.
std::vector<std::array<int, 3>> triangle_neighbors(const ClosedMesh& mesh);

/// Volume, centroid and inertia of a homogeneous closed mesh (Blow & Binstock; physics.md §7).
struct MassProperties {
  double volume = 0;                       ///< unit: m^3
  double mass = 0;                         ///< unit: kg
  Vec3 centroid{0, 0, 0};                  ///< in the mesh frame (unit: m)
  Mat3 inertia = Mat3::Zero();             ///< about the centroid, mesh-frame axes (unit: kg m^2)
  Vec3 principal_moments{0, 0, 0};         ///< ascending (unit: kg m^2)
  Mat3 principal_axes = Mat3::Identity();  ///< columns: principal axes in the mesh frame, det = +1
};

/// Throws std::invalid_argument when density is not positive or finite.
MassProperties mass_properties(const ClosedMesh& mesh, double density);

/// A planar face of a convex block: merged coplanar triangles, vertices counter-clockwise seen
/// from outside.
struct Face {
  Vec3 normal;                ///< outward unit normal (body frame)
  double offset = 0;          ///< plane: normal . x = offset (unit: m)
  std::vector<int> vertices;  ///< polygon loop, CCW from outside
};

/// An edge between two faces (a feature edge: edges inside a merged planar face are dropped).
struct Edge {
  int v0 = 0, v1 = 0;  ///< vertex indices
  int face_left = 0;   ///< face on which v0->v1 runs counter-clockwise
  int face_right = 0;  ///< the other face
};

/// A convex block in its body frame: origin at the centroid, axes along the principal axes of
/// inertia, so the rotational dynamics can use a diagonal inertia tensor.
struct ConvexPolyhedron {
  std::vector<Vec3> vertices;  ///< body frame (unit: m), never moved after build
  std::vector<Face> faces;
  std::vector<Edge> edges;
  std::vector<std::vector<int>> vertex_neighbors;  ///< vertex -> adjacent vertices (feature edges)
  std::vector<std::vector<int>> face_neighbors;    ///< face -> faces sharing a feature edge
  double volume = 0;                               ///< unit: m^3
  double mass = 0;                                 ///< unit: kg
  Vec3 inertia{0, 0, 0};                           ///< principal moments, body frame (unit: kg m^2)
  double bounding_radius = 0;                      ///< max |vertex - bounding_centre| (unit: m)
  /// Centre of the bounding sphere in the body frame (unit: m): the origin for a whole block, the
  /// piece's own middle for a piece of a compound body (make_piece).
  Vec3 bounding_centre{0, 0, 0};
  /// Pose of the body frame in the mesh frame: x_mesh = rotation * x_body + translation.
  Quat rotation = Quat::Identity();
  Vec3 translation{0, 0, 0};
};

/// Builds the body-frame block from a checked mesh and its mass properties.
ConvexPolyhedron make_polyhedron(const ClosedMesh& mesh, const MassProperties& props, const MeshOptions& options);

/// Convenience: soup -> checked mesh -> mass properties -> body-frame block.
ConvexPolyhedron build_block(const TriangleSoup& soup, double density, const MeshOptions& options,
                             const std::string& source, std::vector<std::string>* warnings = nullptr);

/// A convex piece of a compound body, in that body's frame (`body` gives the frame: its rotation
/// and translation map body to mesh coordinates): `convex_mesh` is in mesh coordinates, like the
/// body's own mesh. The piece keeps the body's origin and axes (its rotation and translation are
/// the body's), has no mass of its own (volume only), and a bounding sphere about its own middle.
ConvexPolyhedron make_piece(const ClosedMesh& convex_mesh, const ConvexPolyhedron& body, const MeshOptions& options);

/// A rigid body whose mass properties come from a closed mesh of any shape (`mesh`, e.g. a
/// scanned rock; never its hull) and whose contact shape is a set of convex pieces in the same
/// coordinates (a convex hull or a convex decomposition of the mesh).
struct CompoundBody {
  /// Mass properties of `mesh`; the outline (the convex hull of every piece's vertices) as
  /// geometry, in the body frame of the mesh's centroid and principal axes.
  ConvexPolyhedron shape;
  std::vector<ConvexPolyhedron> pieces;  ///< contact pieces, in shape's body frame
};

/// Moves a block's centre of mass by `offset` (body frame, unit: m) and its body frame with it:
/// vertices, face planes and pieces are re-expressed about the new origin, `translation` keeps the
/// mesh where it was. The principal moments and axes stay those of the uniform block about its
/// centroid (an offset moves the mass centre, not the spread of the mass about it). The bounding
/// sphere of the block is re-centred on the new origin; pieces keep their own. Throws
/// std::invalid_argument when the new centre lies outside the block (its outline for a compound).
void offset_mass_centre(ConvexPolyhedron& shape, std::vector<ConvexPolyhedron>& pieces, const Vec3& offset);

/// Builds a CompoundBody. Throws std::invalid_argument for an empty piece list or bad density.
CompoundBody build_compound(const ClosedMesh& mesh, const std::vector<ClosedMesh>& convex_pieces, double density,
                            const MeshOptions& options);

/// Triangle soup of a convex hull of points (quickhull-style incremental hull), for building
/// synthetic models and tests. Throws std::invalid_argument for fewer than 4 non-coplanar points.
TriangleSoup convex_hull(const std::vector<Vec3>& points);

/// Axis-aligned box [lo, hi] as a triangle soup (12 outward triangles).
TriangleSoup box_soup(const Vec3& lo, const Vec3& hi);

}  // namespace rigid::geometry
