#pragma once
/// The scan import pipeline (`rigid model import`, also run by `rigid shaketable calibrate` for
/// each base model it compares): a scanned rock (OBJ, PLY, STL) to a scene the other commands run.
/// It reads and checks the meshes (mended with CGAL first when asked: the repair module), builds
/// the contact shape and a pedestal, settles the rock and writes the scene, its state, its meshes
/// and OUT.import.json; it returns what it did and prints nothing (the command prints the result).
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rigid/analysis/rocking_parameters.hpp"
#include "rigid/core/types.hpp"
#include "rigid/geometry/contact_shape.hpp"
#include "rigid/repair/mesh_repair.hpp"

namespace rigid::scan {

/// What to import and how. The errors name the command line's options (--scale, --out, ...).
struct ImportOptions {
  std::string scan;
  std::string out;                     ///< DIR/NAME: the files are DIR/NAME.toml, DIR/NAME.state.toml, ...
  double scale = 1.0;                  ///< file unit -> m
  std::string up = "z";                ///< the file's axis that points up
  std::string contact_shape = "hull";  ///< hull or decompose
  int max_vertices = 0;                ///< 0: 128 for a hull, 48 per piece for a decomposition
  double concavity = 0.02;
  int max_pieces = 128;
  std::string pedestal = "box";   ///< box or a scan of the pedestal
  double pedestal_margin = 0.02;  ///< unit: m
  double density = 2600;          ///< unit: kg/m^3
  double flatten_base = 0;        ///< cut the base flat this far above its lowest point (unit: m)
  std::optional<double> split_z;  ///< one scan of rock and pedestal, cut by the plane z = split_z (unit: m)
  bool repair = false;            ///< mend self-intersections, small holes and seams (CGAL)
  double tilt_deg = 0;            ///< failure rule "tilt" beyond this angle (unit: deg); 0: rule "below"
};

/// What a body's contact shape is and what it costs in accuracy.
struct ContactReport {
  std::string body;           ///< rock or pedestal
  double mesh_volume = 0;     ///< unit: m^3
  double contact_volume = 0;  ///< the pieces' summed volume (unit: m^3)
  std::size_t vertices = 0;   ///< of all pieces
  double reduction = 0;       ///< largest Hausdorff distance the vertex budget cost (unit: m)
  double deepest_gap = 0;     ///< hull only: deepest point of the mesh below the hull (unit: m)
  std::vector<geometry::ConvexPiece> pieces;
};

/// What --repair changed in one scan.
struct RepairedScan {
  std::string scan;  ///< the scan's path as given
  repair::ScanRepair changes;
};

/// What an import did, in the order it happened; OUT.import.json holds the same.
struct ImportResult {
  /// What the reader of the written scene repaired (an inward piece flipped), before the rest.
  std::vector<std::string> scene_warnings;
  std::vector<std::string> warnings;  ///< what the import mended or suspects ("SCAN: what")
  std::vector<RepairedScan> repairs;  ///< the rock's scan, then the pedestal's (with --repair)
  std::size_t scan_facets = 0;        ///< facets of the rock's scan once read (and repaired)
  std::vector<std::string> notes;     ///< where it split, how much of the base it cut
  std::vector<ContactReport> bodies;  ///< the rock, then the pedestal when scanned or split off
  Vec3 shift = Vec3::Zero();          ///< the move that put the base at z = 0 over the origin (unit: m)
  /// The settled rock's rocking parameters; none when it does not rest on three support points.
  std::optional<analysis::RockingParameters> rocking;
  std::vector<std::string> written;  ///< the files written, sorted (DIR/NAME.toml, ...)
};

/// Imports a scan. Writes nothing unless every check passes: the files are made in a private
/// folder of the output directory and moved into place at the end. Throws InputError (one line,
/// naming the scan or the option) for bad options or a scan that cannot be imported.
ImportResult import_scan(const ImportOptions& options);

}  // namespace rigid::scan
