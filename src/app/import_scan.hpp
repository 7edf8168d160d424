#pragma once
// The import pipeline of `rigid model import`, also run by `rigid shaketable calibrate` for each
// model of the scanned base it compares.
#include <optional>
#include <string>

namespace rigid::app {

struct ImportOptions {
  std::string scan;
  std::string out;               // DIR/NAME
  double scale = 1.0;            // file unit -> m
  std::string up = "z";          // the file's axis that points up
  std::string contact_shape = "hull";
  int max_vertices = 0;          // 0: 128 for a hull, 48 per piece for a decomposition
  double concavity = 0.02;
  int max_pieces = 128;
  std::string pedestal = "box";  // box or a scan of the pedestal
  double pedestal_margin = 0.02; // m
  double density = 2600;         // kg/m^3
  double flatten_base = 0;       // m: cut the base flat this far above its lowest point
  std::optional<double> split_z;  // m: one scan of rock and pedestal, cut by the plane z = split_z
  bool repair = false;            // mend self-intersections, small holes and seams (CGAL)
  double tilt_deg = 0;           // deg: failure rule "tilt" beyond this angle; 0: rule "below"
};

/// Imports a scan: checks the mesh, builds the contact shape and a pedestal, settles the rock and
/// writes OUT.toml, OUT.state.toml, OUT.import.json and the meshes; prints a report on stdout.
/// Throws InputError for bad options or a bad scan.
void import_scan(const ImportOptions& o);

}  // namespace rigid::app
