#pragma once
/// Variants of a campaign: each one changes the physical assumptions of every object (friction,
/// restitution, stiffness, density, centre of mass, size, contact model, or the mesh itself) so a
/// campaign can carry the epistemic uncertainty of its objects (docs/uncertainty.md). The catalogue of what a
/// variant may change, the seeded designs that sample them (Latin hypercube, grid) and their
/// application to a scene. No I/O.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rigid/scenario/scene.hpp"

namespace rigid::scenario {

/// What a variant may change.
enum class VariantKey {
  friction,          ///< Coulomb coefficient mu
  restitution,       ///< rigid model's normal restitution
  damping,           ///< penalty model's hysteretic damping D
  normal_stiffness,  ///< penalty K_N
  shear_stiffness,   ///< penalty K_S
  contact,           ///< contact model, text: "rigid" or "penalty"
  density,           ///< of every block
  com_offset_x,      ///< centre-of-mass offset of every free block, its mesh frame
  com_offset_y,
  com_offset_z,
  size_scale,  ///< geometric similitude of the whole scene about the origin
  scene,       ///< text: an alternative scene file of the object (another mesh of the rock)
};

/// A parameter's name in job files and cubes, its units and the values it admits.
struct VariantParameterInfo {
  VariantKey key;
  const char* name;
  const char* units;  ///< UDUNITS-2; "" for text
  const char* description;
  bool text = false;
  double lowest = 0;  ///< admitted values: lowest <= v (or < v when lowest_open) and v <= highest
  bool lowest_open = false;
  double highest = 0;
};

/// Every parameter a variant may change, in the order job files and cubes list them.
const std::vector<VariantParameterInfo>& variant_catalogue();
const VariantParameterInfo* find_variant_parameter(std::string_view name);
const VariantParameterInfo& variant_parameter(VariantKey key);
/// The catalogue's names, "a, b, ... or z", for messages.
std::string variant_parameter_list();
/// Why `value` is not admitted for `info` ("must be positive", ...), or nothing.
std::optional<std::string> variant_value_problem(const VariantParameterInfo& info, double value);

/// One parameter's value in one variant: `number` for a numeric parameter, `text` for a text one.
struct VariantValue {
  double number = 0;
  std::string text;
  /// Key `contact`: the method `text` names, parsed once where the value is read (io's job file
  /// reader, which can name the file and line).
  std::optional<contact::ContactMethod> method;
};

/// How a parameter is sampled: a range (uniform, or log-uniform) or a list of values.
struct VariantDomain {
  VariantKey key;
  double low = 0, high = 0;
  bool log_spacing = false;
  std::vector<VariantValue> values;  ///< non-empty: a list, sampled as categories
};

/// The variants of a job: the parameters they change and each variant's values.
struct VariantSpace {
  std::string method;  ///< "lhs", "grid" or "list"
  std::uint64_t seed = 0;
  std::vector<VariantKey> keys;                     ///< the parameters changed, in job order
  std::vector<std::vector<VariantValue>> variants;  ///< [variant][parameter]
  int count() const { return static_cast<int>(variants.size()); }
};

/// Latin hypercube of `count` variants over the domains (McKay, Beckman & Conover 1979): each
/// range is cut into `count` equal-probability strata, every stratum used once, the strata of
/// different parameters paired by seeded permutations, a seeded point within each stratum. A
/// list is sampled the same way over its entries. Counter-based: variant v's values depend only
/// on the seed, the parameter's position and v.
VariantSpace latin_hypercube(const std::vector<VariantDomain>& domains, int count, std::uint64_t seed);

/// Full factorial grid: `levels` points per range (ends included; geometric when log-spaced), a
/// list's own values; the first parameter varies slowest.
VariantSpace grid_design(const std::vector<VariantDomain>& domains, int levels);

/// Number of variants grid_design gives (a double, to refuse huge grids before building them).
double grid_size(const std::vector<VariantDomain>& domains, int levels);

/// Variant v's value of parameter `key`, or nullptr when the variants leave it alone.
const VariantValue* variant_value(const VariantSpace& space, int v, VariantKey key);

/// Applies variant v of `space` to a scene: everything but `scene` (the loader picks the file).
/// The order is the physical one: size first (the offsets are lengths of the resized block), then
/// density, then the centre of mass, then the contact law. Throws std::invalid_argument when the
/// scene cannot take it (a centre of mass outside a block, a contact model name unknown).
void apply_variant(const VariantSpace& space, int v, Scene& scene);

/// The alternative scene file of variant v, or "" when the variants keep the object's own.
std::string variant_scene(const VariantSpace& space, int v);

/// Geometric similitude of a block about the world origin: lengths times s (shape, pieces,
/// position), volume and mass times s^3, moments of inertia times s^5.
void scale_body(dynamics::BodyDef& body, double s);

}  // namespace rigid::scenario
