/// Checked mesh + mass properties -> convex block in its principal body frame, with planar faces.
#include "rigid/geometry/polyhedron.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

namespace rigid::geometry {
namespace {

// Twice-area vector, crossed at the vertex opposite the longest edge (smallest rounding error).
Vec3 area_vector(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(), ca = (a - c).squaredNorm();
  if (bc >= ab && bc >= ca) return (b - a).cross(c - a);
  if (ca >= ab) return (c - b).cross(a - b);
  return (a - c).cross(b - c);
}

// Angle between unit vectors; atan2 keeps it accurate near zero, where acos loses digits.
double angle_between(const Vec3& u, const Vec3& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); }

// Boundary loop of a set of triangles (directed edges whose twin lies outside the set), starting
// at its smallest vertex. Empty when the boundary is not one simple loop (a pinch or a hole).
std::vector<int> boundary_loop(const std::vector<std::array<int, 3>>& tris, const std::vector<std::array<int, 3>>& nb,
                               const std::vector<int>& face_of, const std::vector<int>& members, int face) {
  std::map<int, int> next;  // ordered: the result does not depend on hashing
  std::size_t edges = 0;
  for (int t : members) {
    for (int i = 0; i < 3; ++i) {
      if (face_of[nb[t][i]] == face) continue;
      const int a = tris[t][i], b = tris[t][(i + 1) % 3];
      if (!next.emplace(a, b).second) return {};  // vertex visited twice: pinched region
      ++edges;
    }
  }
  if (next.empty()) return {};
  std::vector<int> loop;
  int v = next.begin()->first;
  do {
    loop.push_back(v);
    const auto it = next.find(v);
    if (it == next.end() || loop.size() > edges) return {};
    v = it->second;
  } while (v != loop.front());
  if (loop.size() != edges) return {};  // more than one loop: the region has a hole
  return loop;
}

}  // namespace

ConvexPolyhedron make_polyhedron(const ClosedMesh& mesh, const MassProperties& props, const MeshOptions& options) {
  if (mesh.triangles.empty()) throw std::invalid_argument("make_polyhedron: mesh has no triangles");
  const std::vector<std::array<int, 3>> nb = triangle_neighbors(mesh);  // checks indices
  for (const auto& n : nb) {
    if (n[0] < 0 || n[1] < 0 || n[2] < 0) {
      throw std::invalid_argument("make_polyhedron: mesh is not closed (use make_closed_mesh)");
    }
  }
  if (!props.principal_axes.allFinite() || !props.centroid.allFinite() ||
      std::abs(props.principal_axes.determinant() - 1) > 1e-6) {
    throw std::invalid_argument("make_polyhedron: principal_axes must be a rotation");
  }

  ConvexPolyhedron poly;
  poly.volume = props.volume;
  poly.mass = props.mass;
  poly.inertia = props.principal_moments;
  poly.rotation = Quat(props.principal_axes).normalized();
  poly.translation = props.centroid;

  // body frame: x_body = R^T (x_mesh - c), with R the (normalised) rotation actually stored, so
  // rotation * x_body + translation reproduces the mesh to rounding
  const Mat3 rt = poly.rotation.toRotationMatrix().transpose();
  poly.vertices.reserve(mesh.vertices.size());
  for (const Vec3& x : mesh.vertices) poly.vertices.push_back(rt * (x - props.centroid));
  const auto& v = poly.vertices;
  const auto& tris = mesh.triangles;
  const int nt = static_cast<int>(tris.size());

  std::vector<Vec3> area(tris.size()), normal(tris.size());
  for (int t = 0; t < nt; ++t) {
    area[t] = area_vector(v[tris[t][0]], v[tris[t][1]], v[tris[t][2]]);
    const double len = area[t].norm();
    normal[t] = len > 0 ? Vec3(area[t] / len) : Vec3::Zero();
  }

  // merge coplanar neighbours by region growing from each unassigned seed, in index order;
  // comparing with the seed's normal (not the neighbour's) stops slow drift over a curved mesh
  std::vector<int> face_of(tris.size(), -1);
  std::vector<std::vector<int>> members;
  std::vector<std::vector<int>> loops;
  for (int seed = 0; seed < nt; ++seed) {
    if (face_of[seed] >= 0) continue;
    const int f = static_cast<int>(members.size());
    std::vector<int> region{seed};
    face_of[seed] = f;
    for (std::size_t k = 0; k < region.size(); ++k) {
      for (int i = 0; i < 3; ++i) {
        const int u = nb[region[k]][i];
        if (face_of[u] >= 0) continue;
        if (angle_between(normal[seed], normal[u]) < options.coplanar_angle) {
          face_of[u] = f;
          region.push_back(u);
        }
      }
    }
    std::vector<int> loop = boundary_loop(tris, nb, face_of, region, f);
    if (!loop.empty()) {
      members.push_back(std::move(region));
      loops.push_back(std::move(loop));
      continue;
    }
    // not a disk (possible only for meshes convex merely within tolerance): keep its triangles
    // as separate faces rather than build a wrong polygon
    for (int t : region) face_of[t] = -1;
    for (int t : region) {
      face_of[t] = static_cast<int>(members.size());
      members.push_back({t});
      loops.push_back({tris[t][0], tris[t][1], tris[t][2]});
    }
  }

  // face planes: area-weighted normal; the offset supports every vertex of the face
  const int nfaces = static_cast<int>(members.size());
  poly.faces.resize(members.size());
  for (int f = 0; f < nfaces; ++f) {
    Vec3 n = Vec3::Zero();
    for (int t : members[f]) n += area[t];
    n.normalize();
    double offset = -std::numeric_limits<double>::infinity();
    for (int t : members[f]) {
      for (int x : tris[t]) offset = std::max(offset, n.dot(v[x]));
    }
    poly.faces[f].normal = n;
    poly.faces[f].offset = offset;
    poly.faces[f].vertices = loops[f];
  }

  // feature edges: each loop edge a -> b runs counter-clockwise on its own face; record it from
  // the face on which the smaller index comes first, so every edge appears once
  std::map<std::pair<int, int>, int> face_of_directed;
  for (int t = 0; t < nt; ++t) {
    for (int i = 0; i < 3; ++i) {
      face_of_directed[{tris[t][i], tris[t][(i + 1) % 3]}] = face_of[t];
    }
  }
  poly.vertex_neighbors.assign(v.size(), {});
  poly.face_neighbors.assign(members.size(), {});
  for (int f = 0; f < nfaces; ++f) {
    const auto& loop = loops[f];
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k], b = loop[(k + 1) % loop.size()];
      if (a > b) continue;
      const int g = face_of_directed.at({b, a});
      poly.edges.push_back({a, b, f, g});
      poly.vertex_neighbors[a].push_back(b);
      poly.vertex_neighbors[b].push_back(a);
      poly.face_neighbors[f].push_back(g);
      poly.face_neighbors[g].push_back(f);
    }
  }
  auto sort_unique = [](std::vector<int>& list) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  };
  for (auto& list : poly.vertex_neighbors) sort_unique(list);
  for (auto& list : poly.face_neighbors) sort_unique(list);

  for (const Vec3& x : v) poly.bounding_radius = std::max(poly.bounding_radius, x.norm());
  return poly;
}

ConvexPolyhedron make_piece(const ClosedMesh& convex_mesh, const ConvexPolyhedron& body, const MeshOptions& options) {
  // into the body frame first; make_polyhedron with an identity frame then keeps it
  ClosedMesh in_body = convex_mesh;
  const Mat3 rt = body.rotation.toRotationMatrix().transpose();
  for (Vec3& x : in_body.vertices) x = rt * (x - body.translation);
  MassProperties frame;
  frame.volume = mass_properties(in_body, 1.0).volume;
  ConvexPolyhedron piece = make_polyhedron(in_body, frame, options);
  piece.rotation = body.rotation;
  piece.translation = body.translation;
  // the sphere about the piece's middle: pieces far from the body's centroid get tight spheres
  Vec3 lo = piece.vertices.front(), hi = lo;
  for (const Vec3& x : piece.vertices) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  piece.bounding_centre = 0.5 * (lo + hi);
  piece.bounding_radius = 0;
  for (const Vec3& x : piece.vertices)
    piece.bounding_radius = std::max(piece.bounding_radius, (x - piece.bounding_centre).norm());
  return piece;
}

void offset_mass_centre(ConvexPolyhedron& shape, std::vector<ConvexPolyhedron>& pieces, const Vec3& offset) {
  if (!offset.allFinite()) throw std::invalid_argument("the offset is not finite");
  for (const Face& f : shape.faces) {
    if (f.normal.dot(offset) >= f.offset) {
      throw std::invalid_argument("the centre of mass would lie outside the block");
    }
  }
  auto shift = [&offset](ConvexPolyhedron& p) {
    for (Vec3& v : p.vertices) v -= offset;
    for (Face& f : p.faces) f.offset -= f.normal.dot(offset);
  };
  shift(shape);
  shape.translation += shape.rotation * offset;
  shape.bounding_radius = 0;
  for (const Vec3& v : shape.vertices) shape.bounding_radius = std::max(shape.bounding_radius, v.norm());
  for (ConvexPolyhedron& piece : pieces) {
    shift(piece);
    piece.bounding_centre -= offset;
    piece.translation = shape.translation;
  }
}

CompoundBody build_compound(const ClosedMesh& mesh, const std::vector<ClosedMesh>& convex_pieces, double density,
                            const MeshOptions& options) {
  if (convex_pieces.empty()) throw std::invalid_argument("build_compound: no contact pieces");
  const MassProperties props = mass_properties(mesh, density);
  std::vector<Vec3> corners;
  for (const ClosedMesh& piece : convex_pieces)
    corners.insert(corners.end(), piece.vertices.begin(), piece.vertices.end());
  MeshOptions hull_options = options;
  hull_options.require_convex = true;
  const ClosedMesh outline = make_closed_mesh(convex_hull(corners), hull_options, "outline of the contact pieces");
  CompoundBody body;
  body.shape = make_polyhedron(outline, props, options);
  for (const ClosedMesh& piece : convex_pieces) body.pieces.push_back(make_piece(piece, body.shape, options));
  return body;
}

ConvexPolyhedron build_block(const TriangleSoup& soup, double density, const MeshOptions& options,
                             const std::string& source, std::vector<std::string>* warnings) {
  // cheap argument check before the mesh work
  if (!(std::isfinite(density) && density > 0)) {
    throw std::invalid_argument("build_block: density must be positive and finite");
  }
  const ClosedMesh mesh = make_closed_mesh(soup, options, source);
  if (warnings) warnings->insert(warnings->end(), mesh.warnings.begin(), mesh.warnings.end());
  const MassProperties props = mass_properties(mesh, density);
  return make_polyhedron(mesh, props, options);
}

}  // namespace rigid::geometry
