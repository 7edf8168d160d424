// Writing the fragility cube's object groups (layout: the top of cube.cpp): coordinates, cell
// datasets with their flags and checksum, derived products; one group per object, or per base
// object holding all its variants.
#include <cmath>
#include <span>
#include <string>
#include <utility>

#include "cube_writer.hpp"

namespace rigid::io {
namespace {

constexpr const char* kLegend = "0 not run, 1 survived, 2 overturned, 3 inferred, 4 failed";

// The coordinate variables of one object group: netCDF-4 (and so xarray) sees a dimension only
// through a dimension scale in the variable's own group or an ancestor, so each object group
// carries its own, named like the dimensions. /axes keeps the shared copies h5py users read.
struct ObjectScales {
  Hid record, scale, rotation, bin;
  Hid variant;           ///< only in a group of variants
  hsize_t variants = 0;  ///< V in a group of variants, 0 in a cube without variants
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
                      scale_description(c,
                                        "target GMRotI50 PGA of each scale as a multiple of standard gravity; the same "
                                        "values in m s-2 are in target_pga"));
  w.long_name(g + "/scale", "target GMRotI50 PGA in units of g (standard gravity, 9.80665 m s-2)");
  w.make_scale(s.scale, g + "/scale", "scale");
  std::vector<double> pga(c.scales_g);
  for (double& x : pga) x *= kGravity;
  w.variable(w.doubles(g + "/target_pga", pga, {S}, "m s-2", scale_description(c, "target GMRotI50 PGA of each scale")),
             g + "/target_pga", "target GMRotI50 PGA", {{s.scale, "scale"}});
  s.rotation =
      w.ints(g + "/rotation", iota32(A), {A}, "1", "rotation index; the angle of each cell is in rotation_deg");
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
  const char* units;  ///< UDUNITS-2; nullptr for text
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
constexpr CellVariable kUnconverged{"unconverged_steps", "1", "steps whose contact solve did not converge",
                                    "steps of the run whose rigid contact solve stopped at its sweep cap without "
                                    "converging; 0 for penalty contact and the 2D model; -1 when not simulated or not "
                                    "recorded; a diagnostic, outside datasets_sha256"};

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
  for (const auto& [v, values] :
       {std::pair{&kRotationDeg, &o.rotation_deg}, std::pair{&kFailureTime, &o.failure_time_s},
        std::pair{&kMaxTilt, &o.max_tilt_deg}, std::pair{&kMaxSlip, &o.max_slip_m}, std::pair{&kWall, &o.wall_s}})
    describe(w.doubles(path(*v), *values, shape, v->units, v->description), *v);
  describe(w.ints(path(kFailureReason), o.failure_reason, shape, kFailureReason.units, kFailureReason.description),
           kFailureReason);
  w.flags(path(kFailureReason), H5T_STD_I32LE, H5T_NATIVE_INT32, kReasonValues.data(), kReasonValues.size(),
          flag_meanings(kReasonValues, failure_reason_name));
  const std::vector<std::string> messages = stored_failure_messages(c, o);
  describe(w.strings(path(kFailureMessage), messages, shape, nullptr, kFailureMessage.description), kFailureMessage);
  describe(
      w.ints(path(kUnconverged), stored_unconverged_steps(c, o), shape, kUnconverged.units, kUnconverged.description),
      kUnconverged);

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
  w.variable(w.doubles(probability, p, rs.shape, "1",
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
    w.variable(w.doubles(g + "/" + name, v, {s.variants}, units, description), g + "/" + name, long_name, by_variant);
  };
  const auto text = [&](const char* name, auto field, const char* long_name, const char* description) {
    std::vector<std::string> v;
    for (const ObjectCube& o : variants) v.push_back(field(o));
    w.variable(w.strings(g + "/" + name, v, {s.variants}, nullptr, description), g + "/" + name, long_name, by_variant);
  };
  number("alpha_rad", &ObjectCube::alpha_rad, "rad", "rocking angle alpha",
         "rocking angle alpha of a single block (analysis::rocking_parameters); NaN when none (stacks)");
  number("p_rad_s", &ObjectCube::p_rad_s, "rad s-1", "rocking frequency parameter p",
         "rocking frequency parameter p of a single block; NaN when none");
  number("rocking_radius_m", &ObjectCube::rocking_radius_m, "m", "rocking radius R",
         "distance from the rocking edge to the centre of mass; NaN when none");
  number("weakest_azimuth_deg", &ObjectCube::weakest_azimuth_deg, "degree", "weakest azimuth",
         "azimuth of the ground acceleration with the smallest alpha; NaN when none");
  text(
      "physics_json", [](const ObjectCube& o) { return o.physics_json; }, "physics and run settings",
      "the variant's own physics and run settings as a JSON object");
  text(
      "inputs_sha256", [](const ObjectCube& o) { return o.inputs; }, "SHA-256 of the inputs",
      "SHA-256 of every file the variant was built from, sha256sum lines (HEX  PATH)");
  write_alpha_by_azimuth(w, g, variants, s);
  text(
      "support_polygon_m", [](const ObjectCube& o) { return corners_text(o.support_polygon_m); }, "support polygon",
      "corners of the support polygon relative to the centroid, \"x0 y0 x1 y1 ...\" (m); "
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
  if (c.calibration) {
    w.attribute(g, "calibration", c.calibration->path);
    w.attribute(g, "calibration_sha256", c.calibration->sha256);
    w.attribute(g, "calibration_weights", c.calibration->weights);
    w.attribute(g, "calibration_summary", c.calibration->summary_json);
  }
  const ObjectScales scales = write_coordinates(w, g, c, V);
  write_variant_values(w, g, variants, scales);
  write_cells(w, g, c, stacked_cells(c, variants), scales);
  write_derived(w, g, c, variants, scales);
}

}  // namespace

void write_objects(Writer& w, const Cube& c) {
  if (c.variants.count > 0) write_variant_table(w, c.variants);
  w.group("/objects");
  if (c.variants.count > 0) {
    const auto V = static_cast<std::size_t>(c.variants.count);
    for (std::size_t base = 0; base < c.objects.size() / V; ++base) write_variant_object(w, c, base);
  } else {
    for (std::size_t i = 0; i < c.objects.size(); ++i) write_object(w, c, i);
  }
}

}  // namespace rigid::io
