#include "rigid/io/mesh_import.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#include "input_file.hpp"
#include "ply_check.hpp"
#include "rigid/core/error.hpp"

namespace rigid::io {
namespace {

// assimp's messages can span lines; a Rigid error is one line
std::string one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

void append_node(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, const std::string& path,
                 geometry::TriangleSoup& soup) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) {
        throw InputError(path, 0,
                         "facet " + std::to_string(soup.size()) + " has " + std::to_string(face.mNumIndices) +
                             " vertices: points and lines are no surface");
      }
      geometry::Triangle t;
      Vec3* corners[3] = {&t.a, &t.b, &t.c};
      for (int k = 0; k < 3; ++k) {
        const aiVector3D v = transform * mesh.mVertices[face.mIndices[k]];
        *corners[k] = Vec3(v.x, v.y, v.z);
      }
      soup.push_back(t);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) append_node(scene, *node.mChildren[c], transform, path, soup);
}

// The format assimp is told: the name's extension, or "ply" for content that starts like a PLY
// (assimp would detect it too, and the checks must run on what assimp reads)
std::string format_hint(std::string_view bytes, const std::string& name) {
  if (bytes.substr(0, 4) == "ply\n" || bytes.substr(0, 5) == "ply\r\n") return "ply";
  std::string ext = std::filesystem::path(name).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// The line of the first vertex coordinate that is not a finite number in a text mesh (OBJ `v`
// lines, ASCII STL `vertex` lines, ASCII PLY lines after end_header); 0 when none is found (a
// binary file has no lines)
long first_non_finite_vertex_line(std::string_view bytes, const std::string& hint) {
  bool in_data = hint != "ply";
  long line = 0;
  std::size_t pos = 0;
  while (pos < bytes.size()) {
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos) end = bytes.size();
    std::istringstream words{std::string(bytes.substr(pos, end - pos))};
    pos = end + 1;
    ++line;
    std::string word;
    if (!(words >> word)) continue;
    if (!in_data) {
      in_data = word == "end_header";
      continue;
    }
    if (hint == "obj" && word != "v") continue;
    if (hint == "stl" && word != "vertex") continue;
    for (int k = 0; k < 3; ++k) {
      if (hint == "ply" && k > 0 && !(words >> word)) break;
      if (hint != "ply" && !(words >> word)) break;
      if (!std::isfinite(std::strtod(word.c_str(), nullptr))) return line;
    }
  }
  return 0;
}

// Every corner a finite point, checked as read: mending (--repair) or welding a NaN corner would
// answer with the wrong defect
void check_finite_vertices(const geometry::TriangleSoup& soup, std::string_view bytes, const std::string& name,
                           const std::string& hint) {
  for (std::size_t f = 0; f < soup.size(); ++f) {
    const geometry::Triangle& t = soup[f];
    if (t.a.allFinite() && t.b.allFinite() && t.c.allFinite()) continue;
    const long line = first_non_finite_vertex_line(bytes, hint);
    throw InputError(
        name, line,
        line > 0 ? "vertex coordinate is not a finite number (NaN or infinite)"
                 : "facet " + std::to_string(f) + ": a vertex coordinate is not a finite number (NaN or infinite)");
  }
}

}  // namespace

geometry::TriangleSoup read_mesh_from_memory(std::string_view bytes, const std::string& name) {
  const std::string hint = format_hint(bytes, name);
  // a PLY is read from its checked canonical form (ply_check.hpp says why)
  const std::string canonical_ply = hint == "ply" ? check_ply(bytes, name) : std::string();
  if (hint != "ply" && hint != "obj" && hint != "stl") {
    throw InputError(name, 0, "cannot read it as a mesh: its name ends in neither .obj, .ply nor .stl");
  }
  if (bytes.empty()) throw InputError(name, 0, "the file is empty");
  Assimp::Importer importer;
  // triangulate polygons; nothing that would weld, repair or drop facets: the geometry checks
  // must see the file's defects to name them
  const std::string_view read = hint == "ply" ? std::string_view(canonical_ply) : bytes;
  const aiScene* scene = importer.ReadFileFromMemory(read.data(), read.size(), aiProcess_Triangulate, hint.c_str());
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw InputError(name, 0, "cannot read it as an OBJ, PLY or STL mesh: " + one_line(importer.GetErrorString()));
  }
  geometry::TriangleSoup soup;
  append_node(*scene, *scene->mRootNode, aiMatrix4x4(), name, soup);
  if (soup.empty()) throw InputError(name, 0, "the file holds no triangles");
  check_finite_vertices(soup, bytes, name, hint);
  return soup;
}

geometry::TriangleSoup read_mesh(const std::string& path) {
  // the same existence, type and size checks as every other input file
  return read_mesh_from_memory(read_input_file(path, kMaxMeshFileBytes), path);
}

Mat3 up_rotation(const std::string& up) {
  const std::pair<const char*, Vec3> axes[] = {{"z", Vec3::UnitZ()},   {"-z", -Vec3::UnitZ()}, {"y", Vec3::UnitY()},
                                               {"-y", -Vec3::UnitY()}, {"x", Vec3::UnitX()},   {"-x", -Vec3::UnitX()}};
  for (const auto& [name, axis] : axes) {
    if (up != name) continue;
    if (axis.z() < 0) return Eigen::AngleAxisd(kPi, Vec3::UnitX()).toRotationMatrix();  // upside down
    return Quat::FromTwoVectors(axis, Vec3::UnitZ()).toRotationMatrix();
  }
  throw InputError("", 0, "--up must be one of x, -x, y, -y, z, -z (the file's axis that points up)");
}

}  // namespace rigid::io
