#pragma once
/// Scanned meshes (OBJ, PLY ascii/binary, STL ascii/binary) read with Debian's libassimp-dev into
/// a triangle soup, in the file's units and axes. The checks of what the soup is (closed,
/// manifold, oriented, finite) are geometry's (make_closed_mesh, find_self_intersection).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "rigid/geometry/polyhedron.hpp"

namespace rigid::io {

/// Reads every triangle of every mesh in the file, in file order (polygons are split into
/// triangles; facets are numbered in that order in later messages). Throws
/// rigid::InputError(path, 0, problem) for a missing or unreadable file, an unknown format, a file
/// with no triangles, or points and lines among its faces.
geometry::TriangleSoup read_mesh(const std::string& path);

/// read_mesh of content already in memory; `name` labels the errors and its extension (.obj,
/// .ply, .stl; any case) names the format. A PLY's structure is checked first (header, counts
/// against the size, every record present, corner indices in range): a malformed file is refused
/// as input, never handed to the reader to crash or allocate on.
geometry::TriangleSoup read_mesh_from_memory(std::string_view bytes, const std::string& name);

/// The rotation that turns the file's `up` axis ("x", "-x", "y", "-y", "z", "-z") into +z: the
/// field convention is x north, z up. Throws rigid::InputError for another name.
Mat3 up_rotation(const std::string& up);

/// What repair_scan changed in a scan (facets compared by their corners, in any order).
struct ScanRepair {
  std::size_t facets_before = 0, facets_after = 0;
  std::size_t facets_removed = 0;  ///< facets of the scan that are not in the repaired surface
  std::size_t facets_added = 0;    ///< facets of the repaired surface that are not in the scan
  std::size_t edges_stitched = 0;  ///< pairs of border edges at one place joined into one edge
  std::size_t holes_filled = 0;
  std::size_t holes_left = 0;      ///< holes of more than kMaxHoleEdges edges, left open
  bool self_intersections_left = false;
  double volume_before = 0;        ///< |signed volume| of the scan's facets (unit: m^3)
  double volume_after = 0;         ///< of the repaired surface (unit: m^3)
};

/// Holes with at most this many border edges are filled by repair_scan: a scanner's gap, not a
/// missing part of the rock (unit: 1).
inline constexpr std::size_t kMaxHoleEdges = 64;

/// `rigid model import --repair` (CGAL Polygon Mesh Processing): merges coincident corners and
/// drops degenerate or repeated facets, orients the facets alike, stitches seams, cuts out facets
/// that cross others and closes the gap, and fills holes of up to kMaxHoleEdges edges. Returns the
/// repaired soup and fills `report`; what it could not mend is left for the checks to name.
/// Throws rigid::InputError(name, ...) when nothing is left.
geometry::TriangleSoup repair_scan(const geometry::TriangleSoup& soup, ScanRepair& report, const std::string& name);

/// A scan as a checked closed mesh in metres, z up: read_mesh, facets with two corners at one
/// point dropped (a scanner's duplicated vertex), coordinates times `scale` after `rotation`, then
/// make_closed_mesh (any shape; an inward mesh is flipped) and a self-intersection search.
/// `warnings` receives what was repaired ("PATH: what"). Throws rigid::InputError naming the
/// file and the first problem (facet numbers are the file's).
/// With `repair` set, repair_scan runs before the checks and fills it.
geometry::ClosedMesh read_scan(const std::string& path, double scale, const Mat3& rotation,
                               std::vector<std::string>& warnings, ScanRepair* repair = nullptr);

}  // namespace rigid::io
