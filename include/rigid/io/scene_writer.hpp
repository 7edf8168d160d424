#pragma once
/// The one writer of TOML scene files (the format io::load_scene reads, docs/user-guide.md):
/// write_scene for a new scene (what `rigid model block`, `rigid model library` and `rigid model
/// import` leave behind) and write_derived_scene for a scene made from another (what `rigid
/// shaketable calibrate` leaves behind). Both write through a temporary renamed into place.
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace rigid::io {

/// One [[block]] of a scene file: a closed mesh and, optionally, the convex pieces its contact uses.
struct SceneBlock {
  std::string name;
  std::string stl;  ///< mesh file, relative to the scene's folder
  bool fixed = false;
  std::vector<std::string> contact;  ///< convex piece files (empty: the mesh's hull)
};

/// What a new scene file says. The physics table holds the default contact law
/// (contact::ContactLaw) with this density; a scene with other values is a derived scene.
struct SceneFile {
  std::vector<std::string> comments;    ///< the header's lines, each written as "# line"
  std::string model;                    ///< a .model file instead of [[block]] tables (or empty)
  std::string state;                    ///< the state file the runs start from (or empty)
  double density = 2600.0;              ///< unit: kg/m^3
  std::optional<double> tilt_rule_deg;  ///< the tilt failure rule's angle; none: the "below" rule
  std::vector<SceneBlock> blocks;
};

/// Writes an original Rigid model file (io::load_scene reads it): each block's mesh and whether
/// it is fixed, at the origin. Throws InputError naming `path` when it cannot be written.
void write_model_file(const std::string& path, const std::vector<SceneBlock>& blocks);

/// Writes `path`. Throws InputError naming `path` when it cannot be written (nothing is left
/// half-written) or when the description is impossible (no blocks nor model, a density that is
/// not a positive number, a tilt angle outside (0, 90) deg).
void write_scene(const std::string& path, const SceneFile& scene);

struct SceneChanges {
  /// [physics] keys to set (contact, friction, restitution, normal_stiffness, ...)
  std::vector<std::pair<std::string, std::variant<double, std::string>>> physics;
  /// Turns every free block about the vertical through the first fixed block's centre by this
  /// angle (unit: deg, counter-clockwise seen from above); the state is saved beside the scene.
  double turn_free_blocks_deg = 0;
  /// A comment for the first lines of the file.
  std::string comment;
};

/// Reads the TOML scene `source`, applies the changes and writes `dest` (TOML) and, for its
/// starting poses, `dest` with .toml replaced by .state.toml. Both through a temporary file
/// renamed into place. Throws InputError naming the file that cannot be read or written.
void write_derived_scene(const std::string& source, const std::string& dest, const SceneChanges& changes);

}  // namespace rigid::io
