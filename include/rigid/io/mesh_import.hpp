#pragma once
/// Scanned meshes (OBJ, PLY ascii/binary, STL ascii/binary) read with Debian's libassimp-dev into
/// a triangle soup, in the file's units and axes. The checks of what the soup is (closed,
/// manifold, oriented, finite) are geometry's (make_closed_mesh, find_self_intersection).
#include <cstddef>
#include <functional>
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

/// A scan as a checked closed mesh in metres, z up: read_mesh, facets with two corners at one
/// point dropped (a scanner's duplicated vertex), coordinates times `scale` after `rotation`, then
/// make_closed_mesh (any shape; an inward mesh is flipped) and a self-intersection search.
/// `warnings` receives what was repaired ("PATH: what"). Throws rigid::InputError naming the
/// file and the first problem (facet numbers are the file's).
/// With `mend` set, it runs on the scaled soup before the checks (`rigid model import --repair`
/// passes repair::repair_scan, kept out of io so that what links io does not compile CGAL).
using SoupMender = std::function<geometry::TriangleSoup(const geometry::TriangleSoup&)>;
geometry::ClosedMesh read_scan(const std::string& path, double scale, const Mat3& rotation,
                               std::vector<std::string>& warnings, const SoupMender& mend = {});

}  // namespace rigid::io
