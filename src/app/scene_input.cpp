#include "scene_input.hpp"

#include <cstdio>

#include "rigid/io/scene_file.hpp"

namespace rigid::app {

scenario::Scene load_scene_with_warnings(const std::string& path) {
  scenario::Scene scene = io::load_scene(path);
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "rigid: warning: %s\n", w.c_str());
  return scene;
}

}  // namespace rigid::app
