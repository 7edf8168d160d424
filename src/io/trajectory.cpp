#include "rigid/io/trajectory.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "hdf5_handle.hpp"
#include "rigid/core/error.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

void write_dataset(hid_t parent, const std::string& name, hid_t type, const void* data,
                   std::initializer_list<hsize_t> dims, const std::string& file) {
  const std::vector<hsize_t> d(dims);
  const Hid space(H5Screate_simple(int(d.size()), d.data(), nullptr), H5Sclose);
  const Hid lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl, 1);
  const Hid set(H5Dcreate2(parent, name.c_str(), type, space, lcpl, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (set < 0 || H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    throw InputError(file, 0, "cannot write dataset " + name);
  }
}

}  // namespace

void TrajectoryRecorder::record(const dynamics::World& world) {
  const auto& bodies = world.bodies();
  if (names_.empty()) {
    for (const auto& b : bodies) {
      names_.push_back(b.name);
      std::vector<int> tri;
      // fan-triangulate each planar face (faces are convex polygons)
      for (const auto& f : b.shape.faces) {
        for (std::size_t k = 1; k + 1 < f.vertices.size(); ++k) {
          tri.insert(tri.end(), {f.vertices[0], f.vertices[k], f.vertices[k + 1]});
        }
      }
      triangles_.push_back(std::move(tri));
    }
  }
  times_.push_back(world.time());
  std::vector<std::vector<double>> frame;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    std::vector<double> xyz;
    for (const auto& v : world.world_vertices(int(i))) xyz.insert(xyz.end(), {v.x(), v.y(), v.z()});
    frame.push_back(std::move(xyz));
  }
  xyz_.push_back(std::move(frame));
}

void TrajectoryRecorder::write(const std::string& xdmf_path) const {
  const fs::path h5_path = fs::path(xdmf_path).replace_extension(".h5");
  if (h5_path.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(h5_path.parent_path(), ec);
  }
  const std::string h5_name = h5_path.filename().string();
  {
    const QuietErrors quiet;
    const Hid file(H5Fcreate(h5_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    if (file < 0) throw InputError(h5_path.string(), 0, "cannot create trajectory file");
    write_dataset(file, "time", H5T_NATIVE_DOUBLE, times_.data(), {times_.size()}, h5_path.string());
    for (std::size_t b = 0; b < names_.size(); ++b) {
      const std::string g = "block" + std::to_string(b);
      write_dataset(file, g + "/triangles", H5T_NATIVE_INT, triangles_[b].data(), {triangles_[b].size() / 3, 3},
                    h5_path.string());
      for (std::size_t f = 0; f < times_.size(); ++f) {
        write_dataset(file, g + "/xyz/" + std::to_string(f), H5T_NATIVE_DOUBLE, xyz_[f][b].data(),
                      {xyz_[f][b].size() / 3, 3}, h5_path.string());
      }
    }
  }
  std::ofstream x(xdmf_path);
  if (!x) throw InputError(xdmf_path, 0, "cannot write trajectory file");
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"rigid\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  char time[64];
  for (std::size_t f = 0; f < times_.size(); ++f) {
    std::snprintf(time, sizeof time, "%.9g", times_[f]);
    x << "   <Grid Name=\"frame" << f << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
      << "    <Time Value=\"" << time << "\"/>\n";
    for (std::size_t b = 0; b < names_.size(); ++b) {
      const std::size_t nt = triangles_[b].size() / 3, nv = xyz_[f][b].size() / 3;
      const std::string g = "/block" + std::to_string(b);
      x << "    <Grid Name=\"" << names_[b] << "\" GridType=\"Uniform\">\n"
        << "     <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << nt << "\">\n"
        << "      <DataItem Dimensions=\"" << nt << " 3\" NumberType=\"Int\" Format=\"HDF\">" << h5_name << ":" << g
        << "/triangles</DataItem>\n     </Topology>\n"
        << "     <Geometry GeometryType=\"XYZ\">\n"
        << "      <DataItem Dimensions=\"" << nv << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
        << h5_name << ":" << g << "/xyz/" << f << "</DataItem>\n     </Geometry>\n    </Grid>\n";
    }
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  if (!x) throw InputError(xdmf_path, 0, "write failed");
}

}  // namespace rigid::io
