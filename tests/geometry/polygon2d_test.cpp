// Plane polygons: convex hulls, intersection and distances on hand-computed configurations.
#include "rigid/geometry/polygon2d.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace rigid::geometry {
namespace {

// shoelace formula: > 0 for a counter-clockwise polygon
double signed_area(const Polygon2& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a;
}

void expect_polygon(const Polygon2& actual, const Polygon2& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(actual[i], expected[i]) << "vertex " << i;
  }
}

TEST(ConvexHull2d, SquareDropsInteriorAndCollinearPoints) {
  // corners of [0, 2]^2, its centre and the midpoints of three edges, in no particular order
  const std::vector<Point2> pts{{1, 1}, {2, 2}, {1, 0}, {0, 0}, {2, 1}, {0, 2}, {0, 1}, {2, 0}};
  // counter-clockwise from the smallest x (then y)
  expect_polygon(convex_hull_2d(pts), {{0, 0}, {2, 0}, {2, 2}, {0, 2}});
  EXPECT_EQ(convex_hull_2d_indices(pts), (std::vector<int>{3, 7, 1, 5}));
}

TEST(ConvexHull2d, TriangleInAnyOrder) {
  const Polygon2 expected{{0, 0}, {4, 0}, {0, 3}};
  expect_polygon(convex_hull_2d(std::vector<Point2>{{0, 3}, {4, 0}, {0, 0}}), expected);
  expect_polygon(convex_hull_2d(std::vector<Point2>{{4, 0}, {0, 0}, {1, 1}, {0, 3}}), expected);
  EXPECT_DOUBLE_EQ(signed_area(expected), 6.0);
}

TEST(ConvexHull2d, DuplicatePointsAppearOnce) {
  const std::vector<Point2> pts{{0, 0}, {1, 0}, {0, 0}, {1, 1}, {1, 0}, {0, 1}, {1, 1}, {0, 1}};
  expect_polygon(convex_hull_2d(pts), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
}

TEST(ConvexHull2d, DegenerateInputs) {
  // fewer than three points: all of them, sorted
  expect_polygon(convex_hull_2d(std::vector<Point2>{{3, 1}, {1, 5}}), {{1, 5}, {3, 1}});
  EXPECT_TRUE(convex_hull_2d(std::vector<Point2>{}).empty());
  // collinear points: only the two ends remain, no area
  expect_polygon(convex_hull_2d(std::vector<Point2>{{1, 1}, {0, 0}, {2, 2}}), {{0, 0}, {2, 2}});
}

TEST(ConvexHull2d, CollinearToleranceDecidesNearlyStraightVertices) {
  // (1, -1e-17) bends the bottom edge of [0, 2]^2 by a turn of 2e-17 m^2: below the default
  // tolerance (dropped), above zero (kept)
  const std::vector<Point2> pts{{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, -1e-17}};
  expect_polygon(convex_hull_2d(pts), {{0, 0}, {2, 0}, {2, 2}, {0, 2}});
  expect_polygon(convex_hull_2d(pts, 0.0), {{0, 0}, {1, -1e-17}, {2, 0}, {2, 2}, {0, 2}});
}

TEST(ConvexHull2d, ScratchFormMatchesAndReuses) {
  const std::vector<Point2> pts{{1, 1}, {2, 2}, {1, 0}, {0, 0}, {2, 1}, {0, 2}, {0, 1}, {2, 0}};
  std::vector<int> hull{42, 43}, order;
  convex_hull_2d(pts, hull, order);
  EXPECT_EQ(hull, convex_hull_2d_indices(pts));
  convex_hull_2d(std::vector<Point2>{{0, 0}, {4, 0}, {0, 3}}, hull, order);
  EXPECT_EQ(hull, (std::vector<int>{0, 1, 2}));
}

TEST(Polygon2d, ClipOfOverlappingSquaresIsTheirCommonSquare) {
  const Polygon2 a{{0, 0}, {2, 0}, {2, 2}, {0, 2}}, b{{1, 1}, {3, 1}, {3, 3}, {1, 3}};
  const Polygon2 c = clip(a, b);
  EXPECT_DOUBLE_EQ(signed_area(c), 1.0);
  for (const auto& p : c) {
    EXPECT_GE(p.x(), 1.0);
    EXPECT_LE(p.x(), 2.0);
    EXPECT_GE(p.y(), 1.0);
    EXPECT_LE(p.y(), 2.0);
  }
  const Polygon2 far{{5, 5}, {6, 5}, {6, 6}};
  EXPECT_TRUE(clip(a, far).empty());
}

TEST(Polygon2d, DistancesToTheBoundary) {
  const Polygon2 square{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const Point2 c(0.5, 1.0);
  EXPECT_DOUBLE_EQ(ray_to_boundary(square, c, Point2(1, 0)), 1.5);
  EXPECT_DOUBLE_EQ(ray_to_boundary(square, c, Point2(-1, 0)), 0.5);
  EXPECT_DOUBLE_EQ(ray_to_boundary(square, c, Point2(0, 1)), 1.0);
  EXPECT_DOUBLE_EQ(distance_to_boundary(square, c), 0.5);
  EXPECT_EQ(ray_to_boundary(square, Point2(3, 1), Point2(1, 0)), 0.0);  // outside
  EXPECT_EQ(distance_to_boundary(square, Point2(3, 1)), 0.0);
  EXPECT_DOUBLE_EQ(turn(Point2(0, 0), Point2(1, 0), Point2(0, 1)), 1.0);  // counter-clockwise
}

}  // namespace
}  // namespace rigid::geometry
