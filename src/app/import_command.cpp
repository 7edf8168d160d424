// `rigid model import`: a scanned rock (OBJ, PLY, STL) to a scene the other commands run: the
// checked mesh (mass properties), its contact shape (a reduced hull or a convex decomposition),
// a pedestal, a settled state, and a report of what the contact shape costs in accuracy.
#include <cmath>
#include <cstring>
#include <optional>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rigid/core/error.hpp"
#include "rigid/geometry/contact_shape.hpp"
#include "rigid/geometry/mesh_split.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/mesh_import.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/io/stl.hpp"
#include "rigid/scenario/rocking_parameters.hpp"
#include "rigid/scenario/scene.hpp"
#include "import_scan.hpp"
#include "scene_input.hpp"

namespace rigid::app {
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

// What a body's contact shape is and what it costs, for the report.
struct ContactReport {
  std::string body;
  double mesh_volume = 0;
  double contact_volume = 0;
  std::size_t vertices = 0;
  double reduction = 0;     // largest Hausdorff distance the vertex budget cost (m)
  double deepest_gap = 0;   // hull only: deepest point of the mesh below the hull (m)
  std::vector<geometry::ConvexPiece> pieces;
};

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

// Writes a body's files (the mesh and its pieces) and returns its [[block]] table.
std::string write_body(const fs::path& dir, const std::string& name, const std::string& body,
                       const geometry::ClosedMesh& mesh, const ContactReport& report, bool fixed) {
  const std::string mesh_file = name + "_" + body + ".stl";
  io::write_stl_binary((dir / mesh_file).string(), soup_of(mesh));
  std::string table = "[[block]]\nname = \"" + body + "\"\nstl = \"" + mesh_file + "\"\nfixed = " +
                      (fixed ? "true" : "false") + "\ncontact = [";
  for (std::size_t k = 0; k < report.pieces.size(); ++k) {
    char piece[64];
    std::snprintf(piece, sizeof piece, "%s_%s_c%03zu.stl", name.c_str(), body.c_str(), k);
    // ASCII: the shortest round-trip decimals keep every piece exactly convex
    io::write_stl_ascii((dir / piece).string(), report.pieces[k].soup, piece);
    table += std::string(k ? ", " : "") + "\"" + piece + "\"";
  }
  return table + "]\n";
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

}  // namespace

void import_scan(const ImportOptions& o) {
  if (!(o.scale > 0) || !std::isfinite(o.scale)) throw InputError("", 0, "--scale must be a positive number");
  if (!(o.flatten_base >= 0 && o.flatten_base < 1)) throw InputError("", 0, "--flatten-base must be in [0, 1) m");
  if (!(o.density >= 1 && o.density <= 1e5)) throw InputError("", 0, "--density must be between 1 and 1e5 kg/m^3");
  if (o.contact_shape != "hull" && o.contact_shape != "decompose") throw InputError("", 0, "--contact-shape must be hull or decompose");
  if (o.max_vertices != 0 && o.max_vertices < 4) throw InputError("", 0, "--max-vertices must be at least 4");
  if (!(o.concavity >= 0 && o.concavity < 1)) throw InputError("", 0, "--concavity must be in [0, 1)");
  if (o.max_pieces < 1) throw InputError("", 0, "--max-pieces must be at least 1");
  if (!(o.pedestal_margin >= 0 && o.pedestal_margin < 10)) throw InputError("", 0, "--pedestal-margin must be in [0, 10) m");
  if (!(o.tilt_deg >= 0 && o.tilt_deg < 90)) throw InputError("", 0, "--tilt-rule must be in (0, 90) deg");
  const Mat3 rotation = io::up_rotation(o.up);
  const fs::path out(o.out);
  const std::string name = out.filename().string();
  if (name.empty()) throw InputError("", 0, "--out needs DIR/NAME");
  std::vector<std::string> warnings, notes;
  geometry::ClosedMesh rock = io::read_scan(o.scan, o.scale, rotation, warnings);
  const std::size_t scan_facets = rock.triangles.size();
  std::optional<geometry::ClosedMesh> split_pedestal;
  if (!std::isnan(o.split_z)) {
    if (o.pedestal != "box") throw InputError("", 0, "give either --split-z or --pedestal FILE, not both");
    geometry::SplitMesh parts;
    try {
      parts = geometry::split_by_plane(rock, o.split_z);
    } catch (const std::invalid_argument& e) {
      throw InputError(o.scan, 0, std::string("--split-z: ") + (std::strchr(e.what(), ':') + 2));
    }
    if (parts.level != o.split_z) notes.push_back("split at z = " + std::to_string(parts.level) + " m (moved off a vertex)");
    rock = closed_part(parts.above, o.scan + " above z = " + std::to_string(parts.level));
    split_pedestal = closed_part(parts.below, o.scan + " below z = " + std::to_string(parts.level));
  }
  const double raw_volume = geometry::mass_properties(rock, 1.0).volume;
  if (o.flatten_base > 0) {
    const std::size_t moved = geometry::cut_base_flat(rock, o.flatten_base);
    // raising vertices can fold the surface where it curls under the base: check again
    const auto crossing = geometry::find_self_intersection(rock);
    if (crossing[0] >= 0) {
      throw InputError(o.scan, 0, "--flatten-base " + std::to_string(o.flatten_base) + " folds facet " +
                                      std::to_string(crossing[1]) + " through facet " + std::to_string(crossing[0]) +
                                      ": use a smaller height");
    }
    notes.push_back("base cut flat " + std::to_string(o.flatten_base) + " m above its lowest point (" +
                       std::to_string(moved) + " vertices raised; volume " + std::to_string(raw_volume) + " -> " +
                       std::to_string(geometry::mass_properties(rock, 1.0).volume) + " m^3)");
  }
  // the rock's base at z = 0, centred over the origin; a pedestal scan moves with it
  Vec3 lo = rock.vertices.front(), hi = lo;
  for (const Vec3& v : rock.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Vec3 shift(-0.5 * (lo.x() + hi.x()), -0.5 * (lo.y() + hi.y()), -lo.z());
  for (Vec3& v : rock.vertices) v += shift;
  const ContactReport rock_report = contact_shape("rock", rock, o);

  if (out.has_parent_path()) fs::create_directories(out.parent_path());
  const fs::path dir = out.parent_path();
  std::string blocks;
  std::vector<ContactReport> reports{rock_report};
  if (split_pedestal) {
    geometry::ClosedMesh& pedestal = *split_pedestal;
    for (Vec3& v : pedestal.vertices) v += shift;
    reports.push_back(contact_shape("pedestal", pedestal, o));
    blocks += write_body(dir, name, "pedestal", pedestal, reports.back(), true) + "\n";
  } else if (o.pedestal == "box") {
    const double depth = std::max(0.2, 0.25 * (hi.z() - lo.z()));
    const Vec3 half = 0.5 * (hi - lo);
    const std::string file = name + "_pedestal.stl";
    io::write_stl_ascii((dir / file).string(),
                        geometry::box_soup(Vec3(-half.x() - o.pedestal_margin, -half.y() - o.pedestal_margin, -depth),
                                           Vec3(half.x() + o.pedestal_margin, half.y() + o.pedestal_margin, 0)),
                        "pedestal");
    blocks += "[[block]]\nname = \"pedestal\"\nstl = \"" + file + "\"\nfixed = true\n\n";
  } else {
    geometry::ClosedMesh pedestal = io::read_scan(o.pedestal, o.scale, rotation, warnings);
    for (Vec3& v : pedestal.vertices) v += shift;
    reports.push_back(contact_shape("pedestal", pedestal, o));
    blocks += write_body(dir, name, "pedestal", pedestal, reports.back(), true) + "\n";
  }
  blocks += write_body(dir, name, "rock", rock, rock_report, false);

  const fs::path scene_path = dir / (name + ".toml");
  const std::string header =
      "# " + name + ": imported from " + o.scan + " by rigid model import (--scale " + std::to_string(o.scale) +
      " --up " + o.up + " --contact-shape " + o.contact_shape + "). The rock's mass properties come from " + name +
      "_rock.stl, its contact from the convex pieces listed with it.\n";
  std::string physics = io::default_physics_table();
  const std::string study_density = "density = 2600.0\n";
  char density[64];
  std::snprintf(density, sizeof density, "density = %.17g\n", o.density);
  physics.replace(physics.find(study_density), study_density.size(), density);
  const std::string failure = o.tilt_deg > 0 ? "rule = \"tilt\"\ntilt_deg = " + std::to_string(o.tilt_deg) : "rule = \"below\"";
  const std::string body = physics + "\n[failure]\n" + failure + "\n\n" + blocks;
  std::ofstream(scene_path) << header << body;
  // settle it on its pedestal: the campaigns start from this state
  const scenario::Scene scene = load_scene_with_warnings(scene_path.string());
  const scenario::Scene settled = scenario::equilibrate(scene, dynamics::StepSettings{});
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const double turned = scenario::tilt(scene.bodies[i].orientation, settled.bodies[i].orientation) * 180 / kPi;
    if (!scene.bodies[i].fixed && turned > 5.0) {
      char text[200];
      std::snprintf(text, sizeof text, "does not stand on its base: it tips over (%.0f deg) while settling on its pedestal", turned);
      throw InputError(o.scan, 0, text);
    }
  }
  const std::string state = name + ".state.toml";
  io::save_state((dir / state).string(), settled);
  std::ofstream(scene_path) << header << "state = \"" << state << "\"\n\n" << body;

  io::Json report;
  report["scan"] = o.scan;
  report["scale"] = o.scale;
  report["up"] = o.up;
  report["shift_m"] = io::Json::array({shift.x(), shift.y(), shift.z()});
  report["contact_shape"] = o.contact_shape;
  report["flatten_base_m"] = o.flatten_base;
  report["warnings"] = warnings;
  report["notes"] = notes;
  io::Json bodies = io::Json::array();
  for (const auto& r : reports) bodies.push_back(report_json(r));
  report["bodies"] = bodies;
  const auto rocking = scenario::rocking_parameters(settled);
  if (rocking) {
    report["alpha_rad"] = rocking->alpha;
    report["static_toppling_g"] = std::tan(rocking->alpha);
  }
  std::ofstream(dir / (name + ".import.json")) << report.dump(2) << "\n";

  for (const auto& w : warnings) std::fprintf(stderr, "rigid: warning: %s\n", w.c_str());
  std::printf("%s: %zu facets, closed, manifold, oriented outward, no self-intersection\n", o.scan.c_str(),
              scan_facets);
  for (const auto& note : notes) std::printf("%s\n", note.c_str());
  std::printf("%-9s %13s %16s %7s %9s %22s\n", "body", "mesh m^3", "contact m^3", "pieces", "vertices",
              "budget Hausdorff m");
  for (const auto& r : reports) {
    std::printf("%-9s %13.6f %9.6f (%+5.1f%%) %7zu %9zu %22.4f\n", r.body.c_str(), r.mesh_volume, r.contact_volume,
                100 * (r.contact_volume / r.mesh_volume - 1), r.pieces.size(), r.vertices, r.reduction);
  }
  if (rock_report.pieces.size() == 1) {
    std::printf("the hull bridges hollows up to %.4f m deep (--contact-shape decompose follows them)\n",
                rock_report.deepest_gap);
  }
  if (rocking) {
    std::printf("settled: alpha %.4f rad, static toppling %.4f g towards azimuth %.0f deg, R %.4f m, p %.3f rad/s\n",
                rocking->alpha, std::tan(rocking->alpha), rocking->azimuth * 180 / kPi + 0.0, rocking->radius, rocking->p);
  }
  std::printf("wrote %s.{toml,state.toml,import.json} and its meshes\n", o.out.c_str());
}

void add_import_subcommand(CLI::App& model_command) {
  auto o = std::make_shared<ImportOptions>();
  CLI::App* cmd = model_command.add_subcommand(
      "import", "A scanned rock (OBJ, PLY, STL) to a scene: checked mesh, contact shape, pedestal, settled state");
  cmd->add_option("scan", o->scan, "The rock's closed mesh: OBJ, PLY (ASCII or binary) or STL")->required();
  cmd->add_option("--out", o->out, "Output DIR/NAME")->required();
  cmd->add_option("--scale", o->scale, "Multiplies the file's coordinates into metres (0.001 for mm)")->capture_default_str();
  cmd->add_option("--up", o->up, "The file's axis that points up: x, -x, y, -y, z, -z")->capture_default_str();
  cmd->add_option("--contact-shape", o->contact_shape,
                  "hull: one convex hull with a vertex budget; decompose: convex pieces that follow the hollows")
      ->capture_default_str();
  cmd->add_option("--max-vertices", o->max_vertices, "Vertex budget of the hull (default 128) or of each piece (48)");
  cmd->add_option("--concavity", o->concavity, "decompose: stop when the pieces exceed the mesh volume by this fraction")
      ->capture_default_str();
  cmd->add_option("--max-pieces", o->max_pieces, "decompose: at most this many pieces")->capture_default_str();
  cmd->add_option("--pedestal", o->pedestal, "box (a fixed box under the rock) or a scan of the pedestal (same units and axes)")
      ->capture_default_str();
  cmd->add_option("--split-z", o->split_z,
                  "One scan of rock and pedestal: the part above the plane z = Z (m, after --scale and --up) is "
                  "the rock, the part below its pedestal");
  cmd->add_option("--pedestal-margin", o->pedestal_margin, "box: overhang beyond the rock's footprint (m)")->capture_default_str();
  cmd->add_option("--flatten-base", o->flatten_base,
                  "Cut the base flat this far above its lowest point (m): a scan's rough base otherwise rests on its "
                  "three lowest asperities")
      ->capture_default_str();
  cmd->add_option("--density", o->density, "Rock density written to the scene (kg/m^3)")->capture_default_str();
  cmd->add_option("--tilt-rule", o->tilt_deg,
                  "Failure rule: overturned once tilted beyond this angle (deg; for a rock on a wide table, where it "
                  "cannot fall below its pedestal); default: fallen below the pedestal");
  cmd->callback([o] { import_scan(*o); });
}

}  // namespace rigid::app
