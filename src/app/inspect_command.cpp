// `rigid inspect`: what Rigid made of a scene's meshes (mass properties and checks).
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/scene_file.hpp"
#include "scene_input.hpp"

namespace rigid::app {
namespace {

io::Json vec_json(const Vec3& v) { return io::Json::array({v.x(), v.y(), v.z()}); }

void inspect(const std::string& path, bool json) {
  // loading runs every mesh check (closed, oriented, convex); a failure throws before this point
  const scenario::Scene scene = load_scene_with_warnings(path);
  for (const auto& b : scene.bodies) {
    const auto& s = b.shape;
    if (json) {
      io::Json j;
      j["block"] = b.name;
      j["fixed"] = b.fixed;
      j["vertices"] = long(s.vertices.size());
      j["faces"] = long(s.faces.size());
      j["volume_m3"] = s.volume;
      j["mass_kg"] = s.mass;
      j["centroid_m"] = vec_json(b.position);
      j["principal_moments_kg_m2"] = vec_json(s.inertia);
      j["bounding_radius_m"] = s.bounding_radius;
      j["checks"] = io::Json::array({"closed", "oriented", "convex", "finite"});
      std::printf("%s\n", io::json_line(j).c_str());
    } else {
      std::printf("%s (%s): %zu vertices, %zu faces\n", b.name.c_str(), b.fixed ? "fixed" : "free",
                  s.vertices.size(), s.faces.size());
      std::printf("  volume %.6g m^3, mass %.6g kg\n", s.volume, s.mass);
      std::printf("  centroid (%.6g, %.6g, %.6g) m\n", b.position.x(), b.position.y(), b.position.z());
      std::printf("  principal moments %.6g %.6g %.6g kg m^2\n", s.inertia.x(), s.inertia.y(), s.inertia.z());
      std::printf("  checks passed: closed, consistently oriented, convex, finite\n");
    }
  }
  if (!json) {
    std::printf("contact model: %s (restitution %.3g, rigid model only)\n", contact::contact_model_name(scene.law.model),
                scene.law.restitution);
    std::printf("contact: K_N %.3g N/m^1.5, K_S %.3g N/m, friction %.3g, damping %.3g s/m; density %.6g kg/m^3\n",
                scene.law.normal_stiffness, scene.law.shear_stiffness, scene.law.friction,
                scene.law.damping, scene.density);
  }
}

}  // namespace

void register_inspect_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("inspect", "Check a scene's meshes and print each block's volume, mass, centroid and principal moments");
  cmd->add_option("scene", *path, "Scene: a Rigid model file or a .toml scene file")->required();
  cmd->add_flag("--json", *json, "One JSON object per block, one per line");
  cmd->callback([path, json] { inspect(*path, *json); });
}

}  // namespace rigid::app
