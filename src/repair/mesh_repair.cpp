// `rigid model import --repair`: a scan's common defects (a fold where the surface crosses
// itself, a small hole, an unstitched seam) mended with CGAL's Polygon Mesh Processing, a
// maintained library of exactly these operations (Debian libcgal-dev, header-only over GMP and
// MPFR), rather than hand-written mesh surgery.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <iterator>
#include <map>
#include <set>
#include <vector>

#include "rigid/core/error.hpp"
#include "rigid/repair/mesh_repair.hpp"

namespace rigid::repair {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

// A facet by its corners, whatever their order: what the report compares before and after.
using FacetKey = std::array<std::array<double, 3>, 3>;

FacetKey key_of(const Vec3& a, const Vec3& b, const Vec3& c) {
  FacetKey k{{{a.x(), a.y(), a.z()}, {b.x(), b.y(), b.z()}, {c.x(), c.y(), c.z()}}};
  std::sort(k.begin(), k.end());
  return k;
}

// The signed volume the facets enclose (unit: m^3; an open surface's is the closed one's up to
// the missing patch).
double soup_volume(const geometry::TriangleSoup& soup) {
  double six = 0;
  for (const auto& t : soup) six += t.a.dot(t.b.cross(t.c));
  return six / 6;
}

geometry::TriangleSoup soup_of(const Mesh& mesh) {
  geometry::TriangleSoup soup;
  soup.reserve(mesh.number_of_faces());
  for (const auto f : mesh.faces()) {
    std::vector<Vec3> corners;
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      const Point& p = mesh.point(v);
      corners.emplace_back(p.x(), p.y(), p.z());
    }
    // hole filling and the self-intersection repair make triangles; split anything else as a fan
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) soup.push_back({corners[0], corners[k], corners[k + 1]});
  }
  return soup;
}

std::size_t cycle_length(const Mesh& mesh, Mesh::Halfedge_index h) {
  std::size_t n = 0;
  for (const auto e : CGAL::halfedges_around_face(h, mesh)) {
    (void)e;
    ++n;
  }
  return n;
}

}  // namespace

geometry::TriangleSoup repair_scan(const geometry::TriangleSoup& soup, ScanRepair& report, const std::string& name) {
  report = ScanRepair{};
  report.facets_before = soup.size();
  report.volume_before = std::abs(soup_volume(soup));

  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> polygons;
  points.reserve(3 * soup.size());
  polygons.reserve(soup.size());
  for (const auto& t : soup) {
    const std::size_t first = points.size();
    for (const Vec3* p : {&t.a, &t.b, &t.c}) points.emplace_back(p->x(), p->y(), p->z());
    polygons.push_back({first, first + 1, first + 2});
  }
  // one point per position, degenerate and repeated facets out; then one orientation throughout
  PMP::repair_polygon_soup(points, polygons);
  PMP::orient_polygon_soup(points, polygons);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  report.edges_stitched = PMP::stitch_borders(mesh);
  // facets that cross others are cut out and the gap closed again
  report.self_intersections_left = !PMP::experimental::remove_self_intersections(mesh);
  // small holes (up to kMaxHoleEdges edges around) are closed with triangles between their
  // border vertices; a larger one is a missing part of the rock, not a scanning defect
  std::vector<Mesh::Halfedge_index> borders;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
  for (const auto h : borders) {
    if (cycle_length(mesh, h) > kMaxHoleEdges) {
      ++report.holes_left;
      continue;
    }
    std::vector<Mesh::Face_index> added;
    PMP::triangulate_hole(mesh, h, std::back_inserter(added));
    if (added.empty())
      ++report.holes_left;
    else
      ++report.holes_filled;
  }
  mesh.collect_garbage();
  geometry::TriangleSoup repaired = soup_of(mesh);
  if (repaired.empty()) throw InputError(name, 0, "--repair: nothing is left of the surface");

  std::set<FacetKey> before, after;
  for (const auto& t : soup) before.insert(key_of(t.a, t.b, t.c));
  for (const auto& t : repaired) after.insert(key_of(t.a, t.b, t.c));
  for (const auto& k : before) report.facets_removed += after.count(k) == 0;
  for (const auto& k : after) report.facets_added += before.count(k) == 0;
  report.facets_after = repaired.size();
  report.volume_after = std::abs(soup_volume(repaired));
  return repaired;
}

}  // namespace rigid::repair
