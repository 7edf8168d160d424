#pragma once
/// A base model's scene standing under a contact law: what calibrate and transfer run their
/// campaigns on. A soft contact sinks and leans the rock, and a run that started from the rigid
/// pose would begin with that motion.
#include <string>

#include "rigid/shaketable/physics.hpp"

namespace rigid::shaketable {

/// The largest tilt settling may give a rock that stands (unit: deg): beyond it the scan does not
/// stand on its base under that law.
inline constexpr double kMaxSettlingTiltDeg = 5.0;

/// The folder name of a base model with a contact law: "flat_5mm_k5e+05" or "flat_5mm_rigid".
std::string settled_name(const Physics& p);

/// Writes WORK/NAME/NAME.toml (settled_name): `base_scene` with p's contact law, and its settled
/// poses beside it (NAME.state.toml, written last); returns the scene's absolute path. Throws
/// InputError naming `scan` when settling tilts a free block more than kMaxSettlingTiltDeg.
std::string settled_scene(const std::string& scan, const std::string& base_scene, const Physics& p,
                          const std::string& work);

}  // namespace rigid::shaketable
