#pragma once
/// `rigid shaketable transfer` as a workflow: carries a calibration's physics ensemble (each
/// member's base model, contact law and compliance, impact law, friction, weight and lapse) to
/// another scanned rock, which no table has shaken. The scan is imported once per base model and
/// settled under each member's contact law; the heading of the new rock on a future table is
/// unknown (a ring of headings) unless given. Members of the same physics merge: the source
/// rock's heading says nothing about the new one. No outcome of the new rock is read, and no
/// campaign runs (docs/validation-shaketable.md).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rigid/io/json.hpp"
#include "rigid/shaketable/calibrate.hpp"
#include "rigid/shaketable/physics.hpp"
#include "rigid/shaketable/workflow.hpp"

namespace rigid::shaketable {

struct TransferSettings {
  std::string calibration, scan, out;  ///< out: DIR/NAME
  std::string command_line;            ///< the command as typed: the document records it
  /// How the scan is imported: calibrate's settings and flags (scale, up, max_vertices,
  /// pedestal_margin, tilt_deg; check_settings checks them); the base models are the members'.
  CalibrationSettings scan_import;
  int headings = 12;                  ///< the ring of headings (unit: count)
  std::optional<double> heading_deg;  ///< the new rock's heading on the table, when known
  /// The heading is the rock's weakest rocking direction (weakest_heading_deg), either way along
  /// the table's axis: a lab that mounts a rock to test its most fragile direction
  bool heading_weakest = false;
  /// with heading_deg (heading_weakest): the ring's headings within this of it (of its axis)
  double heading_spread_deg = 0;
  /// Start over: the work folder OUT.transfer/ of an earlier transfer into the same OUT is removed
  /// first (it is otherwise resumed, and refused when its inputs differ)
  bool restart = false;
};

/// Throws InputError naming the setting (as its flag) when a value is outside its range.
void check_transfer_settings(const TransferSettings& s);

/// One physics of the carried ensemble: every source member with this physics and lapse, merged.
struct CarriedMember {
  Physics physics;
  double weight = 0;  ///< the merged members' summed weight
  double lapse = 0;   ///< the lab's lapse rate the calibration found (kept: it is the table's, not the rock's)
  int source_members = 0;
};

/// The members of a calibration document's ensemble, merged by physics and lapse (their weights
/// add), heaviest first. Throws InputError naming `file` for a member without its physics.
std::vector<CarriedMember> carried_members(const io::Json& calibration, const std::string& file);

/// The headings the new rock is seen at, as turns of the motion relative to the written scene
/// (unit: deg): the whole ring of `headings` without a known heading, else the ring's offsets
/// within the spread (the scene is then turned to the known heading); with heading_weakest, the
/// offsets within the spread of 0 or of 180 deg (a one-axis table pushes the rock both ways, and
/// which way it faced is not known).
std::vector<double> transfer_rotations(const TransferSettings& s);

/// The rock's weakest rocking direction as a heading of a one-axis table (unit: deg in the scene's
/// frame, in [0, 180)): analysis::RockingParameters::azimuth, the direction of the support edge it
/// topples over most easily, modulo 180. Throws InputError naming the scene when the rock does
/// not rest on its base (no rocking parameters).
double weakest_heading_deg(const std::string& scene);

/// What a transfer wrote, for the command to print.
struct TransferSummary {
  std::string scene, json;
  std::size_t source_members = 0, members = 0, rotations = 0;
  std::size_t physics = 0;  ///< distinct physics among the members (one scene each)
  std::string heaviest;     ///< the heaviest member's physics
  double heaviest_weight = 0;
  double wall_s = 0;
};

/// Runs the transfer (rank 0): claims OUT's work folder, imports and settles (resuming what an
/// earlier run of the same inputs finished), writes OUT.toml and OUT.calibration.json.
TransferSummary transfer_calibration(const TransferSettings& settings, const Callbacks& callbacks);

}  // namespace rigid::shaketable
