#include "rigid/io/mesh_import.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <filesystem>
#include <string>

#include "input_file.hpp"
#include "rigid/core/error.hpp"
#include "rigid/geometry/contact_shape.hpp"

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
        throw InputError(path, 0, "facet " + std::to_string(soup.size()) + " has " + std::to_string(face.mNumIndices) +
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

}  // namespace

geometry::TriangleSoup read_mesh(const std::string& path) {
  // the same existence, type and size checks as every other input file
  check_input_file(path, kMaxMeshFileBytes);
  Assimp::Importer importer;
  // triangulate polygons; nothing that would weld, repair or drop facets: the geometry checks
  // must see the file's defects to name them
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw InputError(path, 0, "cannot read it as an OBJ, PLY or STL mesh: " + one_line(importer.GetErrorString()));
  }
  geometry::TriangleSoup soup;
  append_node(*scene, *scene->mRootNode, aiMatrix4x4(), path, soup);
  if (soup.empty()) throw InputError(path, 0, "the file holds no triangles");
  return soup;
}

Mat3 up_rotation(const std::string& up) {
  const std::pair<const char*, Vec3> axes[] = {{"z", Vec3::UnitZ()},  {"-z", -Vec3::UnitZ()}, {"y", Vec3::UnitY()},
                                               {"-y", -Vec3::UnitY()}, {"x", Vec3::UnitX()},   {"-x", -Vec3::UnitX()}};
  for (const auto& [name, axis] : axes) {
    if (up != name) continue;
    if (axis.z() < 0) return Eigen::AngleAxisd(kPi, Vec3::UnitX()).toRotationMatrix();  // upside down
    return Quat::FromTwoVectors(axis, Vec3::UnitZ()).toRotationMatrix();
  }
  throw InputError("", 0, "--up must be one of x, -x, y, -y, z, -z (the file's axis that points up)");
}

geometry::ClosedMesh read_scan(const std::string& path, double scale, const Mat3& rotation,
                               std::vector<std::string>& warnings) {
  geometry::TriangleSoup soup = io::read_mesh(path);
  const std::vector<std::size_t> collapsed = geometry::drop_collapsed_facets(soup);
  if (!collapsed.empty()) {
    std::string list;
    for (std::size_t k = 0; k < collapsed.size() && k < 8; ++k) list += (k ? ", " : "") + std::to_string(collapsed[k]);
    warnings.push_back(path + ": dropped " + std::to_string(collapsed.size()) +
                       " facets with two corners at one point (no area): " + list + (collapsed.size() > 8 ? ", ..." : ""));
  }
  if (soup.empty()) throw InputError(path, 0, "the file holds no facet with an area");
  for (auto& t : soup) {
    for (Vec3* p : {&t.a, &t.b, &t.c}) *p = scale * (rotation * *p);
  }
  geometry::MeshOptions options;
  options.require_convex = false;
  geometry::ClosedMesh mesh = geometry::make_closed_mesh(soup, options, path);
  for (const auto& w : mesh.warnings) warnings.push_back(path + ": " + w);
  const auto crossing = geometry::find_self_intersection(mesh);
  if (crossing[0] >= 0) {
    throw InputError(path, 0, "facet " + std::to_string(crossing[1]) + ": crosses facet " + std::to_string(crossing[0]) +
                                  " (the surface intersects itself)");
  }
  return mesh;
}

}  // namespace rigid::io
