/// Triangle soup -> checked closed mesh: welding, adjacency, closedness, orientation, convexity.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "rigid/core/error.hpp"
#include "rigid/geometry/polyhedron.hpp"

namespace rigid::geometry {
namespace {

// Coordinates beyond this are rejected: it keeps diag^5 * density (inertia) far from overflow and
// no rock is a million kilometres across, even in millimetres (unit: m).
constexpr double kMaxCoordinate = 1e9;
// Floor of the degenerate-triangle height when weld_tolerance is tiny: below it a triangle normal
// is mostly rounding noise (unit: 1, fraction of the bounding-box diagonal).
constexpr double kMinRelativeHeight = 1e-12;
// A closed surface whose signed volume is below this fraction of the summed absolute volumes of
// its tetrahedra is flat (back-to-back facets): its sign would be rounding noise. A thin needle
// or slab is not flat by this measure, since its tetrahedra all have the same sign.
constexpr double kMinRelativeVolume = 1e-12;
// Welding cells are at least this fraction of the diagonal, so cell indices fit in an int64.
constexpr double kMinRelativeCell = 1e-12;

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

std::string fmt(const Vec3& v) { return "(" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + ")"; }

[[noreturn]] void fail(const std::string& source, std::size_t facet, const std::string& what) {
  throw InputError(source, 0, "facet " + std::to_string(facet) + ": " + what);
}

[[noreturn]] void fail_mesh(const std::string& source, const std::string& what) {
  throw InputError(source, 0, "mesh: " + what);
}

// Twice-area vector of triangle (a, b, c), taken at the vertex opposite the longest edge: the two
// shortest edges give the smallest rounding error in the direction.
Vec3 area_vector(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(), ca = (a - c).squaredNorm();
  if (bc >= ab && bc >= ca) return (b - a).cross(c - a);
  if (ca >= ab) return (c - b).cross(a - b);
  return (a - c).cross(b - c);
}

// Unit normal of triangle (a, b, c), or zero for a zero-area triangle.
Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = area_vector(a, b, c);
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey&) const = default;
};

struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    // lookups only, never iterated: the hash does not affect the result order
    std::uint64_t h = static_cast<std::uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(k.y) + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(k.z) + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

// One directed use of an undirected edge by a triangle.
struct EdgeUse {
  std::uint64_t key;  // (min vertex << 32) | max vertex
  int tri;
  int local;     // edge from vertex local to vertex (local+1)%3
  bool forward;  // runs from the smaller to the larger vertex index
};

struct Adjacency {
  std::vector<int> count;  // per (tri*3+local): how many triangles use this undirected edge
  std::vector<int> other;  // per (tri*3+local): the other use (tri*3+local) when count == 2
  std::vector<bool> forward;
};

Adjacency build_adjacency(const std::vector<std::array<int, 3>>& tris) {
  std::vector<EdgeUse> uses;
  uses.reserve(tris.size() * 3);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    for (int i = 0; i < 3; ++i) {
      const auto a = static_cast<std::uint32_t>(tris[t][i]);
      const auto b = static_cast<std::uint32_t>(tris[t][(i + 1) % 3]);
      const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
      uses.push_back({key, static_cast<int>(t), i, a < b});
    }
  }
  // sorting by (key, tri, local) is a total order: deterministic without a hash table
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& p, const EdgeUse& q) {
    if (p.key != q.key) return p.key < q.key;
    if (p.tri != q.tri) return p.tri < q.tri;
    return p.local < q.local;
  });
  Adjacency adj;
  adj.count.assign(uses.size(), 0);
  adj.other.assign(uses.size(), -1);
  adj.forward.assign(uses.size(), false);
  for (std::size_t begin = 0; begin < uses.size();) {
    std::size_t end = begin;
    while (end < uses.size() && uses[end].key == uses[begin].key) ++end;
    for (std::size_t k = begin; k < end; ++k) {
      const int slot = uses[k].tri * 3 + uses[k].local;
      adj.count[slot] = static_cast<int>(end - begin);
      adj.forward[slot] = uses[k].forward;
      if (end - begin == 2) {
        const auto& o = uses[k == begin ? begin + 1 : begin];
        adj.other[slot] = o.tri * 3 + o.local;
      }
    }
    begin = end;
  }
  return adj;
}

// Welds soup vertices closer than eps: the first occurrence keeps its index and position, later
// ones map to the nearest earlier representative (ties: the smaller index).
std::vector<int> weld(const TriangleSoup& soup, const Vec3& lo, double diag, double eps, std::vector<Vec3>& vertices) {
  // cells of 16 eps: a point within eps of another is in its cell or, where it lies within eps of
  // a cell face, in the neighbour across it; so a lookup visits ~2 cells, not 27
  const double cell = std::max(16 * eps, kMinRelativeCell * diag);
  auto cell_of = [&](const Vec3& p) {
    // (p - lo) / cell <= diag / (1e-12 diag): the cast cannot overflow
    return CellKey{static_cast<std::int64_t>(std::floor((p.x() - lo.x()) / cell)),
                   static_cast<std::int64_t>(std::floor((p.y() - lo.y()) / cell)),
                   static_cast<std::int64_t>(std::floor((p.z() - lo.z()) / cell))};
  };
  // each cell's kept vertices as a list threaded through `next` (no vector per cell: a scan of
  // 1e6 facets has ~5e5 occupied cells)
  std::unordered_map<CellKey, int, CellHash> first_in_cell;
  std::vector<int> next;
  // a point equal to a kept vertex welds to it (distance 0 cannot be beaten): one lookup instead
  // of 27 grid cells, for the common case of a mesh whose facets share exact corners
  std::unordered_map<CellKey, int, CellHash> exact;
  // a closed triangle mesh has about half as many vertices as facets
  first_in_cell.reserve(soup.size() / 2 + 16);
  exact.reserve(soup.size() / 2 + 16);
  next.assign(vertices.size(), -1);  // indexed like `vertices`
  next.reserve(vertices.size() + soup.size() / 2 + 16);
  auto bits_of = [](const Vec3& p) {
    return CellKey{std::bit_cast<std::int64_t>(p.x()), std::bit_cast<std::int64_t>(p.y()),
                   std::bit_cast<std::int64_t>(p.z())};
  };
  std::vector<int> index;
  index.reserve(soup.size() * 3);
  const double eps2 = eps * eps;
  for (const Triangle& t : soup) {
    for (const Vec3* p : {&t.a, &t.b, &t.c}) {
      if (const auto same = exact.find(bits_of(*p)); same != exact.end()) {
        index.push_back(same->second);
        continue;
      }
      const CellKey k = cell_of(*p);
      // the neighbours worth visiting per axis: those whose face is within eps (2 eps: rounding)
      std::int64_t from[3], to[3];
      const std::int64_t key[3] = {k.x, k.y, k.z};
      for (int axis = 0; axis < 3; ++axis) {
        const double offset = ((*p)[axis] - lo[axis]) - double(key[axis]) * cell;
        from[axis] = offset <= 2 * eps ? -1 : 0;
        to[axis] = cell - offset <= 2 * eps ? 1 : 0;
      }
      int best = -1;
      double best_d2 = 0;
      for (std::int64_t dx = from[0]; dx <= to[0]; ++dx) {
        for (std::int64_t dy = from[1]; dy <= to[1]; ++dy) {
          for (std::int64_t dz = from[2]; dz <= to[2]; ++dz) {
            const auto it = first_in_cell.find({k.x + dx, k.y + dy, k.z + dz});
            if (it == first_in_cell.end()) continue;
            for (int v = it->second; v >= 0; v = next[v]) {
              const double d2 = (vertices[v] - *p).squaredNorm();
              if (d2 > eps2) continue;
              if (best < 0 || d2 < best_d2 || (d2 == best_d2 && v < best)) {
                best = v;
                best_d2 = d2;
              }
            }
          }
        }
      }
      if (best < 0) {
        best = static_cast<int>(vertices.size());
        vertices.push_back(*p);
        const auto [head, inserted] = first_in_cell.try_emplace(k, best);
        next.push_back(inserted ? -1 : head->second);
        head->second = best;
        exact.emplace(bits_of(*p), best);
      }
      index.push_back(best);
    }
  }
  return index;
}

// Signed enclosed volume and the sum of the absolute tetrahedron volumes it is made of (the
// scale of its rounding error), with the origin at the vertex mean (physics.md §7).
std::pair<double, double> signed_volume(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& tris) {
  Vec3 o = Vec3::Zero();
  for (const Vec3& p : v) o += p;
  o /= static_cast<double>(v.size());
  double six_v = 0, six_abs = 0;
  for (const auto& t : tris) {
    const double det = (v[t[0]] - o).dot((v[t[1]] - o).cross(v[t[2]] - o));
    six_v += det;
    six_abs += std::abs(det);
  }
  return {six_v / 6.0, six_abs / 6.0};
}

// Vertex adjacency of a closed triangle mesh in compressed rows: the neighbours of vertex x are
// list[first[x]] .. list[first[x + 1] - 1] (each twice: once per facet of the edge).
struct VertexNeighbors {
  std::vector<int> first, list;
};

VertexNeighbors vertex_neighbors(const std::vector<std::array<int, 3>>& tris, std::size_t vertices) {
  VertexNeighbors n;
  n.first.assign(vertices + 1, 0);
  for (const auto& t : tris) {
    for (int x : t) n.first[static_cast<std::size_t>(x) + 1] += 2;
  }
  for (std::size_t x = 0; x < vertices; ++x) n.first[x + 1] += n.first[x];
  n.list.resize(static_cast<std::size_t>(n.first[vertices]));
  std::vector<int> fill(n.first.begin(), n.first.end() - 1);
  for (const auto& t : tris) {
    for (int i = 0; i < 3; ++i) {
      n.list[static_cast<std::size_t>(fill[t[i]]++)] = t[(i + 1) % 3];
      n.list[static_cast<std::size_t>(fill[t[i]]++)] = t[(i + 2) % 3];
    }
  }
  return n;
}

// The highest vertex in direction n reachable uphill from `start` (each step to a strictly higher
// neighbour). On a convex mesh it is the global maximum; a dent is climbed out of to its rim.
int climb(const std::vector<Vec3>& v, const VertexNeighbors& nb, const Vec3& n, int start) {
  int at = start;
  double height = n.dot(v[at]);
  for (bool moved = true; moved;) {
    moved = false;
    for (int k = nb.first[at]; k < nb.first[at + 1]; ++k) {
      const int w = nb.list[static_cast<std::size_t>(k)];
      if (n.dot(v[w]) > height) {
        at = w;
        height = n.dot(v[w]);
        moved = true;
      }
    }
  }
  return at;
}

// Solid angle of triangle (a, b, c) seen from the origin, signed by its orientation (Van Oosterom
// and Strackee 1983).
double solid_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double below = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2.0 * std::atan2(a.dot(b.cross(c)), below);
}

// Convexity without the literal O(facets x vertices) test (a million-facet scan would take
// hours): (1) no vertex lies above a facet's plane by more than the tolerance, where the highest
// vertex is found by climbing the vertex graph from the facet (a few steps on a convex mesh: the
// facet's own vertices are the top), and (2) every facet faces away from the vertex mean and the
// surface wraps it exactly once (solid angles sum to 4 pi), so the surface is embedded and no
// far part can hide above a facet where no climb leads. Throws naming the first facet that fails.
void check_convex(const ClosedMesh& mesh, double tolerance, const std::string& source) {
  const auto& v = mesh.vertices;
  const VertexNeighbors nb = vertex_neighbors(mesh.triangles, v.size());
  Vec3 centre = Vec3::Zero();
  for (const Vec3& x : v) centre += x;
  centre /= double(v.size());
  double wrapped = 0;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    const Vec3 a = v[t[0]] - centre, b = v[t[1]] - centre, c = v[t[2]] - centre;
    const Vec3 n = triangle_normal(a, b, c);
    if (!(n.dot(a) > 0)) {
      fail(source, f, "faces toward the mesh's centre " + fmt(centre) + ": the mesh is not convex");
    }
    const double limit = (n.dot(a) + n.dot(b) + n.dot(c)) / 3.0 + tolerance;
    const int top = climb(v, nb, n, t[0]);
    const double height = n.dot(v[top] - centre);
    if (height > limit) {
      fail(source, f,
           "vertex " + fmt(v[top]) + " lies " + fmt(height - limit + tolerance) +
               " m outside the plane of this facet (tolerance " + fmt(tolerance) + " m): the mesh is not convex");
    }
    wrapped += solid_angle(a, b, c);
  }
  const double turns = wrapped / (4.0 * kPi);
  if (std::lround(turns) != 1) {
    fail_mesh(source, "the surface wraps its centre " + fmt(turns) + " times, not once: the mesh is not convex");
  }
}

}  // namespace

std::vector<std::size_t> drop_collapsed_facets(TriangleSoup& soup) {
  std::vector<std::size_t> dropped;
  std::size_t kept = 0;
  for (std::size_t f = 0; f < soup.size(); ++f) {
    const Triangle& t = soup[f];
    if (t.a == t.b || t.b == t.c || t.c == t.a) {
      dropped.push_back(f);
      continue;
    }
    soup[kept++] = t;
  }
  soup.resize(kept);
  return dropped;
}

std::vector<std::array<int, 3>> triangle_neighbors(const ClosedMesh& mesh) {
  const auto nv = static_cast<long long>(mesh.vertices.size());
  for (const auto& t : mesh.triangles) {
    for (int v : t) {
      if (v < 0 || v >= nv) throw std::invalid_argument("triangle_neighbors: vertex index out of range");
    }
  }
  const Adjacency adj = build_adjacency(mesh.triangles);
  std::vector<std::array<int, 3>> nb(mesh.triangles.size(), {-1, -1, -1});
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int i = 0; i < 3; ++i) {
      const std::size_t slot = t * 3 + i;
      const int o = adj.other[slot];
      // a proper neighbour runs the shared edge the other way
      if (adj.count[slot] == 2 && adj.forward[slot] != adj.forward[o]) nb[t][i] = o / 3;
    }
  }
  return nb;
}

namespace {

// Finite, bounded coordinates; the soup's bounding box as (lo, hi).
std::pair<Vec3, Vec3> checked_bounds(const TriangleSoup& soup, const std::string& source) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (std::size_t f = 0; f < soup.size(); ++f) {
    for (const Vec3* p : {&soup[f].a, &soup[f].b, &soup[f].c}) {
      if (!p->allFinite()) fail(source, f, "vertex coordinate is NaN or infinite");
      if (p->cwiseAbs().maxCoeff() > kMaxCoordinate) {
        fail(source, f, "vertex " + fmt(*p) + " is farther than " + fmt(kMaxCoordinate) + " m from the origin");
      }
      lo = lo.cwiseMin(*p);
      hi = hi.cwiseMax(*p);
    }
  }
  return {lo, hi};
}

// Degenerate triangles: coincident vertices or a height below the weld tolerance.
void check_triangle_heights(const ClosedMesh& mesh, double min_height, const std::string& source) {
  const std::vector<Vec3>& v = mesh.vertices;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      fail(source, f, "degenerate triangle (two of its vertices coincide after welding)");
    }
    const Vec3 &a = v[t[0]], &b = v[t[1]], &c = v[t[2]];
    const double longest = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
    const double height = area_vector(a, b, c).norm() / longest;  // the smallest height
    if (!(height > min_height)) {
      fail(source, f,
           "degenerate triangle (zero area: height " + fmt(height) + " m is below the tolerance " + fmt(min_height) +
               " m)");
    }
  }
}

// Closed and manifold: every undirected edge is used by exactly two facets.
void check_closed(const ClosedMesh& mesh, const Adjacency& adj, const std::string& source) {
  const std::vector<Vec3>& v = mesh.vertices;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (int i = 0; i < 3; ++i) {
      const int n = adj.count[f * 3 + i];
      if (n == 2) continue;
      const Vec3& a = v[mesh.triangles[f][i]];
      const Vec3& b = v[mesh.triangles[f][(i + 1) % 3]];
      if (n == 1) {
        // a hole: name its facets (the first few of every open edge's facets), so it can be found
        std::size_t open = 0;
        std::string facets;
        for (std::size_t g = 0; g < mesh.triangles.size(); ++g) {
          for (int j = 0; j < 3; ++j) {
            if (adj.count[g * 3 + j] != 1) continue;
            if (open < 8) facets += (open ? ", " : "") + std::to_string(g);
            ++open;
          }
        }
        fail(source, f,
             "edge " + fmt(a) + "-" + fmt(b) + " belongs to no other facet (open edge): the mesh is not closed; " +
                 std::to_string(open) + " open edges, at facets " + facets + (open > 8 ? ", ..." : ""));
      }
      fail(source, f,
           "edge " + fmt(a) + "-" + fmt(b) + " is shared by " + std::to_string(n) + " facets (non-manifold edge)");
    }
  }
}

// Consistent orientation by breadth-first search from facet 0 (a neighbour must run the shared
// edge the other way); returns how many facets were flipped.
std::size_t orient_consistently(ClosedMesh& mesh, const Adjacency& adj, const std::string& source) {
  const std::size_t nf = mesh.triangles.size();
  std::vector<signed char> flip(nf, -1);
  std::deque<int> queue{0};
  flip[0] = 0;
  while (!queue.empty()) {
    const int t = queue.front();
    queue.pop_front();
    for (int i = 0; i < 3; ++i) {
      const int slot = t * 3 + i;
      const int o = adj.other[slot];
      const int u = o / 3;
      const bool dir_t = adj.forward[slot] != (flip[t] == 1);
      const signed char need = adj.forward[o] == !dir_t ? 0 : 1;
      if (flip[u] < 0) {
        flip[u] = need;
        queue.push_back(u);
      } else if (flip[u] != need) {
        fail(source, static_cast<std::size_t>(std::max(t, u)),
             "orientation cannot be made consistent with facet " + std::to_string(std::min(t, u)) +
                 " (an edge is used twice in the same direction: non-orientable surface)");
      }
    }
  }
  for (std::size_t f = 0; f < nf; ++f) {
    if (flip[f] < 0) fail(source, f, "not connected to facet 0: the mesh has more than one part");
  }
  std::size_t flipped = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    if (flip[f] == 1) {
      std::swap(mesh.triangles[f][1], mesh.triangles[f][2]);
      ++flipped;
    }
  }

  return flipped;
}

// Manifold vertices: the facets around each vertex form a single fan.
void check_vertex_fans(const ClosedMesh& mesh, const Adjacency& adj, const std::string& source) {
  const std::vector<Vec3>& v = mesh.vertices;
  const std::size_t nf = mesh.triangles.size();
  std::vector<int> uses_of_vertex(v.size(), 0), first_tri(v.size(), -1);
  for (std::size_t f = 0; f < nf; ++f) {
    for (int x : mesh.triangles[f]) {
      if (uses_of_vertex[x]++ == 0) first_tri[x] = static_cast<int>(f);
    }
  }
  for (std::size_t x = 0; x < v.size(); ++x) {
    // walk around x: from triangle t leave through the edge x -> next, arriving at its twin
    int t = first_tri[x], steps = 0;
    do {
      const auto& tri = mesh.triangles[t];
      const int i = tri[0] == static_cast<int>(x) ? 0 : tri[1] == static_cast<int>(x) ? 1 : 2;
      t = adj.other[t * 3 + i] / 3;
      ++steps;
    } while (t != first_tri[x] && steps <= uses_of_vertex[x]);
    if (steps != uses_of_vertex[x]) {
      fail(source, static_cast<std::size_t>(first_tri[x]),
           "vertex " + fmt(v[x]) + " joins separate fans of facets (non-manifold vertex)");
    }
  }
}

}  // namespace

ClosedMesh make_closed_mesh(const TriangleSoup& soup, const MeshOptions& options, const std::string& source) {
  if (!(std::isfinite(options.weld_tolerance) && options.weld_tolerance >= 0) ||
      !(std::isfinite(options.convexity_tolerance) && options.convexity_tolerance >= 0) ||
      !(std::isfinite(options.coplanar_angle) && options.coplanar_angle >= 0)) {
    throw std::invalid_argument("MeshOptions: tolerances must be finite and non-negative");
  }
  if (soup.empty()) fail_mesh(source, "no facets");
  if (soup.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() / 3)) {
    fail_mesh(source, "too many facets (" + std::to_string(soup.size()) + ")");
  }

  const auto [lo, hi] = checked_bounds(soup, source);
  const double diag = (hi - lo).norm();
  if (!(diag > 0)) fail(source, 0, "degenerate triangle (all vertices of the mesh coincide)");

  // weld duplicate vertices
  ClosedMesh mesh;
  const double weld_eps = options.weld_tolerance * diag;
  const std::vector<int> index = weld(soup, lo, diag, weld_eps, mesh.vertices);
  const std::vector<Vec3>& v = mesh.vertices;
  mesh.triangles.resize(soup.size());
  for (std::size_t f = 0; f < soup.size(); ++f) {
    mesh.triangles[f] = {index[3 * f], index[3 * f + 1], index[3 * f + 2]};
  }

  check_triangle_heights(mesh, std::max(weld_eps, kMinRelativeHeight * diag), source);

  Adjacency adj = build_adjacency(mesh.triangles);
  check_closed(mesh, adj, source);

  const std::size_t nf = soup.size();
  std::size_t flipped = orient_consistently(mesh, adj, source);
  if (flipped > 0) adj = build_adjacency(mesh.triangles);
  check_vertex_fans(mesh, adj, source);

  // a convex surface is a topological sphere: V - E + F = 2
  const long long euler =
      static_cast<long long>(v.size()) - static_cast<long long>(3 * nf / 2) + static_cast<long long>(nf);
  if (options.require_convex && euler != 2) {
    fail_mesh(source, "Euler characteristic V - E + F is " + std::to_string(euler) +
                          ", not 2: the surface has handles and cannot be convex");
  }

  // outward orientation: the enclosed volume must be positive
  const auto [volume, volume_scale] = signed_volume(v, mesh.triangles);
  if (!(std::abs(volume) > kMinRelativeVolume * volume_scale)) {
    fail_mesh(source, "encloses no volume (" + fmt(volume) + " m^3): the surface is flat or folds back onto itself");
  }
  if (volume < 0) {
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    flipped = nf - flipped;
  }
  if (flipped == nf) {
    mesh.warnings.push_back("orientation was inward; flipped all " + std::to_string(nf) + " facets");
  } else if (flipped > 0) {
    mesh.warnings.push_back(std::to_string(flipped) + " of " + std::to_string(nf) +
                            " facets were oriented inconsistently; flipped to face outward");
  }

  if (options.require_convex) check_convex(mesh, options.convexity_tolerance * diag, source);
  return mesh;
}

}  // namespace rigid::geometry
