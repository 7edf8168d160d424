// GJK distance between convex hulls (Gilbert, Johnson & Keerthi 1988) with Ericson-style
// closest-point sub-steps: the simplex is reduced to the feature nearest the origin each
// iteration, and barycentric weights give the witness points on each hull.
#include "rigid/contact/gjk.hpp"

#include <cmath>
#include <initializer_list>
#include <limits>

namespace rigid::contact {
namespace {

// Small hulls are cheaper to scan than to walk; beyond this the walk wins.
constexpr std::size_t kBruteForceVertices = 24;
constexpr int kMaxIterations = 64;

struct SimplexPoint {
  Vec3 w, a, b;  // w = a - b
};

struct Simplex {
  SimplexPoint p[4];
  double lambda[4] = {1, 0, 0, 0};
  int n = 0;

  void keep(std::initializer_list<int> ids, std::initializer_list<double> weights) {
    SimplexPoint q[4];
    int k = 0;
    for (int i : ids) q[k++] = p[i];
    k = 0;
    for (double w : weights) lambda[k++] = w;
    n = static_cast<int>(ids.size());
    for (int i = 0; i < n; ++i) p[i] = q[i];
  }
  Vec3 point() const {
    Vec3 v = Vec3::Zero();
    for (int i = 0; i < n; ++i) v += lambda[i] * p[i].w;
    return v;
  }
};

void closest_on_segment(Simplex& s) {
  const Vec3& a = s.p[0].w;
  const Vec3 ab = s.p[1].w - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? -a.dot(ab) / len2 : 0.0;
  if (t <= 0) {
    s.keep({0}, {1.0});
  } else if (t >= 1) {
    s.keep({1}, {1.0});
  } else {
    s.keep({0, 1}, {1 - t, t});
  }
}

// Ericson, Real-Time Collision Detection §5.1.5, with the query point at the origin.
void closest_on_triangle(Simplex& s, int ia, int ib, int ic) {
  const Vec3 a = s.p[ia].w, b = s.p[ib].w, c = s.p[ic].w;
  const Vec3 ab = b - a, ac = c - a;
  const double d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= 0 && d2 <= 0) return s.keep({ia}, {1.0});
  const double d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= 0 && d4 <= d3) return s.keep({ib}, {1.0});
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return s.keep({ia, ib}, {1 - v, v});
  }
  const double d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= 0 && d5 <= d6) return s.keep({ic}, {1.0});
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return s.keep({ia, ic}, {1 - w, w});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return s.keep({ib, ic}, {1 - w, w});
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  s.keep({ia, ib, ic}, {1 - v - w, v, w});
}

// True when the origin and `d` are not strictly on the same side of plane (a, b, c).
bool origin_outside_face(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 n = (b - a).cross(c - a);
  return (-a).dot(n) * (d - a).dot(n) <= 0;
}

// Returns false when the origin lies inside the tetrahedron (the hulls overlap).
bool closest_on_tetrahedron(Simplex& s) {
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  bool any_outside = false;
  double best = std::numeric_limits<double>::infinity();
  Simplex best_simplex;
  for (const auto& f : kFaces) {
    if (!origin_outside_face(s.p[f[0]].w, s.p[f[1]].w, s.p[f[2]].w, s.p[f[3]].w)) continue;
    any_outside = true;
    Simplex trial = s;
    closest_on_triangle(trial, f[0], f[1], f[2]);
    const double d2 = trial.point().squaredNorm();
    if (d2 < best) {
      best = d2;
      best_simplex = trial;
    }
  }
  if (!any_outside) return false;
  s = best_simplex;
  return true;
}

Vec3 vertex(const PlacedHull& h, int i) { return h.world_vertices[i] + h.offset; }

}  // namespace

int support_vertex(const PlacedHull& hull, const Vec3& dir, int& hint) {
  const auto& shape = *hull.shape;
  const std::size_t n = shape.vertices.size();
  const Vec3* v = hull.world_vertices;
  if (n <= kBruteForceVertices || shape.vertex_neighbors[hint].empty()) {
    int best = 0;
    double best_dot = dir.dot(v[0]);
    for (std::size_t i = 1; i < n; ++i) {
      const double d = dir.dot(v[i]);
      if (d > best_dot) {
        best_dot = d;
        best = static_cast<int>(i);
      }
    }
    hint = best;
    return best;
  }
  // steepest ascent over the edge graph: on a convex polytope a local maximum is global
  int current = hint;
  double current_dot = dir.dot(v[current]);
  for (;;) {
    int next = current;
    for (int j : shape.vertex_neighbors[current]) {
      const double d = dir.dot(v[j]);
      if (d > current_dot) {
        current_dot = d;
        next = j;
      }
    }
    if (next == current) break;
    current = next;
  }
  hint = current;
  return current;
}

LinkResult shortest_link(const PlacedHull& a, const PlacedHull& b, const Vec3& guess, SupportHints& hints) {
  const double scale = a.shape->bounding_radius + b.shape->bounding_radius;
  const double tiny = 1e-24 * scale * scale;

  auto support = [&](const Vec3& dir) {
    SimplexPoint p;
    p.a = vertex(a, support_vertex(a, dir, hints.a));
    p.b = vertex(b, support_vertex(b, -dir, hints.b));
    p.w = p.a - p.b;
    return p;
  };

  Simplex s;
  s.p[0] = support(-guess);
  s.n = 1;
  Vec3 v = s.p[0].w;
  LinkResult out;
  for (int iter = 0; iter < kMaxIterations; ++iter) {
    const double vv = v.squaredNorm();
    if (vv <= tiny) {
      out.overlapping = true;
      return out;
    }
    const SimplexPoint w = support(-v);
    // no further progress towards the origin: v is the closest point of A - B
    if (vv - v.dot(w.w) <= 1e-12 * vv) break;
    bool duplicate = false;
    for (int i = 0; i < s.n; ++i) duplicate |= (s.p[i].w == w.w);
    if (duplicate) break;
    const Simplex before = s;
    s.p[s.n++] = w;
    switch (s.n) {
      case 2:
        closest_on_segment(s);
        break;
      case 3:
        closest_on_triangle(s, 0, 1, 2);
        break;
      case 4:
        if (!closest_on_tetrahedron(s)) {
          out.overlapping = true;
          return out;
        }
        break;
      default:
        break;
    }
    const Vec3 next = s.point();
    // guard against cycling from round-off: the distance must strictly decrease
    if (next.squaredNorm() >= vv) {
      s = before;
      break;
    }
    v = next;
  }
  if (v.squaredNorm() <= tiny) {
    out.overlapping = true;
    return out;
  }
  out.point_a.setZero();
  out.point_b.setZero();
  for (int i = 0; i < s.n; ++i) {
    out.point_a += s.lambda[i] * s.p[i].a;
    out.point_b += s.lambda[i] * s.p[i].b;
  }
  out.distance = v.norm();
  out.direction = -v / out.distance;
  return out;
}

}  // namespace rigid::contact
