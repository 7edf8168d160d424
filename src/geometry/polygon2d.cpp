#include "rigid/geometry/polygon2d.hpp"

#include <algorithm>
#include <limits>

namespace rigid::geometry {

void convex_hull_2d(std::span<const Point2> points, std::vector<int>& hull, std::vector<int>& order,
                    double collinear_tolerance) {
  order.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return points[a].x() < points[b].x() || (points[a].x() == points[b].x() && points[a].y() < points[b].y());
  });
  hull.clear();
  if (order.size() < 3) {
    hull.assign(order.begin(), order.end());
    return;
  }
  // lower chain left to right, then upper chain right to left; each ends where the other starts
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = hull.size();
    for (std::size_t k = 0; k < order.size(); ++k) {
      const int p = pass == 0 ? order[k] : order[order.size() - 1 - k];
      while (hull.size() >= base + 2 &&
             turn(points[hull[hull.size() - 2]], points[hull.back()], points[p]) <= collinear_tolerance) {
        hull.pop_back();
      }
      hull.push_back(p);
    }
    hull.pop_back();
  }
}

std::vector<int> convex_hull_2d_indices(std::span<const Point2> points, double collinear_tolerance) {
  std::vector<int> hull, order;
  convex_hull_2d(points, hull, order, collinear_tolerance);
  return hull;
}

Polygon2 convex_hull_2d(std::span<const Point2> points, double collinear_tolerance) {
  Polygon2 out;
  for (int i : convex_hull_2d_indices(points, collinear_tolerance)) out.push_back(points[i]);
  return out;
}

Polygon2 clip(const Polygon2& subject, const Polygon2& window) {
  Polygon2 out = subject;
  for (std::size_t i = 0; i < window.size() && !out.empty(); ++i) {
    const Point2 a = window[i], b = window[(i + 1) % window.size()];
    auto inside = [&](const Point2& p) { return cross(b - a, p - a) >= 0; };
    Polygon2 in = std::move(out);
    out.clear();
    for (std::size_t j = 0; j < in.size(); ++j) {
      const Point2 p = in[j], q = in[(j + 1) % in.size()];
      const bool pin = inside(p), qin = inside(q);
      if (pin) out.push_back(p);
      if (pin != qin) {
        const double dp = cross(b - a, p - a), dq = cross(b - a, q - a);
        out.push_back(p + (q - p) * (dp / (dp - dq)));
      }
    }
  }
  return out;
}

double ray_to_boundary(const Polygon2& polygon, const Point2& c, const Point2& d) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    const Point2 e = b - a;
    if (cross(e, c - a) < 0) return 0;  // outside this edge
    const double den = cross(e, d);
    if (den < 0) best = std::min(best, cross(e, c - a) / -den);  // leaves through this edge
  }
  return best;
}

double distance_to_boundary(const Polygon2& polygon, const Point2& c) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    const double s = cross(b - a, c - a) / (b - a).norm();
    best = std::min(best, std::max(0.0, s));
  }
  return best;
}

}  // namespace rigid::geometry
