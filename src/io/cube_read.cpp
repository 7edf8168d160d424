// Reading the fragility cube (layout: the top of cube.cpp) back for resume and tests.
#include <hdf5.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>

#include "cube_hdf5.hpp"
#include "rigid/statistics/fragility_surface.hpp"

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

  Hid open_attribute(const std::string& path, const char* name, H5T_class_t cls, const std::string& what) const {
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
    const std::vector<hsize_t> s = shape(path);
    if (s.size() != 1) h_.fail(what + ": not one-dimensional");
    return s[0];
  }

  /// The dimensions of a dataset.
  std::vector<hsize_t> shape(const std::string& path) const {
    const std::string what = "reading dataset " + path;
    Hid d = h_.own(H5Dopen2(file_, path.c_str(), H5P_DEFAULT), H5Dclose, what);
    return shape(d, what);
  }

  /// The type class of a dataset's values (H5T_FLOAT, H5T_STRING, ...).
  H5T_class_t type_class(const std::string& path) const {
    const std::string what = "reading dataset " + path;
    Hid d = h_.own(H5Dopen2(file_, path.c_str(), H5P_DEFAULT), H5Dclose, what);
    Hid type = h_.own(H5Dget_type(d), H5Tclose, what);
    return H5Tget_class(type);
  }

  template <class T>
  std::vector<T> numbers(const std::string& path, H5T_class_t cls, hid_t mem_type,
                         const std::vector<hsize_t>& dims) const {
    Hid d = open_dataset(path, cls, dims);
    hsize_t n = 1;
    for (hsize_t x : dims) n *= x;
    std::vector<T> v(n);
    if (n > 0) h_.check(H5Dread(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "reading dataset " + path);
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
      h_.check(H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT), what);
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

/// The cell datasets of an object group, each of shape `dims` ([R,S,A]; [V,R,S,A] in a group of
/// variants, the variants' cells end to end), checked against the group's checksum (required
/// from schema_version 3: a deleted checksum is not an old cube).
ObjectCube read_cells(const H5& h, const Reader& rd, const std::string& g, const std::vector<hsize_t>& dims,
                      std::int64_t version) {
  ObjectCube o;
  o.outcome = rd.numbers<std::int8_t>(g + "/outcome", H5T_INTEGER, H5T_NATIVE_INT8, dims);
  o.rotation_deg = rd.doubles(g + "/rotation_deg", dims);
  o.failure_time_s = rd.doubles(g + "/failure_time_s", dims);
  o.max_tilt_deg = rd.doubles(g + "/max_tilt_deg", dims);
  o.max_slip_m = rd.doubles(g + "/max_slip_m", dims);
  o.wall_s = rd.doubles(g + "/wall_s", dims);
  o.failure_reason = rd.numbers<std::int32_t>(g + "/failure_reason", H5T_INTEGER, H5T_NATIVE_INT32, dims);
  // absent from cubes written before them: no messages, no checksum to verify
  if (rd.has_link(g + "/failure_message")) o.failure_message = rd.strings(g + "/failure_message", dims);
  if (rd.has_link(g + "/unconverged_steps"))
    o.unconverged_steps = rd.numbers<std::int32_t>(g + "/unconverged_steps", H5T_INTEGER, H5T_NATIVE_INT32, dims);
  if (rd.has_attribute(g, "datasets_sha256")) {
    verify_checksum(h, g, o, rd.string_attribute(g, "datasets_sha256"));
  } else if (version >= kCubeSchemaVersionChecksummed) {
    h.fail(g + ": no datasets_sha256 (every schema_version " + std::to_string(version) +
           " cube has one): the cube was altered");
  }
  return o;
}

/// From schema_version 3 the axes, records and variant table must hash to axes_sha256; /axes/record
/// (the names h5py readers see) must repeat /records/name, which the hash is computed from.
void verify_axes_checksum(const H5& h, const Reader& rd, const Cube& c) {
  if (!rd.has_attribute("/", "axes_sha256"))
    h.fail("no axes_sha256 (every schema_version 3 cube has one): the cube was altered");
  std::vector<std::string> names;
  for (const RecordMeta& m : c.records) names.push_back(m.name);
  if (rd.strings("/axes/record", c.records.size()) != names)
    h.fail("/axes/record differs from /records/name: the cube was altered");
  const std::string stored = rd.string_attribute("/", "axes_sha256");
  const std::string now = axes_sha256(c);
  if (now != stored)
    h.fail("axes, records or variant table changed since written (checksum mismatch); axes_sha256 is " +
           stored.substr(0, 12) + "..., they hash to " + now.substr(0, 12) + "...");
}

/// The group's position in the job (attribute `index`), in range and not `seen` before.
std::size_t group_index(const H5& h, const Reader& rd, const std::string& g, std::vector<bool>& seen) {
  const auto index = rd.integer_attribute<std::int64_t>(g, "index", H5T_NATIVE_INT64);
  if (index < 0 || static_cast<std::size_t>(index) >= seen.size() || seen[static_cast<std::size_t>(index)])
    h.fail(g + ": attribute index " + std::to_string(index) + " is out of range or repeated");
  seen[static_cast<std::size_t>(index)] = true;
  return static_cast<std::size_t>(index);
}

/// An object group of a cube without variants (schema_version 1).
ObjectCube read_object(const H5& h, const Reader& rd, const std::string& g, const std::vector<hsize_t>& rsa,
                       std::int64_t version) {
  ObjectCube o = read_cells(h, rd, g, rsa, version);
  o.scene = rd.string_attribute(g, "scene");
  if (rd.has_attribute(g, "inputs_sha256")) o.inputs = rd.string_attribute(g, "inputs_sha256");
  if (rd.has_attribute(g, "physics_json")) o.physics_json = rd.string_attribute(g, "physics_json");
  if (rd.has_attribute(g, "alpha_rad")) o.alpha_rad = rd.double_attribute(g, "alpha_rad");
  if (rd.has_attribute(g, "p_rad_s")) o.p_rad_s = rd.double_attribute(g, "p_rad_s");
  if (rd.has_attribute(g, "rocking_radius_m")) o.rocking_radius_m = rd.double_attribute(g, "rocking_radius_m");
  if (rd.has_attribute(g, "weakest_azimuth_deg")) o.weakest_azimuth_deg = rd.double_attribute(g, "weakest_azimuth_deg");
  // bounded: a support polygon of a scanned rock has at most a few thousand corners
  if (rd.has_attribute(g, "alpha_by_azimuth_rad"))
    o.alpha_by_azimuth_rad = rd.double_array_attribute(g, "alpha_by_azimuth_rad", 3600);
  if (rd.has_attribute(g, "support_polygon_m"))
    o.support_polygon_m = rd.double_array_attribute(g, "support_polygon_m", 1 << 20);
  return o;
}

// ---- a cube with variants (schema_version 2)

/// The numbers of a "x0 y0 x1 y1 ..." string (support_polygon_m of a group of variants).
std::vector<double> parse_corners(const H5& h, const std::string& where, const std::string& text) {
  std::vector<double> xy;
  const char* p = text.c_str();
  while (true) {
    while (*p == ' ') ++p;
    if (*p == '\0') return xy;
    char* end = nullptr;
    xy.push_back(std::strtod(p, &end));
    if (end == p || (*end != ' ' && *end != '\0')) h.fail(where + ": not a list of numbers: '" + text + "'");
    p = end;
  }
}

/// /variants: the variant table; its count must match its own dimension scale.
VariantTable read_variant_table(const H5& h, const Reader& rd) {
  if (!rd.has_link("/variants")) h.fail("schema_version 2 cube without its variant table /variants");
  VariantTable t;
  t.method = rd.string_attribute("/variants", "method");
  t.seed = rd.integer_attribute<std::uint64_t>("/variants", "seed", H5T_NATIVE_UINT64);
  const auto count = rd.integer_attribute<std::int64_t>("/variants", "count", H5T_NATIVE_INT64);
  const hsize_t V = rd.length("/variants/variant");
  if (count < 1 || static_cast<hsize_t>(count) != V || count > std::numeric_limits<int>::max())
    h.fail("/variants: count " + std::to_string(count) + " does not match /variants/variant (" + std::to_string(V) +
           " values)");
  t.count = static_cast<int>(count);
  std::istringstream names(rd.string_attribute("/variants", "parameters"));
  for (std::string name; names >> name;) {
    const std::string path = "/variants/" + name;
    VariantParameter p;
    p.name = name;
    if (!rd.has_link(path)) h.fail("/variants: parameter " + name + " has no dataset " + path);
    const H5T_class_t cls = rd.type_class(path);
    if (cls == H5T_STRING) {
      p.labels = rd.strings(path, V);
    } else if (cls == H5T_FLOAT) {
      p.values = rd.doubles(path, {V});
      if (rd.has_attribute(path, "units")) p.units = rd.string_attribute(path, "units");
    } else {
      h.fail("reading dataset " + path + ": neither numbers nor strings");
    }
    if (rd.has_attribute(path, "description")) p.description = rd.string_attribute(path, "description");
    t.parameters.push_back(std::move(p));
  }
  return t;
}

/// alpha_by_azimuth_rad [V, Z] of a group of variants into each variant, when the group has it.
void read_alpha_by_azimuth(const H5& h, const Reader& rd, const std::string& g, std::vector<ObjectCube>& variants) {
  const std::string path = g + "/alpha_by_azimuth_rad";
  if (!rd.has_link(path)) return;
  const std::vector<hsize_t> dims = rd.shape(path);
  // bounded like the attribute of a cube without variants
  if (dims.size() != 2 || dims[0] != variants.size() || dims[1] > 3600)
    h.fail("reading dataset " + path + ": not [variant, azimuth] with at most 3600 azimuths");
  const std::vector<double> alpha = rd.doubles(path, dims);
  for (std::size_t v = 0; v < variants.size(); ++v)
    variants[v].alpha_by_azimuth_rad.assign(alpha.begin() + v * dims[1], alpha.begin() + (v + 1) * dims[1]);
}

/// The per-variant datasets [V] of a group of variants into each variant.
void read_variant_values(const H5& h, const Reader& rd, const std::string& g, std::vector<ObjectCube>& variants) {
  const hsize_t V = variants.size();
  for (const auto& [name, field] :
       {std::pair{"alpha_rad", &ObjectCube::alpha_rad}, std::pair{"p_rad_s", &ObjectCube::p_rad_s},
        std::pair{"rocking_radius_m", &ObjectCube::rocking_radius_m},
        std::pair{"weakest_azimuth_deg", &ObjectCube::weakest_azimuth_deg}}) {
    const std::vector<double> v = rd.doubles(g + "/" + name, {V});
    for (hsize_t k = 0; k < V; ++k) variants[k].*field = v[k];
  }
  for (const auto& [name, field] :
       {std::pair{"physics_json", &ObjectCube::physics_json}, std::pair{"inputs_sha256", &ObjectCube::inputs}}) {
    const std::vector<std::string> v = rd.strings(g + "/" + name, V);
    for (hsize_t k = 0; k < V; ++k) variants[k].*field = v[k];
  }
  read_alpha_by_azimuth(h, rd, g, variants);
  const std::vector<std::string> corners = rd.strings(g + "/support_polygon_m", V);
  for (hsize_t k = 0; k < V; ++k)
    variants[k].support_polygon_m = parse_corners(h, g + "/support_polygon_m[" + std::to_string(k) + "]", corners[k]);
}

/// A group holding every variant of one base object: V ObjectCubes in variant order.
std::vector<ObjectCube> read_variant_object(const H5& h, const Reader& rd, const std::string& name,
                                            const std::vector<hsize_t>& rsa, hsize_t V, std::int64_t version) {
  const std::string g = "/objects/" + name;
  const auto variants_here = rd.integer_attribute<std::int64_t>(g, "variants", H5T_NATIVE_INT64);
  if (variants_here < 0 || static_cast<hsize_t>(variants_here) != V)
    h.fail(g + ": attribute variants " + std::to_string(variants_here) + " does not match /variants count " +
           std::to_string(V));
  std::vector<hsize_t> vrsa{V};
  vrsa.insert(vrsa.end(), rsa.begin(), rsa.end());
  std::vector<ObjectCube> variants = split_cells(read_cells(h, rd, g, vrsa, version), V);
  const std::string scene = rd.string_attribute(g, "scene");
  for (hsize_t v = 0; v < V; ++v) {
    variants[v].name = name;
    variants[v].scene = scene;
    variants[v].variant = static_cast<int>(v);
  }
  read_variant_values(h, rd, g, variants);
  return variants;
}

// ---- the whole file

/// The object groups, in job order (the group attribute `index`; HDF5 lists links by name).
void read_objects(const H5& h, const Reader& rd, Cube& c) {
  const std::vector<hsize_t> rsa{c.records.size(), c.scales_g.size(), static_cast<hsize_t>(c.rotations)};
  const std::vector<std::string> groups = rd.members("/objects");
  std::vector<bool> seen(groups.size(), false);
  // per group: its object, or its variants; sized by what was read, never by a count in the file
  std::vector<std::vector<ObjectCube>> by_index(groups.size());
  for (const std::string& name : groups) {
    const std::string g = "/objects/" + name;
    const std::size_t index = group_index(h, rd, g, seen);
    if (c.variants.count > 0) {
      by_index[index] = read_variant_object(h, rd, name, rsa, static_cast<hsize_t>(c.variants.count), c.schema_version);
    } else {
      by_index[index].push_back(read_object(h, rd, g, rsa, c.schema_version));
      by_index[index].back().name = name;
    }
  }
  for (std::vector<ObjectCube>& objects : by_index) {
    for (ObjectCube& o : objects) c.objects.push_back(std::move(o));
  }
}

Cube read_contents(const H5& h, hid_t file) {
  Reader rd(h, file);
  if (!rd.has_attribute("/", "schema_version")) h.fail("not a Rigid fragility cube (no schema_version)");
  const auto version = rd.integer_attribute<std::int64_t>("/", "schema_version", H5T_NATIVE_INT64);
  if (version < 1 || version > kCubeSchemaVersion)
    h.fail("Rigid fragility cube schema_version " + std::to_string(version) + " is not one this Rigid reads (1 to " +
           std::to_string(kCubeSchemaVersion) + ")");

  Cube c;
  c.schema_version = static_cast<int>(version);
  c.software_version = rd.string_attribute("/", "software_version");
  c.job_text = rd.string_attribute("/", "job_text");
  c.job_hash = rd.string_attribute("/", "job_hash");
  c.physics_json = rd.string_attribute("/", "physics_json");
  c.seed = rd.integer_attribute<std::uint64_t>("/", "seed", H5T_NATIVE_UINT64);
  // provenance hashes: absent from cubes written before them
  if (rd.has_attribute("/", "job_inputs_sha256")) c.job_inputs = rd.string_attribute("/", "job_inputs_sha256");
  if (rd.has_attribute("/", "inputs_sha256")) c.inputs_sha256 = rd.string_attribute("/", "inputs_sha256");

  const hsize_t R = rd.length("/axes/record"), S = rd.length("/axes/scale_g"), A = rd.length("/axes/rotation");
  const hsize_t E = rd.length("/axes/pgv_pga_edges_s");
  if (A < 1 || A > static_cast<hsize_t>(std::numeric_limits<int>::max())) h.fail("/axes/rotation is empty or too long");
  c.rotations = static_cast<int>(A);
  c.scales_g = rd.doubles("/axes/scale_g", {S});
  c.pgv_pga_edges_s = rd.doubles("/axes/pgv_pga_edges_s", {E});
  if (std::string p = statistics::pgv_pga_edges_problem(c.pgv_pga_edges_s); !p.empty())
    h.fail("/axes/pgv_pga_edges_s: " + p);

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

  if (version == kCubeSchemaVersionWithVariants ||
      (version >= kCubeSchemaVersionChecksummed && rd.has_link("/variants")))
    c.variants = read_variant_table(h, rd);
  if (version >= kCubeSchemaVersionChecksummed) verify_axes_checksum(h, rd, c);
  read_objects(h, rd, c);
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
