#include "rigid/io/scene_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include "input_file.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/stl.hpp"
#include "rigid/scenario/run_bounds.hpp"
#include "toml_values.hpp"

namespace rigid::io {
namespace fs = std::filesystem;

namespace {

struct Token {
  std::string text;
  long line;
};

std::vector<Token> tokenize(const std::string& text, long first_line) {
  std::vector<Token> out;
  std::istringstream in(text);
  std::string line;
  long number = first_line;
  while (std::getline(in, line)) {
    // '#' starts a comment (not in the original format, harmless to it)
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string w;
    while (words >> w) out.push_back({w, number});
    ++number;
  }
  return out;
}

double parse_number(const Token& t, const std::string& source, const char* what) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(t.text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != t.text.size()) {
    throw InputError(source, t.line, std::string("expected ") + what + ", found '" + t.text + "'");
  }
  if (!std::isfinite(v)) throw InputError(source, t.line, std::string(what) + " is not finite");
  return v;
}

void check_positive(double v, const std::string& source, long line, const char* what) {
  if (!(v > 0) || !std::isfinite(v)) {
    throw InputError(source, line, std::string(what) + " must be positive and finite");
  }
}

// Densities outside this range are no material (unit: kg/m^3): air is 1.2, osmium 22 600.
constexpr double kMinDensity = 1.0;
constexpr double kMaxDensity = 1e5;
// Block sizes (bounding radius) outside this range are no rock and make the step vanish or the
// numbers overflow (unit: m).
constexpr double kMinBlockRadius = 1e-3;
constexpr double kMaxBlockRadius = 1e3;

void validate_law(const scenario::Scene& s, const std::string& source, long line) {
  check_positive(s.density, source, line, "density");
  if (!(s.density >= kMinDensity && s.density <= kMaxDensity)) {
    throw InputError(source, line, "density must be between 1 and 1e5 kg/m^3");
  }
  check_positive(s.law.normal_stiffness, source, line, "normal stiffness K_N");
  check_positive(s.law.shear_stiffness, source, line, "shear stiffness K_S");
  if (!(s.law.friction >= 0) || !std::isfinite(s.law.friction)) {
    throw InputError(source, line, "friction must be non-negative and finite");
  }
  if (!(s.law.damping >= 0) || !std::isfinite(s.law.damping)) {
    throw InputError(source, line, "damping factor must be non-negative and finite");
  }
}

// Tolerance on the norm of a saved orientation quaternion (unit: 1).
constexpr double kUnitQuaternionTolerance = 1e-3;

// Blocks deep inside each other at the start (a bad state or model) are refused, naming `file`.
void check_overlap(const scenario::Scene& scene, const std::string& file) {
  try {
    scenario::check_start_overlap(scene);
  } catch (const InputError& e) {
    throw InputError(file, 0, e.what());
  }
}

struct BlockSpec {
  std::string stl;
  std::string name;                  ///< empty: the STL's stem
  std::vector<std::string> contact;  ///< convex contact pieces of a compound body (STL paths)
  bool fixed = false;
  Vec3 velocity{0, 0, 0};
  long line = 0;
};

// Two blocks from one STL sit in the same place: refused at the second one's line.
void reject_repeated_stl(const std::vector<BlockSpec>& blocks, const std::string& base_dir, const std::string& source) {
  std::set<std::string> seen;
  for (const auto& b : blocks) {
    const std::string path = (fs::path(base_dir) / b.stl).lexically_normal().string();
    if (!seen.insert(path).second) {
      throw InputError(source, b.line, b.stl + " is listed twice: both blocks would fill the same space");
    }
  }
}

void check_block_size(const dynamics::BodyDef& body, const std::string& stl) {
  const double r = body.shape.bounding_radius;
  if (!(r >= kMinBlockRadius && r <= kMaxBlockRadius)) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g m", r);
    throw InputError(stl, 0, std::string("block radius ") + buf + " is outside 1 mm to 1 km (is the unit m?)");
  }
}

// Pieces may stick out of the mesh they stand for by at most this fraction of its bounding box
// diagonal (a hull reduced to a vertex budget lies inside; a decomposition's pieces hug the mesh).
constexpr double kPieceReach = 0.05;

// The pieces must reach every extreme point of the mesh (a vertex of its convex hull), to `reach`:
// the rock rests on some of them, and a missing piece under its base lets it sink and tip at t = 0.
void check_pieces_cover(const geometry::ClosedMesh& mesh, const std::vector<geometry::ClosedMesh>& pieces, double reach,
                        const std::string& path) {
  struct Plane {
    Vec3 normal;
    double offset;
  };
  std::vector<std::vector<Plane>> planes;
  for (const auto& piece : pieces) {
    auto& p = planes.emplace_back();
    for (const auto& t : piece.triangles) {
      const Vec3 a = piece.vertices[t[0]];
      const Vec3 n = (piece.vertices[t[1]] - a).cross(piece.vertices[t[2]] - a).normalized();
      p.push_back({n, n.dot(a)});
    }
  }
  geometry::TriangleSoup hull;
  try {
    hull = geometry::convex_hull(mesh.vertices);
  } catch (const std::invalid_argument&) {
    return;  // a flat mesh: make_closed_mesh has refused it already
  }
  for (const auto& t : hull) {
    for (const Vec3& v : {t.a, t.b, t.c}) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& piece : planes) {
        double outside = -std::numeric_limits<double>::infinity();  // a lower bound of the distance
        for (const auto& plane : piece) outside = std::max(outside, plane.normal.dot(v) - plane.offset);
        nearest = std::min(nearest, outside);
      }
      if (nearest > reach) {
        char where[128];
        std::snprintf(where, sizeof where, "(%.4g, %.4g, %.4g) lies %.3g m outside every contact piece", v.x(), v.y(),
                      v.z(), nearest);
        throw InputError(path, 0,
                         std::string("the contact pieces do not cover the mesh: its extreme point ") + where +
                             " (more than 5 % of its size): a piece is missing, or belongs to another rock");
      }
    }
  }
}

// A compound body: mass properties from the closed mesh at `path` (any shape), contact from the
// convex pieces listed in the block's `contact`, in the same coordinates.
void build_compound_body(dynamics::BodyDef& body, const geometry::TriangleSoup& soup, const fs::path& path,
                         const BlockSpec& b, const std::string& base_dir, scenario::Scene& scene,
                         std::vector<std::string>& warnings) {
  geometry::MeshOptions any_shape;
  any_shape.require_convex = false;
  const geometry::ClosedMesh mesh = geometry::make_closed_mesh(soup, any_shape, path.string());
  warnings.insert(warnings.end(), mesh.warnings.begin(), mesh.warnings.end());
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double reach = kPieceReach * (hi - lo).norm();
  std::vector<geometry::ClosedMesh> pieces;
  for (const std::string& name : b.contact) {
    const fs::path piece_path = fs::path(base_dir) / name;
    if (!fs::exists(piece_path))
      throw InputError(scene.source, b.line, "contact piece not found: " + piece_path.string());
    geometry::ClosedMesh piece =
        geometry::make_closed_mesh(read_stl(piece_path.string()), geometry::MeshOptions{}, piece_path.string());
    for (const auto& w : piece.warnings) scene.warnings.push_back(piece_path.string() + ": " + w);
    for (const Vec3& v : piece.vertices) {
      if ((v - v.cwiseMax(lo).cwiseMin(hi)).norm() > reach) {
        throw InputError(piece_path.string(), 0,
                         "contact piece reaches beyond its body's mesh " + path.string() +
                             " (by more than 5 % of its size): another rock's piece, or other units?");
      }
    }
    scene.files.push_back(piece_path.lexically_normal().string());
    pieces.push_back(std::move(piece));
  }
  check_pieces_cover(mesh, pieces, reach, path.string());
  geometry::CompoundBody compound = geometry::build_compound(mesh, pieces, scene.density, geometry::MeshOptions{});
  body.shape = std::move(compound.shape);
  body.pieces = std::move(compound.pieces);
}

void build_bodies(scenario::Scene& scene, const std::vector<BlockSpec>& blocks, const std::string& base_dir) {
  if (blocks.empty()) throw InputError(scene.source, 0, "the scene has no blocks");
  reject_repeated_stl(blocks, base_dir, scene.source);
  bool any_free = false, any_fixed = false;
  std::set<std::string> names;
  for (const auto& b : blocks) {
    const fs::path path = fs::path(base_dir) / b.stl;
    if (!fs::exists(path)) {
      throw InputError(scene.source, b.line, "STL file not found: " + path.string());
    }
    const geometry::TriangleSoup soup = read_stl(path.string());
    scene.files.push_back(path.lexically_normal().string());
    dynamics::BodyDef body;
    body.name = b.name.empty() ? fs::path(b.stl).stem().string() : b.name;
    if (!names.insert(body.name).second)
      throw InputError(scene.source, b.line, "two blocks are named '" + body.name + "'");
    std::vector<std::string> mesh_warnings;
    if (b.contact.empty()) {
      body.shape = geometry::build_block(soup, scene.density, geometry::MeshOptions{}, path.string(), &mesh_warnings);
    } else {
      build_compound_body(body, soup, path, b, base_dir, scene, mesh_warnings);
    }
    for (const auto& w : mesh_warnings) scene.warnings.push_back(path.string() + ": " + w);
    check_block_size(body, path.string());
    body.fixed = b.fixed;
    body.position = body.shape.translation;
    body.orientation = body.shape.rotation;
    body.velocity = b.velocity;
    any_free |= !b.fixed;
    any_fixed |= b.fixed;
    scene.bodies.push_back(std::move(body));
  }
  if (!any_free) throw InputError(scene.source, 0, "the scene has no free block (all FIXED = 1)");
  if (!any_fixed) {
    throw InputError(scene.source, 0, "the scene has no fixed block (FIXED = 1): nothing carries the ground motion");
  }
}

// [centre_of_mass_offset] NAME = [dx, dy, dz]: the centre of mass of block NAME moved by that much
// from its mesh's centroid, in the mesh's coordinates (m): a rock denser on one side, or the
// uncertainty of where its mass centre is.
void apply_centre_of_mass_offsets(const toml::node& node, const std::string& path, scenario::Scene& scene) {
  const auto* table = node.as_table();
  if (!table)
    throw InputError(path, line_of(node), "centre_of_mass_offset must be a table: BLOCK_NAME = [dx, dy, dz] (m)");
  for (const auto& [key, value] : *table) {
    const long line = line_of(value);
    const std::string name(key.str());
    auto body = std::find_if(scene.bodies.begin(), scene.bodies.end(), [&](const auto& b) { return b.name == name; });
    if (body == scene.bodies.end())
      throw InputError(path, line, "centre_of_mass_offset: the scene has no block '" + name + "'");
    const auto* list = value.as_array();
    Vec3 offset;
    if (!list || list->size() != 3)
      throw InputError(path, line, "centre_of_mass_offset." + name + " needs 3 numbers (m)");
    for (int k = 0; k < 3; ++k) {
      const auto c = (*list)[k].value<double>();
      if (!c || !std::isfinite(*c))
        throw InputError(path, line, "centre_of_mass_offset." + name + ": components must be finite numbers (m)");
      offset[k] = *c;
    }
    try {
      scenario::offset_centre_of_mass(*body, offset);
    } catch (const std::invalid_argument& e) {
      throw InputError(path, line, "centre_of_mass_offset." + name + ": " + e.what());
    }
  }
}

void parse_model_tokens(const std::vector<Token>& tokens, std::size_t& i, scenario::Scene& scene,
                        std::vector<BlockSpec>& blocks) {
  const std::string& src = scene.source;
  while (i < tokens.size() && tokens[i].text == "block") {
    const long line = tokens[i].line;
    if (i + 5 >= tokens.size()) {
      throw InputError(src, line, "block needs an STL name, FIXED and three initial velocities");
    }
    BlockSpec b;
    b.line = line;
    b.stl = tokens[i + 1].text;
    const double fixed = parse_number(tokens[i + 2], src, "FIXED (0 or 1)");
    if (fixed != 0 && fixed != 1) throw InputError(src, tokens[i + 2].line, "FIXED must be 0 or 1");
    b.fixed = fixed == 1;
    for (int k = 0; k < 3; ++k) b.velocity[k] = parse_number(tokens[i + 3 + k], src, "initial velocity (m/s)");
    blocks.push_back(b);
    i += 6;
  }
}

}  // namespace

scenario::Scene parse_model_text(const std::string& text, const std::string& base_dir, const std::string& source,
                                 long first_line) {
  scenario::Scene scene;
  scene.source = source;
  const auto tokens = tokenize(text, first_line);
  std::size_t i = 0;
  std::vector<BlockSpec> blocks;
  parse_model_tokens(tokens, i, scene, blocks);
  if (blocks.empty()) {
    const long line = tokens.empty() ? 0 : tokens.front().line;
    throw InputError(source, line, "expected 'block NAME.stl FIXED vx vy vz'");
  }
  // optional physical parameters, in the original order
  const std::size_t rest = tokens.size() - i;
  if (rest != 0 && rest != 5) {
    throw InputError(source, tokens[i].line,
                     "after the blocks expected 5 parameters (density K_N K_S friction damping), found " +
                         std::to_string(rest) + " tokens");
  }
  if (rest == 5) {
    scene.density = parse_number(tokens[i], source, "density (kg/m^3)");
    scene.law.normal_stiffness = parse_number(tokens[i + 1], source, "K_N");
    scene.law.shear_stiffness = parse_number(tokens[i + 2], source, "K_S");
    scene.law.friction = parse_number(tokens[i + 3], source, "friction coefficient");
    scene.law.damping = parse_number(tokens[i + 4], source, "hysteretic damping factor");
    validate_law(scene, source, tokens[i].line);
  }
  build_bodies(scene, blocks, base_dir);
  return scene;
}

namespace {

scenario::Scene load_toml_scene(const std::string& path) {
  const toml::table root = parse_toml(read_input_file(path, kMaxTextFileBytes), path);
  const std::string base = fs::path(path).parent_path().string();
  reject_unknown(root, {"model", "model_text", "state", "physics", "failure", "block", "centre_of_mass_offset"}, path,
                 "scene");

  scenario::Scene physics_only;
  physics_only.source = path;
  if (const auto* p = root["physics"].as_table()) {
    reject_unknown(*p,
                   {"contact", "density", "normal_stiffness", "shear_stiffness", "friction", "damping", "restitution"},
                   path, "[physics]");
    if (const auto* c = p->get("contact")) {
      const auto name = c->value<std::string>();
      if (!name || !contact::parse_contact_method(*name, physics_only.law.method)) {
        throw InputError(path, line_of(*c), "contact must be \"rigid\" or \"penalty\"");
      }
    }
    physics_only.law.restitution = optional_number(*p, "restitution", physics_only.law.restitution, path);
    if (!(physics_only.law.restitution >= 0 && physics_only.law.restitution <= 1)) {
      throw InputError(path, line_of(*p->get("restitution")), "restitution must be in [0, 1]");
    }
    physics_only.density = optional_number(*p, "density", physics_only.density, path);
    physics_only.law.normal_stiffness =
        optional_number(*p, "normal_stiffness", physics_only.law.normal_stiffness, path);
    physics_only.law.shear_stiffness = optional_number(*p, "shear_stiffness", physics_only.law.shear_stiffness, path);
    physics_only.law.friction = optional_number(*p, "friction", physics_only.law.friction, path);
    physics_only.law.damping = optional_number(*p, "damping", physics_only.law.damping, path);
    validate_law(physics_only, path, line_of(*p));
  }

  // the blocks: an original model file, inline model text, or [[block]] tables
  const int sources = int(root.contains("model")) + int(root.contains("model_text")) + int(root.contains("block"));
  if (sources != 1) {
    throw InputError(path, 0, "give exactly one of model = \"FILE\", model_text = \"...\" or [[block]] tables");
  }
  std::string model_text;
  std::string model_source = path;
  long model_line = 1;
  std::vector<BlockSpec> blocks;
  if (const auto* m = root.get("model")) {
    const auto name = m->value<std::string>();
    if (!name) throw InputError(path, line_of(*m), "model must be a file name");
    const fs::path model_path = fs::path(base) / *name;
    if (!fs::exists(model_path)) throw InputError(path, line_of(*m), "model file not found: " + model_path.string());
    model_text = read_input_file(model_path.string(), kMaxTextFileBytes);
    model_source = model_path.string();
  } else if (const auto* m = root.get("model_text")) {
    const auto text = m->value<std::string>();
    if (!text) throw InputError(path, line_of(*m), "model_text must be a string");
    model_text = *text;
    model_line = line_of(*m);
  } else {
    const auto* arr = root["block"].as_array();
    if (!arr) throw InputError(path, line_of(*root.get("block")), "block must be an array of tables ([[block]])");
    for (const auto& node : *arr) {
      const auto* t = node.as_table();
      if (!t) throw InputError(path, line_of(node), "each [[block]] must be a table");
      reject_unknown(*t, {"stl", "name", "contact", "fixed", "velocity"}, path, "[[block]]");
      BlockSpec b;
      b.line = line_of(node);
      const auto stl = (*t)["stl"].value<std::string>();
      if (!stl) throw InputError(path, b.line, "[[block]] needs stl = \"FILE.stl\"");
      b.stl = *stl;
      b.fixed = optional_bool(*t, "fixed", false, path);
      b.name = optional_string(*t, "name", "", path);
      if (const auto* node_contact = t->get("contact")) {
        const auto* list = node_contact->as_array();
        if (!list || list->empty()) {
          throw InputError(path, line_of(*node_contact),
                           "contact must be a non-empty list of STL files of convex pieces");
        }
        for (const auto& item : *list) {
          const auto piece = item.value<std::string>();
          if (!piece || piece->empty()) throw InputError(path, line_of(item), "contact lists STL file names (strings)");
          b.contact.push_back(*piece);
        }
      }
      if (const auto* v = (*t)["velocity"].as_array()) {
        if (v->size() != 3) throw InputError(path, line_of(*v), "velocity must have 3 components (m/s)");
        for (int k = 0; k < 3; ++k) {
          const auto c = (*v)[k].value<double>();
          if (!c || !std::isfinite(*c))
            throw InputError(path, line_of(*v), "velocity components must be finite numbers");
          b.velocity[k] = *c;
        }
      }
      blocks.push_back(b);
    }
  }

  scenario::Scene scene;
  if (!model_text.empty()) {
    const std::string model_base = root.contains("model") ? fs::path(model_source).parent_path().string() : base;
    scene = parse_model_text(model_text, model_base, model_source, model_line);
  } else {
    scene = physics_only;
    build_bodies(scene, blocks, base);
  }
  scene.source = path;
  // provenance order: this file, the model file, the STLs, then the state (apply_state adds it)
  std::vector<std::string> files{path};
  if (root.contains("model")) files.push_back(fs::path(model_source).lexically_normal().string());
  files.insert(files.end(), scene.files.begin(), scene.files.end());
  scene.files = std::move(files);
  if (root.contains("physics")) {
    // [physics] wins over parameters in a model file; masses and inertias follow the density
    const double ratio = physics_only.density / scene.density;
    scene.law = physics_only.law;
    scene.density = physics_only.density;
    for (auto& b : scene.bodies) {
      b.shape.mass *= ratio;
      b.shape.inertia *= ratio;
    }
  }

  if (const auto* f = root["failure"].as_table()) {
    reject_unknown(*f, {"rule", "tilt_deg"}, path, "[failure]");
    const std::string rule = optional_string(*f, "rule", "below", path);
    if (rule == "below") {
      scene.failure.kind = scenario::FailureRule::Kind::below;
    } else if (rule == "tilt") {
      scene.failure.kind = scenario::FailureRule::Kind::tilt;
    } else {
      throw InputError(path, line_of(*f), "failure rule must be \"below\" or \"tilt\", not \"" + rule + "\"");
    }
    const double deg = optional_number(*f, "tilt_deg", 90.0, path);
    if (!(deg > 0 && deg <= 180)) throw InputError(path, line_of(*f), "tilt_deg must be in (0, 180]");
    scene.failure.tilt_angle = deg * kPi / 180.0;
  }
  if (const auto* node = root.get("centre_of_mass_offset")) apply_centre_of_mass_offsets(*node, path, scene);
  if (const auto* s = root.get("state")) {
    const auto name = s->value<std::string>();
    if (!name) throw InputError(path, line_of(*s), "state must be a file name");
    const fs::path state_path = fs::path(base) / *name;
    if (!fs::exists(state_path)) throw InputError(path, line_of(*s), "state file not found: " + state_path.string());
    apply_state(state_path.string(), scene);
  }
  return scene;
}

}  // namespace

scenario::Scene load_scene(const std::string& path) {
  if (!fs::exists(path)) throw InputError(path, 0, "file not found");
  if (fs::path(path).extension() == ".toml") {
    scenario::Scene scene = load_toml_scene(path);
    check_overlap(scene, path);
    return scene;
  }
  scenario::Scene scene =
      parse_model_text(read_input_file(path, kMaxTextFileBytes), fs::path(path).parent_path().string(), path);
  scene.files.insert(scene.files.begin(), path);
  check_overlap(scene, path);
  return scene;
}

void save_state(const std::string& path, const scenario::Scene& scene) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw InputError(path, 0, "cannot write state file");
    out.precision(17);
    out << "# Rigid equilibrium state: pose of every block (centroid position in m, orientation\n"
           "# quaternion w x y z of the principal-axes body frame).\n";
    for (const auto& b : scene.bodies) {
      const auto& q = b.orientation;
      const Vec3 centroid = scenario::centroid_position(b);
      out << "\n[[body]]\nname = \"" << b.name << "\"\nposition = [" << centroid.x() << ", " << centroid.y() << ", "
          << centroid.z() << "]\norientation = [" << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << "]\n";
    }
    if (!out) throw InputError(path, 0, "write failed");
  }
  fs::rename(tmp, path);
}

void apply_state(const std::string& path, scenario::Scene& scene) {
  const toml::table root = parse_toml(read_input_file(path, kMaxTextFileBytes), path);
  const auto* arr = root["body"].as_array();
  if (!arr) throw InputError(path, 0, "no [[body]] entries");
  if (arr->size() != scene.bodies.size()) {
    throw InputError(
        path, 0,
        "state has " + std::to_string(arr->size()) + " bodies, the scene " + std::to_string(scene.bodies.size()));
  }
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const auto* t = (*arr)[i].as_table();
    const long line = line_of((*arr)[i]);
    if (!t) throw InputError(path, line, "each [[body]] must be a table");
    const std::string name = optional_string(*t, "name", "", path);
    if (name != scene.bodies[i].name) {
      throw InputError(
          path, line, "body " + std::to_string(i) + " is '" + name + "', the scene has '" + scene.bodies[i].name + "'");
    }
    const auto* p = (*t)["position"].as_array();
    const auto* q = (*t)["orientation"].as_array();
    if (!p || p->size() != 3 || !q || q->size() != 4) {
      throw InputError(path, line, "position needs 3 numbers and orientation 4");
    }
    double v[7];
    for (int k = 0; k < 3; ++k) v[k] = (*p)[k].value<double>().value_or(NAN);
    for (int k = 0; k < 4; ++k) v[3 + k] = (*q)[k].value<double>().value_or(NAN);
    for (double x : v) {
      if (!std::isfinite(x)) throw InputError(path, line, "non-finite or non-numeric pose value");
    }
    const Quat orientation(v[3], v[4], v[5], v[6]);
    // a saved state holds unit quaternions to 1e-16; a zero or wild one is no orientation
    if (!(std::abs(orientation.norm() - 1.0) <= kUnitQuaternionTolerance)) {
      throw InputError(
          path, line,
          "orientation must be a unit quaternion w x y z (its norm is " + std::to_string(orientation.norm()) + ")");
    }
    scene.bodies[i].orientation = orientation.normalized();
    // the state holds the centroid's pose: the centre of mass sits offset from it
    scene.bodies[i].position =
        Vec3(v[0], v[1], v[2]) + scene.bodies[i].orientation * scene.bodies[i].centre_of_mass_offset;
  }
  scene.files.push_back(fs::path(path).lexically_normal().string());
  check_overlap(scene, path);
}

std::string scene_value_problem(const scenario::Scene& scene) {
  try {
    validate_law(scene, "", 0);
    for (const dynamics::BodyDef& body : scene.bodies) check_block_size(body, "block '" + body.name + "'");
  } catch (const InputError& e) {
    return e.file().empty() ? e.problem() : e.file() + ": " + e.problem();
  }
  return "";
}

}  // namespace rigid::io
