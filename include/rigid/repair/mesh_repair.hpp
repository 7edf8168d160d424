#pragma once
/// `rigid model import --repair`: a scan's common defects mended with CGAL's Polygon Mesh
/// Processing. A module of its own (over geometry) so that only the executable that imports scans
/// compiles and links CGAL; io, the tests and the sanitizer build do not.
#include <cstddef>
#include <string>

#include "rigid/geometry/polyhedron.hpp"

namespace rigid::repair {

/// What repair_scan changed in a scan (facets compared by their corners, in any order).
struct ScanRepair {
  std::size_t facets_before = 0, facets_after = 0;
  std::size_t facets_removed = 0;  ///< facets of the scan that are not in the repaired surface
  std::size_t facets_added = 0;    ///< facets of the repaired surface that are not in the scan
  std::size_t edges_stitched = 0;  ///< pairs of border edges at one place joined into one edge
  std::size_t holes_filled = 0;
  std::size_t holes_left = 0;  ///< holes of more than kMaxHoleEdges edges, left open
  bool self_intersections_left = false;
  double volume_before = 0;  ///< |signed volume| of the scan's facets (unit: m^3)
  double volume_after = 0;   ///< of the repaired surface (unit: m^3)
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

}  // namespace rigid::repair
