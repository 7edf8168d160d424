// The rock library: shaped point clouds -> convex hulls -> models, and the quasi-static tilt test.
// Shapes are built from fixed seeds with SplitMix64, so the library is the same on every call
// and the generated files (models/library) can be checked against it bit for bit.
#include "rigid/scenario/rock_library.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "rigid/core/rng.hpp"
#include "rigid/geometry/polygon2d.hpp"
#include "rigid/scenario/builders.hpp"

namespace rigid::scenario {

namespace {

using geometry::TriangleSoup;

// ------------------------------------------------------------------------------------------------
// Shaped point clouds

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

// 2D polygons, for the seats below and the rigid-statics estimate
using P2 = geometry::Point2;
using geometry::cross;

std::vector<P2> face_polygon(const TriangleSoup& soup, double z, double tol) {
  std::vector<P2> p;
  for (const auto& t : soup) {
    for (const Vec3* v : {&t.a, &t.b, &t.c}) {
      if (std::abs(v->z() - z) <= tol) p.emplace_back(v->x(), v->y());
    }
  }
  return geometry::convex_hull_2d(p);
}

// A horizontal face (the floor or the ceiling z of a rock) that must lie inside a polygon, at least
// `margin` from its edges: where a piece rests on another, its base is pulled inside the top face
// of the one below. The engine's subcontacts sit at the vertices of one block inside the other, so
// a base that overhangs the face it rests on is carried only by the few vertices that do not,
// and rocks on them; a base held inside is carried by all its vertices.
struct Seat {
  double z = 0;
  std::vector<P2> polygon;  // counter-clockwise
  double margin = 0.02;     // m
};

// Pulls p towards c until it lies inside the polygon, `margin` from every edge.
P2 pull_inside(const P2& p, const P2& c, const std::vector<P2>& poly, double margin) {
  double t = 1.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const P2 a = poly[i], e = poly[(i + 1) % poly.size()] - a;
    const double fc = cross(e, c - a) / e.norm(), fp = cross(e, p - a) / e.norm();
    if (fc < margin) throw std::logic_error("rock_library: a seat is too small for its margin");
    if (fp < margin) t = std::min(t, (fc - margin) / (fc - fp));
  }
  return c + std::max(0.0, t) * (p - c);
}

// A rock: a superellipsoid |x/a|^e + |y/b|^e + |z/c|^e = 1 sampled along jittered directions of
// a Fibonacci sphere, tapered (wider at the top for taper > 0, as many PBRs are), leaned and
// turned, then cut: first by the side cuts (horizontal projection), then by the floors and
// ceilings (vertical projection onto max(floors) <= z <= min(ceilings)), and its cut faces pulled
// into their seats. Each flat cut also gets a ring of points on its outline (rock_points).
struct RockSpec {
  Vec3 center{0, 0, 0};
  Vec3 semi{0.3, 0.3, 0.3};   // semi-axes a, b, c before the lean (m)
  double exponent = 2.0;      // 2: ellipsoid; larger: blockier
  double taper = 0.0;         // x, y scaled by 1 + taper z / c (local z)
  double lean_x = 0, lean_y = 0, yaw = 0;  // rotations about x, then y, then z (rad)
  double jitter = 0.05;       // radial jitter amplitude (fraction of the radius)
  int points = 56;
  std::uint64_t seed = 1;
  std::vector<HeightPlane> floors, ceilings;
  std::vector<SideCut> sides;
  std::vector<Seat> seats;
};

// Cloud points closer than this to a cut are put on it (see apply_cuts) (unit: m).
constexpr double kSnapBand = 0.005;
// Points on the outline of each flat cut: enough for a round-looking contact face, few enough to
// keep the contact search cheap (its cost grows with the vertices of touching faces).
constexpr int kRingPoints = 10;

// Puts a point of a rock's cloud through its cuts (see RockSpec).
Vec3 apply_cuts(const RockSpec& s, Vec3 p) {
  // Points that end up just inside a cut are moved onto it too. Otherwise a hull vertex sits a
  // fraction of a millimetre off a contact face; the rock's own weight (0.3-1 mm of Hertz
  // indentation) brings it into contact and out again, and the rock chatters instead of settling.
  for (const auto& c : s.sides) {
    const double over = c.nx * p.x() + c.ny * p.y() - c.d;
    if (over > -kSnapBand) {
      p.x() -= over * c.nx;
      p.y() -= over * c.ny;
    }
  }
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  for (const auto& f : s.floors) lo = std::max(lo, f.at(p.x(), p.y()));
  for (const auto& c : s.ceilings) hi = std::min(hi, c.at(p.x(), p.y()));
  if (lo > hi) throw std::logic_error("rock_library: a floor cuts above a ceiling");
  if (p.z() < lo + kSnapBand) p.z() = lo;
  if (p.z() > hi - kSnapBand) p.z() = hi;
  for (const auto& seat : s.seats) {
    if (p.z() != seat.z) continue;  // clamped onto that plane: exactly equal
    P2 c = P2::Zero();
    for (const auto& q : seat.polygon) c += q;
    c /= double(seat.polygon.size());
    p.head<2>() = pull_inside(p.head<2>(), c, seat.polygon, seat.margin);
  }
  return p;
}

std::vector<Vec3> rock_points(const RockSpec& s) {
  SplitMix64 rng(s.seed);
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  const Quat turn = Quat(Eigen::AngleAxisd(s.yaw, Vec3::UnitZ())) *
                    Quat(Eigen::AngleAxisd(s.lean_y, Vec3::UnitY())) *
                    Quat(Eigen::AngleAxisd(s.lean_x, Vec3::UnitX()));
  const Mat3 r = turn.toRotationMatrix();
  std::vector<Vec3> out;
  const double n = s.points;
  for (int i = 0; i < s.points; ++i) {
    // jittered Fibonacci sphere: even coverage without a regular lattice
    const double zf = std::clamp(1.0 - 2.0 * (i + 0.5 + 0.4 * rng.symmetric()) / n, -1.0, 1.0);
    const double phi = golden * i + 0.3 * rng.symmetric();
    const double rr = std::sqrt(std::max(0.0, 1.0 - zf * zf));
    const Vec3 d(rr * std::cos(phi), rr * std::sin(phi), zf);
    double sum = 0;
    for (int k = 0; k < 3; ++k) sum += std::pow(std::abs(d[k] / s.semi[k]), s.exponent);
    Vec3 p = d * (std::pow(sum, -1.0 / s.exponent) * (1.0 + s.jitter * rng.symmetric()));
    const double widen = 1.0 + s.taper * p.z() / s.semi.z();
    p.x() *= widen;
    p.y() *= widen;
    out.push_back(apply_cuts(s, r * p + s.center));
  }
  // Ring points where each cut meets the smooth surface. A cut through a small cap
  // holds only the few cloud points that fell in the cap, whose hull is a polygon well inside the
  // true cross-section; the ring makes the cut face the cross-section (slightly jittered inwards).
  const auto shape = [&](const Vec3& q) {  // > 1 outside the tapered superellipsoid
    const Vec3 l = r.transpose() * (q - s.center);
    const double widen = 1.0 + s.taper * l.z() / s.semi.z();
    if (widen <= 0) return std::numeric_limits<double>::infinity();
    const Vec3 u(l.x() / widen, l.y() / widen, l.z());
    double sum = 0;
    for (int k = 0; k < 3; ++k) sum += std::pow(std::abs(u[k] / s.semi[k]), s.exponent);
    return sum;
  };
  std::vector<HeightPlane> cuts = s.floors;
  cuts.insert(cuts.end(), s.ceilings.begin(), s.ceilings.end());
  const double reach = 2.0 * s.semi.maxCoeff();
  for (const auto& cut : cuts) {
    const Vec3 start(s.center.x(), s.center.y(), cut.at(s.center.x(), s.center.y()));
    if (shape(start) >= 1) continue;  // the cut misses the middle of the rock: no ring
    for (int j = 0; j < kRingPoints; ++j) {
      const double phi = 2.0 * kPi * (j + 0.3 * rng.symmetric()) / kRingPoints;
      const Vec3 dir(std::cos(phi), std::sin(phi), 0);
      const auto at = [&](double t) {
        const Vec3 q = start + t * dir;
        return Vec3(q.x(), q.y(), cut.at(q.x(), q.y()));
      };
      // march out to the surface, then bisect
      double inside = 0, outside = reach;
      for (double t = 0.02 * reach; t <= reach; t += 0.02 * reach) {
        if (shape(at(t)) >= 1) {
          outside = t;
          break;
        }
        inside = t;
      }
      for (int k = 0; k < 40; ++k) {
        const double mid = 0.5 * (inside + outside);
        (shape(at(mid)) < 1 ? inside : outside) = mid;
      }
      out.push_back(apply_cuts(s, at(inside * (1.0 - s.jitter * rng.uniform()))));
    }
  }
  // the same for the side cuts, marching in the vertical plane of the cut
  for (const auto& cut : s.sides) {
    const double off = cut.nx * s.center.x() + cut.ny * s.center.y() - cut.d;
    const Vec3 start(s.center.x() - off * cut.nx, s.center.y() - off * cut.ny, s.center.z());
    if (shape(start) >= 1) continue;
    const Vec3 along(-cut.ny, cut.nx, 0);
    for (int j = 0; j < kRingPoints; ++j) {
      const double phi = 2.0 * kPi * (j + 0.3 * rng.symmetric()) / kRingPoints;
      const Vec3 dir = std::cos(phi) * along + std::sin(phi) * Vec3::UnitZ();
      double inside = 0, outside = reach;
      for (double t = 0.02 * reach; t <= reach; t += 0.02 * reach) {
        if (shape(start + t * dir) >= 1) {
          outside = t;
          break;
        }
        inside = t;
      }
      for (int k = 0; k < 40; ++k) {
        const double mid = 0.5 * (inside + outside);
        (shape(start + mid * dir) < 1 ? inside : outside) = mid;
      }
      out.push_back(apply_cuts(s, start + inside * (1.0 - s.jitter * rng.uniform()) * dir));
    }
  }
  return out;
}

TriangleSoup shaped_rock(const RockSpec& s) { return geometry::convex_hull(rock_points(s)); }

// Semi-axis c and centre height that put the floor at z_bottom and the ceiling at z_top, cutting
// the fractions cut_bottom and cut_top of c below and above the centre (unit: m).
void fit_between(RockSpec& s, double z_bottom, double z_top, double cut_bottom, double cut_top) {
  s.semi.z() = (z_top - z_bottom) / (cut_bottom + cut_top);
  s.center.z() = z_bottom + cut_bottom * s.semi.z();
  s.floors.push_back({z_bottom, 0, 0});
  s.ceilings.push_back({z_top, 0, 0});
}

// Same for a top piece (no ceiling) of height about `height` above its floor.
void fit_on(RockSpec& s, double z_bottom, double height, double cut_bottom) {
  s.semi.z() = height / (1.0 + cut_bottom);
  s.center.z() = z_bottom + cut_bottom * s.semi.z();
  s.floors.push_back({z_bottom, 0, 0});
}

// Vertices of a soup that lie on a plane (within rounding), e.g. a cut face, each once.
std::vector<Vec3> vertices_on(const TriangleSoup& soup, const HeightPlane& plane) {
  std::vector<Vec3> out;
  for (const auto& t : soup) {
    for (const Vec3* v : {&t.a, &t.b, &t.c}) {
      if (std::abs(v->z() - plane.at(v->x(), v->y())) <= 1e-12) out.push_back(*v);
    }
  }
  const auto less = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::sort(out.begin(), out.end(), less);
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double min_z(const TriangleSoup& soup) {
  double z = std::numeric_limits<double>::infinity();
  for (const auto& t : soup) z = std::min({z, t.a.z(), t.b.z(), t.c.z()});
  return z;
}

double max_z(const TriangleSoup& soup) {
  double z = -std::numeric_limits<double>::infinity();
  for (const auto& t : soup) z = std::max({z, t.a.z(), t.b.z(), t.c.z()});
  return z;
}

// The top face of `lower` as the seat of the piece above it.
Seat seat_on(const TriangleSoup& lower) {
  const double z = max_z(lower);
  return {z, face_polygon(lower, z, 1e-12), 0.02};
}

// A fixed support under the points `top` (on `surface`): its top face, on the same plane, is their
// outline widened by `margin` (so it holds them, and a rock that tips past its edge falls off);
// below it narrows like a rock column to `narrow` of that width at `depth` under the top, with
// jittered rings so it looks like a rock, not a prism (unit: m).
TriangleSoup support_under(const std::vector<Vec3>& top, const HeightPlane& surface, double margin,
                           double depth, double narrow, std::uint64_t seed) {
  SplitMix64 rng(seed);
  Vec3 c = Vec3::Zero();
  for (const auto& v : top) c += v;
  c /= double(top.size());
  std::vector<Vec3> pts;
  double low = std::numeric_limits<double>::infinity();
  for (const auto& v : top) low = std::min(low, v.z());
  for (const auto& v : top) {
    Vec3 d(v.x() - c.x(), v.y() - c.y(), 0);
    const double r = d.norm();
    if (r < 1e-9) continue;
    const Vec3 w = c + d * ((r + margin) / r);
    pts.emplace_back(w.x(), w.y(), surface.at(w.x(), w.y()));
    for (const double f : {0.5, 1.0}) {
      const double scale = 1.0 - f * (1.0 - narrow) + 0.03 * rng.symmetric();
      const Vec3 q = c + d * ((r + margin) / r * scale);
      pts.emplace_back(q.x(), q.y(), low - f * depth * (1.0 + 0.1 * rng.symmetric()));
    }
  }
  return geometry::convex_hull(pts);
}

TriangleSoup rotated(const TriangleSoup& soup, const Mat3& r) {
  TriangleSoup out = soup;
  for (auto& t : out) {
    t.a = r * t.a;
    t.b = r * t.b;
    t.c = r * t.c;
  }
  return out;
}

// ------------------------------------------------------------------------------------------------
// The models

constexpr double kMargin = 0.03;  // pedestal top beyond the rock's base outline (m)

LibraryModel rectangular_block(double alpha, const std::string& name) {
  // the study's validation blocks (physics.md §11), as `rigid model block` and block_on_pedestal
  const double h = 0.5, b = h * std::tan(alpha), depth = 0.5, m = 0.02;
  LibraryModel model;
  model.name = name;
  char text[160];
  std::snprintf(text, sizeof text,
                "Rectangular block 1 m tall, alpha %.1f rad (width %.4f m), 0.5 m deep, on a pedestal "
                "0.02 m wider on every side (the study's validation set, physics.md 11)", alpha, 2 * b);
  model.description = text;
  model.pieces.push_back({"pedestal", geometry::box_soup(Vec3(-b - m, -0.5 * depth - m, -0.2),
                                                         Vec3(b + m, 0.5 * depth + m, 0)), true});
  model.pieces.push_back({"block", geometry::box_soup(Vec3(-b, -0.5 * depth, 0), Vec3(b, 0.5 * depth, 1.0)), false});
  model.failure_note = "below: a toppled block falls off the pedestal";
  model.simple_stack = true;
  return model;
}

LibraryModel geode() {
  LibraryModel model;
  model.name = "geode";
  model.description =
      "Geode: 320-facet geodesic near-sphere, radius 0.15 m, resting on a facet on a 2 m x 2 m plane "
      "(the study's speed test object, physics.md 11)";
  TriangleSoup g = geodesic_sphere(0.15, 2);
  // turn the facet that faces most downwards to face straight down, so it rests on it
  Vec3 down_normal(0, 0, 1);
  for (const auto& t : g) {
    const Vec3 n = (t.b - t.a).cross(t.c - t.a).normalized();
    if (n.z() < down_normal.z()) down_normal = n;
  }
  g = rotated(g, Quat::FromTwoVectors(down_normal, -Vec3::UnitZ()).toRotationMatrix());
  // rounding leaves the three bottom vertices ~1e-17 m apart in z: snap them onto z = 0 exactly
  const double bottom = min_z(g);
  for (auto& t : g) {
    for (Vec3* v : {&t.a, &t.b, &t.c}) {
      v->z() = std::abs(v->z() - bottom) < 1e-12 ? 0.0 : v->z() - bottom;
    }
  }
  model.pieces.push_back({"plane", geometry::box_soup(Vec3(-1, -1, -0.2), Vec3(1, 1, 0)), true});
  model.pieces.push_back({"geode", g, false});
  model.failure_note = "below: once it rolls it rolls off the plane";
  model.simple_stack = true;
  return model;
}

// A single PBR on a pedestal: a flattened, top-heavy boulder (wider at the top, cut flat at a
// narrow base). `height` sizes the smooth shape (the jittered hull comes out within a few per cent
// of it); `cut` is the fraction of the vertical semi-axis below the centre where the base is cut:
// the deeper the cut, the narrower the base and the more fragile the rock.
LibraryModel single_rock(const std::string& name, double height, double cut, double lean,
                         double yaw, std::uint64_t seed) {
  LibraryModel model;
  model.name = name;
  RockSpec rock;
  rock.semi = Vec3(0.46 * height, 0.33 * height, 0);
  rock.exponent = 2.2;
  rock.taper = 0.25;
  rock.lean_x = lean;
  rock.lean_y = 0.5 * lean;
  rock.yaw = yaw;
  rock.seed = seed;
  rock.points = 64;
  fit_on(rock, 0.0, height, cut);
  const TriangleSoup r = shaped_rock(rock);
  char text[200];
  std::snprintf(text, sizeof text,
                "Single rock %.2f m tall: flattened top-heavy boulder on a narrow flat base, on a rock "
                "pedestal (analogue of the study's single Yucca Mountain rocks, 0.5-0.9 m)", max_z(r));
  model.description = text;
  const TriangleSoup pedestal =
      support_under(vertices_on(r, {0, 0, 0}), {0, 0, 0}, kMargin, 0.3, 0.8, seed + 1000);
  model.pieces.push_back({"pedestal", pedestal, true});
  model.pieces.push_back({"rock", r, false});
  model.failure_note = "below: a toppled rock falls off its pedestal";
  model.simple_stack = true;
  return model;
}

LibraryModel two_piece_rock() {
  LibraryModel model;
  model.name = "two_piece_rock";
  model.description =
      "Two-piece rock, 1.2 m: a boulder split along a flat horizontal joint, both pieces on a rock "
      "pedestal (analogue of the study's two-piece Yucca Mountain rock)";
  RockSpec lower;
  lower.semi = Vec3(0.42, 0.34, 0);
  lower.center.head<2>() = Eigen::Vector2d(0, 0);
  lower.exponent = 2.3;
  lower.taper = 0.15;
  lower.lean_x = 0.04;
  lower.seed = 201;
  fit_between(lower, 0.0, 0.62, 0.78, 0.55);
  const TriangleSoup lo = shaped_rock(lower);
  RockSpec upper;
  upper.semi = Vec3(0.34, 0.27, 0);
  upper.center.head<2>() = Eigen::Vector2d(0.03, -0.02);
  upper.exponent = 2.1;
  upper.taper = 0.1;
  upper.lean_y = 0.05;
  upper.yaw = 0.6;
  upper.seed = 202;
  upper.seats.push_back(seat_on(lo));
  fit_on(upper, max_z(lo), 0.58, 0.6);
  const TriangleSoup up = shaped_rock(upper);
  model.pieces.push_back({"pedestal", support_under(vertices_on(lo, {0, 0, 0}), {0, 0, 0}, kMargin, 0.3, 0.8, 203), true});
  model.pieces.push_back({"lower", lo, false});
  model.pieces.push_back({"upper", up, false});
  model.failure_note = "below: a toppled piece falls off the pedestal";
  model.simple_stack = true;
  return model;
}

// Stacks against a wall or rock face are built upright in a local frame (base top z = 0, wall
// face x = 0, pieces on x <= 0 cut flat where they touch the wall) and then the whole model is
// leaned by `lean` towards the wall, so gravity presses the free pieces against it.
LibraryModel five_stack_wall() {
  LibraryModel model;
  model.name = "five_stack_wall";
  model.description =
      "Five-piece stack, 1.6 m, of flat slabs leaning 7 degrees against a rock wall (analogue of the "
      "study's five-piece stack against a wall)";
  const double lean = 0.12;
  std::vector<TriangleSoup> free;
  double z = 0;
  const double thickness[5] = {0.36, 0.34, 0.32, 0.31, 0.3};
  for (int i = 0; i < 5; ++i) {
    RockSpec s;
    s.semi = Vec3(0.36 - 0.015 * i, 0.32 - 0.01 * i, 0);
    s.center.head<2>() = Eigen::Vector2d(-0.24 + 0.01 * i, 0.02 * ((i % 2) ? 1 : -1));
    s.exponent = 2.6;
    s.yaw = 0.3 * i;
    s.jitter = 0.06;
    s.seed = 301 + std::uint64_t(i);
    s.points = 40;
    s.sides.push_back({1, 0, 0});  // x <= 0: flat against the wall
    if (i > 0) s.seats.push_back(seat_on(free.back()));
    if (i < 4) {
      fit_between(s, z, z + thickness[i], 0.7, 0.7);
    } else {
      fit_on(s, z, thickness[i], 0.7);
    }
    free.push_back(shaped_rock(s));
    z = max_z(free.back());
  }
  RockSpec wall;
  wall.center = Vec3(0.25, 0, 0.8);
  wall.semi = Vec3(0.32, 0.75, 1.3);
  wall.exponent = 4;
  wall.jitter = 0.03;
  wall.seed = 310;
  wall.sides.push_back({-1, 0, 0});  // x >= 0: the wall face
  RockSpec base;
  base.center = Vec3(-0.3, 0, -0.2);
  base.semi = Vec3(0.55, 0.6, 0.3);
  base.exponent = 4;
  base.jitter = 0.03;
  base.seed = 311;
  base.ceilings.push_back({0, 0, 0});  // runs on under the wall, so the corner is inside its top
  const Mat3 r = Eigen::AngleAxisd(lean, Vec3::UnitY()).toRotationMatrix();
  model.pieces.push_back({"base", rotated(shaped_rock(base), r), true});
  model.pieces.push_back({"wall", rotated(shaped_rock(wall), r), true});
  for (int i = 0; i < 5; ++i) {
    model.pieces.push_back({"slab" + std::to_string(i + 1), rotated(free[i], r), false});
  }
  model.failure = {FailureRule::Kind::tilt, 45.0 * kPi / 180.0};
  model.failure_note = "tilt 45 deg: pieces toppling away from the wall land on the base, so they "
                       "never fall below the fixed blocks";
  return model;
}

LibraryModel block_against_face() {
  LibraryModel model;
  model.name = "block_against_face";
  model.description =
      "1 m blocky rock standing on a ledge and leaning 6 degrees against a rock face (analogue of the "
      "study's 1 m block against a rock face)";
  const double lean = 0.1;
  RockSpec s;
  s.semi = Vec3(0.3, 0.26, 0);
  s.center.head<2>() = Eigen::Vector2d(-0.2, 0);
  s.exponent = 3.2;
  s.taper = 0.08;
  s.yaw = 0.2;
  s.jitter = 0.04;
  s.seed = 401;
  s.points = 64;
  s.sides.push_back({1, 0, 0});
  fit_on(s, 0.0, 1.0, 0.85);
  RockSpec face;
  face.center = Vec3(0.25, 0, 0.5);
  face.semi = Vec3(0.32, 0.7, 1.0);
  face.exponent = 4;
  face.jitter = 0.03;
  face.seed = 402;
  face.sides.push_back({-1, 0, 0});
  RockSpec ledge;
  ledge.center = Vec3(-0.25, 0, -0.2);
  ledge.semi = Vec3(0.45, 0.5, 0.3);
  ledge.exponent = 4;
  ledge.jitter = 0.03;
  ledge.seed = 403;
  ledge.ceilings.push_back({0, 0, 0});  // runs on under the face, so the corner is inside its top
  const Mat3 r = Eigen::AngleAxisd(lean, Vec3::UnitY()).toRotationMatrix();
  model.pieces.push_back({"ledge", rotated(shaped_rock(ledge), r), true});
  model.pieces.push_back({"face", rotated(shaped_rock(face), r), true});
  model.pieces.push_back({"block", rotated(shaped_rock(s), r), false});
  model.failure = {FailureRule::Kind::tilt, 45.0 * kPi / 180.0};
  model.failure_note = "tilt 45 deg: leaning on the face, the block cannot fall below the ledge in "
                       "most directions";
  return model;
}

LibraryModel four_stack_unstable_pedestal() {
  LibraryModel model;
  model.name = "four_stack_unstable_pedestal";
  model.description =
      "Four-rock stack, 1.6 m in all, on an unstable pedestal: the pedestal is itself a free rock "
      "on a narrow base, sitting on fixed bedrock (analogue of the study's four-rock stack)";
  RockSpec ped;
  ped.semi = Vec3(0.36, 0.3, 0);
  ped.exponent = 2.2;
  ped.taper = 0.2;
  ped.lean_x = 0.03;
  ped.seed = 501;
  ped.points = 56;
  fit_between(ped, 0.0, 0.42, 0.8, 0.5);
  std::vector<TriangleSoup> free{shaped_rock(ped)};
  const double thickness[4] = {0.34, 0.3, 0.28, 0.3};
  const double width[4] = {0.33, 0.3, 0.27, 0.25};
  for (int i = 0; i < 4; ++i) {
    RockSpec s;
    s.semi = Vec3(width[i], 0.82 * width[i], 0);
    s.center.head<2>() = Eigen::Vector2d(0.025 * ((i % 2) ? 1 : -1), 0.015 * i);
    s.exponent = 2.3;
    s.taper = 0.1;
    s.yaw = 0.5 + 0.7 * i;
    s.jitter = 0.06;
    s.seed = 502 + std::uint64_t(i);
    s.points = 48;
    s.seats.push_back(seat_on(free.back()));
    const double z = max_z(free.back());
    if (i < 3) {
      fit_between(s, z, z + thickness[i], 0.65, 0.6);
    } else {
      fit_on(s, z, thickness[i], 0.65);
    }
    free.push_back(shaped_rock(s));
  }
  model.pieces.push_back({"bedrock", support_under(vertices_on(free[0], {0, 0, 0}), {0, 0, 0}, 0.1, 0.3, 0.8, 510), true});
  model.pieces.push_back({"pedestal", free[0], false});
  for (int i = 0; i < 4; ++i) model.pieces.push_back({"rock" + std::to_string(i + 1), free[i + 1], false});
  model.failure_note = "below: rocks that topple, and the pedestal if it goes, fall off the bedrock";
  model.simple_stack = true;
  return model;
}

LibraryModel three_stack_wedge() {
  LibraryModel model;
  model.name = "three_stack_wedge";
  model.description =
      "Three-rock stack, 1.3 m, on a pedestal sloping 14 degrees, its bottom rock held up on the "
      "downhill side by a small wedge (analogue of the study's three-rock stack with a wedge)";
  const double slope = std::tan(0.245);        // the pedestal top falls towards +x
  const HeightPlane pedestal_top{0, -slope, 0};
  const double crease = -0.15;                  // where the rock's base turns from slope to flat
  const double flat = pedestal_top.at(crease, 0);  // z of the flat part of the base = wedge top
  RockSpec bottom;
  bottom.semi = Vec3(0.4, 0.32, 0);
  bottom.center.head<2>() = Eigen::Vector2d(0.06, 0);
  bottom.exponent = 2.3;
  bottom.taper = 0.1;
  bottom.seed = 601;
  bottom.points = 56;
  fit_between(bottom, flat, 0.45, 0.6, 0.6);  // floor z = flat, ceiling 0.45
  bottom.floors.push_back(pedestal_top);      // uphill the base follows the slope
  const TriangleSoup b = shaped_rock(bottom);
  RockSpec wedge;
  wedge.center = Vec3(crease + 0.3, 0.0, flat - 0.06);
  wedge.semi = Vec3(0.28, 0.3, 0.14);
  wedge.exponent = 2.5;
  wedge.jitter = 0.04;
  wedge.seed = 602;
  wedge.points = 32;
  wedge.sides.push_back({-1, 0, -(crease + 0.05)});  // x >= crease + 5 cm: no knife edge
  wedge.floors.push_back(pedestal_top);
  wedge.ceilings.push_back({flat, 0, 0});
  wedge.seats.push_back({flat, face_polygon(b, flat, 1e-12), 0.02});  // under the rock's flat base
  const TriangleSoup w = shaped_rock(wedge);
  std::vector<TriangleSoup> free{b};
  const double thickness[2] = {0.4, 0.45};
  const double width[2] = {0.33, 0.27};
  for (int i = 0; i < 2; ++i) {
    RockSpec s;
    s.semi = Vec3(width[i], 0.8 * width[i], 0);
    s.center.head<2>() = Eigen::Vector2d(0.04 - 0.03 * i, 0.02);
    s.exponent = 2.2;
    s.taper = 0.15;
    s.yaw = 1.1 + 0.9 * i;
    s.seed = 603 + std::uint64_t(i);
    s.points = 48;
    s.seats.push_back(seat_on(free.back()));
    const double z = max_z(free.back());
    if (i == 0) {
      fit_between(s, z, z + thickness[i], 0.65, 0.6);
    } else {
      fit_on(s, z, thickness[i], 0.65);
    }
    free.push_back(shaped_rock(s));
  }
  std::vector<Vec3> top = vertices_on(b, pedestal_top);
  for (const auto& v : vertices_on(w, pedestal_top)) top.push_back(v);
  model.pieces.push_back({"pedestal", support_under(top, pedestal_top, kMargin, 0.35, 0.85, 610), true});
  model.pieces.push_back({"wedge", w, false});
  model.pieces.push_back({"rock1", free[0], false});
  model.pieces.push_back({"rock2", free[1], false});
  model.pieces.push_back({"rock3", free[2], false});
  model.failure_note = "below: rocks (or the wedge) that go fall off the sloping pedestal";
  return model;
}

// ------------------------------------------------------------------------------------------------
// The tilt test

// Decides when a free block has gone: tilt, displacement relative to the ground, or the scene's
// failure rule, all measured from the settled state.
class GoneWatch {
 public:
  GoneWatch(const Scene& scene, const TiltTestSettings& s) : scene_(scene), s_(s) {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].fixed && ground_ < 0) ground_ = static_cast<int>(i);
    }
    if (ground_ < 0) throw std::invalid_argument("tilt test: the scene has no fixed block");
  }

  // index of the first free block that has gone, or -1
  int gone(const dynamics::World& w) const {
    const auto& defs = scene_.bodies;
    const Vec3 ground_shift = w.states()[ground_].position - defs[ground_].position;
    double lowest_fixed = std::numeric_limits<double>::infinity();
    if (scene_.failure.kind == FailureRule::Kind::below) {
      for (std::size_t i = 0; i < defs.size(); ++i) {
        if (!defs[i].fixed) continue;
        for (const auto& v : w.world_vertices(static_cast<int>(i))) lowest_fixed = std::min(lowest_fixed, v.z());
      }
    }
    for (std::size_t i = 0; i < defs.size(); ++i) {
      if (defs[i].fixed) continue;
      const auto& st = w.states()[i];
      if (!st.position.allFinite() || !st.orientation.coeffs().allFinite()) {
        throw std::runtime_error("tilt test: non-finite state of block " + defs[i].name);
      }
      const double a = tilt(defs[i].orientation, st.orientation);
      const double moved = (st.position - defs[i].position - ground_shift).norm();
      const bool rule = scene_.failure.kind == FailureRule::Kind::below ? st.position.z() < lowest_fixed
                                                                        : a > scene_.failure.tilt_angle;
      if (a > s_.tilt_threshold || moved > s_.displacement_threshold || rule) return static_cast<int>(i);
    }
    return -1;
  }

 private:
  const Scene& scene_;
  const TiltTestSettings& s_;
  int ground_ = -1;
};

// Ground velocity of a ramp a(t) = rate t up to t_hold, then a constant acceleration rate t_hold.
struct RampHold {
  double rate;    // m/s^3
  double t_hold;  // s (infinity: ramp only)
  Vec3 dir;
  Vec3 at(double t) const {
    if (t <= t_hold) return 0.5 * rate * t * t * dir;
    return (0.5 * rate * t_hold * t_hold + rate * t_hold * (t - t_hold)) * dir;
  }
};

}  // namespace

// ------------------------------------------------------------------------------------------------

std::vector<LibraryModel> rock_library() {
  std::vector<LibraryModel> lib;
  lib.push_back(rectangular_block(0.1, "block_a01"));
  lib.push_back(rectangular_block(0.2, "block_a02"));
  lib.push_back(rectangular_block(0.3, "block_a03"));
  lib.push_back(rectangular_block(0.4, "block_a04"));
  lib.push_back(geode());
  lib.push_back(two_piece_rock());
  lib.push_back(five_stack_wall());
  lib.push_back(block_against_face());
  lib.push_back(four_stack_unstable_pedestal());
  lib.push_back(three_stack_wedge());
  lib.push_back(single_rock("single_rock_050", 0.50, 0.66, 0.03, 0.3, 901));
  lib.push_back(single_rock("single_rock_060", 0.60, 0.76, 0.03, 1.4, 902));
  lib.push_back(single_rock("single_rock_075", 0.765, 0.84, 0.03, 2.5, 903));
  lib.push_back(single_rock("single_rock_090", 0.915, 0.88, 0.03, 4.0, 904));
  return lib;
}

Scene library_scene(const LibraryModel& model, const contact::ContactLaw& law, double density) {
  Scene s;
  s.law = law;
  s.density = density;
  s.failure = model.failure;
  s.source = model.name;
  for (const auto& p : model.pieces) s.bodies.push_back(body_from_soup(p.name, p.soup, density, p.fixed));
  return s;
}

double static_toppling(const LibraryModel& model, double azimuth, double density) {
  if (!model.simple_stack) throw std::invalid_argument("static_toppling: " + model.name + " is not a simple stack");
  std::size_t first_free = 0;
  while (first_free < model.pieces.size() && model.pieces[first_free].fixed) ++first_free;
  if (first_free == 0 || first_free == model.pieces.size()) {
    throw std::invalid_argument("static_toppling: " + model.name + " needs fixed pieces then free ones");
  }
  // mass and centroid of each free piece
  std::vector<double> mass(model.pieces.size(), 0);
  std::vector<Vec3> centroid(model.pieces.size(), Vec3::Zero());
  for (std::size_t k = first_free; k < model.pieces.size(); ++k) {
    const auto mesh = geometry::make_closed_mesh(model.pieces[k].soup, geometry::MeshOptions{}, model.pieces[k].name);
    const auto props = geometry::mass_properties(mesh, density);
    mass[k] = props.mass;
    centroid[k] = props.centroid;
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = first_free; k < model.pieces.size(); ++k) {
    const auto& upper = model.pieces[k].soup;
    const auto& lower = model.pieces[k - 1].soup;
    const double z = min_z(upper);
    if (std::abs(max_z(lower) - z) > 1e-9) {
      throw std::invalid_argument("static_toppling: " + model.pieces[k].name + " does not rest on the top of " +
                                  model.pieces[k - 1].name);
    }
    const auto contact = geometry::clip(face_polygon(upper, z, 1e-9), face_polygon(lower, z, 1e-9));
    double m = 0;
    Vec3 c = Vec3::Zero();
    for (std::size_t j = k; j < model.pieces.size(); ++j) {
      m += mass[j];
      c += mass[j] * centroid[j];
    }
    c /= m;
    const double h = c.z() - z;
    const P2 cxy(c.x(), c.y());
    double s = 0;
    if (contact.size() >= 3) {
      s = azimuth < 0 ? geometry::distance_to_boundary(contact, cxy)
                      : geometry::ray_to_boundary(contact, cxy, -P2(std::cos(azimuth), std::sin(azimuth)));
    }
    best = std::min(best, s / h);
  }
  return best;
}

TiltTestResult tilt_test(const Scene& settled, double azimuth, const TiltTestSettings& s) {
  TiltTestResult out;
  out.azimuth = azimuth;
  const GoneWatch watch(settled, s);
  const Vec3 dir(std::cos(azimuth), std::sin(azimuth), 0);
  const double rate = s.ramp_rate * kGravity;  // m/s^3
  dynamics::World world(settled.bodies, settled.law, s.step);
  const double dt = world.dt();
  const auto level_at = [&](long k) { return s.ramp_rate * double(k) * dt; };  // g

  // 1. the ramp, keeping snapshots every 0.02 g to restart the hold tests from
  struct Snapshot {
    long k;
    dynamics::World world;
  };
  std::vector<Snapshot> snaps;
  const long snap_every = std::max(1L, std::lround(0.02 / s.ramp_rate / dt));
  const RampHold ramp{rate, std::numeric_limits<double>::infinity(), dir};
  snaps.push_back({0, world});
  long k = 0;
  int gone = -1;
  while (gone < 0 && level_at(k) < s.max_acceleration) {
    world.step(dt, ramp.at(double(k) * dt), ramp.at(double(k + 1) * dt));
    ++k;
    gone = watch.gone(world);
    if (gone < 0 && k % snap_every == 0) snaps.push_back({k, world});
  }
  out.steps = k;
  if (gone < 0) {
    out.acceleration = out.bracket_high = out.ramp_detection = std::numeric_limits<double>::infinity();
    out.bracket_low = s.max_acceleration;
    return out;
  }
  out.ramp_detection = level_at(k);
  out.block = settled.bodies[static_cast<std::size_t>(gone)].name;

  // 2. hold tests: does the model stand `level` (g) for hold_time? Returns the block that went.
  const auto hold = [&](double level) {
    ++out.hold_tests;
    const double t_hold = level / s.ramp_rate;
    std::size_t i = 0;
    while (i + 1 < snaps.size() && level_at(snaps[i + 1].k) <= level) ++i;
    dynamics::World w = snaps[i].world;
    const RampHold drive{rate, t_hold, dir};
    const long end = static_cast<long>(std::ceil((t_hold + s.hold_time) / dt));
    for (long j = snaps[i].k; j < end; ++j) {
      w.step(dt, drive.at(double(j) * dt), drive.at(double(j + 1) * dt));
      ++out.steps;
      const int g = watch.gone(w);
      if (g >= 0) return g;
    }
    return -1;
  };
  double hi = out.ramp_detection, lo = -1;
  double step = std::min(0.03, 0.5 * hi);
  while (lo < 0) {
    const double level = hi - step;
    if (level <= 0) {
      lo = 0;
      break;
    }
    const int g = hold(level);
    if (g >= 0) {
      hi = level;
      out.block = settled.bodies[static_cast<std::size_t>(g)].name;
      step *= 2;
    } else {
      lo = level;
    }
  }
  while (hi - lo > s.relative_tolerance * hi) {
    const double mid = 0.5 * (lo + hi);
    const int g = hold(mid);
    if (g >= 0) {
      hi = mid;
      out.block = settled.bodies[static_cast<std::size_t>(g)].name;
    } else {
      lo = mid;
    }
  }
  out.bracket_low = lo;
  out.bracket_high = hi;
  out.acceleration = 0.5 * (lo + hi);
  return out;
}

TiltSurvey tilt_survey(const Scene& settled, int azimuths, const TiltTestSettings& settings) {
  if (azimuths < 1) throw std::invalid_argument("tilt_survey: need at least one azimuth");
  TiltSurvey out;
  out.minimum = std::numeric_limits<double>::infinity();
  for (int j = 0; j < azimuths; ++j) {
    const double az = 2.0 * kPi * double(j) / double(azimuths);
    out.results.push_back(tilt_test(settled, az, settings));
    if (out.results.back().acceleration < out.minimum) {
      out.minimum = out.results.back().acceleration;
      out.azimuth_of_minimum = az;
    }
  }
  return out;
}

}  // namespace rigid::scenario
