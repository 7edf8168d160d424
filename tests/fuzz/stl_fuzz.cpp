// libFuzzer target: STL bytes -> read_stl_from_memory -> build_block, plus convex_hull of the
// parsed vertices. Only rigid::InputError and std::invalid_argument may escape the library;
// anything else (a crash, a sanitizer report, another exception) is a bug.
// With -DRIGID_FUZZ_STRICT_HULL the target also aborts when a hull of the parsed points fails
// make_closed_mesh or leaves an input point outside: a robustness probe of convex_hull, not a
// library contract.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "rigid/core/error.hpp"
#include "rigid/geometry/polyhedron.hpp"
#include "rigid/io/stl.hpp"

namespace {

// keeps each input fast: the convexity check is O(facets * vertices)
constexpr std::size_t kMaxFacets = 4096;

void build(const rigid::geometry::TriangleSoup& soup) {
  try {
    rigid::geometry::build_block(soup, 2650.0, {}, "fuzz.stl");
  } catch (const rigid::InputError&) {
  } catch (const std::invalid_argument&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  rigid::geometry::TriangleSoup soup;
  try {
    soup = rigid::io::read_stl_from_memory(bytes, "fuzz.stl");
  } catch (const rigid::InputError&) {
    return 0;
  }
  if (soup.size() > kMaxFacets) return 0;
  build(soup);

  std::vector<rigid::Vec3> points;
  for (const auto& t : soup) points.insert(points.end(), {t.a, t.b, t.c});
  rigid::geometry::TriangleSoup hull;
  try {
    hull = rigid::geometry::convex_hull(points);
  } catch (const std::invalid_argument&) {
    return 0;
  }
  build(hull);
#ifdef RIGID_FUZZ_STRICT_HULL
  bool bounded = true;
  for (const auto& p : points) bounded = bounded && p.cwiseAbs().maxCoeff() <= 1e9;
  if (bounded) {
    try {
      rigid::geometry::make_closed_mesh(hull, {}, "hull");
    } catch (const rigid::InputError&) {
      std::abort();
    }
    // every input point inside the hull, to the convexity tolerance (1e-6 of its size)
    rigid::Vec3 lo = points[0], hi = points[0];
    for (const auto& p : points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const double tol = 1e-6 * (hi - lo).norm();
    for (const auto& t : hull) {
      const rigid::Vec3 n = (t.b - t.a).cross(t.c - t.a).normalized();
      for (const auto& p : points) {
        if (n.dot(p - t.a) > tol) std::abort();
      }
    }
  }
#endif
  return 0;
}
