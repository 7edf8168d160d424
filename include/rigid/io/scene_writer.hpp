#pragma once
/// Writes a scene derived from another: the same blocks and meshes (paths re-based to the new
/// file's folder), other physical parameters, and the rock turned on its pedestal. What
/// `rigid shaketable calibrate` leaves behind is such a scene: every other command runs it.
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace rigid::io {

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
