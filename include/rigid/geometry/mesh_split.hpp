#pragma once
/// Splitting one scan of a rock and its pedestal into two closed meshes by a horizontal plane
/// (rigid model import --split-z). No I/O.
#include "rigid/geometry/polyhedron.hpp"

namespace rigid::geometry {

/// The two closed parts of a closed, outward mesh on either side of the plane z = level: every
/// facet is clipped by the plane, and each part is closed by a cap, the cross-section's polygons
/// triangulated by ear clipping. When a vertex lies within 1e-6 of the mesh's size of the plane,
/// the plane moves by twice that towards the mesh's middle, so the cut never runs through a vertex. Throws
/// std::invalid_argument when the plane misses the mesh or the cross-section has a hole (a loop
/// inside another: the rock's contact ring around a hollow; split such scans by hand).
struct SplitMesh {
  TriangleSoup above, below;
  double level = 0;  ///< the plane actually used (unit: m)
};
SplitMesh split_by_plane(const ClosedMesh& mesh, double level);

}  // namespace rigid::geometry
