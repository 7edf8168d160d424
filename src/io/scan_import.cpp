// A scan as a checked closed mesh (rigid model import): read_mesh, then geometry's checks. Apart
// from the reader so that the readers' fuzz targets link the reader alone.
#include "rigid/core/error.hpp"
#include "rigid/geometry/contact_shape.hpp"
#include "rigid/io/mesh_import.hpp"

namespace rigid::io {

namespace {

// make_closed_mesh (any shape; an inward mesh is flipped) and the self-intersection search
geometry::ClosedMesh checked_scan(const geometry::TriangleSoup& soup, const std::string& path,
                                  std::vector<std::string>& warnings) {
  geometry::MeshOptions options;
  options.require_convex = false;
  geometry::ClosedMesh mesh = geometry::make_closed_mesh(soup, options, path);
  for (const auto& w : mesh.warnings) warnings.push_back(path + ": " + w);
  const auto crossing = geometry::find_self_intersection(mesh);
  if (crossing[0] >= 0) {
    throw InputError(path, 0,
                     "facet " + std::to_string(crossing[1]) + ": crosses facet " + std::to_string(crossing[0]) +
                         " (the surface intersects itself; --repair mends it)");
  }
  return mesh;
}

}  // namespace

geometry::ClosedMesh read_scan(const std::string& path, double scale, const Mat3& rotation,
                               std::vector<std::string>& warnings, const SoupMender& mend) {
  geometry::TriangleSoup soup = io::read_mesh(path);
  const std::vector<std::size_t> collapsed = geometry::drop_collapsed_facets(soup);
  if (!collapsed.empty()) {
    std::string list;
    for (std::size_t k = 0; k < collapsed.size() && k < 8; ++k) list += (k ? ", " : "") + std::to_string(collapsed[k]);
    warnings.push_back(path + ": dropped " + std::to_string(collapsed.size()) +
                       " facets with two corners at one point (no area): " + list +
                       (collapsed.size() > 8 ? ", ..." : ""));
  }
  if (soup.empty()) throw InputError(path, 0, "the file holds no facet with an area");
  for (auto& t : soup) {
    for (Vec3* p : {&t.a, &t.b, &t.c}) *p = scale * (rotation * *p);
  }
  if (!mend) return checked_scan(soup, path, warnings);
  soup = mend(soup);
  try {
    return checked_scan(soup, path, warnings);
  } catch (const InputError& e) {
    throw InputError(e.file(), e.line(),
                     e.problem() + " (left after --repair; facets numbered in the repaired surface)");
  }
}

}  // namespace rigid::io
