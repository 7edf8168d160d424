#include "rigid/contact/contact.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace rigid::contact {

const char* contact_method_name(ContactMethod model) { return model == ContactMethod::rigid ? "rigid" : "penalty"; }

bool parse_contact_method(std::string_view name, ContactMethod& model) {
  if (name == "rigid") {
    model = ContactMethod::rigid;
  } else if (name == "penalty") {
    model = ContactMethod::penalty;
  } else {
    return false;
  }
  return true;
}

namespace {

constexpr int kMaxOverlapSteps = 8;
// Key bit of an edge-crossing subcontact: (side << 30) | kCrossingBit | (v0 << 9) | (slot << 1) |
// end, for the edge from vertex v0 to its neighbour number `slot` (v0 the lower-numbered end).
constexpr int kCrossingBit = 1 << 29;

double support_value(const PlacedHull& h, const Vec3& dir, int& hint) {
  return dir.dot(h.world_vertices[support_vertex(h, dir, hint)] + h.offset);
}

// Overlap of A and B measured along n (A -> B): max_A n.x - min_B n.x.
double overlap_along(const PlacedHull& a, const PlacedHull& b, const Vec3& n, SupportHints& hints) {
  return support_value(a, n, hints.a) + support_value(b, -n, hints.b);
}

// Whether world_point lies inside the block (within tolerance of its face planes) and, if so, its
// indentation `depth` (unit: m): the distance along the unit direction `exit_dir` to the plane of
// the block's face most aligned with exit_dir (the face it is pressed into). One loop over the
// faces does both.
bool inside(const geometry::ConvexPolyhedron& shape, const Mat3& rotation, const Vec3& position,
            const Vec3& world_point, const Vec3& exit_dir, double tolerance, double& depth) {
  const Vec3 p = rotation.transpose() * (world_point - position);
  const Vec3 d = rotation.transpose() * exit_dir;
  double best_alignment = -2, best_below = 0;
  for (const auto& f : shape.faces) {
    const double below = f.offset - f.normal.dot(p);  // >= 0 inside
    if (below < -tolerance) return false;
    const double alignment = f.normal.dot(d);
    if (alignment > best_alignment) {
      best_alignment = alignment;
      best_below = below;
    }
  }
  depth = best_alignment > 0 ? best_below / best_alignment : std::numeric_limits<double>::infinity();
  return true;
}

// Distance along the unit direction `exit_dir` from world_point to the plane of the block's face
// most aligned with exit_dir (the face it is pressed into), for a point known to be on or in the
// block (unit: m).
double depth_to_contact_face(const geometry::ConvexPolyhedron& shape, const Mat3& rotation, const Vec3& position,
                             const Vec3& world_point, const Vec3& exit_dir) {
  const Vec3 p = rotation.transpose() * (world_point - position);
  const Vec3 d = rotation.transpose() * exit_dir;
  double best_alignment = -2, best_below = 0;
  for (const auto& f : shape.faces) {
    const double alignment = f.normal.dot(d);
    if (alignment > best_alignment) {
      best_alignment = alignment;
      best_below = f.offset - f.normal.dot(p);
    }
  }
  return best_alignment > 0 ? best_below / best_alignment : 0.0;
}

// Clips the segment q0 -> q1 (body frame) by the block's face planes pushed out by `tolerance`
// (Cyrus-Beck), testing face `first` first (one q0 is outside of, for a quick rejection). Returns
// false when no part of it is inside; else [t0, t1], the inside part's parameters, and the faces
// through which it enters and leaves (-1 at an end inside every face).
bool clip_segment(const geometry::ConvexPolyhedron& shape, const Vec3& q0, const Vec3& q1, double tolerance, int first,
                  double& t0, double& t1, int& enter, int& leave) {
  t0 = 0;
  t1 = 1;
  enter = leave = -1;
  auto clip = [&](int index) {
    const auto& f = shape.faces[index];
    const double s0 = f.offset + tolerance - f.normal.dot(q0);  // >= 0 inside
    const double s1 = f.offset + tolerance - f.normal.dot(q1);
    if (s0 < 0 && s1 < 0) return false;
    if (s0 < 0) {
      const double t = s0 / (s0 - s1);
      if (t > t0) {
        t0 = t;
        enter = index;
      }
    } else if (s1 < 0) {
      const double t = s0 / (s0 - s1);
      if (t < t1) {
        t1 = t;
        leave = index;
      }
    }
    return t0 <= t1;
  };
  if (first >= 0 && !clip(first)) return false;
  const int nf = static_cast<int>(shape.faces.size());
  for (int f = 0; f < nf; ++f) {
    if (f != first && !clip(f)) return false;
  }
  return true;
}

// The face of `h` whose world normal is closest to `dir`, by a walk over the face adjacency
// from `hint` (temporal coherence makes it one or two moves).
int best_aligned_face(const PlacedHull& h, const Vec3& dir, int& hint) {
  const auto& faces = h.shape->faces;
  const Vec3 local = h.rotation.transpose() * dir;
  int current = hint < static_cast<int>(faces.size()) ? hint : 0;
  double best = faces[current].normal.dot(local);
  for (;;) {
    int next = current;
    for (int f : h.shape->face_neighbors[current]) {
      const double d = faces[f].normal.dot(local);
      if (d > best) {
        best = d;
        next = f;
      }
    }
    if (next == current) break;
    current = next;
  }
  hint = current;
  return current;
}

// Vertex-face, edge-face and face-face contacts have the face's normal as their common-plane
// normal. Snapping to it removes the ~1e-13 rad direction noise of the distance iteration, which
// an unstable contact (a rock balanced on a vertex) would otherwise amplify.
Vec3 snap_to_face(const PlacedHull& a, const PlacedHull& b, const Vec3& n, SupportHints& hints) {
  constexpr double kAligned = 1e-16;  // squared angle: 1e-8 rad
  const int fa = best_aligned_face(a, n, hints.face_a);
  const Vec3 na = a.rotation * a.shape->faces[fa].normal;
  if ((na - n).squaredNorm() < kAligned) return na;
  const int fb = best_aligned_face(b, -n, hints.face_b);
  const Vec3 nb = -(b.rotation * b.shape->faces[fb].normal);
  if ((nb - n).squaredNorm() < kAligned) return nb;
  return n;
}

}  // namespace

CommonPlane find_common_plane(const PlacedHull& a, const PlacedHull& b, const Vec3& previous_normal,
                              SupportHints& hints) {
  CommonPlane cp;
  LinkResult link = shortest_link(a, b, previous_normal, hints);
  if (!link.overlapping) {
    cp.normal = link.direction;
    cp.overlap = -link.distance;
    cp.point_a = link.point_a;
    cp.point_b = link.point_b;
    return cp;
  }
  // overlap step: separate virtually along the estimate, take the shortest link's direction
  const double margin = 1e-3 * (a.shape->bounding_radius + b.shape->bounding_radius);
  Vec3 n = previous_normal.normalized();
  PlacedHull shifted = b;
  double shift = 0;
  for (int iter = 0; iter < kMaxOverlapSteps; ++iter) {
    shift = overlap_along(a, b, n, hints) + margin;
    shifted.offset = b.offset + shift * n;
    link = shortest_link(a, shifted, n, hints);
    if (link.overlapping) break;  // round-off at a degenerate configuration: keep n
    const Vec3 next = link.direction;
    const bool settled = (next - n).squaredNorm() < 1e-20;
    n = next;
    if (settled) break;
  }
  n = snap_to_face(a, b, n, hints);
  // invariant (debug builds): the common plane's normal is a unit vector (or NaN from a
  // non-finite input, which the run reports as such)
  assert(!n.allFinite() || std::abs(n.norm() - 1.0) < 1e-9);
  cp.normal = n;
  cp.overlap = overlap_along(a, b, n, hints);
  if (!link.overlapping) {
    cp.point_a = link.point_a;
    cp.point_b = link.point_b - shift * n;
  } else {
    cp.point_a = a.position;
    cp.point_b = b.position;
  }
  return cp;
}

namespace {

// Edge crossings: where an edge of one block enters the other through a side face, the contact
// region has a corner that is no vertex of either block (a block overhanging its pedestal's edge,
// the pedestal's edge under the block's base; two faces overlapping crosswise). Without these
// points such a contact had no support between the vertex subcontacts, and the edge sank into
// the face unresisted (by 1.4 cm under 10 g shaking) until the last vertex left and one
// subcontact at full depth threw the block. Each end of the edge's inside part that is not the
// edge's own vertex and lies on a side face of the other block is a subcontact, indented along
// n to the face it is pressed into. Such a corner is where an edge of A crosses an edge of B
// (seen along n) and is found from either block, so A's edges suffice; and there is none when
// every vertex of one block past the other's supporting plane is inside the other (one contact
// polygon inside the other: a block standing within its pedestal's top costs nothing more).
// The scale of the search (normal, tolerance, merge distance) and the first of the pair's points
// in `out` come from collect_subcontacts.
void add_edge_crossings(const PlacedHull& edges_of, const PlacedHull& other, int side, double limit, const Vec3& n,
                        double tolerance, double same2, std::size_t first, std::vector<SubcontactPoint>& out) {
  const auto& shape = *edges_of.shape;
  const double sign = side == 0 ? 1.0 : -1.0;  // A's edges press along +n into B, B's along -n
  const Vec3 other_position = other.position + other.offset;
  // the other block's bounding sphere (about its own middle for a piece of a compound body)
  const Vec3 other_centre = other_position + other.rotation * other.shape->bounding_centre;
  const double reach2 = other.shape->bounding_radius * other.shape->bounding_radius;
  auto past = [&](int v) {  // beyond the other block's supporting plane
    return sign * n.dot(edges_of.world_vertices[v] + edges_of.offset) > sign * limit;
  };
  auto has_subcontact = [&](int v) {  // the vertex is inside the other block (found above)
    const int key = subcontact_key(side, v);
    for (std::size_t k = first; k < out.size(); ++k) {
      if (out[k].key == key) return true;
    }
    return false;
  };
  // An edge can reach into the other block only past its supporting plane, so only edges with
  // an end there are tried, each once, from its lower-numbered end when both ends are there.
  const int nv = static_cast<int>(shape.vertices.size());
  const Mat3 to_other = other.rotation.transpose();
  for (int v = 0; v < nv; ++v) {
    if (!past(v)) continue;
    const bool v_inside = has_subcontact(v);
    const auto& around = shape.vertex_neighbors[v];
    Vec3 qv{0, 0, 0};  // v in the other block's body frame, and the face it is most outside of
    int v_out = -2;    // -2: not computed yet; -1: inside every face
    for (std::size_t slot = 0; slot < around.size(); ++slot) {
      const int u = around[slot];
      const bool u_past = past(u);
      if (u_past && u < v) continue;
      if (v_inside && u_past && has_subcontact(u)) continue;  // both ends inside: all of it
      // the edge runs from its lower-numbered end; its key is that end and the other's slot
      const int v0 = std::min(v, u), v1 = std::max(v, u);
      std::size_t slot0 = slot;
      if (v0 != v) {
        const auto& list = shape.vertex_neighbors[v0];
        slot0 = static_cast<std::size_t>(std::lower_bound(list.begin(), list.end(), v1) - list.begin());
      }
      const Vec3 p0 = edges_of.world_vertices[v0] + edges_of.offset;
      const Vec3 p1 = edges_of.world_vertices[v1] + edges_of.offset;
      const Vec3 d = p1 - p0;
      const double len2 = d.squaredNorm();
      const double t_near = len2 > 0 ? std::clamp((other_centre - p0).dot(d) / len2, 0.0, 1.0) : 0.0;
      if ((p0 + t_near * d - other_centre).squaredNorm() > reach2) continue;
      if (v_out == -2) {
        qv = to_other * (edges_of.world_vertices[v] + edges_of.offset - other_position);
        double most = 0;
        v_out = -1;
        const auto& faces = other.shape->faces;
        for (std::size_t f = 0; f < faces.size(); ++f) {
          const double outside = faces[f].normal.dot(qv) - faces[f].offset - tolerance;
          if (outside > most) {
            most = outside;
            v_out = static_cast<int>(f);
          }
        }
      }
      const Vec3 qu = to_other * (edges_of.world_vertices[u] + edges_of.offset - other_position);
      const Vec3& q0 = v0 == v ? qv : qu;
      const Vec3& q1 = v0 == v ? qu : qv;
      double t0 = 0, t1 = 1;
      int enter = -1, leave = -1;
      if (!clip_segment(*other.shape, q0, q1, tolerance, v_out, t0, t1, enter, leave)) continue;
      const double t_ends[2] = {t0, t1};
      const int faces_at[2] = {enter, leave};
      for (int end = 0; end < 2; ++end) {
        const double t = t_ends[end];
        if (t <= 1e-9 || t >= 1 - 1e-9) continue;  // the edge's own vertex: handled above
        // only where the edge passes through a side face (within 60 degrees of parallel to n);
        // through a face turned towards the contact the edge just leaves the overlap, and an
        // edge-edge contact (faces at 45 degrees either side) is left to the shortest link
        const Vec3 side_normal = other.rotation * other.shape->faces[faces_at[end]].normal;
        if (std::abs(side_normal.dot(n)) > 0.5) continue;
        const Vec3 x = p0 + t * d;
        const double depth = std::min(sign * (n.dot(x) - limit), depth_to_contact_face(*other.shape, other.rotation,
                                                                                       other_position, x, -sign * n));
        if (depth <= tolerance) continue;
        const Vec3 point = x - sign * 0.5 * depth * n;
        bool duplicate = false;
        for (std::size_t k = first; k < out.size(); ++k) {
          duplicate |= (out[k].point - point).squaredNorm() < same2;
        }
        if (duplicate) continue;
        // unique while v0 < 2^20 and slot0 < 256; beyond, keys may repeat (a shear spring may
        // then be handed to another crossing: harmless, and no such mesh is realistic)
        const int index = ((v0 & 0xFFFFF) << 9) | (static_cast<int>(slot0 & 0xFF) << 1) | end;
        out.push_back({(side << 30) | kCrossingBit | index, point, depth});
      }
    }
  }
}

}  // namespace

void collect_subcontacts(const PlacedHull& a, const PlacedHull& b, const CommonPlane& plane,
                         std::vector<SubcontactPoint>& out) {
  const Vec3& n = plane.normal;
  const double scale = a.shape->bounding_radius + b.shape->bounding_radius;
  const double tolerance = 1e-9 * scale;
  // subcontact points closer than this are one contact (a fraction of the smaller block)
  const double small = std::min(a.shape->bounding_radius, b.shape->bounding_radius);
  const double same2 = 1e-6 * small * small;
  const std::size_t first = out.size();
  // supporting planes: B's lowest point and A's highest point along n
  double min_b = std::numeric_limits<double>::infinity();
  double max_a = -std::numeric_limits<double>::infinity();
  const std::size_t na = a.shape->vertices.size(), nb = b.shape->vertices.size();
  for (std::size_t i = 0; i < na; ++i) max_a = std::max(max_a, n.dot(a.world_vertices[i] + a.offset));
  for (std::size_t j = 0; j < nb; ++j) min_b = std::min(min_b, n.dot(b.world_vertices[j] + b.offset));

  // A vertex's indentation is measured along n to the plane of the face of the other block it is
  // pressed into (that block's face most aligned with n), capped by the distance to the other
  // block's supporting plane. The supporting plane alone (the plane through the other block's
  // extreme vertex along n) depends on n to first order whenever that face is not exactly
  // perpendicular to n: the normal's noise, or its switching between the two blocks' faces, then
  // moved the indentation of a vertex 0.1 m from the extreme one by 1e-5 m per 1e-4 rad, and a
  // stack of offset blocks gained energy from nothing at every switch.
  double exit = 0;
  int a_past = 0, a_inside = 0, b_past = 0, b_inside = 0;  // vertices past the other's plane / inside
  for (std::size_t i = 0; i < na; ++i) {
    const Vec3 p = a.world_vertices[i] + a.offset;
    double depth = n.dot(p) - min_b;
    if (depth <= 0) continue;
    ++a_past;
    if (!inside(*b.shape, b.rotation, b.position + b.offset, p, -n, tolerance, exit)) continue;
    ++a_inside;
    depth = std::min(depth, exit);
    if (depth <= 0) continue;
    out.push_back({subcontact_key(0, static_cast<int>(i)), p - 0.5 * depth * n, depth});
  }
  const std::size_t from_a = out.size();
  for (std::size_t j = 0; j < nb; ++j) {
    const Vec3 p = b.world_vertices[j] + b.offset;
    double depth = max_a - n.dot(p);
    if (depth <= 0) continue;
    ++b_past;
    if (!inside(*a.shape, a.rotation, a.position + a.offset, p, n, tolerance, exit)) continue;
    ++b_inside;
    depth = std::min(depth, exit);
    if (depth <= 0) continue;
    // a vertex of B sitting on a vertex of A is one contact, not two
    bool duplicate = false;
    for (std::size_t k = first; k < from_a; ++k) {
      duplicate |= (out[k].point - (p + 0.5 * depth * n)).squaredNorm() < same2;
    }
    if (duplicate) continue;
    out.push_back({subcontact_key(1, static_cast<int>(j)), p + 0.5 * depth * n, depth});
  }

  // edge crossings (add_edge_crossings); none when one contact polygon lies inside the other
  if (a_inside < a_past && b_inside < b_past) add_edge_crossings(a, b, 0, min_b, n, tolerance, same2, first, out);

  if (out.size() == first && plane.overlap > 0) {
    out.push_back({kEdgeSubcontact, 0.5 * (plane.point_a + plane.point_b), plane.overlap});
  }
#ifndef NDEBUG
  // invariant (debug builds): a pair's subcontact keys are distinct (the shear springs carried
  // from step to step are matched by key), meshes being below 2^20 vertices
  for (std::size_t i = first; i < out.size(); ++i) {
    for (std::size_t k = first; k < i; ++k) assert(out[i].key != out[k].key);
  }
#endif
}

Vec3 subcontact_force(const ContactLaw& law, const Vec3& normal, double overlap, double overlap_rate,
                      const Vec3& tangential_step, Vec3& shear_force, double& slip) {
  slip = 0;
  // normal: Hertz-type spring with hysteretic damping, never pulling (physics.md §3)
  const double elastic = law.normal_stiffness * overlap * std::sqrt(overlap);
  const double fn = std::max(0.0, elastic * (1.0 + law.damping * overlap_rate));
  // shear: carry the old force into the current tangent plane, keeping its magnitude
  const double old_magnitude = shear_force.norm();
  shear_force -= normal.dot(shear_force) * normal;
  const double projected = shear_force.norm();
  if (projected > 0) shear_force *= old_magnitude / projected;
  shear_force -= law.shear_stiffness * tangential_step;
  const double cap = law.friction * fn;
  const double magnitude = shear_force.norm();
  if (magnitude > cap) {
    slip = (magnitude - cap) / law.shear_stiffness;
    shear_force *= (magnitude > 0 ? cap / magnitude : 0.0);
  }
  return fn * normal + shear_force;
}

}  // namespace rigid::contact
