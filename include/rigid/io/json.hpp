#pragma once
/// The JSON the project writes, all through one library: nlohmann-json (Debian
/// nlohmann-json3-dev, header-only). Objects keep their keys in insertion order (Json =
/// ordered_json), so each output keeps the key order its documentation gives.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "rigid/motion/measures.hpp"
#include "rigid/scenario/scene.hpp"

namespace rigid::io {

using Json = nlohmann::ordered_json;

/// One line, no trailing newline: compact (no spaces), numbers in the shortest form that reads
/// back to the same double, NaN and infinities as null, invalid UTF-8 replaced by U+FFFD.
std::string json_line(const Json& j);

/// The value, or null when there is none.
inline Json json_or_null(const std::optional<double>& v) { return v ? Json(*v) : Json(nullptr); }

/// An object's full physics and run settings as one JSON object (the cube's physics_json
/// attributes): its own contact model and law, density, failure rule and the time step its runs
/// take (dynamics::time_step), with a job's run settings, accuracy preset and stop rule. Keys, in order: contact,
/// restitution, normal_stiffness, shear_stiffness, friction, damping, density, failure_rule, failure_tilt_deg, step_s,
/// dt_s, safety, integrator, duration_s, free_time_s, stop_after, accuracy, rest_speed_m_s, rest_angular_speed_rad_s,
/// rest_time_s, effects.
std::string physics_json(const scenario::Scene& scene, const scenario::RunSettings& run, const std::string& accuracy,
                         int stop_after);

/// `rigid motion info --json`: one line (units g, cm/s, cm, s as the keys say): name, sources,
/// alignment, npts, dt_s, duration_s, components [{axis,label,pga_g,pgv_cm_s,pgd_cm}], with two
/// horizontals gmrotd50_pga_g, gmrotd50_pgv_cm_s, gmroti50_pga_g, gmroti50_pgv_cm_s,
/// gmroti50_angle_deg, rotd50_pga_g, rotd100_pga_g; always pgv_pga_s; with periods sa
/// [{period_s, <axis>_g..., gmrotd50_g, rotd50_g}].
std::string motion_info_json(const motion::MotionInfo& info);

}  // namespace rigid::io
