// The HDF5 fragility cube (include/rigid/io/cube.hpp), written and read with the HDF5 C API. This
// file and its test are the only HDF5 users; the derived products (probability, fragility) are
// pure functions so the campaign summary can print them without HDF5.
//
// Layout, schema_version 1 (R records, S scales, A rotations, B = E - 1 PGV/PGA bins):
//
//   /                      attributes: schema_version (int32), software_version, job_text,
//                          job_hash, physics_json (strings), seed (uint64),
//                          units = "SI unless the name says otherwise",
//                          job_inputs_sha256 (sha256sum lines: settings, job file, record list),
//                          inputs_sha256 (one SHA-256 over every input of every cell)
//   /axes/record           [R] string     dimension scale "record" (names, job order)
//   /axes/scale_g          [S] float64 g  dimension scale "scale_g" (target GMRotI50 PGA)
//   /axes/rotation         [A] int32      dimension scale "rotation" (0..A-1)
//   /axes/pgv_pga_bin      [B] int32      dimension scale "pgv_pga_bin" (0..B-1)
//   /axes/pgv_pga_edges_s  [E] float64 s  bin i holds edges[i] <= PGV/PGA < edges[i+1]
//                                         (the last bin also holds PGV/PGA == edges[E-1])
//   /records/{name, source, earthquake}                               [R] string
//   /records/{start_s, end_s, gmroti_pga_g, gmroti_pgv_cm_s, pgv_pga_s,
//             listed_pga_g, listed_pgv_cm_s}                          [R] float64
//   /records/inputs_sha256                                            [R] string (sha256sum lines)
//   /records/alignment                                                [R] string (empty: matched)
//   /objects/<name>/       attributes: scene (string), index (int32, position in the job),
//                          inputs_sha256 (string, sha256sum lines: scene, model, STLs, state),
//                          alpha_rad, p_rad_s (float64, only for single-block objects),
//                          physics_json (string: the object's own physics and run settings)
//       outcome            [R,S,A] int8   attribute legend = "0 not run, 1 survived, ..."
//       rotation_deg, failure_time_s, max_tilt_deg, max_slip_m, wall_s   [R,S,A] float64
//       failure_reason     [R,S,A] int32  0 = none, else the campaign's FailureReason code
//       probability        [R,S]   float64  derived: overturn_probability()
//       fragility          [S,B]   float64  derived: fragility_surface().probability
//       fragility_count    [S,B]   int32    derived: fragility_surface().count
//
// Every dataset has `units` ("1" = dimensionless number, "none" = text, codes, indices) and
// `description` string attributes; every dimension of an indexed dataset has its scale attached
// (H5DSattach_scale) and a label (H5DSset_label) equal to the scale's name. Strings are
// variable-length UTF-8; numbers are stored little-endian (f64, i8, i32, u64) whatever the host.
//
// Determinism: the same cube gives the same datasets and attributes, created in the same order,
// contiguous (no chunking, no compression) and without object time stamps
// (H5Pset_obj_track_times false). No creation time is stored anywhere. wall_s is the only
// run-dependent dataset (tests/python/compare_cubes.py skips it).
//
// Atomicity: write_cube builds the file in memory (HDF5's core driver), writes it to PATH.tmp,
// fsyncs it, renames it over PATH and fsyncs the directory, so a kill at any instant leaves the
// previous or the new complete file, and a failed write (disk full) leaves the previous one and
// removes PATH.tmp.
#include "rigid/io/cube.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <utility>

#include "hdf5_handle.hpp"
#include "rigid/core/error.hpp"

namespace rigid::io {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr const char* kLegend = "0 not run, 1 survived, 2 overturned, 3 inferred, 4 failed";

std::size_t cell_count(const Cube& c) {
  return c.records.size() * c.scales_g.size() * static_cast<std::size_t>(std::max(c.rotations, 0));
}

std::string edges_problem(const std::vector<double>& e) {
  if (e.size() < 2) return "pgv_pga_edges_s needs at least 2 edges (has " + std::to_string(e.size()) + ")";
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (std::isnan(e[i])) return "pgv_pga_edges_s[" + std::to_string(i) + "] is NaN";
    if (i > 0 && !(e[i] > e[i - 1]))
      return "pgv_pga_edges_s must increase strictly (edge " + std::to_string(i) + ")";
  }
  return {};
}

// HDF5 C strings end at the first NUL, so such a string would not read back as written.
std::string nul_problem(const std::string& s, const std::string& what) {
  return s.find('\0') == std::string::npos ? std::string() : what + " contains a NUL byte";
}

// Sizes, names and codes of the cube as a whole, without looking at the objects.
std::string cube_level_problem(const Cube& c) {
  if (c.rotations < 1) return "rotations must be at least 1 (is " + std::to_string(c.rotations) + ")";
  if (!c.pgv_pga_edges_s.empty()) {
    if (std::string p = edges_problem(c.pgv_pga_edges_s); !p.empty()) return p;
  }
  const std::pair<const std::string*, const char*> texts[] = {{&c.job_text, "job_text"},
                                                              {&c.job_hash, "job_hash"},
                                                              {&c.software_version, "software_version"},
                                                              {&c.physics_json, "physics_json"}};
  for (const auto& [s, what] : texts) {
    if (std::string p = nul_problem(*s, what); !p.empty()) return p;
  }
  for (std::size_t r = 0; r < c.records.size(); ++r) {
    const RecordMeta& m = c.records[r];
    const std::string at = "record " + std::to_string(r) + " ";
    const std::pair<const std::string*, const char*> fields[] = {
        {&m.name, "name"}, {&m.source, "source"}, {&m.earthquake, "earthquake"}};
    for (const auto& [s, what] : fields) {
      if (std::string p = nul_problem(*s, at + what); !p.empty()) return p;
    }
  }
  return {};
}

std::string object_problem(const Cube& c, const ObjectCube& o) {
  const std::string at = "object '" + o.name + "': ";
  // the name becomes an HDF5 link name: no '/', and not "." (the group itself)
  if (o.name.empty() || o.name == "." || o.name.find('/') != std::string::npos)
    return at + "not a valid group name (empty, \".\" or containing '/')";
  if (std::string p = nul_problem(o.name, at + "name"); !p.empty()) return p;
  if (std::string p = nul_problem(o.scene, at + "scene"); !p.empty()) return p;
  const std::size_t n = cell_count(c);
  const std::pair<std::size_t, const char*> sizes[] = {{o.outcome.size(), "outcome"},
                                                       {o.rotation_deg.size(), "rotation_deg"},
                                                       {o.failure_time_s.size(), "failure_time_s"},
                                                       {o.max_tilt_deg.size(), "max_tilt_deg"},
                                                       {o.max_slip_m.size(), "max_slip_m"},
                                                       {o.wall_s.size(), "wall_s"},
                                                       {o.failure_reason.size(), "failure_reason"}};
  for (const auto& [size, what] : sizes) {
    if (size != n)
      return at + what + " has " + std::to_string(size) + " values, expected " + std::to_string(n) +
             " (records x scales x rotations)";
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (o.outcome[i] < 0 || o.outcome[i] > static_cast<std::int8_t>(CellOutcome::failed))
      return at + "outcome[" + std::to_string(i) + "] = " + std::to_string(o.outcome[i]) +
             " is not a CellOutcome";
  }
  return {};
}

void require_consistent(const Cube& c, const ObjectCube& o) {
  std::string p = cube_level_problem(c);
  if (p.empty()) p = object_problem(c, o);
  if (!p.empty()) throw std::invalid_argument("inconsistent cube: " + p);
}

}  // namespace

std::vector<double> default_pgv_pga_edges() {
  return {0.0, 0.06, 0.08, 0.10, 0.12, 0.15, 0.20, 0.25, 0.35, kInf};
}

std::vector<double> pgv_pga_edges(const Cube& cube) {
  return cube.pgv_pga_edges_s.empty() ? default_pgv_pga_edges() : cube.pgv_pga_edges_s;
}

int pgv_pga_bin(const std::vector<double>& edges_s, double pgv_pga_s) {
  if (edges_s.size() < 2 || std::isnan(pgv_pga_s)) return -1;
  if (pgv_pga_s < edges_s.front() || pgv_pga_s > edges_s.back()) return -1;
  const auto above = std::upper_bound(edges_s.begin(), edges_s.end(), pgv_pga_s);
  const int bins = static_cast<int>(edges_s.size()) - 1;
  return std::min(static_cast<int>(above - edges_s.begin()) - 1, bins - 1);
}

std::string cube_problem(const Cube& cube) {
  if (std::string p = cube_level_problem(cube); !p.empty()) return p;
  for (std::size_t i = 0; i < cube.objects.size(); ++i) {
    if (std::string p = object_problem(cube, cube.objects[i]); !p.empty()) return p;
    for (std::size_t j = 0; j < i; ++j) {
      if (cube.objects[j].name == cube.objects[i].name)
        return "two objects are named '" + cube.objects[i].name + "'";
    }
  }
  return {};
}

std::vector<double> overturn_probability(const Cube& cube, const ObjectCube& object) {
  require_consistent(cube, object);
  const std::size_t R = cube.records.size(), S = cube.scales_g.size();
  const auto A = static_cast<std::size_t>(cube.rotations);
  std::vector<double> p(R * S, kNaN);
  for (std::size_t rs = 0; rs < R * S; ++rs) {
    int over = 0, known = 0;
    for (std::size_t a = 0; a < A; ++a) {
      switch (static_cast<CellOutcome>(object.outcome[rs * A + a])) {
        case CellOutcome::overturned:
        case CellOutcome::inferred:  // the stop rule infers overturning above full-failure scales
          ++over;
          ++known;
          break;
        case CellOutcome::survived:
          ++known;
          break;
        case CellOutcome::not_run:
        case CellOutcome::failed:  // a failed simulation says nothing about the rock
          break;
      }
    }
    if (known > 0) p[rs] = static_cast<double>(over) / static_cast<double>(known);
  }
  return p;
}

std::vector<double> mean_overturn_probability(const Cube& cube, const ObjectCube& object) {
  const std::vector<double> p = overturn_probability(cube, object);
  const std::size_t R = cube.records.size(), S = cube.scales_g.size();
  std::vector<double> mean(S, kNaN);
  for (std::size_t s = 0; s < S; ++s) {
    double sum = 0.0;
    int known = 0;
    for (std::size_t r = 0; r < R; ++r) {
      if (std::isnan(p[r * S + s])) continue;
      sum += p[r * S + s];
      ++known;
    }
    if (known > 0) mean[s] = sum / known;
  }
  return mean;
}

FragilitySurface fragility_surface(const Cube& cube, const ObjectCube& object) {
  const std::vector<double> p = overturn_probability(cube, object);
  FragilitySurface f;
  f.edges_s = pgv_pga_edges(cube);
  const std::size_t S = cube.scales_g.size(), B = f.bins();
  std::vector<double> sum(S * B, 0.0);
  f.count.assign(S * B, 0);
  for (std::size_t r = 0; r < cube.records.size(); ++r) {
    const int b = pgv_pga_bin(f.edges_s, cube.records[r].pgv_pga_s);
    if (b < 0) continue;
    for (std::size_t s = 0; s < S; ++s) {
      const double v = p[r * S + s];
      if (std::isnan(v)) continue;
      sum[s * B + static_cast<std::size_t>(b)] += v;
      ++f.count[s * B + static_cast<std::size_t>(b)];
    }
  }
  f.probability.assign(S * B, kNaN);
  for (std::size_t i = 0; i < S * B; ++i) {
    if (f.count[i] > 0) f.probability[i] = sum[i] / f.count[i];
  }
  return f;
}

// ------------------------------------------------------------------------------------------------
// HDF5 plumbing: RAII handles, errors with the path and HDF5's own explanation.

namespace {

herr_t collect_error(unsigned, const H5E_error2_t* e, void* out) {
  if (e->desc != nullptr && e->desc[0] != '\0')
    static_cast<std::vector<std::string>*>(out)->push_back(e->desc);
  return 0;
}

/// " (HDF5: outermost problem: innermost cause)", or "" when HDF5 recorded nothing.
std::string hdf5_explanation() {
  std::vector<std::string> d;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_error, &d);
  if (d.empty()) return {};
  std::string s = " (HDF5: " + d.front();
  if (d.size() > 1 && d.back() != d.front()) s += ": " + d.back();
  for (char& c : s) {
    if (c == '\n') c = ' ';  // some descriptions span lines; ours is one
  }
  return s + ")";
}

/// Error context of one file: every failure becomes InputError(path, 0, what + HDF5's reason).
class H5 {
 public:
  explicit H5(std::string path) : path_(std::move(path)) {}
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_, 0, what + hdf5_explanation());
  }
  [[noreturn]] void fail_errno(const std::string& what) const {
    throw InputError(path_, 0, what + ": " + std::strerror(errno));
  }
  template <class T>
  T check(T status, const std::string& what) const {
    if (status < 0) fail(what);
    return status;
  }
  Hid own(hid_t id, Hid::Closer close, const std::string& what) const { return Hid(check(id, what), close); }

 private:
  std::string path_;
};

Hid string_type(const H5& h) {
  Hid t = h.own(H5Tcopy(H5T_C_S1), H5Tclose, "copying the string type");
  h.check(H5Tset_size(t, H5T_VARIABLE), "making the string type variable-length");
  h.check(H5Tset_cset(t, H5T_CSET_UTF8), "setting the string type to UTF-8");
  return t;
}

Hid dataspace(const H5& h, const std::vector<hsize_t>& dims) {
  if (dims.empty()) return h.own(H5Screate(H5S_SCALAR), H5Sclose, "creating a scalar dataspace");
  return h.own(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
               "creating a dataspace");
}

/// File access: the file is only ever written under a private PATH.tmp name and renamed into
/// place, so HDF5's file lock buys nothing; it fails on some Lustre/NFS mounts (style.md §5).
Hid file_access(const H5& h) {
  Hid fapl = h.own(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "creating a file access property list");
#if (H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 10 && H5_VERS_RELEASE >= 7) || H5_VERSION_GE(1, 12, 1)
  h.check(H5Pset_file_locking(fapl, false, true), "disabling file locking");
#endif
  return fapl;
}

// ------------------------------------------------------------------------------------------------
// Writing

class Writer {
 public:
  Writer(const H5& h, hid_t file) : h_(h), file_(file), str_(string_type(h)) {
    dcpl_ = h.own(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "creating a dataset creation property list");
    h.check(H5Pset_obj_track_times(dcpl_, false), "switching off dataset time stamps");
    gcpl_ = h.own(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "creating a group creation property list");
    h.check(H5Pset_obj_track_times(gcpl_, false), "switching off group time stamps");
  }

  void group(const std::string& path) {
    h_.own(H5Gcreate2(file_, path.c_str(), H5P_DEFAULT, gcpl_, H5P_DEFAULT), H5Gclose,
           "creating group " + path);
  }

  /// Scalar attribute `name` on the object at `path`.
  void attribute(const std::string& path, const char* name, hid_t file_type, hid_t mem_type,
                 const void* value) {
    const std::string what = "writing attribute " + std::string(name) + " of " + path;
    Hid space = dataspace(h_, {});
    Hid a = h_.own(
        H5Acreate_by_name(file_, path.c_str(), name, file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose, what);
    h_.check(H5Awrite(a, mem_type, value), what);
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
    Hid d = h_.own(H5Dcreate2(file_, path.c_str(), file_type, space, H5P_DEFAULT, dcpl_, H5P_DEFAULT),
                   H5Dclose, "creating dataset " + path);
    hsize_t n = 1;
    for (hsize_t x : dims) n *= x;
    // an empty selection needs no buffer, and HDF5 rejects a null one
    if (n > 0)
      h_.check(H5Dwrite(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "writing dataset " + path);
    attribute(path, "units", units);
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
  Hid strings(const std::string& path, const std::vector<std::string>& v, const std::string& description) {
    std::vector<const char*> p;
    p.reserve(v.size());
    for (const std::string& s : v) p.push_back(s.c_str());
    return dataset(path, str_, str_, {v.size()}, p.data(), "none", description);
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

std::vector<std::int32_t> iota32(std::size_t n) {
  std::vector<std::int32_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::int32_t>(i);
  return v;
}

void write_contents(const H5& h, hid_t file, const Cube& c) {
  Writer w(h, file);
  const std::vector<double> edges = pgv_pga_edges(c);
  const hsize_t R = c.records.size(), S = c.scales_g.size(), A = static_cast<hsize_t>(c.rotations);
  const hsize_t B = edges.size() - 1;

  w.attribute("/", "schema_version", std::int32_t{kCubeSchemaVersion});
  w.attribute("/", "software_version", c.software_version);
  w.attribute("/", "job_text", c.job_text);
  w.attribute("/", "job_hash", c.job_hash);
  w.attribute("/", "physics_json", c.physics_json);
  w.attribute("/", "seed", std::uint64_t{c.seed});
  w.attribute("/", "units", std::string("SI unless the name says otherwise"));
  w.attribute("/", "job_inputs_sha256", c.job_inputs);
  w.attribute("/", "inputs_sha256", c.inputs_sha256);

  w.group("/axes");
  Hid record =
      w.strings("/axes/record", column<std::string>(c.records, [](const RecordMeta& m) { return m.name; }),
                "record (set) names, in job order");
  w.make_scale(record, "/axes/record", "record");
  Hid scale = w.doubles("/axes/scale_g", c.scales_g, {S}, "g", "target GMRotI50 PGA of each scale");
  w.make_scale(scale, "/axes/scale_g", "scale_g");
  Hid rotation = w.ints("/axes/rotation", iota32(A), {A}, "none",
                        "rotation index; the angle of each cell is in rotation_deg");
  w.make_scale(rotation, "/axes/rotation", "rotation");
  Hid bin = w.ints("/axes/pgv_pga_bin", iota32(B), {B}, "none",
                   "PGV/PGA bin index; bin i holds pgv_pga_edges_s[i] <= PGV/PGA < pgv_pga_edges_s[i+1] "
                   "(the last bin also holds its upper edge)");
  w.make_scale(bin, "/axes/pgv_pga_bin", "pgv_pga_bin");
  w.doubles("/axes/pgv_pga_edges_s", edges, {B + 1}, "s",
            "edges of the PGV/PGA bins of the fragility surface");

  w.group("/records");
  const auto text = [&](const char* name, auto field, const char* description) {
    const std::string path = std::string("/records/") + name;
    Hid d = w.strings(path, column<std::string>(c.records, field), description);
    w.attach(d, path, 0, record, "record");
  };
  const auto number = [&](const char* name, auto field, const char* units, const char* description) {
    const std::string path = std::string("/records/") + name;
    Hid d = w.doubles(path, column<double>(c.records, field), {R}, units, description);
    w.attach(d, path, 0, record, "record");
  };
  text(
      "name", [](const RecordMeta& m) { return m.name; }, "record (set) name");
  text(
      "source", [](const RecordMeta& m) { return m.source; }, "motion-set spec the record was read from");
  text(
      "earthquake", [](const RecordMeta& m) { return m.earthquake; },
      "earthquake, from the record list (may be empty)");
  text(
      "alignment", [](const RecordMeta& m) { return m.alignment; },
      "how the components were aligned to one length (zero-padding, resampling); empty if they matched");
  text(
      "inputs_sha256", [](const RecordMeta& m) { return m.inputs; },
      "SHA-256 of the record's motion files, sha256sum lines (HEX  PATH)");
  number(
      "start_s", [](const RecordMeta& m) { return m.start_s; }, "s", "start of the time window");
  number(
      "end_s", [](const RecordMeta& m) { return m.end_s; }, "s", "end of the time window");
  number(
      "gmroti_pga_g", [](const RecordMeta& m) { return m.gmroti_pga_g; }, "g",
      "GMRotI50 PGA of the windowed record, as computed");
  number(
      "gmroti_pgv_cm_s", [](const RecordMeta& m) { return m.gmroti_pgv_cm_s; }, "cm/s",
      "GMRotI50 PGV of the windowed record, as computed");
  number(
      "pgv_pga_s", [](const RecordMeta& m) { return m.pgv_pga_s; }, "s",
      "PGV/PGA of the record (bins the fragility surface)");
  number(
      "listed_pga_g", [](const RecordMeta& m) { return m.listed_pga_g; }, "g",
      "GMRotI PGA given by the record list, 0 if none");
  number(
      "listed_pgv_cm_s", [](const RecordMeta& m) { return m.listed_pgv_cm_s; }, "cm/s",
      "GMRotI PGV given by the record list, 0 if none");

  w.group("/objects");
  for (std::size_t i = 0; i < c.objects.size(); ++i) {
    const ObjectCube& o = c.objects[i];
    const std::string g = "/objects/" + o.name;
    w.group(g);
    w.attribute(g, "scene", o.scene);
    w.attribute(g, "index", static_cast<std::int32_t>(i));
    w.attribute(g, "inputs_sha256", o.inputs);
    if (!o.physics_json.empty()) w.attribute(g, "physics_json", o.physics_json);
    if (std::isfinite(o.alpha_rad)) w.attribute(g, "alpha_rad", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &o.alpha_rad);
    if (std::isfinite(o.p_rad_s)) w.attribute(g, "p_rad_s", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &o.p_rad_s);
    const auto cells = [&](Hid d, const std::string& path) {
      w.attach(d, path, 0, record, "record");
      w.attach(d, path, 1, scale, "scale_g");
      w.attach(d, path, 2, rotation, "rotation");
    };
    const std::vector<hsize_t> rsa{R, S, A};
    {
      const std::string path = g + "/outcome";
      Hid d = w.dataset(path, H5T_STD_I8LE, H5T_NATIVE_INT8, rsa, o.outcome.data(), "none",
                        "outcome of each cell (record, scale, rotation); see legend");
      w.attribute(path, "legend", std::string(kLegend));
      cells(std::move(d), path);
    }
    const auto cell_doubles = [&](const char* name, const std::vector<double>& v, const char* units,
                                  const char* description) {
      const std::string path = g + "/" + name;
      cells(w.doubles(path, v, rsa, units, description), path);
    };
    cell_doubles("rotation_deg", o.rotation_deg, "deg", "rotation of the horizontal components about z");
    cell_doubles("failure_time_s", o.failure_time_s, "s", "time at which failure was decided; NaN when none");
    cell_doubles("max_tilt_deg", o.max_tilt_deg, "deg",
                 "largest tilt of a free block; NaN when not simulated");
    cell_doubles("max_slip_m", o.max_slip_m, "m", "largest slip of a free block; NaN when not simulated");
    cell_doubles("wall_s", o.wall_s, "s",
                 "wall-clock time of the simulation; NaN when none; run-dependent (ignored by comparisons)");
    {
      const std::string path = g + "/failure_reason";
      cells(w.ints(path, o.failure_reason, rsa, "none", "0 = none, else the campaign's FailureReason code"),
            path);
    }

    // derived products, recomputed from the cells above at every write
    {
      const std::string path = g + "/probability";
      Hid d =
          w.doubles(path, overturn_probability(c, o), {R, S}, "1",
                    "overturning probability per (record, scale): (overturned + inferred) / (overturned + "
                    "inferred + survived) over the rotations; not run and failed cells left out; NaN when "
                    "none is known");
      w.attach(d, path, 0, record, "record");
      w.attach(d, path, 1, scale, "scale_g");
    }
    const FragilitySurface f = fragility_surface(c, o);
    const auto surface = [&](Hid d, const std::string& path) {
      w.attach(d, path, 0, scale, "scale_g");
      w.attach(d, path, 1, bin, "pgv_pga_bin");
    };
    {
      const std::string path = g + "/fragility";
      surface(w.doubles(path, f.probability, {S, B}, "1",
                        "P(overturn | scale, PGV/PGA bin): mean of probability over the records of the bin "
                        "whose probability is known; NaN for empty bins"),
              path);
    }
    {
      const std::string path = g + "/fragility_count";
      surface(w.ints(path, f.count, {S, B}, "1", "number of records averaged in fragility"), path);
    }
  }
}

// Writes bytes to a new file and fsyncs it; errors name the file and errno.
void write_file(const H5& h, const std::string& p, const std::vector<unsigned char>& bytes) {
  const int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) h.fail_errno("creating " + p);
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      ::close(fd);
      errno = err;
      h.fail_errno("writing " + p);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    errno = err;
    h.fail_errno("syncing " + p);
  }
  if (::close(fd) != 0) h.fail_errno("closing " + p);
}

void fsync_path(const H5& h, const std::string& p, bool directory) {
  const int fd = ::open(p.c_str(), O_RDONLY | (directory ? O_DIRECTORY : 0));
  if (fd < 0) h.fail_errno("opening " + p + " to sync it");
  const int status = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  // some file systems cannot sync a directory; the rename has happened all the same
  if (status != 0 && !(directory && (err == EINVAL || err == ENOTSUP))) {
    errno = err;
    h.fail_errno("syncing " + p);
  }
}

// ------------------------------------------------------------------------------------------------
// Reading

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
    Hid d = open_dataset(path, H5T_STRING, {n});
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
    o.outcome = rd.numbers<std::int8_t>(g + "/outcome", H5T_INTEGER, H5T_NATIVE_INT8, rsa);
    o.rotation_deg = rd.doubles(g + "/rotation_deg", rsa);
    o.failure_time_s = rd.doubles(g + "/failure_time_s", rsa);
    o.max_tilt_deg = rd.doubles(g + "/max_tilt_deg", rsa);
    o.max_slip_m = rd.doubles(g + "/max_slip_m", rsa);
    o.wall_s = rd.doubles(g + "/wall_s", rsa);
    o.failure_reason = rd.numbers<std::int32_t>(g + "/failure_reason", H5T_INTEGER, H5T_NATIVE_INT32, rsa);
  }
  if (std::string p = cube_problem(c); !p.empty()) h.fail("inconsistent cube: " + p);
  return c;
}

}  // namespace

void write_cube(const std::string& path, const Cube& cube) {
  if (std::string p = cube_problem(cube); !p.empty())
    throw InputError(path, 0, "cannot write the cube: " + p);
  const QuietErrors quiet;
  const H5 h(path);
  const std::string tmp = path + ".tmp";
  // Built in memory (HDF5's core driver, no backing store) and written out here: HDF5 never
  // meets a disk error, which it reports as a multi-line stack and, in 1.10, follows with a crash
  // at exit while closing the file it could not write (issue 12); ours is one errno line.
  std::vector<unsigned char> image;
  {
    Hid fcpl = h.own(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "creating a file creation property list");
    h.check(H5Pset_obj_track_times(fcpl, false), "switching off root group time stamps");
    Hid fapl = file_access(h);
    h.check(H5Pset_fapl_core(fapl, 1 << 20, false), "selecting the in-memory file driver");
    // SEMI: closing the file fails rather than lingers if a handle were still open
    h.check(H5Pset_fclose_degree(fapl, H5F_CLOSE_SEMI), "setting the file close degree");
    Hid file = h.own(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl, fapl), H5Fclose, "creating the cube in memory");
    write_contents(h, file, cube);
    h.check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flushing the cube in memory");
    const ssize_t size = h.check(H5Fget_file_image(file, nullptr, 0), "sizing the cube's file image");
    image.resize(static_cast<std::size_t>(size));
    h.check(H5Fget_file_image(file, image.data(), image.size()), "copying the cube's file image");
    h.check(file.close(), "closing the cube in memory");
  }
  try {
    write_file(h, tmp, image);
    if (std::rename(tmp.c_str(), path.c_str()) != 0) h.fail_errno("renaming " + tmp + " over " + path);
    const fs::path dir = fs::path(path).parent_path();
    fsync_path(h, dir.empty() ? std::string(".") : dir.string(), true);
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);  // a partial PATH.tmp is useless; PATH is untouched
    throw;
  }
}

void silence_hdf5_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

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
