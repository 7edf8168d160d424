#pragma once
/// The contact shape of a scanned rock: its convex hull reduced to a vertex budget, or an
/// approximate convex decomposition of its (non-convex) mesh into pieces that one rigid body
/// carries (dynamics::BodyDef::pieces). The mass properties never come from these: they come
/// from the mesh itself (geometry::mass_properties). No I/O.
#include <span>
#include <vector>

#include "rigid/geometry/polyhedron.hpp"

namespace rigid::geometry {

/// One convex piece of a contact shape.
struct ConvexPiece {
  TriangleSoup soup;         ///< its hull, outward triangles
  std::size_t vertices = 0;  ///< hull vertices
  double volume = 0;         ///< unit: m^3
  /// Hausdorff distance between this piece and the full hull of the points it was reduced from:
  /// the reduced hull lies inside the full one, so it is the largest distance of a full-hull
  /// vertex outside the reduced hull (exact, not sampled; unit: m). 0 when nothing was dropped.
  double reduction = 0;
};

/// The convex hull of `points` reduced to at most `max_vertices` vertices (>= 4) by farthest-point
/// refinement: from an extreme simplex and the corners of the hull's lowest plane (a rock's flat
/// base: its support polygon is kept whole, budget permitting), the hull vertex farthest outside the current hull is
/// added until the budget is used or no vertex is farther out than `tolerance` (unit: m). Throws std::invalid_argument
/// for fewer than four points not in one plane, or a budget below 4.
ConvexPiece reduced_hull(std::span<const Vec3> points, int max_vertices, double tolerance = 0);

/// Settings of the approximate convex decomposition.
struct DecompositionOptions {
  /// Stop once the pieces' hulls exceed the mesh's volume by at most this fraction (unit: 1).
  /// (A scan's surface is rough at the centimetre scale: sp1_rock, 8.8 % below its hull, needs
  /// ~8 pieces for 5.6 %, ~100 for 2.5 %, ~220 for 1 %.)
  double concavity = 0.02;
  int max_pieces = 128;   ///< never more pieces than this
  int max_vertices = 48;  ///< vertex budget of each piece (reduced_hull)
  int positions = 7;      ///< candidate cut positions per axis and split
};

/// Outcome of a decomposition.
struct Decomposition {
  std::vector<ConvexPiece> pieces;
  double mesh_volume = 0;  ///< unit: m^3
  double hull_volume = 0;  ///< the pieces' full hulls, summed (disjoint cells; unit: m^3)
};

/// Approximate convex decomposition of a closed mesh by recursive plane cuts (V-HACD's cost, on
/// the exact geometry instead of voxels): the cells are boxes in the mesh's principal frame; a
/// part is the mesh inside its cell, whose hull is that of the part's clipped surface, its cut
/// edges and the cell corners inside the mesh. The part whose best cut (along a principal axis,
/// at one of `positions` places) most reduces the summed hull volume is cut next, until the hulls
/// exceed the mesh volume by at most `concavity`, or `max_pieces`. Every piece's hull lies in its
/// own cell, so the pieces never overlap and their union contains the mesh (before the vertex
/// budget, which cuts at most each piece's `reduction` off).
Decomposition convex_decomposition(const ClosedMesh& mesh, const DecompositionOptions& options);

/// Cuts a scanned rock's base flat `height` above its lowest point (unit: m): every vertex below
/// that level is raised to it. A photogrammetric "flat" base is rough at the millimetre scale, and
/// a rigid rock on a flat pedestal rests on the three lowest asperities around its centroid
/// (sp1_rock: one vertex 1.5 mm below the rest, 46 within 2 mm, 674 within 1 cm), so its support
/// polygon and toppling threshold would depend on noise; the study's analysts flattened such
/// surfaces by hand. Returns the number of vertices moved.
std::size_t cut_base_flat(ClosedMesh& mesh, double height);

/// Whether `point` lies inside the closed, outward-oriented mesh (generalized winding number
/// above one half; Jacobson et al. 2013).
bool mesh_contains(const ClosedMesh& mesh, const Vec3& point);

/// Two facets of the mesh that cross each other and share no vertex, found with a uniform grid,
/// or {-1, -1} when there is none.
std::array<int, 2> find_self_intersection(const ClosedMesh& mesh);

/// Signed volume of a closed triangle soup (unit: m^3; > 0 when outward).
double soup_volume(const TriangleSoup& soup);

}  // namespace rigid::geometry
