#include "rigid/io/scene_writer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <toml++/toml.h>

#include "input_file.hpp"
#include "rigid/contact/contact.hpp"
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

// The shortest decimal that reads back as `x`, always with a point or exponent (a TOML float).
std::string float_text(double x) {
  char text[64];
  const auto end = std::to_chars(text, text + sizeof text, x).ptr;
  std::string out(text, end);
  if (out.find_first_of(".en") == std::string::npos) out += ".0";
  return out;
}

// A TOML basic string ("..."): quotes, backslashes and control characters escaped.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += escape;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

void write_model_file(const std::string& path, const std::vector<SceneBlock>& blocks) {
  if (blocks.empty()) throw InputError(path, 0, "a model needs at least one block");
  write_output_file(path, [&](std::ostream& out) {
    for (const SceneBlock& b : blocks) out << "block " << b.stl << "\n" << (b.fixed ? 1 : 0) << " 0 0 0\n";
  });
}

void write_scene(const std::string& path, const SceneFile& scene) {
  if (scene.blocks.empty() == scene.model.empty()) {
    throw InputError(path, 0, "a scene needs either blocks or a model file (not both)");
  }
  if (!(scene.density > 0) || !std::isfinite(scene.density))
    throw InputError(path, 0, "density must be a positive number");
  if (scene.tilt_rule_deg && !(*scene.tilt_rule_deg > 0 && *scene.tilt_rule_deg < 90)) {
    throw InputError(path, 0, "the tilt rule's angle must be in (0, 90) deg");
  }
  const contact::ContactLaw law;
  write_output_file(path, [&](std::ostream& out) {
    for (std::string line : scene.comments) {
      std::replace(line.begin(), line.end(), '\n', ' ');  // one comment line stays one line
      out << "# " << line << "\n";
    }
    if (!scene.model.empty()) out << "model = " << quoted(scene.model) << "\n";
    if (!scene.state.empty()) out << "state = " << quoted(scene.state) << "\n";
    if (!scene.model.empty() || !scene.state.empty()) out << "\n";
    out << "[physics]  # the default contact model; density and the penalty model's values are the study's "
           "(physics.md 11)\ncontact = \""
        << contact::contact_method_name(law.method) << "\"\ndensity = " << float_text(scene.density)
        << "\nnormal_stiffness = 1e8\nshear_stiffness = 1e8\nfriction = 0.6\ndamping = 2.0\n";
    out << "\n[failure]\n";
    if (scene.tilt_rule_deg) {
      out << "rule = \"tilt\"\ntilt_deg = " << float_text(*scene.tilt_rule_deg) << "\n";
    } else {
      out << "rule = \"below\"\n";
    }
    for (const SceneBlock& b : scene.blocks) {
      out << "\n[[block]]\nname = " << quoted(b.name) << "\nstl = " << quoted(b.stl)
          << "\nfixed = " << (b.fixed ? "true" : "false") << "\n";
      if (b.contact.empty()) continue;
      out << "contact = [";
      for (std::size_t k = 0; k < b.contact.size(); ++k) out << (k ? ", " : "") << quoted(b.contact[k]);
      out << "]\n";
    }
  });
}

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
    if (const double* d = std::get_if<double>(&value))
      physics->insert_or_assign(key, *d);
    else
      physics->insert_or_assign(key, std::get<std::string>(value));
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
  state = state.size() > 5 && state.ends_with(".toml") ? state.substr(0, state.size() - 5) + ".state.toml"
                                                       : state + ".state.toml";
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
