#pragma once
// Shaped rocks for the rock library (module-private): seeded superellipsoid point clouds, cut flat
// where they touch their neighbours, and the helpers that fit them together.
#include <cstdint>
#include <vector>

#include "rigid/geometry/polygon2d.hpp"
#include "rigid/geometry/polyhedron.hpp"

namespace rigid::library::shapes {

using geometry::Polygon2;
using geometry::TriangleSoup;

// A plane written as a height field, z = z0 + sx x + sy y: the cuts that make flat contact faces
// are applied by vertical projection onto such planes, which is exact (the projected point lies
// on the plane to rounding), so two pieces cut by the same plane touch face to face.
struct HeightPlane {
  double z0 = 0, sx = 0, sy = 0;
  double at(double x, double y) const { return z0 + sx * x + sy * y; }
};

// A vertical cut nx x + ny y <= d, (nx, ny) a unit vector: a flat face against a wall.
struct SideCut {
  double nx = 1, ny = 0, d = 0;
};

// A horizontal face (the floor or the ceiling z of a rock) that must lie inside a polygon, at least
// `margin` from its edges: where a piece rests on another, its base is pulled inside the top face
// of the one below. The engine's subcontacts sit at the vertices of one block inside the other, so
// a base that overhangs the face it rests on is carried only by the few vertices that do not,
// and rocks on them; a base held inside is carried by all its vertices.
struct Seat {
  double z = 0;
  Polygon2 polygon;      // counter-clockwise
  double margin = 0.02;  // m
};

// A rock: a superellipsoid |x/a|^e + |y/b|^e + |z/c|^e = 1 sampled along jittered directions of
// a Fibonacci sphere, tapered (wider at the top for taper > 0, as many PBRs are), leaned and
// turned, then cut: first by the side cuts (horizontal projection), then by the floors and
// ceilings (vertical projection onto max(floors) <= z <= min(ceilings)), and its cut faces pulled
// into their seats. Each flat cut also gets a ring of points on its outline (rock_points).
struct RockSpec {
  Vec3 center{0, 0, 0};
  Vec3 semi{0.3, 0.3, 0.3};                // semi-axes a, b, c before the lean (m)
  double exponent = 2.0;                   // 2: ellipsoid; larger: blockier
  double taper = 0.0;                      // x, y scaled by 1 + taper z / c (local z)
  double lean_x = 0, lean_y = 0, yaw = 0;  // rotations about x, then y, then z (rad)
  double jitter = 0.05;                    // radial jitter amplitude (fraction of the radius)
  int points = 56;
  std::uint64_t seed = 1;
  std::vector<HeightPlane> floors, ceilings;
  std::vector<SideCut> sides;
  std::vector<Seat> seats;
};

/// The cloud of a rock: its jittered surface points through its cuts, plus rings on the cuts.
std::vector<Vec3> rock_points(const RockSpec& s);
/// The convex hull of rock_points.
TriangleSoup shaped_rock(const RockSpec& s);

// Semi-axis c and centre height that put the floor at z_bottom and the ceiling at z_top, cutting
// the fractions cut_bottom and cut_top of c below and above the centre (unit: m).
void fit_between(RockSpec& s, double z_bottom, double z_top, double cut_bottom, double cut_top);
// Same for a top piece (no ceiling) of height about `height` above its floor.
void fit_on(RockSpec& s, double z_bottom, double height, double cut_bottom);

// Vertices of a soup that lie on a plane (within rounding), e.g. a cut face, each once.
std::vector<Vec3> vertices_on(const TriangleSoup& soup, const HeightPlane& plane);
double min_z(const TriangleSoup& soup);
double max_z(const TriangleSoup& soup);
// Outline (convex hull) of a soup's vertices within tol of height z.
Polygon2 face_polygon(const TriangleSoup& soup, double z, double tol);
// The top face of `lower` as the seat of the piece above it.
Seat seat_on(const TriangleSoup& lower);

// A fixed support under the points `top` (on `surface`): its top face, on the same plane, is their
// outline widened by `margin` (so it holds them, and a rock that tips past its edge falls off);
// below it narrows like a rock column to `narrow` of that width at `depth` under the top, with
// jittered rings so it looks like a rock, not a prism (unit: m).
TriangleSoup support_under(const std::vector<Vec3>& top, const HeightPlane& surface, double margin, double depth,
                           double narrow, std::uint64_t seed);

TriangleSoup rotated(const TriangleSoup& soup, const Mat3& r);

}  // namespace rigid::library::shapes
