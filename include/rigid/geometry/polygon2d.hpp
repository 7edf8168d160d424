#pragma once
/// Plane polygons (x, y): convex hulls of support points and contact faces, their intersection and
/// distances to their edges. Polygons are counter-clockwise vertex lists.
#include <span>
#include <vector>

#include "rigid/core/types.hpp"

namespace rigid::geometry {

using Point2 = Eigen::Vector2d;
using Polygon2 = std::vector<Point2>;

/// z of the cross product u x v.
inline double cross(const Point2& u, const Point2& v) { return u.x() * v.y() - u.y() * v.x(); }

/// (a - o) x (b - o): > 0 when o, a, b turn counter-clockwise (unit: m^2).
inline double turn(const Point2& o, const Point2& a, const Point2& b) { return cross(a - o, b - o); }

/// Points that turn by at most this (unit: m^2) are on a hull edge and dropped.
inline constexpr double kHullCollinearTolerance = 1e-15;

/// Counter-clockwise convex hull of `points` (Andrew's monotone chain) as indices into them,
/// starting at the smallest x (then y). A point whose turn is at most `collinear_tolerance` is
/// dropped, and so are duplicates. Fewer than three points: all of them, sorted. `order` is
/// scratch: neither vector allocates once it is large enough (for per-step callers).
void convex_hull_2d(std::span<const Point2> points, std::vector<int>& hull, std::vector<int>& order,
                    double collinear_tolerance = kHullCollinearTolerance);

/// The same, returning the indices.
std::vector<int> convex_hull_2d_indices(std::span<const Point2> points,
                                        double collinear_tolerance = kHullCollinearTolerance);

/// The same, returning the hull's vertices.
Polygon2 convex_hull_2d(std::span<const Point2> points, double collinear_tolerance = kHullCollinearTolerance);

/// Intersection of two convex polygons (Sutherland-Hodgman); empty when they do not overlap.
Polygon2 clip(const Polygon2& subject, const Polygon2& window);

/// Distance from c to the boundary of a convex polygon along the unit direction d; 0 when c is
/// outside.
double ray_to_boundary(const Polygon2& polygon, const Point2& c, const Point2& d);

/// Distance from c to the nearest edge line of a convex polygon; 0 when c is outside.
double distance_to_boundary(const Polygon2& polygon, const Point2& c);

}  // namespace rigid::geometry
