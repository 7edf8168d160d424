#pragma once
/// Loading a scene for a command: io::load_scene, then each repair the reader made (an inward
/// mesh flipped) printed as one `rigid: warning: FILE: ...` line on stderr.
#include <string>

#include "rigid/scenario/scene.hpp"

namespace rigid::app {

scenario::Scene load_scene_with_warnings(const std::string& path);

}  // namespace rigid::app
