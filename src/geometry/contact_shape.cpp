/// Contact shapes of scanned rocks: reduced hulls and the approximate convex decomposition.
#include "rigid/geometry/contact_shape.hpp"

#include "rigid/geometry/polygon2d.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <stdexcept>

namespace rigid::geometry {
namespace {

struct Plane {
  Vec3 normal;
  double offset;
};

std::vector<Plane> planes_of(const TriangleSoup& hull) {
  std::vector<Plane> out;
  out.reserve(hull.size());
  for (const auto& t : hull) {
    const Vec3 n = (t.b - t.a).cross(t.c - t.a);
    const double len = n.norm();
    if (len > 0) out.push_back({n / len, n.dot(t.a) / len});
  }
  return out;
}

// How far a point lies outside a convex hull given by its facet planes (<= 0 inside).
double outside(const std::vector<Plane>& planes, const Vec3& p) {
  double most = -std::numeric_limits<double>::infinity();
  for (const auto& f : planes) most = std::max(most, f.normal.dot(p) - f.offset);
  return most;
}

// The distinct points of a hull soup, sorted.
std::vector<Vec3> hull_points(const TriangleSoup& hull) {
  std::vector<Vec3> out;
  out.reserve(3 * hull.size());
  for (const auto& t : hull) {
    out.push_back(t.a);
    out.push_back(t.b);
    out.push_back(t.c);
  }
  auto less = [](const Vec3& a, const Vec3& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() != b.y() ? a.y() < b.y() : a.z() < b.z();
  };
  std::sort(out.begin(), out.end(), less);
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Indices of four points spanning a tetrahedron of large volume: extremes along x, then the
// farthest from their line, then from their plane.
std::vector<int> extreme_simplex(const std::vector<Vec3>& p) {
  int a = 0;
  for (int i = 0; i < int(p.size()); ++i) {
    if (p[i].x() < p[a].x()) a = i;
  }
  auto farthest = [&](auto&& distance) {
    int best = 0;
    double most = -1;
    for (int i = 0; i < int(p.size()); ++i) {
      const double d = distance(p[i]);
      if (d > most) {
        most = d;
        best = i;
      }
    }
    return best;
  };
  const int b = farthest([&](const Vec3& x) { return (x - p[a]).squaredNorm(); });
  const Vec3 line = (p[b] - p[a]).normalized();
  const int c = farthest([&](const Vec3& x) { return (x - p[a]).cross(line).squaredNorm(); });
  const Vec3 normal = (p[b] - p[a]).cross(p[c] - p[a]).normalized();
  const int d = farthest([&](const Vec3& x) { return std::abs((x - p[a]).dot(normal)); });
  return {a, b, c, d};
}

Vec3 orient_cross(const Vec3& a, const Vec3& b, const Vec3& c) { return (b - a).cross(c - a); }

// Sutherland-Hodgman: the part of a convex polygon with sign * (x[axis] - s) <= 0.
void clip(const std::vector<Vec3>& polygon, int axis, double s, double sign, std::vector<Vec3>& out) {
  out.clear();
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = polygon[i];
    const Vec3& q = polygon[(i + 1) % n];
    const double dp = sign * (p[axis] - s), dq = sign * (q[axis] - s);
    if (dp <= 0) out.push_back(p);
    if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) {
      Vec3 x = p + (dp / (dp - dq)) * (q - p);
      x[axis] = s;  // exactly on the cut, so both sides share the point
      out.push_back(x);
    }
  }
}

// A part of the mesh: its surface inside the cell (convex polygons, principal-frame coordinates)
// and the cell, a box.
struct Part {
  std::vector<std::vector<Vec3>> polygons;
  Vec3 lo, hi;
  double hull_volume = 0;
  // the best cut found for it
  int axis = -1;
  double position = 0;
  double gain = 0;
};

double hull_volume_of(std::vector<Vec3> points) {
  if (points.size() < 4) return 0;
  try {
    return soup_volume(convex_hull(points));
  } catch (const std::invalid_argument&) {
    return 0;  // flat: no volume
  }
}

// The distinct corners of the part's polygons (neighbouring polygons share theirs).
std::vector<Vec3> part_points(const Part& part) {
  std::vector<Vec3> points;
  for (const auto& polygon : part.polygons) points.insert(points.end(), polygon.begin(), polygon.end());
  auto less = [](const Vec3& a, const Vec3& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() != b.y() ? a.y() < b.y() : a.z() < b.z();
  };
  std::sort(points.begin(), points.end(), less);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

// The two parts of `part` on either side of the cut x[axis] = s.
std::pair<Part, Part> cut(const Part& part, int axis, double s) {
  Part below, above;
  below.lo = above.lo = part.lo;
  below.hi = above.hi = part.hi;
  below.hi[axis] = above.lo[axis] = s;
  std::vector<Vec3> piece;
  for (const auto& polygon : part.polygons) {
    clip(polygon, axis, s, 1.0, piece);
    if (piece.size() >= 3) below.polygons.push_back(piece);
    clip(polygon, axis, s, -1.0, piece);
    if (piece.size() >= 3) above.polygons.push_back(piece);
  }
  return {std::move(below), std::move(above)};
}

// The points whose hull is the part's: its surface and the cell corners inside the mesh (where
// cuts meet inside the rock, the part's hull has a corner no surface point gives).
std::vector<Vec3> hull_input(const Part& part, const ClosedMesh& mesh_in_frame) {
  std::vector<Vec3> points = part_points(part);
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner((k & 1) ? part.hi.x() : part.lo.x(), (k & 2) ? part.hi.y() : part.lo.y(),
                      (k & 4) ? part.hi.z() : part.lo.z());
    if (mesh_contains(mesh_in_frame, corner)) points.push_back(corner);
  }
  return points;
}

// Finds the part's best cut: the largest drop of the summed hull volume over the candidates.
void find_best_cut(Part& part, int positions) {
  part.axis = -1;
  part.gain = 0;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& polygon : part.polygons) {
    for (const Vec3& p : polygon) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (int j = 1; j <= positions; ++j) {
      const double s = lo[axis] + (hi[axis] - lo[axis]) * j / (positions + 1);
      const auto [below, above] = cut(part, axis, s);
      const double gain = part.hull_volume - hull_volume_of(part_points(below)) - hull_volume_of(part_points(above));
      if (gain > part.gain) {
        part.gain = gain;
        part.axis = axis;
        part.position = s;
      }
    }
  }
}

}  // namespace

double soup_volume(const TriangleSoup& soup) {
  double six = 0;
  for (const auto& t : soup) six += t.a.dot(t.b.cross(t.c));
  return six / 6.0;
}

ConvexPiece reduced_hull(std::span<const Vec3> points, int max_vertices, double tolerance) {
  if (max_vertices < 4) throw std::invalid_argument("reduced_hull: the vertex budget must be at least 4");
  ConvexPiece piece;
  if (std::size_t(max_vertices) >= points.size()) {
    piece.soup = convex_hull(std::vector<Vec3>(points.begin(), points.end()));
    piece.vertices = hull_points(piece.soup).size();
    piece.volume = soup_volume(piece.soup);
    return piece;
  }
  // no full hull first (an incremental hull of a million scan points, most of them on it, is the
  // slow part): the greedy runs over all points; the farthest point outside is always a corner of
  // the full hull, and when none is left outside, the hull of the kept points is the full hull
  const std::vector<Vec3> corners(points.begin(), points.end());
  std::vector<Vec3> kept;
  for (int i : extreme_simplex(corners)) kept.push_back(corners[i]);
  // the base first: the corners of the hull's lowest plane are the support polygon, which decides
  // when a rock topples; the farthest-point rule alone drops them (a few mm of Hausdorff distance,
  // centimetres of support: sp1_rock's weakest direction fell from 0.19 g to 0.07 g)
  double lowest = std::numeric_limits<double>::infinity(), size = 0;
  for (const Vec3& c : corners) {
    lowest = std::min(lowest, c.z());
    size = std::max(size, (c - corners.front()).norm());
  }
  std::vector<Point2> base;
  std::vector<const Vec3*> base_corners;
  for (const Vec3& c : corners) {
    if (c.z() <= lowest + 1e-9 * size) {
      base.push_back(c.head<2>());
      base_corners.push_back(&c);
    }
  }
  if (base.size() >= 3) {
    for (int i : convex_hull_2d_indices(base)) {
      if (int(kept.size()) >= max_vertices) break;
      if (std::find(kept.begin(), kept.end(), *base_corners[i]) == kept.end()) kept.push_back(*base_corners[i]);
    }
  }
  TriangleSoup hull = convex_hull(kept);
  // lazy greedy: a corner's distance outside the hull only shrinks as the hull grows, so a stale
  // distance is an upper bound, and the corner on top of the heap is the farthest once its
  // distance, brought up to date, still tops the next one (a few updates per step, not all)
  std::vector<Plane> planes = planes_of(hull);
  std::priority_queue<std::pair<double, int>> queue;
  for (int i = 0; i < int(corners.size()); ++i) {
    const double d = outside(planes, corners[i]);
    if (d > 0) queue.push({d, i});
  }
  while (!queue.empty()) {
    auto [bound, i] = queue.top();
    queue.pop();
    const double d = outside(planes, corners[i]);
    if (d <= 0) continue;
    if (!queue.empty() && d < queue.top().first) {
      queue.push({d, i});
      continue;
    }
    // corners[i] is the farthest outside: the Hausdorff distance of the hull as it stands
    piece.reduction = d;
    if (d <= tolerance || int(kept.size()) >= max_vertices) break;
    kept.push_back(corners[i]);
    hull = convex_hull(kept);
    planes = planes_of(hull);
    piece.reduction = 0;
  }
  piece.soup = hull;
  piece.vertices = hull_points(hull).size();
  piece.volume = soup_volume(hull);
  return piece;
}

Decomposition convex_decomposition(const ClosedMesh& mesh, const DecompositionOptions& options) {
  if (!(options.concavity >= 0) || options.max_pieces < 1 || options.max_vertices < 4 || options.positions < 1) {
    throw std::invalid_argument(
        "convex_decomposition: concavity >= 0, max_pieces >= 1, max_vertices >= 4, positions >= 1");
  }
  // the principal frame: cells are boxes along the rock's own axes
  const MassProperties props = mass_properties(mesh, 1.0);
  const Mat3& axes = props.principal_axes;
  ClosedMesh local = mesh;
  for (Vec3& v : local.vertices) v = axes.transpose() * (v - props.centroid);
  Part whole;
  whole.lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  whole.hi = -whole.lo;
  for (const auto& t : local.triangles) {
    whole.polygons.push_back({local.vertices[t[0]], local.vertices[t[1]], local.vertices[t[2]]});
  }
  for (const Vec3& v : local.vertices) {
    whole.lo = whole.lo.cwiseMin(v);
    whole.hi = whole.hi.cwiseMax(v);
  }
  whole.hull_volume = hull_volume_of(part_points(whole));
  std::vector<Part> parts{std::move(whole)};
  double total = parts[0].hull_volume;
  const double target = (1 + options.concavity) * props.volume;
  find_best_cut(parts[0], options.positions);
  while (total > target && int(parts.size()) < options.max_pieces) {
    const std::size_t best = std::size_t(
        std::max_element(parts.begin(), parts.end(), [](const Part& a, const Part& b) { return a.gain < b.gain; }) -
        parts.begin());
    if (parts[best].axis < 0 || parts[best].gain <= 1e-9 * props.volume) break;
    auto [below, above] = cut(parts[best], parts[best].axis, parts[best].position);
    total -= parts[best].hull_volume;
    parts[best] = std::move(below);
    parts.push_back(std::move(above));
    for (Part* p : {&parts[best], &parts.back()}) {
      p->hull_volume = hull_volume_of(hull_input(*p, local));
      total += p->hull_volume;
      find_best_cut(*p, options.positions);
    }
  }
  Decomposition out;
  out.mesh_volume = props.volume;
  for (const Part& part : parts) {
    std::vector<Vec3> points = hull_input(part, local);
    if (hull_volume_of(points) <= 1e-9 * props.volume) continue;  // a sliver with no room inside
    for (Vec3& p : points) p = axes * p + props.centroid;
    ConvexPiece piece = reduced_hull(points, options.max_vertices);
    out.hull_volume += hull_volume_of(points);
    out.pieces.push_back(std::move(piece));
  }
  return out;
}

std::size_t cut_base_flat(ClosedMesh& mesh, double height) {
  if (!(height >= 0)) throw std::invalid_argument("cut_base_flat: height must be non-negative");
  if (height == 0 || mesh.vertices.empty()) return 0;
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec3& v : mesh.vertices) lowest = std::min(lowest, v.z());
  const double level = lowest + height;
  std::size_t moved = 0;
  for (Vec3& v : mesh.vertices) {
    if (v.z() < level) {
      v.z() = level;
      ++moved;
    }
  }
  return moved;
}

bool mesh_contains(const ClosedMesh& mesh, const Vec3& point) {
  double solid_angle = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]] - point, b = mesh.vertices[t[1]] - point, c = mesh.vertices[t[2]] - point;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    // Van Oosterom & Strackee (1983): the solid angle of a triangle seen from the origin
    solid_angle += 2 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return solid_angle > 2 * kPi;  // winding number above 1/2
}

std::array<int, 2> find_self_intersection(const ClosedMesh& mesh) {
  const auto& v = mesh.vertices;
  const auto& tris = mesh.triangles;
  const std::size_t n = tris.size();
  if (n < 2) return {-1, -1};
  Vec3 lo = v.front(), hi = lo;
  for (const Vec3& p : v) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // cells twice a facet's mean size: a closed mesh's facets lie on its surface, so a cell sized
  // from the box's volume per facet holds a row of ~n^(1/3) of them and the pair test per cell
  // grows with its square; at the facet scale a cell holds a handful
  const Vec3 extent = (hi - lo).cwiseMax(Vec3::Constant(1e-12));
  std::vector<std::array<Vec3, 2>> boxes(n);  // each facet's bounding box: low and high corner
  double mean_size = 0;
  for (std::size_t t = 0; t < n; ++t) {
    const Vec3 &a = v[tris[t][0]], &b = v[tris[t][1]], &c = v[tris[t][2]];
    boxes[t] = {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
    mean_size += (boxes[t][1] - boxes[t][0]).maxCoeff();
  }
  mean_size /= double(n);
  double cell = std::max(2.0 * mean_size, 1e-9 * extent.maxCoeff());
  Eigen::Vector3i dims;
  double covered = 0;
  auto index = [&](const Vec3& p, int k) {
    return std::clamp(int((p[k] - lo[k]) / extent[k] * dims[k]), 0, dims[k] - 1);
  };
  // a few large facets among many small ones would each cover a great many small cells: coarsen
  // until the facets cover at most 16 n cells in all
  for (;;) {
    dims = ((extent / cell).array().floor().cast<int>() + 1).cwiseMin(1024).matrix();
    covered = 0;
    for (const auto& [tlo, thi] : boxes) {
      covered += double(index(thi, 0) - index(tlo, 0) + 1) * double(index(thi, 1) - index(tlo, 1) + 1) *
                 double(index(thi, 2) - index(tlo, 2) + 1);
    }
    if (covered <= 16.0 * double(n) || dims.maxCoeff() == 1) break;
    cell *= 2;
  }
  std::vector<std::pair<std::uint64_t, int>> entries;
  entries.reserve(static_cast<std::size_t>(covered));
  for (std::size_t t = 0; t < n; ++t) {
    const auto& [tlo, thi] = boxes[t];
    for (int x = index(tlo, 0); x <= index(thi, 0); ++x) {
      for (int y = index(tlo, 1); y <= index(thi, 1); ++y) {
        for (int z = index(tlo, 2); z <= index(thi, 2); ++z) {
          entries.push_back({(std::uint64_t(x) << 40) | (std::uint64_t(y) << 20) | std::uint64_t(z), int(t)});
        }
      }
    }
  }
  std::sort(entries.begin(), entries.end());
  const double eps = 1e-12 * extent.norm() * extent.norm() * extent.norm();
  auto orient = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return orient_cross(a, b, c).dot(d - a);
  };
  // segment p-q crosses triangle abc properly (no touching)
  auto crosses = [&](const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
    const double sp = orient(a, b, c, p), sq = orient(a, b, c, q);
    if (!((sp > eps && sq < -eps) || (sp < -eps && sq > eps))) return false;
    const double s1 = orient(p, q, a, b), s2 = orient(p, q, b, c), s3 = orient(p, q, c, a);
    return (s1 > eps && s2 > eps && s3 > eps) || (s1 < -eps && s2 < -eps && s3 < -eps);
  };
  auto intersect = [&](int s, int t) {
    for (int i : tris[s]) {
      for (int j : tris[t]) {
        if (i == j) return false;  // neighbours meet by construction
      }
    }
    const Vec3* p[3] = {&v[tris[s][0]], &v[tris[s][1]], &v[tris[s][2]]};
    const Vec3* q[3] = {&v[tris[t][0]], &v[tris[t][1]], &v[tris[t][2]]};
    for (int e = 0; e < 3; ++e) {
      if (crosses(*p[e], *p[(e + 1) % 3], *q[0], *q[1], *q[2])) return true;
      if (crosses(*q[e], *q[(e + 1) % 3], *p[0], *p[1], *p[2])) return true;
    }
    return false;
  };
  for (std::size_t i = 0; i < entries.size();) {
    std::size_t j = i;
    while (j < entries.size() && entries[j].first == entries[i].first) ++j;
    for (std::size_t a = i; a < j; ++a) {
      for (std::size_t b = a + 1; b < j; ++b) {
        if (intersect(entries[a].second, entries[b].second)) {
          return {std::min(entries[a].second, entries[b].second), std::max(entries[a].second, entries[b].second)};
        }
      }
    }
    i = j;
  }
  return {-1, -1};
}

}  // namespace rigid::geometry
