// Writing the fragility cube (layout: the top of cube.cpp): built in memory with HDF5's core
// driver, then written to PATH.tmp, fsynced and renamed over PATH.
#include <fcntl.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <utility>

#include "cube_hdf5.hpp"
#include "rigid/core/types.hpp"

namespace rigid::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kLegend = "0 not run, 1 survived, 2 overturned, 3 inferred, 4 failed";

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
  /// One-dimensional float64 attribute (an empty vector writes nothing).
  void attribute(const std::string& path, const char* name, const std::vector<double>& values) {
    if (values.empty()) return;
    const std::string what = "writing attribute " + std::string(name) + " of " + path;
    Hid space = dataspace(h_, {hsize_t(values.size())});
    Hid a = h_.own(H5Acreate_by_name(file_, path.c_str(), name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT,
                                     H5P_DEFAULT),
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
    Hid d = h_.own(H5Dcreate2(file_, path.c_str(), file_type, space, H5P_DEFAULT, dcpl_, H5P_DEFAULT),
                   H5Dclose, "creating dataset " + path);
    hsize_t n = 1;
    for (hsize_t x : dims) n *= x;
    // an empty selection needs no buffer, and HDF5 rejects a null one
    if (n > 0)
      h_.check(H5Dwrite(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "writing dataset " + path);
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
    Hid a = h_.own(H5Acreate_by_name(file_, path.c_str(), "flag_values", file_type, space, H5P_DEFAULT,
                                     H5P_DEFAULT, H5P_DEFAULT),
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

std::vector<std::string> record_names(const Cube& c) {
  return column<std::string>(c.records, [](const RecordMeta& m) { return m.name; });
}

std::vector<std::int32_t> iota32(std::size_t n) {
  std::vector<std::int32_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::int32_t>(i);
  return v;
}

void write_root_attributes(Writer& w, const Cube& c) {
  w.attribute("/", "schema_version", std::int32_t{kCubeSchemaVersion});
  w.attribute("/", "software_version", c.software_version);
  w.attribute("/", "job_text", c.job_text);
  w.attribute("/", "job_hash", c.job_hash);
  w.attribute("/", "physics_json", c.physics_json);
  w.attribute("/", "seed", std::uint64_t{c.seed});
  w.attribute("/", "units", std::string("SI unless the name says otherwise"));
  w.attribute("/", "job_inputs_sha256", c.job_inputs);
  w.attribute("/", "inputs_sha256", c.inputs_sha256);
  w.attribute("/", "axes_sha256", axes_sha256(c));
  w.attribute("/", "axes_sha256_covers", std::string(kAxesChecksumCovers));
}

// A campaign "as recorded" has the one scale 0: no target PGA, every record at factor 1; its
// measured PGA and PGV/PGA are in /records.
bool as_recorded(const Cube& c) { return c.scales_g.size() == 1 && c.scales_g[0] == 0.0; }

std::string scale_description(const Cube& c, const std::string& plain) {
  return as_recorded(c) ? "0: the campaign ran \"as recorded\" (each record at factor 1, not scaled to a PGA; its "
                          "measured PGA and PGV/PGA are /records/gmroti_pga_g and /records/pgv_pga_s)"
                        : plain;
}

// The legacy shared axes (/axes, read by h5py users by path) and the per-record table (/records).
void write_axes_and_records(Writer& w, const Cube& c) {
  const std::vector<double> edges = pgv_pga_edges(c);
  const hsize_t R = c.records.size(), S = c.scales_g.size(), A = static_cast<hsize_t>(c.rotations);
  const hsize_t B = edges.size() - 1;

  w.group("/axes");
  Hid record = w.strings("/axes/record", record_names(c), "record (set) names, in job order");
  w.make_scale(record, "/axes/record", "record");
  Hid scale = w.doubles("/axes/scale_g", c.scales_g, {S}, "g", scale_description(c, "target GMRotI50 PGA of each scale"));
  w.make_scale(scale, "/axes/scale_g", "scale_g");
  Hid rotation = w.ints("/axes/rotation", iota32(A), {A}, "none",
                        "rotation index; the angle of each cell is in rotation_deg");
  w.make_scale(rotation, "/axes/rotation", "rotation");
  Hid bin = w.ints("/axes/pgv_pga_bin", iota32(B), {B}, "none",
                   "PGV/PGA bin index; bin i holds pgv_pga_edges_s[i] <= PGV/PGA < pgv_pga_edges_s[i+1] "
                   "(the last bin also holds its upper edge)");
  w.make_scale(bin, "/axes/pgv_pga_bin", "pgv_pga_bin");
  // its own dimension (E = B + 1 values), of which it is the coordinate: netCDF-4 readers see no
  // dimension without a scale
  Hid edge = w.doubles("/axes/pgv_pga_edges_s", edges, {B + 1}, "s", "edges of the PGV/PGA bins of the fragility surface");
  w.make_scale(edge, "/axes/pgv_pga_edges_s", "pgv_pga_edges_s");

  w.group("/records");
  // its own dimension scale: netCDF-4 cannot see one in the sibling group /axes
  const Hid own_record = w.strings("/records/record", record_names(c), "record (set) names, in job order");
  w.long_name("/records/record", "record (set) name");
  w.make_scale(own_record, "/records/record", "record");
  const auto text = [&](const char* name, auto field, const char* description) {
    const std::string path = std::string("/records/") + name;
    Hid d = w.strings(path, column<std::string>(c.records, field), description);
    w.attach(d, path, 0, own_record, "record");
  };
  const auto number = [&](const char* name, auto field, const char* units, const char* description) {
    const std::string path = std::string("/records/") + name;
    Hid d = w.doubles(path, column<double>(c.records, field), {R}, units, description);
    w.attach(d, path, 0, own_record, "record");
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
}

// The coordinate variables of one object group: netCDF-4 (and so xarray) sees a dimension only
// through a dimension scale in the variable's own group or an ancestor, so each object group
// carries its own, named like the dimensions. /axes keeps the shared copies h5py users read.
struct ObjectScales {
  Hid record, scale, rotation, bin;
  Hid variant;            ///< only in a group of variants
  hsize_t variants = 0;   ///< V in a group of variants, 0 in a cube without variants
};

/// The variant index 0..V-1 as a dimension scale named "variant" at `path`.
Hid write_variant_scale(Writer& w, const std::string& path, hsize_t variants) {
  Hid d = w.ints(path, iota32(variants), {variants}, "1",
                 "variant index 0..count-1; the parameters of each variant are in /variants");
  w.long_name(path, "variant index");
  w.make_scale(d, path, "variant");
  return d;
}

/// `variants` > 0: the group holds that many variants of its object and gets its own scale.
ObjectScales write_coordinates(Writer& w, const std::string& g, const Cube& c, hsize_t variants) {
  const std::vector<double> edges = pgv_pga_edges(c);
  const hsize_t S = c.scales_g.size(), A = static_cast<hsize_t>(c.rotations), B = edges.size() - 1;
  ObjectScales s;
  if (variants > 0) {
    s.variant = write_variant_scale(w, g + "/variant", variants);
    s.variants = variants;
  }
  s.record = w.strings(g + "/record", record_names(c), {c.records.size()}, nullptr, "record (set) names, in job order");
  w.long_name(g + "/record", "record (set) name");
  w.make_scale(s.record, g + "/record", "record");
  s.scale = w.doubles(g + "/scale", c.scales_g, {S}, "1",
                      scale_description(c, "target GMRotI50 PGA of each scale as a multiple of standard gravity; the same "
                                            "values in m s-2 are in target_pga"));
  w.long_name(g + "/scale", "target GMRotI50 PGA in units of g (standard gravity, 9.80665 m s-2)");
  w.make_scale(s.scale, g + "/scale", "scale");
  std::vector<double> pga(c.scales_g);
  for (double& x : pga) x *= kGravity;
  w.variable(w.doubles(g + "/target_pga", pga, {S}, "m s-2", scale_description(c, "target GMRotI50 PGA of each scale")),
                    g + "/target_pga", "target GMRotI50 PGA", {{s.scale, "scale"}});
  s.rotation = w.ints(g + "/rotation", iota32(A), {A}, "1",
                      "rotation index; the angle of each cell is in rotation_deg");
  w.long_name(g + "/rotation", "rotation index");
  w.make_scale(s.rotation, g + "/rotation", "rotation");
  s.bin = w.ints(g + "/pgv_pga_bin", iota32(B), {B}, "1",
                 "PGV/PGA bin index; bin i holds /axes/pgv_pga_edges_s[i] <= PGV/PGA < "
                 "/axes/pgv_pga_edges_s[i+1] (the last bin also holds its upper edge)");
  w.long_name(g + "/pgv_pga_bin", "PGV/PGA bin index");
  w.make_scale(s.bin, g + "/pgv_pga_bin", "pgv_pga_bin");
  return s;
}

/// The shape of a dataset and the dimension scale (with its label) of each of its dimensions.
struct Dims {
  std::vector<hsize_t> shape;
  std::vector<std::pair<hid_t, const char*>> scales;
};

/// `inner` led by the variant dimension in a group of variants; `inner` itself otherwise.
Dims led_by_variant(const ObjectScales& s, Dims inner) {
  if (s.variants == 0) return inner;
  inner.shape.insert(inner.shape.begin(), s.variants);
  inner.scales.insert(inner.scales.begin(), {s.variant, "variant"});
  return inner;
}

/// CF names, units and flag tables of the cell variables [record, scale, rotation].
struct CellVariable {
  const char* name;
  const char* units;      ///< UDUNITS-2; nullptr for text
  const char* long_name;
  const char* description;
};

constexpr CellVariable kOutcome{"outcome", "1", "outcome of the cell",
                                "outcome of each cell (record, scale, rotation); see flag_values, flag_meanings"};
constexpr CellVariable kRotationDeg{"rotation_deg", "degree", "rotation of the horizontal components about z",
                                    "rotation of the horizontal components about z"};
constexpr CellVariable kFailureTime{"failure_time_s", "s", "time of failure",
                                    "time at which failure was decided; NaN when none"};
constexpr CellVariable kMaxTilt{"max_tilt_deg", "degree", "largest tilt of a free block",
                                "largest tilt of a free block; NaN when not simulated"};
constexpr CellVariable kMaxSlip{"max_slip_m", "m", "largest slip of a free block",
                                "largest slip of a free block; NaN when not simulated"};
constexpr CellVariable kWall{"wall_s", "s", "wall-clock time of the simulation",
                             "wall-clock time of the simulation; NaN when none; run-dependent (ignored by "
                             "comparisons)"};
constexpr CellVariable kFailureReason{"failure_reason", "1", "reason a cell failed",
                                      "0 = none, else the campaign's FailureReason code; see flag_values, "
                                      "flag_meanings"};
constexpr CellVariable kFailureMessage{"failure_message", nullptr, "error message of a failed cell",
                                       "the error's text of each failed cell, empty elsewhere"};

// Flag tables of scenario::CellOutcome and scenario::FailureReason (include/rigid/scenario/case.hpp).
const std::vector<std::int8_t> kOutcomeValues{0, 1, 2, 3, 4};
const std::vector<std::int32_t> kReasonValues{0, 1, 2, 3};

/// CF flag_meanings: the codes' names, space-separated.
template <class T>
std::string flag_meanings(const std::vector<T>& codes, const char* (*name)(int)) {
  std::string s;
  for (const T code : codes) s += (s.empty() ? "" : " ") + std::string(name(code));
  return s;
}

/// The cell datasets [record, scale, rotation] of one object, with their flags and checksum; in a
/// group of variants [variant, record, scale, rotation], `o` holding the variants' cells end to end
/// (stacked_cells).
void write_cells(Writer& w, const std::string& g, const Cube& c, const ObjectCube& o, const ObjectScales& s) {
  const Dims dims = led_by_variant(s, {{c.records.size(), c.scales_g.size(), static_cast<hsize_t>(c.rotations)},
                                       {{s.record, "record"}, {s.scale, "scale"}, {s.rotation, "rotation"}}});
  const std::vector<hsize_t>& shape = dims.shape;
  const auto describe = [&](Hid d, const CellVariable& v) {
    w.variable(std::move(d), g + "/" + v.name, v.long_name, dims.scales);
    w.attribute(g + "/" + v.name, "coordinates", std::string("target_pga"));
  };
  const auto path = [&](const CellVariable& v) { return g + "/" + v.name; };

  describe(w.dataset(path(kOutcome), H5T_STD_I8LE, H5T_NATIVE_INT8, shape, o.outcome.data(), kOutcome.units,
                     kOutcome.description),
           kOutcome);
  w.attribute(path(kOutcome), "legend", std::string(kLegend));
  w.flags(path(kOutcome), H5T_STD_I8LE, H5T_NATIVE_INT8, kOutcomeValues.data(), kOutcomeValues.size(),
          flag_meanings(kOutcomeValues, outcome_name));
  for (const auto& [v, values] : {std::pair{&kRotationDeg, &o.rotation_deg}, std::pair{&kFailureTime, &o.failure_time_s},
                                  std::pair{&kMaxTilt, &o.max_tilt_deg}, std::pair{&kMaxSlip, &o.max_slip_m},
                                  std::pair{&kWall, &o.wall_s}})
    describe(w.doubles(path(*v), *values, shape, v->units, v->description), *v);
  describe(w.ints(path(kFailureReason), o.failure_reason, shape, kFailureReason.units, kFailureReason.description),
           kFailureReason);
  w.flags(path(kFailureReason), H5T_STD_I32LE, H5T_NATIVE_INT32, kReasonValues.data(), kReasonValues.size(),
          flag_meanings(kReasonValues, failure_reason_name));
  const std::vector<std::string> messages = stored_failure_messages(c, o);
  describe(w.strings(path(kFailureMessage), messages, shape, nullptr, kFailureMessage.description), kFailureMessage);

  w.attribute(g, "datasets_sha256", cell_datasets_sha256(o, messages));
  w.attribute(g, "datasets_sha256_covers", std::string(kChecksumCovers));
}

template <class T>
void append(std::vector<T>& to, const std::vector<T>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

/// The derived products, recomputed from the cells at every write: of one object, or of each of
/// a group's variants end to end (led by the variant dimension).
void write_derived(Writer& w, const std::string& g, const Cube& c, std::span<const ObjectCube> objects,
                   const ObjectScales& s) {
  const hsize_t R = c.records.size(), S = c.scales_g.size(), B = pgv_pga_edges(c).size() - 1;
  std::vector<double> p, fragility_p;
  std::vector<std::int32_t> fragility_n;
  for (const ObjectCube& o : objects) {
    append(p, overturn_probability(c, o));
    const FragilitySurface f = fragility_surface(c, o);
    append(fragility_p, f.probability);
    append(fragility_n, f.count);
  }

  const std::string probability = g + "/probability";
  const Dims rs = led_by_variant(s, {{R, S}, {{s.record, "record"}, {s.scale, "scale"}}});
  w.variable(
      w.doubles(probability, p, rs.shape, "1",
                "overturning probability per (record, scale): (overturned + inferred) / (overturned + "
                "inferred + survived) over the rotations; not run and failed cells left out; NaN when "
                "none is known"),
      probability, "probability of overturning", rs.scales);
  w.attribute(probability, "coordinates", std::string("target_pga"));

  const Dims surface = led_by_variant(s, {{S, B}, {{s.scale, "scale"}, {s.bin, "pgv_pga_bin"}}});
  const std::string fragility = g + "/fragility", count = g + "/fragility_count";
  w.variable(w.doubles(fragility, fragility_p, surface.shape, "1",
                              "P(overturn | scale, PGV/PGA bin): mean of probability over the records of the "
                              "bin whose probability is known; NaN for empty bins"),
                    fragility, "fragility: probability of overturning per scale and PGV/PGA bin", surface.scales);
  w.attribute(fragility, "coordinates", std::string("target_pga"));
  w.variable(w.ints(count, fragility_n, surface.shape, "1", "number of records averaged in fragility"), count,
                    "number of records averaged in fragility", surface.scales);
  w.attribute(count, "coordinates", std::string("target_pga"));
}

void write_object(Writer& w, const Cube& c, std::size_t index) {
  const ObjectCube& o = c.objects[index];
  const std::string g = "/objects/" + o.name;
  w.group(g);
  w.attribute(g, "scene", o.scene);
  w.attribute(g, "index", static_cast<std::int32_t>(index));
  w.attribute(g, "inputs_sha256", o.inputs);
  if (!o.physics_json.empty()) w.attribute(g, "physics_json", o.physics_json);
  if (std::isfinite(o.alpha_rad)) w.attribute(g, "alpha_rad", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &o.alpha_rad);
  if (std::isfinite(o.p_rad_s)) w.attribute(g, "p_rad_s", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &o.p_rad_s);
  if (std::isfinite(o.alpha_rad)) {
    for (const auto& [name, value] : {std::pair{"rocking_radius_m", &o.rocking_radius_m},
                                      std::pair{"weakest_azimuth_deg", &o.weakest_azimuth_deg}}) {
      if (std::isfinite(*value)) w.attribute(g, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, value);
    }
    w.attribute(g, "alpha_by_azimuth_rad", o.alpha_by_azimuth_rad);
    w.attribute(g, "support_polygon_m", o.support_polygon_m);
  }
  const ObjectScales scales = write_coordinates(w, g, c, 0);
  write_cells(w, g, c, o, scales);
  write_derived(w, g, c, std::span(&o, 1), scales);
}

// ---- a cube with variants (schema_version 2)

/// /variants: the table of the parameters' values per variant, with the axis' dimension scale.
void write_variant_table(Writer& w, const VariantTable& t) {
  const hsize_t V = static_cast<hsize_t>(t.count);
  std::string names;
  for (const VariantParameter& p : t.parameters) names += (names.empty() ? "" : " ") + p.name;
  w.group("/variants");
  w.attribute("/variants", "method", t.method);
  w.attribute("/variants", "seed", std::uint64_t{t.seed});
  w.attribute("/variants", "count", std::int32_t{t.count});
  w.attribute("/variants", "parameters", names);
  const Hid index = write_variant_scale(w, "/variants/variant", V);
  for (const VariantParameter& p : t.parameters) {
    const std::string path = "/variants/" + p.name;
    // numeric when it has values (cube_problem: exactly one of values and labels has V entries)
    Hid d = p.values.size() == V ? w.doubles(path, p.values, {V}, p.units.c_str(), p.description)
                                 : w.strings(path, p.labels, {V}, nullptr, p.description);
    w.variable(std::move(d), path, p.name.c_str(), {{index, "variant"}});
  }
}

/// A polygon's corners as one string, "x0 y0 x1 y1 ..." with 17 significant digits (exact).
std::string corners_text(const std::vector<double>& xy) {
  std::string s;
  char buf[32];
  for (const double x : xy) {
    std::snprintf(buf, sizeof buf, "%.17g", x);
    s += (s.empty() ? "" : " ") + std::string(buf);
  }
  return s;
}

/// alpha_by_azimuth_rad [variant, azimuth] and its azimuth scale, when every variant has the same
/// number of azimuths (a rectangular array); nothing otherwise.
void write_alpha_by_azimuth(Writer& w, const std::string& g, std::span<const ObjectCube> variants,
                            const ObjectScales& s) {
  const std::size_t Z = variants.front().alpha_by_azimuth_rad.size();
  for (const ObjectCube& o : variants) {
    if (o.alpha_by_azimuth_rad.size() != Z) return;
  }
  if (Z == 0) return;
  std::vector<double> azimuth_deg(Z), alpha;
  for (std::size_t k = 0; k < Z; ++k) azimuth_deg[k] = static_cast<double>(k) * 360.0 / static_cast<double>(Z);
  for (const ObjectCube& o : variants) append(alpha, o.alpha_by_azimuth_rad);
  const std::string azimuth = g + "/azimuth";
  Hid scale = w.doubles(azimuth, azimuth_deg, {Z}, "degree", "azimuth of the ground acceleration, k * 360 / Z");
  w.long_name(azimuth, "azimuth of the ground acceleration");
  w.make_scale(scale, azimuth, "azimuth");
  w.variable(w.doubles(g + "/alpha_by_azimuth_rad", alpha, {s.variants, Z}, "rad",
                       "rocking angle alpha for a ground acceleration along each azimuth"),
             g + "/alpha_by_azimuth_rad", "rocking angle alpha per azimuth",
             {{s.variant, "variant"}, {scale, "azimuth"}});
}

/// The per-variant values that are group attributes in a cube without variants, as datasets [variant].
void write_variant_values(Writer& w, const std::string& g, std::span<const ObjectCube> variants,
                          const ObjectScales& s) {
  const std::vector<std::pair<hid_t, const char*>> by_variant{{s.variant, "variant"}};
  const auto number = [&](const char* name, double ObjectCube::*field, const char* units, const char* long_name,
                          const char* description) {
    std::vector<double> v;
    for (const ObjectCube& o : variants) v.push_back(o.*field);
    w.variable(w.doubles(g + "/" + name, v, {s.variants}, units, description), g + "/" + name, long_name,
               by_variant);
  };
  const auto text = [&](const char* name, auto field, const char* long_name, const char* description) {
    std::vector<std::string> v;
    for (const ObjectCube& o : variants) v.push_back(field(o));
    w.variable(w.strings(g + "/" + name, v, {s.variants}, nullptr, description), g + "/" + name, long_name,
               by_variant);
  };
  number("alpha_rad", &ObjectCube::alpha_rad, "rad", "rocking angle alpha",
         "rocking angle alpha of a single block (scenario::rocking_parameters); NaN when none (stacks)");
  number("p_rad_s", &ObjectCube::p_rad_s, "rad s-1", "rocking frequency parameter p",
         "rocking frequency parameter p of a single block; NaN when none");
  number("rocking_radius_m", &ObjectCube::rocking_radius_m, "m", "rocking radius R",
         "distance from the rocking edge to the centre of mass; NaN when none");
  number("weakest_azimuth_deg", &ObjectCube::weakest_azimuth_deg, "degree", "weakest azimuth",
         "azimuth of the ground acceleration with the smallest alpha; NaN when none");
  text("physics_json", [](const ObjectCube& o) { return o.physics_json; }, "physics and run settings",
       "the variant's own physics and run settings as a JSON object");
  text("inputs_sha256", [](const ObjectCube& o) { return o.inputs; }, "SHA-256 of the inputs",
       "SHA-256 of every file the variant was built from, sha256sum lines (HEX  PATH)");
  write_alpha_by_azimuth(w, g, variants, s);
  text("support_polygon_m", [](const ObjectCube& o) { return corners_text(o.support_polygon_m); },
       "support polygon", "corners of the support polygon relative to the centroid, \"x0 y0 x1 y1 ...\" (m); "
       "empty when none");
}

/// One group holding every variant of base object `base` (Cube::objects[base * V .. base * V + V)).
void write_variant_object(Writer& w, const Cube& c, std::size_t base) {
  const auto V = static_cast<std::size_t>(c.variants.count);
  const std::span<const ObjectCube> variants(c.objects.data() + base * V, V);
  const std::string g = "/objects/" + variants.front().name;
  w.group(g);
  w.attribute(g, "scene", variants.front().scene);
  w.attribute(g, "index", static_cast<std::int32_t>(base));
  w.attribute(g, "variants", static_cast<std::int32_t>(V));
  const ObjectScales scales = write_coordinates(w, g, c, V);
  write_variant_values(w, g, variants, scales);
  write_cells(w, g, c, stacked_cells(c, variants), scales);
  write_derived(w, g, c, variants, scales);
}

void write_contents(const H5& h, hid_t file, const Cube& c) {
  Writer w(h, file);
  write_root_attributes(w, c);
  write_axes_and_records(w, c);
  if (c.variants.count > 0) write_variant_table(w, c.variants);
  w.group("/objects");
  if (c.variants.count > 0) {
    const auto V = static_cast<std::size_t>(c.variants.count);
    for (std::size_t base = 0; base < c.objects.size() / V; ++base) write_variant_object(w, c, base);
  } else {
    for (std::size_t i = 0; i < c.objects.size(); ++i) write_object(w, c, i);
  }
}

// A string attribute, or "" when absent or unreadable.
std::string string_attribute_or_empty(hid_t loc, const char* object, const char* name) {
  if (H5Aexists_by_name(loc, object, name, H5P_DEFAULT) <= 0) return "";
  const Hid a(H5Aopen_by_name(loc, object, name, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  const Hid type(H5Aget_type(a), H5Tclose);
  if (a < 0 || type < 0 || H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) <= 0) return "";
  const Hid mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(mem, H5T_VARIABLE);
  H5Tset_cset(mem, H5T_CSET_UTF8);
  char* p = nullptr;
  if (H5Aread(a, mem, &p) < 0) return "";
  std::string v = p != nullptr ? p : "";
  H5free_memory(p);
  return v;
}

// The fits `rigid fragility` stored in the cube being replaced (its /fragility group) stay with
// it while they still describe it: when the axes and every object's cells hash as before (a
// finished campaign run again). Cells added by a resume make them stale, and they are dropped.
void carry_stored_fits(const H5& h, hid_t file, const std::string& path, const Cube& c) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return;
#if H5_VERSION_GE(1, 12, 0)
  if (H5Fis_accessible(path.c_str(), H5P_DEFAULT) <= 0) return;
#else
  if (H5Fis_hdf5(path.c_str()) <= 0) return;
#endif
  const Hid fapl = file_access(h);
  const Hid old(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl), H5Fclose);
  if (old < 0 || H5Lexists(old, "/fragility", H5P_DEFAULT) <= 0) return;
  if (string_attribute_or_empty(old, "/", "axes_sha256") != string_attribute_or_empty(file, "/", "axes_sha256")) return;
  std::vector<std::string> groups;
  if (c.variants.count > 0) {
    for (std::size_t i = 0; i < c.objects.size(); i += static_cast<std::size_t>(c.variants.count))
      groups.push_back("/objects/" + c.objects[i].name);
  } else {
    for (const ObjectCube& o : c.objects) groups.push_back("/objects/" + o.name);
  }
  for (const std::string& g : groups) {
    if (H5Lexists(old, "/objects", H5P_DEFAULT) <= 0 || H5Lexists(old, g.c_str(), H5P_DEFAULT) <= 0) return;
    const std::string before = string_attribute_or_empty(old, g.c_str(), "datasets_sha256");
    if (before.empty() || before != string_attribute_or_empty(file, g.c_str(), "datasets_sha256")) return;
  }
  H5Ocopy(old, "/fragility", file, "/fragility", H5P_DEFAULT, H5P_DEFAULT);
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

}  // namespace

void write_cube(const std::string& path, const Cube& cube) {
  if (std::string p = cube_problem(cube); !p.empty())
    throw InputError(path, 0, "cannot write the cube: " + p);
  const QuietErrors quiet;
  const H5 h(path);
  const std::string tmp = path + ".tmp";
  // Built in memory (HDF5's core driver, no backing store) and written out here: HDF5 never
  // meets a disk error, which it reports as a multi-line stack and, in 1.10, follows with a crash
  // at exit while closing the file it could not write; ours is one errno line.
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
    carry_stored_fits(h, file, path, cube);
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

}  // namespace rigid::io
