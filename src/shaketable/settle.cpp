#include "rigid/shaketable/settle.hpp"
#include "text.hpp"

#include <cstdio>
#include <filesystem>

#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/io/scene_writer.hpp"
#include "rigid/scenario/scene.hpp"

namespace rigid::shaketable {
namespace {

namespace fs = std::filesystem;

}  // namespace

std::string settled_name(const Physics& p) {
  return p.penalty() ? format("%s_k%.3g", p.base.c_str(), p.law.normal_stiffness) : format("%s_rigid", p.base.c_str());
}

std::string settled_scene(const std::string& scan, const std::string& base_scene, const Physics& p,
                          const std::string& work) {
  const std::string name = settled_name(p);
  fs::create_directories(fs::path(work) / name);
  const std::string scene = fs::absolute(fs::path(work) / name / (name + ".toml")).lexically_normal().string();
  io::SceneChanges changes;
  changes.physics = p.contact_law_table();
  changes.comment = name + ": " + base_scene + " with the " + contact::contact_method_name(p.law.method) +
                    " contact model, settled with it";
  io::write_derived_scene(base_scene, scene, changes);
  const scenario::Scene placed = io::load_scene(scene);
  const scenario::Scene settled = scenario::equilibrate(placed, dynamics::StepSettings{});
  for (std::size_t i = 0; i < placed.bodies.size(); ++i) {
    const double turned = scenario::tilt(placed.bodies[i].orientation, settled.bodies[i].orientation) * 180 / kPi;
    if (!placed.bodies[i].fixed && turned > kMaxSettlingTiltDeg) {
      throw InputError(scan, 0,
                       format("does not stand on its base: settling with %s contact tilted it %.1f deg",
                              contact::contact_method_name(p.law.method), turned));
    }
  }
  io::save_state(scene.substr(0, scene.size() - 5) + ".state.toml", settled);
  return scene;
}

}  // namespace rigid::shaketable
