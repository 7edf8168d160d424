// Shaped rocks: seeded superellipsoid clouds, cut flat, hulled. Fixed seeds (SplitMix64) make the
// library the same on every call, so the generated files (models/library) can be checked bit for bit.
#include "rock_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "rigid/core/rng.hpp"

namespace rigid::library::shapes {
namespace {

using P2 = geometry::Point2;
using geometry::cross;

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

}  // namespace

std::vector<P2> face_polygon(const TriangleSoup& soup, double z, double tol) {
  std::vector<P2> p;
  for (const auto& t : soup) {
    for (const Vec3* v : {&t.a, &t.b, &t.c}) {
      if (std::abs(v->z() - z) <= tol) p.emplace_back(v->x(), v->y());
    }
  }
  return geometry::convex_hull_2d(p);
}

std::vector<Vec3> rock_points(const RockSpec& s) {
  SplitMix64 rng(s.seed);
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  const Quat turn = Quat(Eigen::AngleAxisd(s.yaw, Vec3::UnitZ())) * Quat(Eigen::AngleAxisd(s.lean_y, Vec3::UnitY())) *
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
TriangleSoup support_under(const std::vector<Vec3>& top, const HeightPlane& surface, double margin, double depth,
                           double narrow, std::uint64_t seed) {
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

}  // namespace rigid::library::shapes
