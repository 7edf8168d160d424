// `rigid model import`'s work: the checked mesh (mass properties), its contact shape (a reduced
// hull or a convex decomposition), a pedestal, a settled state, and a report of what the contact
// shape costs in accuracy.
#include "rigid/scan/import.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "rigid/core/error.hpp"
#include "rigid/geometry/mesh_split.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/mesh_import.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/io/scene_writer.hpp"
#include "rigid/io/stl.hpp"
#include "rigid/scenario/scene.hpp"
#include "staging.hpp"

namespace rigid::scan {
namespace {

namespace fs = std::filesystem;

// A closed mesh from a soup the split made (both parts are closed by construction).
geometry::ClosedMesh closed_part(const geometry::TriangleSoup& soup, const std::string& what) {
  geometry::MeshOptions options;
  options.require_convex = false;
  return geometry::make_closed_mesh(soup, options, what);
}

geometry::TriangleSoup soup_of(const geometry::ClosedMesh& mesh) {
  geometry::TriangleSoup soup;
  soup.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) soup.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
  return soup;
}

ContactReport contact_shape(const std::string& body, const geometry::ClosedMesh& mesh, const ImportOptions& o) {
  ContactReport r;
  r.body = body;
  r.mesh_volume = geometry::mass_properties(mesh, 1.0).volume;
  if (o.contact_shape == "hull") {
    r.pieces.push_back(geometry::reduced_hull(mesh.vertices, o.max_vertices > 0 ? o.max_vertices : 128));
    // how deep the hull bridges the rock's hollows: the mesh vertex farthest inside it
    const auto& hull = r.pieces.front().soup;
    for (const Vec3& v : mesh.vertices) {
      double depth = 1e300;
      for (const auto& t : hull) {
        const Vec3 n = (t.b - t.a).cross(t.c - t.a).normalized();
        depth = std::min(depth, n.dot(t.a - v));
      }
      r.deepest_gap = std::max(r.deepest_gap, depth);
    }
  } else {
    geometry::DecompositionOptions d;
    d.concavity = o.concavity;
    d.max_pieces = o.max_pieces;
    if (o.max_vertices > 0) d.max_vertices = o.max_vertices;
    r.pieces = geometry::convex_decomposition(mesh, d).pieces;
  }
  for (const auto& p : r.pieces) {
    r.contact_volume += p.volume;
    r.vertices += p.vertices;
    r.reduction = std::max(r.reduction, p.reduction);
  }
  return r;
}

// Writes a body's files (the mesh and its pieces) and returns its block of the scene.
io::SceneBlock write_body(const fs::path& dir, const std::string& name, const std::string& body,
                          const geometry::ClosedMesh& mesh, const ContactReport& report, bool fixed) {
  io::SceneBlock block{body, name + "_" + body + ".stl", fixed, {}};
  io::write_stl_binary((dir / block.stl).string(), soup_of(mesh));
  for (std::size_t k = 0; k < report.pieces.size(); ++k) {
    char piece[64];
    std::snprintf(piece, sizeof piece, "%s_%s_c%03zu.stl", name.c_str(), body.c_str(), k);
    // ASCII: the shortest round-trip decimals keep every piece exactly convex
    io::write_stl_ascii((dir / piece).string(), report.pieces[k].soup, piece);
    block.contact.push_back(piece);
  }
  return block;
}

io::Json report_json(const ContactReport& r) {
  io::Json j;
  j["body"] = r.body;
  j["mesh_volume_m3"] = r.mesh_volume;
  j["contact_volume_m3"] = r.contact_volume;
  j["pieces"] = long(r.pieces.size());
  j["vertices"] = long(r.vertices);
  j["vertex_budget_hausdorff_m"] = r.reduction;
  if (r.pieces.size() == 1) j["deepest_hollow_bridged_m"] = r.deepest_gap;
  return j;
}

io::Json repair_json(const RepairedScan& scan) {
  const repair::ScanRepair& r = scan.changes;
  io::Json j;
  j["scan"] = scan.scan;
  j["facets_before"] = long(r.facets_before);
  j["facets_after"] = long(r.facets_after);
  j["facets_removed"] = long(r.facets_removed);
  j["facets_added"] = long(r.facets_added);
  j["holes_filled"] = long(r.holes_filled);
  j["holes_left"] = long(r.holes_left);
  j["edges_stitched"] = long(r.edges_stitched);
  j["self_intersections_left"] = r.self_intersections_left;
  j["volume_before_m3"] = r.volume_before;
  j["volume_after_m3"] = r.volume_after;
  return j;
}

// OUT.import.json: the options that shaped the model and what the import found.
io::Json import_json(const ImportOptions& o, const ImportResult& result) {
  io::Json report;
  report["scan"] = o.scan;
  report["scale"] = o.scale;
  report["up"] = o.up;
  report["shift_m"] = io::Json::array({result.shift.x(), result.shift.y(), result.shift.z()});
  report["contact_shape"] = o.contact_shape;
  report["flatten_base_m"] = o.flatten_base;
  report["warnings"] = result.warnings;
  report["notes"] = result.notes;
  io::Json repaired = io::Json::array();
  for (const RepairedScan& r : result.repairs) repaired.push_back(repair_json(r));
  if (o.repair) report["repair"] = repaired;
  io::Json bodies = io::Json::array();
  for (const auto& r : result.bodies) bodies.push_back(report_json(r));
  report["bodies"] = bodies;
  if (result.rocking) {
    report["alpha_rad"] = result.rocking->alpha;
    report["static_toppling_g"] = analysis::static_toppling_g(*result.rocking);
  }
  return report;
}

// The bounding box of a mesh's vertices.
std::pair<Vec3, Vec3> bounds(const std::vector<Vec3>& vertices) {
  Vec3 lo = vertices.front(), hi = lo;
  for (const Vec3& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return {lo, hi};
}

// Rock sizes a scan in metres falls between (unit: m): outside, the units are the likely mistake.
constexpr double kSmallestRock = 0.01, kLargestRock = 50;

std::string metres(double m) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g m", m);
  return buf;
}

// A pedestal scan must lie under the rock: their footprints overlap.
void check_pedestal_under_rock(const geometry::ClosedMesh& rock, const geometry::ClosedMesh& pedestal,
                               const ImportOptions& o) {
  const auto [rlo, rhi] = bounds(rock.vertices);
  const auto [plo, phi] = bounds(pedestal.vertices);
  const bool overlap = rlo.x() < phi.x() && plo.x() < rhi.x() && rlo.y() < phi.y() && plo.y() < rhi.y();
  if (!overlap) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "its footprint x %.3g..%.3g, y %.3g..%.3g m misses the rock's x %.3g..%.3g, y %.3g..%.3g m", plo.x(),
                  phi.x(), plo.y(), phi.y(), rlo.x(), rhi.x(), rlo.y(), rhi.y());
    throw InputError(
        o.pedestal, 0,
        std::string("the pedestal is not under the rock: ") + buf + " (both scans must share units, axes and origin)");
  }
  if (plo.z() >= rhi.z()) {
    throw InputError(o.pedestal, 0, "the pedestal lies above the rock (both scans must share units, axes and origin)");
  }
}

// Why a settled rock rests on nothing, as far as the import can tell.
std::string likely_cause(const scenario::LooseBlock& loose, const ImportOptions& o, double size) {
  if (!(size >= kSmallestRock && size <= kLargestRock)) {
    return "the rock is " + metres(size) + " across: is --scale right (the file's unit in metres)?";
  }
  if (loose.turn > 0.5) {
    return "it toppled off its pedestal: is --up right (the file's axis that points up, now " + o.up + ")?";
  }
  return "is the pedestal under the rock, and are --up (now " + o.up + ") and --scale right?";
}

void check_options(const ImportOptions& o) {
  if (!(o.scale > 0) || !std::isfinite(o.scale)) throw InputError("", 0, "--scale must be a positive number");
  if (!(o.flatten_base >= 0 && o.flatten_base < 1)) throw InputError("", 0, "--flatten-base must be in [0, 1) m");
  if (!(o.density >= 1 && o.density <= 1e5)) throw InputError("", 0, "--density must be between 1 and 1e5 kg/m^3");
  if (o.contact_shape != "hull" && o.contact_shape != "decompose")
    throw InputError("", 0, "--contact-shape must be hull or decompose");
  if (o.max_vertices != 0 && o.max_vertices < 4) throw InputError("", 0, "--max-vertices must be at least 4");
  if (!(o.concavity >= 0 && o.concavity < 1)) throw InputError("", 0, "--concavity must be in [0, 1)");
  if (o.max_pieces < 1) throw InputError("", 0, "--max-pieces must be at least 1");
  if (!(o.pedestal_margin >= 0 && o.pedestal_margin < 10))
    throw InputError("", 0, "--pedestal-margin must be in [0, 10) m");
  if (!(o.tilt_deg >= 0 && o.tilt_deg < 90)) throw InputError("", 0, "--tilt-rule must be in (0, 90) deg");
  if (o.split_z && !std::isfinite(*o.split_z)) throw InputError("", 0, "--split-z must be a finite height (m)");
  if (o.split_z && o.pedestal != "box") throw InputError("", 0, "give either --split-z or --pedestal FILE, not both");
  if (fs::path(o.out).filename().empty()) throw InputError("", 0, "--out needs DIR/NAME");
}

// The imported scene settled on its pedestal; InputError when the rock does not come to rest on
// it standing on its base, naming the likely cause.
scenario::Scene settled_on_pedestal(const fs::path& scene_path, const ImportOptions& o, double size,
                                    std::vector<std::string>& scene_warnings) {
  const scenario::Scene scene = io::load_scene(scene_path.string());
  scene_warnings = scene.warnings;
  const scenario::Settled settled = scenario::settle(scene, dynamics::StepSettings{});
  if (settled.loose) {
    throw InputError(o.scan, 0, scenario::describe(*settled.loose) + ": " + likely_cause(*settled.loose, o, size));
  }
  // resting on the pedestal is not enough: a rock that fell over onto a wide one does not stand
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const double turned = scenario::tilt(scene.bodies[i].orientation, settled.scene.bodies[i].orientation) * 180 / kPi;
    if (!scene.bodies[i].fixed && turned > 5.0) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "does not stand on its base: it tips over (%.0f deg) while settling on its pedestal", turned);
      throw InputError(o.scan, 0, text);
    }
  }
  return settled.scene;
}

// The scanned meshes in metres, z up, the rock's base at z = 0 centred over the origin.
struct Meshes {
  geometry::ClosedMesh rock;
  std::optional<geometry::ClosedMesh> pedestal;  // scanned or split off; none: a box
  Vec3 lo, hi;                                   // the rock's bounds before the shift
  double size = 0;                               // the rock's largest extent (unit: m)
};

// Reads the rock (and the pedestal's scan), splits, cuts the base and moves them into place.
Meshes read_meshes(const ImportOptions& o, ImportResult& result) {
  const Mat3 rotation = io::up_rotation(o.up);
  const auto read = [&](const std::string& path) {
    if (!o.repair) return io::read_scan(path, o.scale, rotation, result.warnings);
    repair::ScanRepair report;
    geometry::ClosedMesh mesh =
        io::read_scan(path, o.scale, rotation, result.warnings,
                      [&](const geometry::TriangleSoup& soup) { return repair::repair_scan(soup, report, path); });
    result.repairs.push_back({path, report});
    return mesh;
  };
  Meshes m;
  m.rock = read(o.scan);
  result.scan_facets = m.rock.triangles.size();
  if (o.split_z) {
    geometry::SplitMesh parts;
    try {
      parts = geometry::split_by_plane(m.rock, *o.split_z);
    } catch (const std::invalid_argument& e) {
      throw InputError(o.scan, 0, std::string("--split-z: ") + (std::strchr(e.what(), ':') + 2));
    }
    if (parts.level != *o.split_z)
      result.notes.push_back("split at z = " + std::to_string(parts.level) + " m (moved off a vertex)");
    m.rock = closed_part(parts.above, o.scan + " above z = " + std::to_string(parts.level));
    m.pedestal = closed_part(parts.below, o.scan + " below z = " + std::to_string(parts.level));
  }
  const double raw_volume = geometry::mass_properties(m.rock, 1.0).volume;
  if (o.flatten_base > 0) {
    const std::size_t moved = geometry::cut_base_flat(m.rock, o.flatten_base);
    // raising vertices can fold the surface where it curls under the base: check again
    const auto crossing = geometry::find_self_intersection(m.rock);
    if (crossing[0] >= 0) {
      throw InputError(o.scan, 0,
                       "--flatten-base " + std::to_string(o.flatten_base) + " folds facet " +
                           std::to_string(crossing[1]) + " through facet " + std::to_string(crossing[0]) +
                           ": use a smaller height");
    }
    result.notes.push_back("base cut flat " + std::to_string(o.flatten_base) + " m above its lowest point (" +
                           std::to_string(moved) + " vertices raised; volume " + std::to_string(raw_volume) + " -> " +
                           std::to_string(geometry::mass_properties(m.rock, 1.0).volume) + " m^3)");
  }
  // the rock's base at z = 0, centred over the origin; a pedestal scan moves with it
  std::tie(m.lo, m.hi) = bounds(m.rock.vertices);
  m.size = (m.hi - m.lo).maxCoeff();
  if (!(m.size >= kSmallestRock && m.size <= kLargestRock)) {
    result.warnings.push_back(o.scan + ": the rock is " + metres(m.size) + " across, outside " + metres(kSmallestRock) +
                              " to " + metres(kLargestRock) +
                              ": is --scale right (the file's unit in metres, 0.001 for millimetres)?");
  }
  result.shift = Vec3(-0.5 * (m.lo.x() + m.hi.x()), -0.5 * (m.lo.y() + m.hi.y()), -m.lo.z());
  for (Vec3& v : m.rock.vertices) v += result.shift;
  if (m.pedestal) {
    for (Vec3& v : m.pedestal->vertices) v += result.shift;
  } else if (o.pedestal != "box") {
    m.pedestal = read(o.pedestal);
    for (Vec3& v : m.pedestal->vertices) v += result.shift;
    check_pedestal_under_rock(m.rock, *m.pedestal, o);
  }
  return m;
}

// Writes the pedestal's and the rock's files into `dir`; returns the scene's blocks.
std::vector<io::SceneBlock> write_bodies(const fs::path& dir, const std::string& name, const Meshes& m,
                                         const ImportOptions& o, ImportResult& result) {
  std::vector<io::SceneBlock> blocks;
  if (m.pedestal) {
    result.bodies.push_back(contact_shape("pedestal", *m.pedestal, o));
    blocks.push_back(write_body(dir, name, "pedestal", *m.pedestal, result.bodies.back(), true));
  } else {
    const double depth = std::max(0.2, 0.25 * (m.hi.z() - m.lo.z()));
    const Vec3 half = 0.5 * (m.hi - m.lo);
    const std::string file = name + "_pedestal.stl";
    io::write_stl_ascii((dir / file).string(),
                        geometry::box_soup(Vec3(-half.x() - o.pedestal_margin, -half.y() - o.pedestal_margin, -depth),
                                           Vec3(half.x() + o.pedestal_margin, half.y() + o.pedestal_margin, 0)),
                        "pedestal");
    blocks.push_back({"pedestal", file, true, {}});
  }
  blocks.push_back(write_body(dir, name, "rock", m.rock, result.bodies.front(), false));
  return blocks;
}

}  // namespace

ImportResult import_scan(const ImportOptions& o) {
  check_options(o);
  const fs::path out(o.out);
  const std::string name = out.filename().string();
  ImportResult result;
  const Meshes meshes = read_meshes(o, result);
  result.bodies.push_back(contact_shape("rock", meshes.rock, o));

  Staging staging(out.parent_path(), name);
  const fs::path& dir = staging.path();
  io::SceneFile scene_file;
  scene_file.blocks = write_bodies(dir, name, meshes, o, result);
  const fs::path scene_path = dir / (name + ".toml");
  scene_file.comments = {name + ": imported from " + o.scan + " by rigid model import (--scale " +
                         std::to_string(o.scale) + " --up " + o.up + " --contact-shape " + o.contact_shape +
                         "). The rock's mass properties come from " + name +
                         "_rock.stl, its contact from the convex pieces listed with it."};
  scene_file.density = o.density;
  if (o.tilt_deg > 0) scene_file.tilt_rule_deg = o.tilt_deg;
  io::write_scene(scene_path.string(), scene_file);
  // settle it on its pedestal: the campaigns start from this state, which must rest on it
  const scenario::Scene settled = settled_on_pedestal(scene_path, o, meshes.size, result.scene_warnings);
  scene_file.state = name + ".state.toml";
  io::save_state((dir / scene_file.state).string(), settled);
  io::write_scene(scene_path.string(), scene_file);

  result.rocking = analysis::rocking_parameters(settled);
  const io::Json report = import_json(o, result);
  io::write_output_file((dir / (name + ".import.json")).string(),
                        [&](std::ostream& stream) { stream << report.dump(2) << "\n"; });
  result.written = staging.commit();
  return result;
}

}  // namespace rigid::scan
