// `rigid model import`: a scanned rock (OBJ, PLY, STL) to a scene the other commands run: the
// checked mesh (mass properties), its contact shape (a reduced hull or a convex decomposition),
// a pedestal, a settled state, and a report of what the contact shape costs in accuracy.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include "commands.hpp"
#include "import_scan.hpp"
#include "rigid/core/error.hpp"
#include "rigid/geometry/contact_shape.hpp"
#include "rigid/geometry/mesh_split.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/mesh_import.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/io/scene_writer.hpp"
#include "rigid/io/stl.hpp"
#include "rigid/repair/mesh_repair.hpp"
#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/scenario/scene.hpp"
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

// The import writes into a private directory inside the output directory and moves its files
// into place only once every check has passed: a failed import leaves neither half a model nor a
// directory it created.
class Staging {
 public:
  explicit Staging(const fs::path& dir, const std::string& name) : dir_(dir.empty() ? fs::path(".") : dir) {
    std::error_code ec;
    for (fs::path level = dir_; !level.empty() && !fs::exists(level, ec); level = level.parent_path()) {
      created_.push_back(level);
      if (level == level.parent_path()) break;
    }
    fs::create_directories(dir_, ec);
    if (ec) {
      remove_created();
      throw InputError("", 0, "--out: cannot create directory " + dir_.string() + ": " + ec.message());
    }
    path_ = dir_ / ("." + name + ".import-" + std::to_string(::getpid()));
    fs::remove_all(path_, ec);
    if (!fs::create_directory(path_, ec) || ec) {
      remove_created();
      throw InputError(
          "", 0,
          "--out: cannot write in directory " + dir_.string() + ": " + (ec ? ec.message() : std::string("it exists")));
    }
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;
  ~Staging() {
    std::error_code ec;
    fs::remove_all(path_, ec);
    if (!committed_) remove_created();
  }
  const fs::path& path() const { return path_; }
  // every staged file to the output directory (replacing the files of an earlier import)
  void commit() {
    for (const auto& entry : fs::directory_iterator(path_)) {
      std::error_code ec;
      fs::rename(entry.path(), dir_ / entry.path().filename(), ec);
      if (ec) throw InputError((dir_ / entry.path().filename()).string(), 0, "cannot write it: " + ec.message());
    }
    committed_ = true;
  }

 private:
  void remove_created() {
    std::error_code ec;
    for (const fs::path& level : created_) fs::remove(level, ec);  // innermost first; only if empty
  }
  fs::path dir_, path_;
  std::vector<fs::path> created_;  // directories this import created, innermost first
  bool committed_ = false;
};

// What a body's contact shape is and what it costs, for the report.
struct ContactReport {
  std::string body;
  double mesh_volume = 0;
  double contact_volume = 0;
  std::size_t vertices = 0;
  double reduction = 0;    // largest Hausdorff distance the vertex budget cost (m)
  double deepest_gap = 0;  // hull only: deepest point of the mesh below the hull (m)
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

// What --repair changed in one scan, in a line and in the report.
std::string describe(const std::string& path, const repair::ScanRepair& r) {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "%s: --repair: %zu -> %zu facets (%zu removed, %zu added), %zu holes filled, %zu left open, %zu edge "
                "pairs stitched, %s; volume %.6g -> %.6g m^3 (%+.3f %%)",
                path.c_str(), r.facets_before, r.facets_after, r.facets_removed, r.facets_added, r.holes_filled,
                r.holes_left, r.edges_stitched,
                r.self_intersections_left ? "self-intersections left" : "no self-intersection left", r.volume_before,
                r.volume_after, 100 * (r.volume_after / r.volume_before - 1));
  return buf;
}

io::Json repair_json(const std::string& path, const repair::ScanRepair& r) {
  io::Json j;
  j["scan"] = path;
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

// The imported scene settled on its pedestal; exit 2 (InputError) when the rock does not come to
// rest on it standing on its base, naming the likely cause.
scenario::Scene settled_on_pedestal(const fs::path& scene_path, const ImportOptions& o, double size) {
  const scenario::Scene scene = load_scene_with_warnings(scene_path.string());
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

// What the import did, for the person who ran it: warnings on stderr, the rest on stdout.
void print_summary(const ImportOptions& o, const std::vector<std::string>& warnings,
                   const std::vector<std::pair<std::string, repair::ScanRepair>>& repairs,
                   const std::vector<std::string>& notes, std::size_t scan_facets,
                   const std::vector<ContactReport>& reports,
                   const std::optional<analysis::RockingParameters>& rocking) {
  const ContactReport& rock_report = reports.front();
  for (const auto& w : warnings) std::fprintf(stderr, "rigid: warning: %s\n", w.c_str());
  for (const auto& [path, r] : repairs) std::printf("%s\n", describe(path, r).c_str());
  std::printf("%s: %zu facets%s, closed, manifold, oriented outward, no self-intersection\n", o.scan.c_str(),
              scan_facets, o.repair ? " after --repair" : "");
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
                rocking->alpha, std::tan(rocking->alpha), rocking->azimuth * 180 / kPi + 0.0, rocking->radius,
                rocking->p);
  }
}

}  // namespace

void import_scan(const ImportOptions& o) {
  check_options(o);
  const Mat3 rotation = io::up_rotation(o.up);
  const fs::path out(o.out);
  const std::string name = out.filename().string();
  std::vector<std::string> warnings, notes;
  std::vector<std::pair<std::string, repair::ScanRepair>> repairs;  // scan -> what --repair changed
  const auto read = [&](const std::string& path) {
    if (!o.repair) return io::read_scan(path, o.scale, rotation, warnings);
    repair::ScanRepair report;
    geometry::ClosedMesh mesh =
        io::read_scan(path, o.scale, rotation, warnings,
                      [&](const geometry::TriangleSoup& soup) { return repair::repair_scan(soup, report, path); });
    repairs.emplace_back(path, report);
    return mesh;
  };
  geometry::ClosedMesh rock = read(o.scan);
  const std::size_t scan_facets = rock.triangles.size();
  std::optional<geometry::ClosedMesh> split_pedestal;
  if (o.split_z) {
    geometry::SplitMesh parts;
    try {
      parts = geometry::split_by_plane(rock, *o.split_z);
    } catch (const std::invalid_argument& e) {
      throw InputError(o.scan, 0, std::string("--split-z: ") + (std::strchr(e.what(), ':') + 2));
    }
    if (parts.level != *o.split_z)
      notes.push_back("split at z = " + std::to_string(parts.level) + " m (moved off a vertex)");
    rock = closed_part(parts.above, o.scan + " above z = " + std::to_string(parts.level));
    split_pedestal = closed_part(parts.below, o.scan + " below z = " + std::to_string(parts.level));
  }
  const double raw_volume = geometry::mass_properties(rock, 1.0).volume;
  if (o.flatten_base > 0) {
    const std::size_t moved = geometry::cut_base_flat(rock, o.flatten_base);
    // raising vertices can fold the surface where it curls under the base: check again
    const auto crossing = geometry::find_self_intersection(rock);
    if (crossing[0] >= 0) {
      throw InputError(o.scan, 0,
                       "--flatten-base " + std::to_string(o.flatten_base) + " folds facet " +
                           std::to_string(crossing[1]) + " through facet " + std::to_string(crossing[0]) +
                           ": use a smaller height");
    }
    notes.push_back("base cut flat " + std::to_string(o.flatten_base) + " m above its lowest point (" +
                    std::to_string(moved) + " vertices raised; volume " + std::to_string(raw_volume) + " -> " +
                    std::to_string(geometry::mass_properties(rock, 1.0).volume) + " m^3)");
  }
  // the rock's base at z = 0, centred over the origin; a pedestal scan moves with it
  const auto [lo, hi] = bounds(rock.vertices);
  const double size = (hi - lo).maxCoeff();
  if (!(size >= kSmallestRock && size <= kLargestRock)) {
    warnings.push_back(o.scan + ": the rock is " + metres(size) + " across, outside " + metres(kSmallestRock) + " to " +
                       metres(kLargestRock) + ": is --scale right (the file's unit in metres, 0.001 for millimetres)?");
  }
  const Vec3 shift(-0.5 * (lo.x() + hi.x()), -0.5 * (lo.y() + hi.y()), -lo.z());
  for (Vec3& v : rock.vertices) v += shift;
  std::optional<geometry::ClosedMesh> pedestal_scan;
  if (!split_pedestal && o.pedestal != "box") {
    pedestal_scan = read(o.pedestal);
    for (Vec3& v : pedestal_scan->vertices) v += shift;
    check_pedestal_under_rock(rock, *pedestal_scan, o);
  }
  const ContactReport rock_report = contact_shape("rock", rock, o);

  Staging staging(out.parent_path(), name);
  const fs::path& dir = staging.path();
  io::SceneFile scene_file;
  std::vector<ContactReport> reports{rock_report};
  if (split_pedestal) {
    geometry::ClosedMesh& pedestal = *split_pedestal;
    for (Vec3& v : pedestal.vertices) v += shift;
    reports.push_back(contact_shape("pedestal", pedestal, o));
    scene_file.blocks.push_back(write_body(dir, name, "pedestal", pedestal, reports.back(), true));
  } else if (pedestal_scan) {
    reports.push_back(contact_shape("pedestal", *pedestal_scan, o));
    scene_file.blocks.push_back(write_body(dir, name, "pedestal", *pedestal_scan, reports.back(), true));
  } else {
    const double depth = std::max(0.2, 0.25 * (hi.z() - lo.z()));
    const Vec3 half = 0.5 * (hi - lo);
    const std::string file = name + "_pedestal.stl";
    io::write_stl_ascii((dir / file).string(),
                        geometry::box_soup(Vec3(-half.x() - o.pedestal_margin, -half.y() - o.pedestal_margin, -depth),
                                           Vec3(half.x() + o.pedestal_margin, half.y() + o.pedestal_margin, 0)),
                        "pedestal");
    scene_file.blocks.push_back({"pedestal", file, true, {}});
  }
  scene_file.blocks.push_back(write_body(dir, name, "rock", rock, rock_report, false));

  const fs::path scene_path = dir / (name + ".toml");
  scene_file.comments = {name + ": imported from " + o.scan + " by rigid model import (--scale " +
                         std::to_string(o.scale) + " --up " + o.up + " --contact-shape " + o.contact_shape +
                         "). The rock's mass properties come from " + name +
                         "_rock.stl, its contact from the convex pieces listed with it."};
  scene_file.density = o.density;
  if (o.tilt_deg > 0) scene_file.tilt_rule_deg = o.tilt_deg;
  io::write_scene(scene_path.string(), scene_file);
  // settle it on its pedestal: the campaigns start from this state, which must rest on it
  const scenario::Scene settled = settled_on_pedestal(scene_path, o, size);
  scene_file.state = name + ".state.toml";
  io::save_state((dir / scene_file.state).string(), settled);
  io::write_scene(scene_path.string(), scene_file);

  io::Json report;
  report["scan"] = o.scan;
  report["scale"] = o.scale;
  report["up"] = o.up;
  report["shift_m"] = io::Json::array({shift.x(), shift.y(), shift.z()});
  report["contact_shape"] = o.contact_shape;
  report["flatten_base_m"] = o.flatten_base;
  report["warnings"] = warnings;
  report["notes"] = notes;
  io::Json repaired = io::Json::array();
  for (const auto& [path, r] : repairs) repaired.push_back(repair_json(path, r));
  if (o.repair) report["repair"] = repaired;
  io::Json bodies = io::Json::array();
  for (const auto& r : reports) bodies.push_back(report_json(r));
  report["bodies"] = bodies;
  const auto rocking = analysis::rocking_parameters(settled);
  if (rocking) {
    report["alpha_rad"] = rocking->alpha;
    report["static_toppling_g"] = std::tan(rocking->alpha);
  }
  io::write_output_file((dir / (name + ".import.json")).string(),
                        [&](std::ostream& out) { out << report.dump(2) << "\n"; });
  staging.commit();

  print_summary(o, warnings, repairs, notes, scan_facets, reports, rocking);
  std::printf("wrote %s.{toml,state.toml,import.json} and its meshes\n", o.out.c_str());
}

void add_import_subcommand(CLI::App& model_command) {
  auto o = std::make_shared<ImportOptions>();
  CLI::App* cmd = model_command.add_subcommand(
      "import", "A scanned rock (OBJ, PLY, STL) to a scene: checked mesh, contact shape, pedestal, settled state");
  cmd->add_option("scan", o->scan, "The rock's closed mesh: OBJ, PLY (ASCII or binary) or STL")->required();
  cmd->add_option("--out", o->out, "Output DIR/NAME")->required();
  cmd->add_option("--scale", o->scale, "Multiplies the file's coordinates into metres (0.001 for mm)")
      ->capture_default_str();
  cmd->add_option("--up", o->up, "The file's axis that points up: x, -x, y, -y, z, -z")->capture_default_str();
  cmd->add_option("--contact-shape", o->contact_shape,
                  "hull: one convex hull with a vertex budget; decompose: convex pieces that follow the hollows")
      ->capture_default_str();
  cmd->add_option("--max-vertices", o->max_vertices, "Vertex budget of the hull (default 128) or of each piece (48)");
  cmd->add_option("--concavity", o->concavity,
                  "decompose: stop when the pieces exceed the mesh volume by this fraction")
      ->capture_default_str();
  cmd->add_option("--max-pieces", o->max_pieces, "decompose: at most this many pieces")->capture_default_str();
  cmd->add_option("--pedestal", o->pedestal,
                  "box (a fixed box under the rock) or a scan of the pedestal (same units and axes)")
      ->capture_default_str();
  cmd->add_option("--split-z", o->split_z,
                  "One scan of rock and pedestal: the part above the plane z = Z (m, after --scale and --up) is "
                  "the rock, the part below its pedestal");
  cmd->add_option("--pedestal-margin", o->pedestal_margin, "box: overhang beyond the rock's footprint (m)")
      ->capture_default_str();
  cmd->add_option("--flatten-base", o->flatten_base,
                  "Cut the base flat this far above its lowest point (m): a scan's rough base otherwise rests on its "
                  "three lowest asperities")
      ->capture_default_str();
  cmd->add_flag("--repair", o->repair,
                "Mend a scan's self-intersections, small holes (up to 64 edges) and open seams with CGAL, and "
                "report what changed (facets removed and added, holes filled, volume)");
  cmd->add_option("--density", o->density, "Rock density written to the scene (kg/m^3)")->capture_default_str();
  cmd->add_option("--tilt-rule", o->tilt_deg,
                  "Failure rule: overturned once tilted beyond this angle (deg; for a rock on a wide table, where it "
                  "cannot fall below its pedestal); default: fallen below the pedestal");
  cmd->callback([o] { import_scan(*o); });
}

}  // namespace rigid::app
