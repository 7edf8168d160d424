#pragma once
/// Scene files: the original Rigid model file (`block NAME.stl` then FIXED vx vy vz per block,
/// then optionally density K_N K_S friction damping), and Rigid's TOML scene file, which carries
/// the physical parameters, the failure rule, a saved equilibrium state and the model itself.
#include <string>

#include "rigid/scenario/scene.hpp"

namespace rigid::io {

/// Loads a scene: a `.toml` file is a TOML scene, anything else an original model file (study
/// defaults for every parameter it does not give). Throws rigid::InputError naming the file and
/// line of the first problem.
scenario::Scene load_scene(const std::string& path);

/// Parses an original Rigid model file's text; STL paths are relative to `base_dir`.
/// `source` names the text in messages; `first_line` is the line number of its first line.
scenario::Scene parse_model_text(const std::string& text, const std::string& base_dir, const std::string& source,
                                 long first_line = 1);

/// What a scene changed after loading (a campaign variant's size_scale, density, physics) must
/// still satisfy of the checks load_scene makes: a density of 1 to 1e5 kg/m^3, a positive normal
/// and shear stiffness, a friction and damping >= 0, every block's radius 1 mm to 1 km. Returns
/// the first problem, empty when there is none.
std::string scene_value_problem(const scenario::Scene& scene);

/// Writes the poses of all blocks (a saved equilibrium state) as TOML, full precision.
void save_state(const std::string& path, const scenario::Scene& scene);

/// Replaces the blocks' poses by those of a saved state; the block count and names must match.
void apply_state(const std::string& path, scenario::Scene& scene);

}  // namespace rigid::io
