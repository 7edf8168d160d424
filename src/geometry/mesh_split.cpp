/// Cutting a closed mesh by a horizontal plane into two closed meshes.
#include "rigid/geometry/mesh_split.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

#include "rigid/geometry/polygon2d.hpp"

namespace rigid::geometry {
namespace {

using EdgeKey = std::pair<int, int>;

// Ear clipping of a simple polygon (counter-clockwise seen from +z); triangles as index triples.
std::vector<std::array<int, 3>> ear_clip(const std::vector<Point2>& polygon) {
  std::vector<int> left(polygon.size());
  for (std::size_t i = 0; i < left.size(); ++i) left[i] = int(i);
  std::vector<std::array<int, 3>> out;
  std::size_t guard = 0;
  while (left.size() > 3 && guard++ < 4 * polygon.size() * polygon.size()) {
    bool clipped = false;
    for (std::size_t k = 0; k < left.size() && !clipped; ++k) {
      const int a = left[(k + left.size() - 1) % left.size()], b = left[k], c = left[(k + 1) % left.size()];
      if (turn(polygon[a], polygon[b], polygon[c]) <= 0) continue;  // reflex or flat
      bool empty = true;
      for (int p : left) {
        if (p == a || p == b || p == c) continue;
        if (turn(polygon[a], polygon[b], polygon[p]) >= 0 && turn(polygon[b], polygon[c], polygon[p]) >= 0 &&
            turn(polygon[c], polygon[a], polygon[p]) >= 0) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      out.push_back({a, b, c});
      left.erase(left.begin() + long(k));
      clipped = true;
    }
    if (!clipped) throw std::invalid_argument("split_by_plane: the cross-section is not a simple polygon");
  }
  if (left.size() == 3) out.push_back({left[0], left[1], left[2]});
  return out;
}

double signed_area(const std::vector<Point2>& polygon) {
  double a = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) a += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * a;
}

bool inside(const std::vector<Point2>& polygon, const Point2& p) {
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Point2 &a = polygon[i], &b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

}  // namespace

SplitMesh split_by_plane(const ClosedMesh& mesh, double level) {
  const auto& v = mesh.vertices;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, size = 0;
  for (const Vec3& p : v) {
    lo = std::min(lo, p.z());
    hi = std::max(hi, p.z());
    size = std::max(size, (p - v.front()).norm());
  }
  // a cut closer than this to a vertex leaves facets thinner than make_closed_mesh accepts
  const double eps = 1e-6 * size;
  // keep the plane off every vertex, stepping towards the mesh's middle
  const double step = level > 0.5 * (lo + hi) ? -2 * eps : 2 * eps;
  for (int attempt = 0; attempt < 100; ++attempt) {
    bool clear = true;
    for (const Vec3& p : v) clear = clear && std::abs(p.z() - level) > eps;
    if (clear) break;
    level += step;
  }
  if (!(level > lo && level < hi)) throw std::invalid_argument("split_by_plane: the plane misses the mesh");
  SplitMesh out;
  out.level = level;
  // the crossing point of each cut edge, computed once from the edge's lower-numbered end so both
  // facets that share the edge get the same point bit for bit
  std::map<EdgeKey, Vec3> crossing;
  auto cut = [&](int a, int b) {
    const EdgeKey key{std::min(a, b), std::max(a, b)};
    auto it = crossing.find(key);
    if (it != crossing.end()) return it->second;
    const Vec3 &p = v[key.first], &q = v[key.second];
    Vec3 x = p + (level - p.z()) / (q.z() - p.z()) * (q - p);
    x.z() = level;
    return crossing.emplace(key, x).first->second;
  };
  // cross-section segments, oriented so that the part below sees them counter-clockwise from +z
  std::map<std::pair<double, double>, std::pair<Vec3, Vec3>> segment_from;  // keyed by start (x, y)
  for (const auto& t : mesh.triangles) {
    std::vector<Vec3> above, below;
    Vec3 enter{0, 0, 0}, leave{0, 0, 0};
    int crossings = 0;
    for (int i = 0; i < 3; ++i) {
      const int a = t[i], b = t[(i + 1) % 3];
      const bool a_up = v[a].z() > level, b_up = v[b].z() > level;
      (a_up ? above : below).push_back(v[a]);
      if (a_up != b_up) {
        const Vec3 x = cut(a, b);
        above.push_back(x);
        below.push_back(x);
        // walking the facet counter-clockwise (outward), the surface goes from below to above
        // at `leave` and back at `enter`
        if (!a_up)
          leave = x;
        else
          enter = x;
        ++crossings;
      }
    }
    auto fan = [](const std::vector<Vec3>& polygon, TriangleSoup& soup) {
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k) soup.push_back({polygon[0], polygon[k], polygon[k + 1]});
    };
    fan(above, out.above);
    fan(below, out.below);
    // the part below is closed by a cap facing +z whose boundary runs opposite to its surface's:
    // from where the surface rises (leave) to where it comes down (enter), reversed
    if (crossings == 2) segment_from[{enter.x(), enter.y()}] = {enter, leave};
  }
  // chain the segments into loops
  std::vector<std::vector<Point2>> loops;
  while (!segment_from.empty()) {
    std::vector<Point2> loop;
    auto it = segment_from.begin();
    const std::pair<double, double> start = it->first;
    std::pair<double, double> at = start;
    while (true) {
      auto s = segment_from.find(at);
      if (s == segment_from.end()) throw std::invalid_argument("split_by_plane: the cross-section does not close");
      loop.push_back(s->second.first.head<2>());
      at = {s->second.second.x(), s->second.second.y()};
      segment_from.erase(s);
      if (at == start) break;
    }
    loops.push_back(std::move(loop));
  }
  for (std::size_t i = 0; i < loops.size(); ++i) {
    for (std::size_t j = 0; j < loops.size(); ++j) {
      if (i != j && inside(loops[j], loops[i].front())) {
        throw std::invalid_argument("split_by_plane: the cross-section at z = " + std::to_string(level) +
                                    " has a hole (one loop inside another)");
      }
    }
  }
  for (auto& loop : loops) {
    if (signed_area(loop) < 0) std::reverse(loop.begin(), loop.end());
    for (const auto& t : ear_clip(loop)) {
      const Vec3 a(loop[t[0]].x(), loop[t[0]].y(), level), b(loop[t[1]].x(), loop[t[1]].y(), level),
          c(loop[t[2]].x(), loop[t[2]].y(), level);
      out.below.push_back({a, b, c});  // counter-clockwise from +z: the top of the part below
      out.above.push_back({a, c, b});  // the bottom of the part above
    }
  }
  return out;
}

}  // namespace rigid::geometry
