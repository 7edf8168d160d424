// `rigid model import`: the command line of the scan import (scan::import_scan does the work) and
// the summary it prints.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "import_report.hpp"
#include "output_options.hpp"
#include "rigid/core/types.hpp"

namespace rigid::app {
namespace {

// What --repair changed in one scan, in a line.
std::string describe(const scan::RepairedScan& scan) {
  const repair::ScanRepair& r = scan.changes;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "%s: --repair: %zu -> %zu facets (%zu removed, %zu added), %zu holes filled, %zu left open, %zu edge "
                "pairs stitched, %s; volume %.6g -> %.6g m^3 (%+.3f %%)",
                scan.scan.c_str(), r.facets_before, r.facets_after, r.facets_removed, r.facets_added, r.holes_filled,
                r.holes_left, r.edges_stitched,
                r.self_intersections_left ? "self-intersections left" : "no self-intersection left", r.volume_before,
                r.volume_after, 100 * (r.volume_after / r.volume_before - 1));
  return buf;
}

// What the import did, for the person who ran it: warnings on stderr, the rest on stdout.
void print_summary(const scan::ImportOptions& o, const scan::ImportResult& result) {
  const scan::ContactReport& rock_report = result.bodies.front();
  for (const auto& w : result.scene_warnings) std::fprintf(stderr, "rigid: warning: %s\n", w.c_str());
  for (const auto& w : result.warnings) std::fprintf(stderr, "rigid: warning: %s\n", w.c_str());
  for (const auto& r : result.repairs) std::printf("%s\n", describe(r).c_str());
  std::printf("%s: %zu facets%s, closed, manifold, oriented outward, no self-intersection\n", o.scan.c_str(),
              result.scan_facets, o.repair ? " after --repair" : "");
  for (const auto& note : result.notes) std::printf("%s\n", note.c_str());
  std::printf("%-9s %13s %16s %7s %9s %22s\n", "body", "mesh m^3", "contact m^3", "pieces", "vertices",
              "budget Hausdorff m");
  for (const auto& r : result.bodies) {
    std::printf("%-9s %13.6f %9.6f (%+5.1f%%) %7zu %9zu %22.4f\n", r.body.c_str(), r.mesh_volume, r.contact_volume,
                100 * (r.contact_volume / r.mesh_volume - 1), r.pieces.size(), r.vertices, r.reduction);
  }
  if (rock_report.pieces.size() == 1) {
    // below a tenth of a millimetre a hollow is the scan's noise, not a shape the contact misses
    if (rock_report.deepest_gap < 1e-4) {
      std::printf("the hull bridges no hollow deeper than 0.1 mm\n");
    } else {
      std::printf("the hull bridges hollows up to %.2g m deep (--contact-shape decompose follows them)\n",
                  rock_report.deepest_gap);
    }
  }
  if (const auto& rocking = result.rocking) {
    std::printf("settled: alpha %.4f rad, static toppling %.4f g towards azimuth %.0f deg, R %.4f m, p %.3f rad/s\n",
                rocking->alpha, analysis::static_toppling_g(*rocking), rocking->azimuth * 180 / kPi + 0.0,
                rocking->radius, rocking->p);
  }
}

}  // namespace

void import_and_report(const scan::ImportOptions& o) {
  const scan::ImportResult result = scan::import_scan(o);
  print_summary(o, result);
  std::printf("wrote %s.{toml,state.toml,import.json} and its meshes\n", o.out.c_str());
}

void add_import_subcommand(CLI::App& model_command) {
  auto o = std::make_shared<scan::ImportOptions>();
  CLI::App* cmd = model_command.add_subcommand(
      "import", "A scanned rock (OBJ, PLY, STL) to a scene: checked mesh, contact shape, pedestal, settled state");
  cmd->add_option("scan", o->scan, "The rock's closed mesh: OBJ, PLY (ASCII or binary) or STL")->required();
  add_output_prefix(*cmd, o->out, "the scene NAME.toml, NAME.state.toml, NAME.import.json and the meshes")->required();
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
  cmd->callback([o] { import_and_report(*o); });
}

}  // namespace rigid::app
