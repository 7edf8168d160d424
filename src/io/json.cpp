// The JSON writers of io (include/rigid/io/json.hpp), on nlohmann-json.
#include "rigid/io/json.hpp"

#include "rigid/contact/contact.hpp"
#include "rigid/core/types.hpp"
#include "rigid/dynamics/world.hpp"

namespace rigid::io {

std::string json_line(const Json& j) { return j.dump(-1, ' ', false, Json::error_handler_t::replace); }

std::string physics_json(const scenario::Scene& scene, const scenario::RunSettings& run, const std::string& accuracy,
                         int stop_after) {
  const auto& law = scene.law;
  const bool tilt = scene.failure.kind == scenario::FailureRule::Kind::tilt;
  Json j;
  j["contact"] = contact::contact_method_name(law.method);
  j["restitution"] = law.restitution;
  j["normal_stiffness"] = law.normal_stiffness;
  j["shear_stiffness"] = law.shear_stiffness;
  j["friction"] = law.friction;
  j["damping"] = law.damping;
  j["density"] = scene.density;
  j["failure_rule"] = tilt ? "tilt" : "below";
  j["failure_tilt_deg"] = tilt ? scene.failure.tilt_angle * 180.0 / kPi : 0.0;
  j["step_s"] = dynamics::time_step(scene.bodies, law, run.step);
  j["dt_s"] = run.step.dt;
  j["safety"] = run.step.safety;
  j["integrator"] = run.step.rotation == dynamics::RotationIntegrator::rk4 ? "rk4" : "splitting";
  j["duration_s"] = run.duration;
  j["free_time_s"] = run.free_time;
  j["stop_after"] = stop_after;
  j["accuracy"] = accuracy;
  j["rest_speed_m_s"] = run.rest_speed;
  j["rest_angular_speed_rad_s"] = run.rest_angular_speed;
  j["rest_time_s"] = run.rest_time;
  j["effects"] = run.select_effects ? "auto" : "all";
  j["solver_tolerance"] = run.step.solver_tolerance;
  j["solver_max_sweeps"] = run.step.solver_max_sweeps;
  return json_line(j);
}

std::string motion_info_json(const motion::MotionInfo& info) {
  constexpr double g = kGravity, cm = 100.0;
  Json j;
  j["name"] = info.name;
  j["sources"] = info.sources;
  j["alignment"] = info.alignment;
  j["npts"] = info.npts;
  j["dt_s"] = info.dt;
  j["duration_s"] = info.duration;
  Json components = Json::array();
  for (const auto& a : info.axes) {
    Json c;
    c["axis"] = std::string(1, a.axis);
    c["label"] = a.label;
    c["pga_g"] = a.peaks.pga / g;
    c["pgv_cm_s"] = a.peaks.pgv * cm;
    c["pgd_cm"] = a.peaks.pgd * cm;
    components.push_back(std::move(c));
  }
  j["components"] = std::move(components);
  if (info.two_horizontals) {
    const auto& h = info.horizontal;
    j["gmrotd50_pga_g"] = h.gmrotd50_pga / g;
    j["gmrotd50_pgv_cm_s"] = h.gmrotd50_pgv * cm;
    j["gmroti50_pga_g"] = h.gmroti50_pga / g;
    j["gmroti50_pgv_cm_s"] = h.gmroti50_pgv * cm;
    j["gmroti50_angle_deg"] = h.gmroti50_angle_deg;
    j["rotd50_pga_g"] = h.rotd50_pga / g;
    j["rotd100_pga_g"] = h.rotd100_pga / g;
  }
  j["pgv_pga_s"] = info.pgv_pga;
  if (!info.spectrum.empty()) {
    Json sa = Json::array();
    for (const auto& s : info.spectrum) {
      Json v;
      v["period_s"] = s.period;
      for (std::size_t k = 0; k < s.per_axis.size() && k < info.axes.size(); ++k)
        v[std::string(1, info.axes[k].axis) + "_g"] = s.per_axis[k] / g;
      if (info.two_horizontals) {
        v["gmrotd50_g"] = s.gmrotd50 / g;
        v["rotd50_g"] = s.rotd50 / g;
      }
      sa.push_back(std::move(v));
    }
    j["sa"] = std::move(sa);
  }
  return json_line(j);
}

}  // namespace rigid::io
