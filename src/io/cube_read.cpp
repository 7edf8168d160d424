// Reading the fragility cube (layout: the top of cube.cpp) back for resume and tests.
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <limits>

#include "cube_hdf5.hpp"

namespace rigid::io {

namespace fs = std::filesystem;

namespace {

class Reader {
 public:
  Reader(const H5& h, hid_t file) : h_(h), file_(file), str_(string_type(h)) {}

  bool has_attribute(const std::string& path, const char* name) const {
    return h_.check(H5Aexists_by_name(file_, path.c_str(), name, H5P_DEFAULT),
                    "looking for attribute " + std::string(name) + " of " + path) > 0;
  }

  bool has_link(const std::string& path) const {
    return h_.check(H5Lexists(file_, path.c_str(), H5P_DEFAULT), "looking for " + path) > 0;
  }

  Hid open_attribute(const std::string& path, const char* name, H5T_class_t cls,
                     const std::string& what) const {
    Hid a = h_.own(H5Aopen_by_name(file_, path.c_str(), name, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, what);
    Hid space = h_.own(H5Aget_space(a), H5Sclose, what);
    Hid type = h_.own(H5Aget_type(a), H5Tclose, what);
    if (h_.check(H5Sget_simple_extent_npoints(space), what) != 1 || H5Tget_class(type) != cls)
      h_.fail(what + ": not a single " + (cls == H5T_STRING ? "string" : "number"));
    if (cls == H5T_STRING && h_.check(H5Tis_variable_str(type), what) <= 0)
      h_.fail(what + ": not a variable-length string");
    return a;
  }

  std::string string_attribute(const std::string& path, const char* name) const {
    const std::string what = "reading attribute " + std::string(name) + " of " + path;
    Hid a = open_attribute(path, name, H5T_STRING, what);
    char* p = nullptr;
    h_.check(H5Aread(a, str_, &p), what);
    std::string s = p != nullptr ? p : "";
    H5free_memory(p);
    return s;
  }

  template <class T>
  T integer_attribute(const std::string& path, const char* name, hid_t mem_type) const {
    const std::string what = "reading attribute " + std::string(name) + " of " + path;
    Hid a = open_attribute(path, name, H5T_INTEGER, what);
    T v{};
    h_.check(H5Aread(a, mem_type, &v), what);
    return v;
  }

  double double_attribute(const std::string& path, const char* name) const {
    const std::string what = "reading attribute " + std::string(name) + " of " + path;
    Hid a = open_attribute(path, name, H5T_FLOAT, what);
    double v = 0;
    h_.check(H5Aread(a, H5T_NATIVE_DOUBLE, &v), what);
    return v;
  }

  /// A one-dimensional float64 attribute (at most `limit` values).
  std::vector<double> double_array_attribute(const std::string& path, const char* name, hssize_t limit) const {
    const std::string what = "reading attribute " + std::string(name) + " of " + path;
    Hid a = h_.own(H5Aopen_by_name(file_, path.c_str(), name, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, what);
    Hid space = h_.own(H5Aget_space(a), H5Sclose, what);
    Hid type = h_.own(H5Aget_type(a), H5Tclose, what);
    const hssize_t n = h_.check(H5Sget_simple_extent_npoints(space), what);
    if (H5Tget_class(type) != H5T_FLOAT || h_.check(H5Sget_simple_extent_ndims(space), what) != 1 || n > limit)
      h_.fail(what + ": not a list of at most " + std::to_string(limit) + " numbers");
    std::vector<double> v(static_cast<std::size_t>(n));
    if (n > 0) h_.check(H5Aread(a, H5T_NATIVE_DOUBLE, v.data()), what);
    return v;
  }

  /// Opens a dataset and checks its type class and shape.
  Hid open_dataset(const std::string& path, H5T_class_t cls, const std::vector<hsize_t>& dims) const {
    const std::string what = "reading dataset " + path;
    Hid d = h_.own(H5Dopen2(file_, path.c_str(), H5P_DEFAULT), H5Dclose, what);
    Hid type = h_.own(H5Dget_type(d), H5Tclose, what);
    if (H5Tget_class(type) != cls) h_.fail(what + ": unexpected data type");
    if (cls == H5T_STRING && h_.check(H5Tis_variable_str(type), what) <= 0)
      h_.fail(what + ": not variable-length strings");
    if (shape(d, what) != dims) h_.fail(what + ": shape " + str(shape(d, what)) + ", expected " + str(dims));
    return d;
  }

  /// Length of a 1D dataset (an axis).
  hsize_t length(const std::string& path) const {
    const std::string what = "reading dataset " + path;
    Hid d = h_.own(H5Dopen2(file_, path.c_str(), H5P_DEFAULT), H5Dclose, what);
    const std::vector<hsize_t> s = shape(d, what);
    if (s.size() != 1) h_.fail(what + ": not one-dimensional");
    return s[0];
  }

  template <class T>
  std::vector<T> numbers(const std::string& path, H5T_class_t cls, hid_t mem_type,
                         const std::vector<hsize_t>& dims) const {
    Hid d = open_dataset(path, cls, dims);
    hsize_t n = 1;
    for (hsize_t x : dims) n *= x;
    std::vector<T> v(n);
    if (n > 0)
      h_.check(H5Dread(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "reading dataset " + path);
    return v;
  }
  std::vector<double> doubles(const std::string& path, const std::vector<hsize_t>& dims) const {
    return numbers<double>(path, H5T_FLOAT, H5T_NATIVE_DOUBLE, dims);
  }

  std::vector<std::string> strings(const std::string& path, hsize_t n) const {
    return strings(path, std::vector<hsize_t>{n});
  }
  std::vector<std::string> strings(const std::string& path, const std::vector<hsize_t>& dims) const {
    Hid d = open_dataset(path, H5T_STRING, dims);
    hsize_t n = 1;
    for (hsize_t x : dims) n *= x;
    std::vector<char*> p(n, nullptr);
    if (n > 0) h_.check(H5Dread(d, str_, H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data()), "reading dataset " + path);
    std::vector<std::string> v;
    v.reserve(n);
    for (char* s : p) {
      v.emplace_back(s != nullptr ? s : "");
      H5free_memory(s);
    }
    return v;
  }

  /// Names of the links in a group, in name order.
  std::vector<std::string> members(const std::string& path) const {
    const std::string what = "listing group " + path;
    Hid g = h_.own(H5Gopen2(file_, path.c_str(), H5P_DEFAULT), H5Gclose, what);
    H5G_info_t info;
    h_.check(H5Gget_info(g, &info), what);
    std::vector<std::string> names;
    for (hsize_t i = 0; i < info.nlinks; ++i) {
      const ssize_t size =
          h_.check(H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT), what);
      std::string name(static_cast<std::size_t>(size) + 1, '\0');
      h_.check(
          H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT),
          what);
      name.resize(static_cast<std::size_t>(size));
      names.push_back(std::move(name));
    }
    return names;
  }

 private:
  std::vector<hsize_t> shape(hid_t d, const std::string& what) const {
    Hid space = h_.own(H5Dget_space(d), H5Sclose, what);
    const int rank = h_.check(H5Sget_simple_extent_ndims(space), what);
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    h_.check(H5Sget_simple_extent_dims(space, dims.data(), nullptr), what);
    return dims;
  }
  static std::string str(const std::vector<hsize_t>& dims) {
    std::string s = "[";
    for (std::size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
    return s + "]";
  }

  const H5& h_;
  hid_t file_;
  Hid str_;
};

/// A resume must not build on results altered after they were written (a flipped byte in
/// `outcome` would pass into probability and fragility).
void verify_checksum(const H5& h, const std::string& group, const ObjectCube& o, const std::string& stored) {
  const std::string now = cell_datasets_sha256(o, o.failure_message);
  if (now != stored)
    throw InputError(h.path(), 0,
                     group + ": datasets changed since written (checksum mismatch); datasets_sha256 is " +
                         stored.substr(0, 12) + "..., the datasets hash to " + now.substr(0, 12) + "...");
}

Cube read_contents(const H5& h, hid_t file) {
  Reader rd(h, file);
  if (!rd.has_attribute("/", "schema_version")) h.fail("not a Rigid fragility cube (no schema_version)");
  const auto version = rd.integer_attribute<std::int64_t>("/", "schema_version", H5T_NATIVE_INT64);
  if (version < 1 || version > kCubeSchemaVersion)
    h.fail("Rigid fragility cube schema_version " + std::to_string(version) +
           " is not one this Rigid reads (1 to " + std::to_string(kCubeSchemaVersion) + ")");

  Cube c;
  c.software_version = rd.string_attribute("/", "software_version");
  c.job_text = rd.string_attribute("/", "job_text");
  c.job_hash = rd.string_attribute("/", "job_hash");
  c.physics_json = rd.string_attribute("/", "physics_json");
  c.seed = rd.integer_attribute<std::uint64_t>("/", "seed", H5T_NATIVE_UINT64);
  // provenance hashes: absent from cubes written before them
  if (rd.has_attribute("/", "job_inputs_sha256")) c.job_inputs = rd.string_attribute("/", "job_inputs_sha256");
  if (rd.has_attribute("/", "inputs_sha256")) c.inputs_sha256 = rd.string_attribute("/", "inputs_sha256");

  const hsize_t R = rd.length("/axes/record"), S = rd.length("/axes/scale_g"),
                A = rd.length("/axes/rotation");
  const hsize_t E = rd.length("/axes/pgv_pga_edges_s");
  if (A < 1 || A > static_cast<hsize_t>(std::numeric_limits<int>::max()))
    h.fail("/axes/rotation is empty or too long");
  c.rotations = static_cast<int>(A);
  c.scales_g = rd.doubles("/axes/scale_g", {S});
  c.pgv_pga_edges_s = rd.doubles("/axes/pgv_pga_edges_s", {E});
  if (std::string p = edges_problem(c.pgv_pga_edges_s); !p.empty()) h.fail("/axes/pgv_pga_edges_s: " + p);

  const std::vector<std::string> names = rd.strings("/records/name", R);
  const std::vector<std::string> sources = rd.strings("/records/source", R);
  const std::vector<std::string> quakes = rd.strings("/records/earthquake", R);
  c.records.resize(R);
  for (hsize_t r = 0; r < R; ++r) {
    c.records[r].name = names[r];
    c.records[r].source = sources[r];
    c.records[r].earthquake = quakes[r];
  }
  if (rd.has_link("/records/alignment")) {
    const std::vector<std::string> alignment = rd.strings("/records/alignment", R);
    for (hsize_t r = 0; r < R; ++r) c.records[r].alignment = alignment[r];
  }
  if (rd.has_link("/records/inputs_sha256")) {
    const std::vector<std::string> inputs = rd.strings("/records/inputs_sha256", R);
    for (hsize_t r = 0; r < R; ++r) c.records[r].inputs = inputs[r];
  }
  const auto number = [&](const char* name, double RecordMeta::*field) {
    const std::vector<double> v = rd.doubles(std::string("/records/") + name, {R});
    for (hsize_t r = 0; r < R; ++r) c.records[r].*field = v[r];
  };
  number("start_s", &RecordMeta::start_s);
  number("end_s", &RecordMeta::end_s);
  number("gmroti_pga_g", &RecordMeta::gmroti_pga_g);
  number("gmroti_pgv_cm_s", &RecordMeta::gmroti_pgv_cm_s);
  number("pgv_pga_s", &RecordMeta::pgv_pga_s);
  number("listed_pga_g", &RecordMeta::listed_pga_g);
  number("listed_pgv_cm_s", &RecordMeta::listed_pgv_cm_s);

  // objects come back in job order: the group attribute `index` (HDF5 lists links by name)
  const std::vector<std::string> objects = rd.members("/objects");
  c.objects.resize(objects.size());
  std::vector<bool> seen(objects.size(), false);
  const std::vector<hsize_t> rsa{R, S, A};
  for (const std::string& name : objects) {
    const std::string g = "/objects/" + name;
    const auto index = rd.integer_attribute<std::int64_t>(g, "index", H5T_NATIVE_INT64);
    if (index < 0 || static_cast<std::size_t>(index) >= objects.size() ||
        seen[static_cast<std::size_t>(index)])
      h.fail(g + ": attribute index " + std::to_string(index) + " is out of range or repeated");
    seen[static_cast<std::size_t>(index)] = true;
    ObjectCube& o = c.objects[static_cast<std::size_t>(index)];
    o.name = name;
    o.scene = rd.string_attribute(g, "scene");
    if (rd.has_attribute(g, "inputs_sha256")) o.inputs = rd.string_attribute(g, "inputs_sha256");
    if (rd.has_attribute(g, "physics_json")) o.physics_json = rd.string_attribute(g, "physics_json");
    if (rd.has_attribute(g, "alpha_rad")) o.alpha_rad = rd.double_attribute(g, "alpha_rad");
    if (rd.has_attribute(g, "p_rad_s")) o.p_rad_s = rd.double_attribute(g, "p_rad_s");
    if (rd.has_attribute(g, "rocking_radius_m")) o.rocking_radius_m = rd.double_attribute(g, "rocking_radius_m");
    if (rd.has_attribute(g, "weakest_azimuth_deg")) o.weakest_azimuth_deg = rd.double_attribute(g, "weakest_azimuth_deg");
    // bounded: a support polygon of a scanned rock has at most a few thousand corners
    if (rd.has_attribute(g, "alpha_by_azimuth_rad")) o.alpha_by_azimuth_rad = rd.double_array_attribute(g, "alpha_by_azimuth_rad", 3600);
    if (rd.has_attribute(g, "support_polygon_m")) o.support_polygon_m = rd.double_array_attribute(g, "support_polygon_m", 1 << 20);
    o.outcome = rd.numbers<std::int8_t>(g + "/outcome", H5T_INTEGER, H5T_NATIVE_INT8, rsa);
    o.rotation_deg = rd.doubles(g + "/rotation_deg", rsa);
    o.failure_time_s = rd.doubles(g + "/failure_time_s", rsa);
    o.max_tilt_deg = rd.doubles(g + "/max_tilt_deg", rsa);
    o.max_slip_m = rd.doubles(g + "/max_slip_m", rsa);
    o.wall_s = rd.doubles(g + "/wall_s", rsa);
    o.failure_reason = rd.numbers<std::int32_t>(g + "/failure_reason", H5T_INTEGER, H5T_NATIVE_INT32, rsa);
    // absent from cubes written before them: no messages, no checksum to verify
    if (rd.has_link(g + "/failure_message")) o.failure_message = rd.strings(g + "/failure_message", rsa);
    if (rd.has_attribute(g, "datasets_sha256")) verify_checksum(h, g, o, rd.string_attribute(g, "datasets_sha256"));
  }
  if (std::string p = cube_problem(c); !p.empty()) h.fail("inconsistent cube: " + p);
  return c;
}

}  // namespace

Cube read_cube(const std::string& path) {
  const QuietErrors quiet;
  const H5 h(path);
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw InputError(path, 0, "cannot read the cube: no such file");
  if (!fs::is_regular_file(st)) throw InputError(path, 0, "cannot read the cube: not a regular file");
    // H5Fis_hdf5 only looks for the signature; 0 = a readable file of another kind
#if H5_VERSION_GE(1, 12, 0)
  const htri_t is_hdf5 = H5Fis_accessible(path.c_str(), H5P_DEFAULT);
#else
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
#endif
  if (is_hdf5 <= 0) throw InputError(path, 0, "not a Rigid fragility cube (not an HDF5 file)");
  Hid fapl = file_access(h);
  Hid file = h.own(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl), H5Fclose, "cannot open the HDF5 file");
  return read_contents(h, file);
}

}  // namespace rigid::io
