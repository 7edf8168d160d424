// The HDF5 fragility cube (include/rigid/io/cube.hpp): this file holds its layout, its validation
// and the adapters that hand a cube's arrays to the statistics module for the derived products
// (probability, fragility: the rules live in statistics/overturn.hpp and
// statistics/fragility_surface.hpp); cube_write.cpp and cube_read.cpp write and read it with the
// HDF5 C API (shared plumbing: cube_hdf5.hpp).
//
// Layout, schema_version 1: a cube without variants (R records, S scales, A rotations, B = E - 1
// PGV/PGA bins):
//
//   /                      attributes: schema_version (int32), software_version, job_text,
//                          job_hash, physics_json (strings), seed (uint64),
//                          units = "SI unless the name says otherwise",
//                          job_inputs_sha256 (sha256sum lines: settings, job file, record list),
//                          inputs_sha256 (one SHA-256 over every input of every cell),
//                          axes_sha256, axes_sha256_covers (from schema_version 3: the checksum
//                          of the axes, the records and the variant table, kAxesChecksumCovers)
//   /axes/record           [R] string     dimension scale "record" (names, job order)
//   /axes/scale_g          [S] float64 g  dimension scale "scale_g" (target GMRotI50 PGA)
//   /axes/rotation         [A] int32      dimension scale "rotation" (0..A-1)
//   /axes/pgv_pga_bin      [B] int32      dimension scale "pgv_pga_bin" (0..B-1)
//   /axes/pgv_pga_edges_s  [E] float64 s  dimension scale "pgv_pga_edges_s" (its own dimension);
//                                         bin i holds edges[i] <= PGV/PGA < edges[i+1]
//                                         (the last bin also holds PGV/PGA == edges[E-1])
//   /records/{name, source, earthquake}                               [R] string
//   /records/{start_s, end_s, gmroti_pga_g, gmroti_pgv_cm_s, pgv_pga_s,
//             listed_pga_g, listed_pgv_cm_s}                          [R] float64
//   /records/inputs_sha256                                            [R] string (sha256sum lines)
//   /records/alignment                                                [R] string (empty: matched)
//   /records/record                                                   [R] string dimension scale
//   /objects/<name>/       attributes: scene (string), index (int32, position in the job),
//                          inputs_sha256 (string, sha256sum lines: scene, model, STLs, state),
//                          alpha_rad, p_rad_s, rocking_radius_m, weakest_azimuth_deg (float64)
//                          and the float64 arrays alpha_by_azimuth_rad [Z] (azimuth k*360/Z deg
//                          of the ground acceleration) and support_polygon_m [2V] (x0 y0 x1 y1..,
//                          relative to the centroid): only for single-block objects,
//                          physics_json (string: the object's own physics and run settings),
//                          datasets_sha256, datasets_sha256_covers (checksum of the cell datasets)
//       record, scale, rotation, pgv_pga_bin   the group's own dimension scales (netCDF-4
//                          coordinate variables): names; target PGA in g (units "1"); indices
//       target_pga         [S]     float64 m s-2, auxiliary coordinate of scale
//       outcome            [R,S,A] int8   flag_values/flag_meanings (CellOutcome), legend
//       rotation_deg, failure_time_s, max_tilt_deg, max_slip_m, wall_s   [R,S,A] float64
//       failure_reason     [R,S,A] int32  flag_values/flag_meanings (FailureReason)
//       failure_message    [R,S,A] string the error's text of failed cells, "" elsewhere
//       unconverged_steps  [R,S,A] int32  steps whose contact solve hit its sweep cap; -1 when not
//                          simulated or not recorded (outside datasets_sha256)
//       probability        [R,S]   float64  derived: statistics::overturn_probability()
//       fragility          [S,B]   float64  derived: statistics::fragility_surface().probability
//       fragility_count    [S,B]   int32    derived: statistics::fragility_surface().count
//
// Layout, schema_version 2: a cube with variants (Cube::variants.count = V > 0). Everything above
// stays where it is, with these changes:
//
//   /variants              attributes: method (string), seed (uint64), count (int32 V),
//                          parameters (string: the parameters' names, space-separated, job order)
//   /variants/variant      [V] int32      dimension scale "variant" (0..V-1), long_name "variant index"
//   /variants/<parameter>  [V] float64 with `units`, or string (a text parameter); description,
//                          long_name; attached to /variants/variant
//   /objects/<name>/       one group per base object; attributes scene, index (the base object's
//                          position in the job), variants (int32 V), datasets_sha256 (over the
//                          cell datasets of all V variants, as stored: variant 0's cells first),
//                          datasets_sha256_covers. The per-variant values that are attributes in
//                          schema_version 1 are datasets [V] attached to the group's scale variant:
//       variant            [V]     int32  the group's own dimension scale "variant" (0..V-1)
//       alpha_rad, p_rad_s, rocking_radius_m, weakest_azimuth_deg   [V] float64, NaN when none
//       physics_json, inputs_sha256                                 [V] string
//       alpha_by_azimuth_rad [V,Z] float64 rad, with its scale azimuth [Z] (degree, k*360/Z): only
//                          when every variant has the same Z > 0
//       support_polygon_m  [V]     string "x0 y0 x1 y1 ..." (%.17g), "" when none
//       outcome, rotation_deg, failure_time_s, max_tilt_deg, max_slip_m, wall_s, failure_reason,
//       failure_message, unconverged_steps    [V,R,S,A]
//       probability        [V,R,S]; fragility, fragility_count [V,S,B] (per variant, as above)
//
// Layout, schema_version 3 (what write_cube writes): either layout above, the variant axis present
// when /variants is, with both checksums required: axes_sha256 at the root and datasets_sha256 in
// every object group. A reader refuses a version 3 cube without them (a deleted checksum is not an
// old cube); a cube of version 1 or 2 is read with a warning (old_cube_warning). The derived
// datasets (probability, fragility, fragility_count) follow from the checksummed cells: readers
// recompute them (the Python side refuses stored ones that disagree). A /fragility group written
// by `rigid fragility` is kept by a rewrite whose cells and axes hash as before.
//
// Every dataset has a `description`; numbers outside the object groups `units` ("1" =
// dimensionless, "none" = text, codes, indices). In an object group every variable has a CF
// `long_name` and every number a UDUNITS-2 `units`, and each dimension has exactly one scale
// attached (H5DSattach_scale), from the same group, labelled with its name: netCDF-4, and so
// xarray, sees scales only in a variable's group or its ancestors. /axes keeps the shared scales
// for h5py readers. Strings are variable-length UTF-8; numbers are stored little-endian (f64, i8,
// i32, u64) whatever the host.
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

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "cube_hdf5.hpp"
#include "rigid/io/provenance.hpp"
#include "rigid/statistics/overturn.hpp"

namespace rigid::io {

namespace {

std::size_t cell_count(const Cube& c) { return cell_shape(c).cells(); }

// HDF5 C strings end at the first NUL, so such a string would not read back as written.
std::string nul_problem(const std::string& s, const std::string& what) {
  return s.find('\0') == std::string::npos ? std::string() : what + " contains a NUL byte";
}

// A name that becomes an HDF5 link name: not empty, no '/', not "." (the group itself).
bool valid_link_name(const std::string& name) {
  return !name.empty() && name != "." && name.find('/') == std::string::npos;
}

// Sizes, names and codes of the cube as a whole, without looking at the objects.
std::string cube_level_problem(const Cube& c) {
  if (c.rotations < 1) return "rotations must be at least 1 (is " + std::to_string(c.rotations) + ")";
  if (!c.pgv_pga_edges_s.empty()) {
    if (std::string p = statistics::pgv_pga_edges_problem(c.pgv_pga_edges_s); !p.empty()) return p;
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
  if (!valid_link_name(o.name)) return at + "not a valid group name (empty, \".\" or containing '/')";
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
  if (!o.failure_message.empty() && o.failure_message.size() != n)
    return at + "failure_message has " + std::to_string(o.failure_message.size()) + " values, expected 0 or " +
           std::to_string(n);
  if (!o.unconverged_steps.empty() && o.unconverged_steps.size() != n)
    return at + "unconverged_steps has " + std::to_string(o.unconverged_steps.size()) + " values, expected 0 or " +
           std::to_string(n);
  for (std::size_t i = 0; i < o.failure_message.size(); ++i) {
    if (std::string p = nul_problem(o.failure_message[i], at + "failure_message[" + std::to_string(i) + "]");
        !p.empty())
      return p;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (o.outcome[i] < 0 || o.outcome[i] > static_cast<std::int8_t>(CellOutcome::failed))
      return at + "outcome[" + std::to_string(i) + "] = " + std::to_string(o.outcome[i]) + " is not a CellOutcome";
  }
  return {};
}

std::string variant_parameter_problem(const VariantParameter& p, int count) {
  const std::string at = "variant parameter '" + p.name + "': ";
  // /variants/variant is the axis' own dimension scale
  if (!valid_link_name(p.name) || p.name == "variant")
    return at + "not a valid dataset name (empty, \".\", \"variant\" or containing '/')";
  for (const auto& [s, what] :
       {std::pair{&p.name, "name"}, std::pair{&p.units, "units"}, std::pair{&p.description, "description"}}) {
    if (std::string q = nul_problem(*s, at + what); !q.empty()) return q;
  }
  const auto n = static_cast<std::size_t>(count);
  const bool text = !p.labels.empty();
  if (text && !p.values.empty()) return at + "has both numbers and labels";
  if (text && !p.units.empty()) return at + "a text parameter has no units (has '" + p.units + "')";
  const std::size_t has = text ? p.labels.size() : p.values.size();
  if (has != n)
    return at + "has " + std::to_string(has) + (text ? " labels" : " values") + ", expected " + std::to_string(n) +
           " (one per variant)";
  for (std::size_t v = 0; v < p.labels.size(); ++v) {
    if (std::string q = nul_problem(p.labels[v], at + "label " + std::to_string(v)); !q.empty()) return q;
  }
  return {};
}

// The table by itself: its count, and each parameter's name and number of values.
std::string variant_table_problem(const VariantTable& t) {
  if (t.count < 0) return "variants: count must be 0 (none) or more (is " + std::to_string(t.count) + ")";
  if (t.count == 0) {
    if (!t.parameters.empty()) return "variants: parameters given but count is 0";
    return {};
  }
  if (std::string p = nul_problem(t.method, "variants: method"); !p.empty()) return p;
  for (std::size_t i = 0; i < t.parameters.size(); ++i) {
    // the names are stored space-separated in /variants' attribute `parameters`
    if (t.parameters[i].name.find_first_of(" \t\n") != std::string::npos)
      return "variant parameter '" + t.parameters[i].name + "': the name contains white space";
    if (std::string p = variant_parameter_problem(t.parameters[i], t.count); !p.empty()) return p;
    for (std::size_t j = 0; j < i; ++j) {
      if (t.parameters[j].name == t.parameters[i].name)
        return "two variant parameters are named '" + t.parameters[i].name + "'";
    }
  }
  return {};
}

// Base objects (every `stride`-th ObjectCube) must have distinct names: each is one HDF5 group.
std::string unique_names_problem(const std::vector<ObjectCube>& objects, std::size_t stride) {
  for (std::size_t i = 0; i < objects.size(); i += stride) {
    for (std::size_t j = 0; j < i; j += stride) {
      if (objects[j].name == objects[i].name) return "two objects are named '" + objects[i].name + "'";
    }
  }
  return {};
}

// With variants: each base object is `count` consecutive ObjectCubes, variants 0..count-1 in
// order, one name and scene; without, no ObjectCube claims a variant.
std::string variant_order_problem(const Cube& c) {
  const auto count = static_cast<std::size_t>(c.variants.count);
  for (std::size_t i = 0; i < c.objects.size(); ++i) {
    const ObjectCube& o = c.objects[i];
    const ObjectCube& base = c.objects[i - i % count];
    const std::string at = "object " + std::to_string(i) + " ('" + o.name + "'): ";
    if (o.variant != static_cast<int>(i % count))
      return at + "variant " + std::to_string(o.variant) + ", expected " + std::to_string(i % count) +
             " (each base object needs its " + std::to_string(count) + " variants consecutive, in order)";
    if (o.name != base.name || o.scene != base.scene)
      return at + "variant " + std::to_string(o.variant) + " of '" + base.name +
             "' has another name or scene than its variant 0";
  }
  if (c.objects.size() % count != 0)
    return "object '" + c.objects.back().name + "' has " + std::to_string(c.objects.size() % count) + " of the " +
           std::to_string(count) + " variants";
  return unique_names_problem(c.objects, count);
}

std::string no_variant_problem(const Cube& c) {
  for (const ObjectCube& o : c.objects) {
    if (o.variant != -1)
      return "object '" + o.name + "': variant " + std::to_string(o.variant) + " in a cube without variants";
  }
  return {};
}

void require_consistent(const Cube& c, const ObjectCube& o) {
  std::string p = cube_level_problem(c);
  if (p.empty()) p = object_problem(c, o);
  if (!p.empty()) throw std::invalid_argument("inconsistent cube: " + p);
}

}  // namespace

const char* outcome_name(int code) {
  switch (static_cast<CellOutcome>(code)) {
    case CellOutcome::not_run:
      return "not_run";
    case CellOutcome::survived:
      return "survived";
    case CellOutcome::overturned:
      return "overturned";
    case CellOutcome::inferred:
      return "inferred";
    case CellOutcome::failed:
      return "failed";
  }
  return "unknown";
}

const char* failure_reason_name(int code) {
  switch (static_cast<scenario::FailureReason>(code)) {
    case scenario::FailureReason::none:
      return "none";
    case scenario::FailureReason::exception:
      return "exception";
    case scenario::FailureReason::non_finite:
      return "non_finite";
    case scenario::FailureReason::worker_lost:
      return "worker_lost";
  }
  return "unknown";
}

std::vector<double> pgv_pga_edges(const Cube& cube) {
  return cube.pgv_pga_edges_s.empty() ? statistics::default_pgv_pga_edges() : cube.pgv_pga_edges_s;
}

statistics::CellShape cell_shape(const Cube& c) {
  return {c.records.size(), c.scales_g.size(), static_cast<std::size_t>(std::max(c.rotations, 0))};
}

std::string object_label(const ObjectCube& object) {
  if (object.variant < 0) return object.name;
  return object.name + " [v" + std::to_string(object.variant) + "]";
}

std::string cube_problem(const Cube& cube) {
  if (std::string p = cube_level_problem(cube); !p.empty()) return p;
  if (std::string p = variant_table_problem(cube.variants); !p.empty()) return p;
  for (const ObjectCube& o : cube.objects) {
    if (std::string p = object_problem(cube, o); !p.empty()) return p;
  }
  if (cube.calibration && cube.calibration->weights.size() != std::size_t(cube.variants.count))
    return "calibration_weights: " + std::to_string(cube.calibration->weights.size()) + " weights for " +
           std::to_string(cube.variants.count) + " variants";
  if (cube.variants.count > 0) return variant_order_problem(cube);
  if (std::string p = no_variant_problem(cube); !p.empty()) return p;
  return unique_names_problem(cube.objects, 1);
}

std::vector<double> overturn_probability(const Cube& cube, const ObjectCube& object) {
  require_consistent(cube, object);
  return statistics::overturn_probability(object.outcome, cell_shape(cube));
}

std::vector<double> mean_overturn_probability(const Cube& cube, const ObjectCube& object) {
  return statistics::mean_over_records(overturn_probability(cube, object), cell_shape(cube));
}

FragilitySurface fragility_surface(const Cube& cube, const ObjectCube& object) {
  const std::vector<double> p = overturn_probability(cube, object);
  std::vector<double> pgv_pga_s;
  pgv_pga_s.reserve(cube.records.size());
  for (const RecordMeta& r : cube.records) pgv_pga_s.push_back(r.pgv_pga_s);
  return statistics::fragility_surface(p, cube.scales_g.size(), pgv_pga_s, pgv_pga_edges(cube));
}

// ------------------------------------------------------------------------------------------------
// The checksum of an object's cell datasets (cube_hdf5.hpp), over their bytes as stored.

namespace {

void append_little_endian(std::string& bytes, std::uint64_t v, std::size_t width) {
  for (std::size_t i = 0; i < width; ++i) bytes.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}

template <class T>
void append_numbers(std::string& bytes, const std::vector<T>& values) {
  for (const T x : values) {
    if constexpr (std::is_floating_point_v<T>)
      append_little_endian(bytes, std::bit_cast<std::uint64_t>(x), sizeof x);
    else
      append_little_endian(bytes, static_cast<std::make_unsigned_t<T>>(x), sizeof x);
  }
}

void append_strings(std::string& bytes, const std::vector<std::string>& values) {
  for (const std::string& s : values) {
    append_little_endian(bytes, s.size(), sizeof(std::uint64_t));
    bytes += s;
  }
}

}  // namespace

std::vector<std::string> stored_failure_messages(const Cube& cube, const ObjectCube& object) {
  if (!object.failure_message.empty()) return object.failure_message;
  return std::vector<std::string>(cell_count(cube));
}

std::vector<std::int32_t> stored_unconverged_steps(const Cube& cube, const ObjectCube& object) {
  if (!object.unconverged_steps.empty()) return object.unconverged_steps;
  return std::vector<std::int32_t>(cell_count(cube), -1);
}

namespace {

/// Calls f(to, from) for each cell array of two ObjectCubes, in the order kChecksumCovers names
/// them, then wall_s and unconverged_steps (outside the checksum): the one list the stacking and
/// splitting of variants go through.
template <class Into, class From, class F>
void for_each_cell_array(Into& to, From& from, F f) {
  f(to.outcome, from.outcome);
  f(to.rotation_deg, from.rotation_deg);
  f(to.failure_time_s, from.failure_time_s);
  f(to.max_tilt_deg, from.max_tilt_deg);
  f(to.max_slip_m, from.max_slip_m);
  f(to.failure_reason, from.failure_reason);
  f(to.failure_message, from.failure_message);
  f(to.wall_s, from.wall_s);
  f(to.unconverged_steps, from.unconverged_steps);
}

}  // namespace

ObjectCube stacked_cells(const Cube& cube, std::span<const ObjectCube> variants) {
  ObjectCube stacked;
  for (const ObjectCube& o : variants) {
    for_each_cell_array(stacked, o, [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); });
    // as stored_failure_messages: "" for every cell of a variant that kept no messages
    if (o.failure_message.empty()) stacked.failure_message.resize(stacked.failure_message.size() + cell_count(cube));
    // as stored_unconverged_steps: -1 (not recorded) for every cell of a variant that kept none
    if (o.unconverged_steps.empty())
      stacked.unconverged_steps.resize(stacked.unconverged_steps.size() + cell_count(cube), -1);
  }
  return stacked;
}

std::vector<ObjectCube> split_cells(const ObjectCube& stacked, std::size_t count) {
  std::vector<ObjectCube> variants(count);
  const std::size_t n = count > 0 ? stacked.outcome.size() / count : 0;
  for (std::size_t v = 0; v < count; ++v) {
    for_each_cell_array(variants[v], stacked, [&](auto& to, const auto& from) {
      // an array absent from the file (failure_message of older cubes) stays absent
      if (from.size() == n * count) to.assign(from.begin() + v * n, from.begin() + (v + 1) * n);
    });
  }
  return variants;
}

std::string axes_sha256(const Cube& c) {
  std::string bytes;
  const auto strings = [&](auto field) {
    std::vector<std::string> v;
    for (const RecordMeta& m : c.records) v.push_back(m.*field);
    append_strings(bytes, v);
  };
  const auto numbers = [&](auto field) {
    std::vector<double> v;
    for (const RecordMeta& m : c.records) v.push_back(m.*field);
    append_numbers(bytes, v);
  };
  strings(&RecordMeta::name);  // /axes/record
  append_numbers(bytes, c.scales_g);
  append_numbers(bytes, pgv_pga_edges(c));
  for (auto field :
       {&RecordMeta::name, &RecordMeta::source, &RecordMeta::earthquake, &RecordMeta::alignment, &RecordMeta::inputs})
    strings(field);
  for (auto field : {&RecordMeta::start_s, &RecordMeta::end_s, &RecordMeta::gmroti_pga_g, &RecordMeta::gmroti_pgv_cm_s,
                     &RecordMeta::pgv_pga_s, &RecordMeta::listed_pga_g, &RecordMeta::listed_pgv_cm_s})
    numbers(field);
  for (const VariantParameter& p : c.variants.parameters) {
    if (p.labels.empty()) {
      append_numbers(bytes, p.values);
    } else {
      append_strings(bytes, p.labels);
    }
  }
  return sha256_hex(bytes);
}

std::string old_cube_warning(const std::string& path, const Cube& cube) {
  if (cube.schema_version >= kCubeSchemaVersionChecksummed) return "";
  return path + ": schema_version " + std::to_string(cube.schema_version) +
         " cube, written before checksums covered its axes and records: those are read unchecked";
}

std::string cell_datasets_sha256(const ObjectCube& o, const std::vector<std::string>& failure_message) {
  std::string bytes;
  append_numbers(bytes, o.outcome);
  for (const std::vector<double>* v : {&o.rotation_deg, &o.failure_time_s, &o.max_tilt_deg, &o.max_slip_m})
    append_numbers(bytes, *v);
  append_numbers(bytes, o.failure_reason);
  append_strings(bytes, failure_message);
  return sha256_hex(bytes);
}

}  // namespace rigid::io
