/// Incremental 3D convex hull (quickhull-style) and box soups, for synthetic models and tests.
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <vector>

#include "rigid/geometry/polyhedron.hpp"

namespace rigid::geometry {
namespace {

// Points closer than this fraction of the bounding-box diagonal to the current hull count as on
// it. It sits above MeshOptions::weld_tolerance (1e-9) so every hull triangle is thicker than
// the weld/degeneracy threshold of make_closed_mesh, and far below its convexity tolerance.
constexpr double kHullRelativeTolerance = 1e-8;
// New faces thinner than this fraction of the tolerance are repaired rather than kept, so the
// hull's triangles stay thicker than the weld tolerance too (unit: 1).
constexpr double kSliver = 0.25;
// A vertex removed from the hull but found outside the new faces is retried at most this often,
// which bounds the work on adversarial input.
constexpr int kMaxRequeue = 8;
// Floor of the bend tolerance, as a fraction of the hull tolerance, so rounding between
// coplanar faces does not count as a bend (unit: 1).
constexpr double kMinBend = 1e-3;

// Bounding-box diagonals outside this range would overflow or underflow the products of
// coordinates the predicates use (unit: m).
constexpr double kMinDiagonal = 1e-100;
constexpr double kMaxDiagonal = 1e100;

struct HullFace {
  std::array<int, 3> v;               // counter-clockwise seen from outside
  std::array<int, 3> nb{-1, -1, -1};  // face across edge v[i] -> v[(i+1)%3]
  Vec3 normal;                        // outward unit normal
  double offset = 0;                  // plane: normal . x = offset
  bool alive = true;
  std::vector<int> outside;  // points above this face by more than the tolerance
};

// Twice-area vector, crossed at the vertex opposite the longest edge (smallest rounding error).
Vec3 area_vector(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(), ca = (a - c).squaredNorm();
  if (bc >= ab && bc >= ca) return (b - a).cross(c - a);
  if (ca >= ab) return (c - b).cross(a - b);
  return (a - c).cross(b - c);
}

class Hull {
 public:
  explicit Hull(const std::vector<Vec3>& points) : p_(points) {}

  TriangleSoup build() {
    const int n = static_cast<int>(p_.size());
    if (n < 4) throw std::invalid_argument("convex_hull: need at least 4 points");
    for (const Vec3& q : p_) {
      if (!q.allFinite()) throw std::invalid_argument("convex_hull: point is NaN or infinite");
    }
    Vec3 lo = p_[0], hi = p_[0];
    for (const Vec3& q : p_) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const double diag = (hi - lo).norm();
    if (!(diag > 0)) throw std::invalid_argument("convex_hull: all points coincide");
    if (!(diag >= kMinDiagonal && diag <= kMaxDiagonal)) {
      throw std::invalid_argument("convex_hull: points span a box too small or too large");
    }
    eps_ = kHullRelativeTolerance * diag;
    diag_ = diag;
    center_ = 0.5 * (lo + hi);

    initial_simplex(lo, hi);
    std::deque<int> work;
    for (int f = 0; f < 4; ++f) {
      if (!faces_[f].outside.empty()) work.push_back(f);
    }
    mark_.assign(faces_.size(), -1);
    start_.assign(p_.size(), -1);
    end_.assign(p_.size(), -1);
    seen_.assign(p_.size(), -1);
    requeued_.assign(p_.size(), 0);
    // each round removes the farthest outside point of a face from every list: terminates
    while (!work.empty()) {
      const int f = work.front();
      work.pop_front();
      if (!faces_[f].alive || faces_[f].outside.empty()) continue;
      auto& out = faces_[f].outside;
      const int apex = best(out, [&](int i) { return distance(f, i); });
      if (apex < 0) {  // no finite score: cannot happen with bounded coordinates
        out.clear();
        continue;
      }
      out.erase(std::find(out.begin(), out.end(), apex));
      add_point(apex, f, work);
      if (faces_[f].alive && !faces_[f].outside.empty()) work.push_back(f);
    }

    TriangleSoup soup;
    for (const HullFace& face : faces_) {
      if (face.alive) soup.push_back({p_[face.v[0]], p_[face.v[1]], p_[face.v[2]]});
    }
    return soup;
  }

 private:
  // signed distance of point i above the plane of face f (unit: m)
  double distance(int f, int i) const { return height(faces_[f], i); }

  // lexicographic order of coordinates, then index: the smallest point of a set of ties is a
  // vertex of their convex hull, so ties never pick a point inside a face or edge
  bool lex_less(int i, int j) const {
    const Vec3 &a = p_[i], &b = p_[j];
    if (a.x() != b.x()) return a.x() < b.x();
    if (a.y() != b.y()) return a.y() < b.y();
    if (a.z() != b.z()) return a.z() < b.z();
    return i < j;
  }

  // the candidate with the largest score; scores within the tolerance of it count as ties
  template <class Score>
  int best(const std::vector<int>& candidates, Score score) const {
    double top = -std::numeric_limits<double>::infinity();
    for (int i : candidates) top = std::max(top, score(i));
    int pick = -1;
    for (int i : candidates) {
      if (score(i) >= top - eps_ && (pick < 0 || lex_less(i, pick))) pick = i;
    }
    return pick;
  }

  bool set_plane(HullFace& face) const {
    const Vec3 a = p_[face.v[0]] - center_, b = p_[face.v[1]] - center_, c = p_[face.v[2]] - center_;
    const Vec3 n = area_vector(a, b, c);
    const double len = n.norm();
    if (!(len > 0)) return false;
    face.normal = n / len;
    face.offset = (face.normal.dot(a) + face.normal.dot(b) + face.normal.dot(c)) / 3.0;
    return true;
  }

  void initial_simplex(const Vec3& lo, const Vec3& hi) {
    std::vector<int> all(p_.size());
    for (std::size_t i = 0; i < p_.size(); ++i) all[i] = static_cast<int>(i);
    // the two extremes along the widest axis
    Eigen::Index axis = 0;
    (hi - lo).maxCoeff(&axis);
    const int i0 = best(all, [&](int i) { return -p_[i][axis]; });
    const int i1 = best(all, [&](int i) { return p_[i][axis]; });
    // the point farthest from their line
    const Vec3 dir = (p_[i1] - p_[i0]).normalized();
    auto line_distance = [&](int i) {
      const Vec3 d = p_[i] - p_[i0];
      return (d - d.dot(dir) * dir).norm();
    };
    const int i2 = best(all, line_distance);
    if (!(line_distance(i2) > eps_)) {
      throw std::invalid_argument("convex_hull: points are collinear (need 4 non-coplanar points)");
    }
    // the point farthest from their plane
    const Vec3 n = (p_[i1] - p_[i0]).cross(p_[i2] - p_[i0]).normalized();
    auto plane_distance = [&](int i) { return std::abs(n.dot(p_[i] - p_[i0])); };
    const int i3 = best(all, plane_distance);
    if (!(plane_distance(i3) > eps_)) {
      throw std::invalid_argument("convex_hull: points are coplanar (need 4 non-coplanar points)");
    }

    // four outward faces: each must have the remaining vertex below it
    const std::array<int, 4> s{i0, i1, i2, i3};
    inner_ = (p_[i0] + p_[i1] + p_[i2] + p_[i3]) / 4.0;
    const std::array<std::array<int, 3>, 4> tri{{{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}}};
    const bool below = n.dot(p_[i3] - p_[i0]) < 0;  // i3 below (i0, i1, i2): keep this winding
    for (const auto& t : tri) {
      HullFace face;
      face.v = {s[t[0]], s[t[1]], s[t[2]]};
      if (!below) std::swap(face.v[1], face.v[2]);
      if (!set_plane(face)) throw std::invalid_argument("convex_hull: points are coplanar");
      faces_.push_back(face);
    }
    // adjacency of the tetrahedron: the face running an edge the other way
    for (int f = 0; f < 4; ++f) {
      for (int i = 0; i < 3; ++i) {
        const int a = faces_[f].v[i], b = faces_[f].v[(i + 1) % 3];
        for (int g = 0; g < 4; ++g) {
          for (int j = 0; j < 3; ++j) {
            if (faces_[g].v[j] == b && faces_[g].v[(j + 1) % 3] == a) faces_[f].nb[i] = g;
          }
        }
      }
    }
    // conflict lists: each point goes to the face it is farthest above
    for (std::size_t i = 0; i < p_.size(); ++i) {
      const int q = static_cast<int>(i);
      if (q == i0 || q == i1 || q == i2 || q == i3) continue;
      assign(q, 0, 4);
    }
  }

  // puts point q on the outside list of the face in [first, last) it is farthest above, if any
  void assign(int q, int first, int last) {
    int target = -1;
    double far = eps_;
    for (int f = first; f < last; ++f) {
      if (!faces_[f].alive) continue;
      const double d = distance(f, q);
      if (d > far) {
        far = d;
        target = f;
      }
    }
    if (target >= 0) faces_[target].outside.push_back(q);
  }

  // How hard a new cap is checked: bends scaled by their lever arm, bends against the plain
  // tolerance, or not at all.
  enum class Checks { strict, plain, none };

  struct HorizonEdge {
    int a, b;  // runs a -> b on the visible face being removed
    int face;  // the invisible face across
    int slot;  // edge index of b -> a in that face
  };

  // Horizon of the marked (visible) faces: edges from a visible to an invisible face, checked to
  // form one simple loop. start_/end_ are left set for the loop on success and cleared on failure.
  bool horizon_of(const std::vector<int>& visible, int stamp, std::vector<HorizonEdge>& horizon) {
    horizon.clear();
    for (int f : visible) {
      for (int i = 0; i < 3; ++i) {
        const int g = faces_[f].nb[i];
        if (mark_[g] == stamp) continue;
        const int a = faces_[f].v[i], b = faces_[f].v[(i + 1) % 3];
        int slot = 0;
        while (slot < 3 && !(faces_[g].v[slot] == b && faces_[g].v[(slot + 1) % 3] == a)) ++slot;
        if (slot == 3) return false;  // broken adjacency cannot happen; refuse rather than corrupt
        horizon.push_back({a, b, g, slot});
      }
    }
    bool ok = !horizon.empty();
    for (std::size_t h = 0; ok && h < horizon.size(); ++h) {
      if (start_[horizon[h].a] >= 0 || end_[horizon[h].b] >= 0) ok = false;
      start_[horizon[h].a] = static_cast<int>(h);
      end_[horizon[h].b] = static_cast<int>(h);
    }
    if (ok) {
      std::size_t walked = 0;
      int h = 0;
      do {
        h = start_[horizon[h].b];
        ++walked;
      } while (h > 0 && walked <= horizon.size());
      ok = h == 0 && walked == horizon.size();
    }
    if (!ok) {
      for (const auto& e : horizon) start_[e.a] = end_[e.b] = -1;
    }
    return ok;
  }

  // Adds the apex, trying first to treat faces it is coplanar with (within the tolerance) as
  // visible, which merges flat regions and avoids sliver faces whose planes tilt badly, then
  // only the faces it is clearly above.
  void add_point(int apex, int seed, std::deque<int>& work) {
    // strict bend checks keep long thin hulls tight; near-degenerate input may need plain ones
    for (const Checks checks : {Checks::strict, Checks::plain}) {
      if (try_add(apex, seed, -eps_, checks, work) || try_add(apex, seed, eps_, checks, work)) {
        return;
      }
    }
    // last resort, so no clearly outside point is lost: any simple cap, convex or not (a
    // concavity beyond the convexity tolerance then shows up in make_closed_mesh)
    try_add(apex, seed, 0, Checks::none, work);
  }

  bool try_add(int apex, int seed, double threshold, Checks checks, std::deque<int>& work) {
    const int stamp = ++stamp_;
    // visible faces: connected to the seed, apex above by more than the threshold
    std::vector<int> visible{seed};
    mark_[seed] = stamp;
    for (std::size_t k = 0; k < visible.size(); ++k) {
      for (int g : faces_[visible[k]].nb) {
        if (mark_[g] == stamp || !faces_[g].alive) continue;
        if (distance(g, apex) > threshold) {
          mark_[g] = stamp;
          visible.push_back(g);
        }
      }
    }

    // A tolerance can misjudge faces the apex is nearly coplanar with, leaving the cap of new
    // faces concave. Each repair grows the visible region: by the old face beside a concave
    // horizon edge, or by every face around a reflex horizon vertex (which the apex hides), so
    // the loop ends after at most one round per face.
    std::vector<HorizonEdge> horizon;
    std::vector<HullFace> created;
    for (std::size_t round = 0;; ++round) {
      if (round > faces_.size() || !horizon_of(visible, stamp, horizon)) return false;
      // new faces need an area and must face away from the interior point
      created.clear();
      bool ok = true;
      for (std::size_t h = 0; ok && h < horizon.size(); ++h) {
        HullFace face;
        face.v = {horizon[h].a, horizon[h].b, apex};
        ok = set_plane(face) && face.normal.dot(inner_ - center_) - face.offset < 0;
        created.push_back(std::move(face));
      }
      int grow_face = -1, hide_vertex = -1;
      for (std::size_t h = 0; ok && checks != Checks::none && h < horizon.size(); ++h) {
        const auto& e = horizon[h];
        // slivers first: one vertex near the line of the longest edge. The apex near a horizon
        // vertex is a near-duplicate, better left out; the apex near the horizon edge means the
        // old face beside it is seen edge-on; a horizon vertex near the line to the apex is
        // hidden (it lies between the apex and the other end).
        const Vec3 &pa = p_[e.a], &pb = p_[e.b], &pc = p_[apex];
        const double ab = (pb - pa).norm(), bc = (pc - pb).norm(), ca = (pa - pc).norm();
        const double twice_area = area_vector(pa, pb, pc).norm();
        if (twice_area <= kSliver * eps_ * std::max({ab, bc, ca})) {
          if (std::min(bc, ca) <= eps_) {
            ok = false;
          } else if (ab >= bc && ab >= ca) {
            grow_face = e.face;
          } else {
            hide_vertex = bc >= ca ? e.a : e.b;
          }
          break;
        }
      }
      // then bends (a sliver's plane is unreliable, so slivers are resolved first)
      for (std::size_t h = 0; ok && checks != Checks::none && grow_face < 0 && hide_vertex < 0 && h < horizon.size();
           ++h) {
        const auto& e = horizon[h];
        // the edge with the old face across: bent the wrong way either side means that face
        // should have been visible
        const int far_old = faces_[e.face].v[(e.slot + 2) % 3];
        if (bent(created[h], e.a, e.b, far_old, checks) || bent(faces_[e.face], e.a, e.b, apex, checks)) {
          grow_face = e.face;
          break;
        }
        // the edge b -> apex with the next new face: bent the wrong way means b is reflex, so
        // the apex hides it (if that cuts off too much, b comes back as an outside point)
        const std::size_t next = static_cast<std::size_t>(start_[e.b]);
        if (bent(created[h], e.b, apex, horizon[next].b, checks) || bent(created[next], e.b, apex, e.a, checks)) {
          hide_vertex = e.b;
          break;
        }
      }
      for (const auto& e : horizon) start_[e.a] = end_[e.b] = -1;
      if (!ok) return false;
      if (grow_face < 0 && hide_vertex < 0) break;
      if (grow_face >= 0) {
        mark_[grow_face] = stamp;
        visible.push_back(grow_face);
      } else {
        for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
          const auto& v = faces_[f].v;
          if (faces_[f].alive && mark_[f] != stamp &&
              (v[0] == hide_vertex || v[1] == hide_vertex || v[2] == hide_vertex)) {
            mark_[f] = stamp;
            visible.push_back(f);
          }
        }
      }
    }
    // the final horizon is valid: record its loop links again for gluing
    for (std::size_t h = 0; h < horizon.size(); ++h) {
      start_[horizon[h].a] = static_cast<int>(h);
      end_[horizon[h].b] = static_cast<int>(h);
    }

    // new faces (a, b, apex) glued to the horizon and to each other
    const int base = static_cast<int>(faces_.size());
    for (std::size_t h = 0; h < horizon.size(); ++h) {
      const auto& e = horizon[h];
      HullFace& face = created[h];
      face.nb[0] = e.face;
      face.nb[1] = base + start_[e.b];  // edge b -> apex meets apex -> b of the face starting at b
      face.nb[2] = base + end_[e.a];    // edge apex -> a meets a -> apex of the face ending at a
      faces_[e.face].nb[e.slot] = base + static_cast<int>(h);
    }
    for (const auto& e : horizon) start_[e.a] = end_[e.b] = -1;
    for (auto& face : created) faces_.push_back(std::move(face));
    mark_.resize(faces_.size(), -1);

    // retire the visible faces, handing their outside points to the new faces; vertices that
    // leave the hull with them are handed over too, since near-coplanar faces judged visible
    // can leave such a vertex above the new cap (each may come back a bounded number of times)
    const int end = static_cast<int>(faces_.size());
    for (int f : visible) faces_[f].alive = false;
    for (const auto& e : horizon) seen_[e.a] = apex;
    seen_[apex] = apex;
    for (int f : visible) {
      for (int q : faces_[f].outside) assign(q, base, end);
      faces_[f].outside.clear();
      faces_[f].outside.shrink_to_fit();
      for (int q : faces_[f].v) {
        if (seen_[q] == apex) continue;
        seen_[q] = apex;
        if (requeued_[q]++ < kMaxRequeue) assign(q, base, end);
      }
    }
    for (int f = base; f < static_cast<int>(faces_.size()); ++f) {
      if (!faces_[f].outside.empty()) work.push_back(f);
    }
    return true;
  }

  // Whether vertex `far` of a neighbour sharing edge (a, b) with `face` lies above the face's
  // plane by more than the tolerance. Strict: the tolerance is scaled by the vertex's distance
  // from the edge over the diagonal, which bounds the bend angle, so vertices far along a long
  // thin hull stay inside it too.
  bool bent(const HullFace& face, int a, int b, int far, Checks checks) const {
    if (checks != Checks::strict) return height(face, far) > eps_;
    const Vec3 edge = (p_[b] - p_[a]).normalized();
    const double arm = edge.cross(p_[far] - p_[a]).norm();
    return height(face, far) > eps_ * std::max(arm / diag_, kMinBend);
  }

  // signed distance of point i above the plane of a face (unit: m)
  double height(const HullFace& face, int i) const { return face.normal.dot(p_[i] - center_) - face.offset; }

  const std::vector<Vec3>& p_;
  std::vector<HullFace> faces_;
  std::vector<int> mark_;  // visit stamp per face
  int stamp_ = 0;
  std::vector<int> start_, end_;  // per point: horizon edge starting / ending there, or -1
  std::vector<int> seen_;         // per point: the last apex whose removed faces it was on
  std::vector<int> requeued_;     // per point: how often it was handed back after removal
  double eps_ = 0;
  double diag_ = 0;
  Vec3 center_ = Vec3::Zero();  // planes are stored relative to the box centre (precision)
  Vec3 inner_ = Vec3::Zero();   // centroid of the first tetrahedron: strictly inside
};

}  // namespace

TriangleSoup convex_hull(const std::vector<Vec3>& points) { return Hull(points).build(); }

TriangleSoup box_soup(const Vec3& lo, const Vec3& hi) {
  if (!lo.allFinite() || !hi.allFinite() || !(lo.array() < hi.array()).all()) {
    throw std::invalid_argument("box_soup: need finite lo < hi in every coordinate");
  }
  auto corner = [&](int i, int j, int k) {
    return Vec3(i ? hi.x() : lo.x(), j ? hi.y() : lo.y(), k ? hi.z() : lo.z());
  };
  // each quad counter-clockwise seen from outside
  const int quads[6][4][3] = {
      {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}},  // -x
      {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},  // +x
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},  // -y
      {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},  // +y
      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}},  // -z
      {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},  // +z
  };
  TriangleSoup soup;
  for (const auto& q : quads) {
    Vec3 c[4];
    for (int k = 0; k < 4; ++k) c[k] = corner(q[k][0], q[k][1], q[k][2]);
    soup.push_back({c[0], c[1], c[2]});
    soup.push_back({c[0], c[2], c[3]});
  }
  return soup;
}

}  // namespace rigid::geometry
