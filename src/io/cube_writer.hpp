#pragma once
// Private to io: the HDF5 dataset and attribute writer the cube's writing shares between the file
// and its axes (cube_write.cpp) and the object groups (cube_write_objects.cpp).
#include <hdf5.h>
#include <hdf5_hl.h>

#include <cstdint>
#include <string>
#include <vector>

#include "cube_hdf5.hpp"

namespace rigid::io {

/// Writes the groups, datasets and attributes of one cube file, without time stamps.
class Writer {
 public:
  Writer(const H5& h, hid_t file) : h_(h), file_(file), str_(string_type(h)) {
    dcpl_ = h.own(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "creating a dataset creation property list");
    h.check(H5Pset_obj_track_times(dcpl_, false), "switching off dataset time stamps");
    gcpl_ = h.own(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "creating a group creation property list");
    h.check(H5Pset_obj_track_times(gcpl_, false), "switching off group time stamps");
  }

  void group(const std::string& path) {
    h_.own(H5Gcreate2(file_, path.c_str(), H5P_DEFAULT, gcpl_, H5P_DEFAULT), H5Gclose, "creating group " + path);
  }

  /// Scalar attribute `name` on the object at `path`.
  void attribute(const std::string& path, const char* name, hid_t file_type, hid_t mem_type, const void* value) {
    const std::string what = "writing attribute " + std::string(name) + " of " + path;
    Hid space = dataspace(h_, {});
    Hid a =
        h_.own(H5Acreate_by_name(file_, path.c_str(), name, file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
               H5Aclose, what);
    h_.check(H5Awrite(a, mem_type, value), what);
  }
  /// One-dimensional float64 attribute (an empty vector writes nothing).
  void attribute(const std::string& path, const char* name, const std::vector<double>& values) {
    if (values.empty()) return;
    const std::string what = "writing attribute " + std::string(name) + " of " + path;
    Hid space = dataspace(h_, {hsize_t(values.size())});
    Hid a = h_.own(
        H5Acreate_by_name(file_, path.c_str(), name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose, what);
    h_.check(H5Awrite(a, H5T_NATIVE_DOUBLE, values.data()), what);
  }
  void attribute(const std::string& path, const char* name, const std::string& value) {
    const char* p = value.c_str();
    attribute(path, name, str_, str_, &p);
  }
  void attribute(const std::string& path, const char* name, std::int32_t value) {
    attribute(path, name, H5T_STD_I32LE, H5T_NATIVE_INT32, &value);
  }
  void attribute(const std::string& path, const char* name, std::uint64_t value) {
    attribute(path, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value);
  }

  /// A dataset with its units and description; returned open for dimension scales.
  Hid dataset(const std::string& path, hid_t file_type, hid_t mem_type, const std::vector<hsize_t>& dims,
              const void* data, const char* units, const std::string& description) {
    Hid space = dataspace(h_, dims);
    Hid d = h_.own(H5Dcreate2(file_, path.c_str(), file_type, space, H5P_DEFAULT, dcpl_, H5P_DEFAULT), H5Dclose,
                   "creating dataset " + path);
    hsize_t n = 1;
    for (hsize_t x : dims) n *= x;
    // an empty selection needs no buffer, and HDF5 rejects a null one
    if (n > 0) h_.check(H5Dwrite(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "writing dataset " + path);
    if (units != nullptr) attribute(path, "units", units);  // text has none (CF)
    attribute(path, "description", description);
    return d;
  }
  Hid doubles(const std::string& path, const std::vector<double>& v, const std::vector<hsize_t>& dims,
              const char* units, const std::string& description) {
    return dataset(path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, v.data(), units, description);
  }
  Hid ints(const std::string& path, const std::vector<std::int32_t>& v, const std::vector<hsize_t>& dims,
           const char* units, const std::string& description) {
    return dataset(path, H5T_STD_I32LE, H5T_NATIVE_INT32, dims, v.data(), units, description);
  }
  Hid strings(const std::string& path, const std::vector<std::string>& v, const std::vector<hsize_t>& dims,
              const char* units, const std::string& description) {
    std::vector<const char*> p;
    p.reserve(v.size());
    for (const std::string& s : v) p.push_back(s.c_str());
    return dataset(path, str_, str_, dims, p.data(), units, description);
  }
  Hid strings(const std::string& path, const std::vector<std::string>& v, const std::string& description) {
    return strings(path, v, {v.size()}, "none", description);
  }

  void long_name(const std::string& path, const char* name) { attribute(path, "long_name", std::string(name)); }

  /// Names a netCDF variable (long_name) and attaches a dimension scale to each of its dimensions.
  void variable(Hid d, const std::string& path, const char* name,
                const std::vector<std::pair<hid_t, const char*>>& dims) {
    long_name(path, name);
    for (unsigned i = 0; i < dims.size(); ++i) attach(d, path, i, dims[i].first, dims[i].second);
  }

  /// CF flag table: flag_values (of the variable's own type) and flag_meanings (space-separated).
  void flags(const std::string& path, hid_t file_type, hid_t mem_type, const void* values, std::size_t n,
             const std::string& meanings) {
    const std::string what = "writing attribute flag_values of " + path;
    Hid space = dataspace(h_, {n});
    Hid a = h_.own(
        H5Acreate_by_name(file_, path.c_str(), "flag_values", file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose, what);
    h_.check(H5Awrite(a, mem_type, values), what);
    attribute(path, "flag_meanings", meanings);
  }

  void make_scale(hid_t d, const std::string& path, const char* name) {
    h_.check(H5DSset_scale(d, name), "making " + path + " a dimension scale");
  }
  void attach(hid_t d, const std::string& path, unsigned dim, hid_t scale, const char* label) {
    const std::string what = "attaching dimension scale " + std::string(label) + " to " + path;
    h_.check(H5DSattach_scale(d, scale, dim), what);
    h_.check(H5DSset_label(d, dim, label), what);
  }

 private:
  const H5& h_;
  hid_t file_;
  Hid str_;
  Hid dcpl_;
  Hid gcpl_;
};

template <class T, class F>
std::vector<T> column(const std::vector<RecordMeta>& records, F field) {
  std::vector<T> v;
  v.reserve(records.size());
  for (const RecordMeta& m : records) v.push_back(field(m));
  return v;
}

inline std::vector<std::string> record_names(const Cube& c) {
  return column<std::string>(c.records, [](const RecordMeta& m) { return m.name; });
}

inline std::vector<std::int32_t> iota32(std::size_t n) {
  std::vector<std::int32_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::int32_t>(i);
  return v;
}

// A campaign "as recorded" has the one scale 0: no target PGA, every record at factor 1; its
// measured PGA and PGV/PGA are in /records.
inline bool as_recorded(const Cube& c) { return c.scales_g.size() == 1 && c.scales_g[0] == 0.0; }

inline std::string scale_description(const Cube& c, const std::string& plain) {
  return as_recorded(c) ? "0: the campaign ran \"as recorded\" (each record at factor 1, not scaled to a PGA; its "
                          "measured PGA and PGV/PGA are /records/gmroti_pga_g and /records/pgv_pga_s)"
                        : plain;
}

/// /variants (with variants) and /objects: every object group with its cells and derived products
/// (cube_write_objects.cpp).
void write_objects(Writer& w, const Cube& c);

}  // namespace rigid::io
