#include "rigid/io/scene_writer.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>

#include <toml++/toml.h>

#include "input_file.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/io/scene_file.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

// A path of the source scene, as the destination scene must write it.
std::string rebase(const std::string& path, const fs::path& from_dir, const fs::path& to_dir) {
  if (fs::path(path).is_absolute()) return path;
  const fs::path absolute = fs::absolute(from_dir / path).lexically_normal();
  return fs::absolute(absolute).lexically_relative(fs::absolute(to_dir)).generic_string();
}

}  // namespace

void write_derived_scene(const std::string& source, const std::string& dest, const SceneChanges& changes) {
  toml::table root;
  try {
    root = toml::parse(read_input_file(source, kMaxTextFileBytes), source);
  } catch (const toml::parse_error& e) {
    throw InputError(source, long(e.source().begin.line), std::string(e.description()));
  }
  const fs::path from = fs::path(source).parent_path(), to = fs::path(dest).parent_path();
  if (root.contains("model")) {
    if (const auto m = root["model"].value<std::string>()) root.insert_or_assign("model", rebase(*m, from, to));
  }
  if (toml::array* blocks = root["block"].as_array()) {
    for (toml::node& node : *blocks) {
      toml::table* block = node.as_table();
      if (!block) continue;
      if (const auto stl = (*block)["stl"].value<std::string>()) block->insert_or_assign("stl", rebase(*stl, from, to));
      if (toml::array* pieces = (*block)["contact"].as_array()) {
        for (toml::node& piece : *pieces) {
          if (auto* p = piece.as_string()) *p = rebase(p->get(), from, to);
        }
      }
    }
  }
  toml::table* physics = root["physics"].as_table();
  if (!physics) {
    root.insert("physics", toml::table{});
    physics = root["physics"].as_table();
  }
  for (const auto& [key, value] : changes.physics) {
    if (const double* d = std::get_if<double>(&value)) physics->insert_or_assign(key, *d);
    else physics->insert_or_assign(key, std::get<std::string>(value));
  }
  // the starting poses: the source's (its state file, or the blocks as placed), turned
  scenario::Scene scene = load_scene(source);
  if (changes.turn_free_blocks_deg != 0) {
    Vec3 centre(0, 0, 0);
    for (const auto& b : scene.bodies) {
      if (b.fixed) {
        centre = b.position;
        break;
      }
    }
    const double angle = changes.turn_free_blocks_deg * kPi / 180.0;
    const Quat turn(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
    for (auto& b : scene.bodies) {
      if (b.fixed) continue;
      Vec3 r = b.position - centre;
      r = turn * r;
      b.position = centre + r;
      b.orientation = (turn * b.orientation).normalized();
    }
  }
  std::string state = fs::path(dest).filename().string();
  state = state.size() > 5 && state.ends_with(".toml") ? state.substr(0, state.size() - 5) + ".state.toml" : state + ".state.toml";
  const std::string state_path = (to / state).string();
  save_state(state_path, scene);
  root.insert_or_assign("state", state);

  std::ostringstream text;
  std::istringstream comment(changes.comment);
  for (std::string line; std::getline(comment, line);) text << "# " << line << "\n";
  text << toml::toml_formatter(root, toml::toml_formatter::default_flags & ~toml::format_flags::indentation) << "\n";
  write_output_file(dest, [&](std::ostream& out) { out << text.str(); });
}

}  // namespace rigid::io
