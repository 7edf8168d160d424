#pragma once
/// The physics a shake-table calibration varies: a model of the scanned rock's rough base and the
/// contact law the rock stands on it with (docs/validation-shaketable.md).
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "rigid/contact/contact.hpp"
#include "rigid/io/json.hpp"
#include "rigid/scenario/variant.hpp"

namespace rigid::shaketable {

/// [physics] keys and values of a scene file, as io::SceneChanges takes them.
using PhysicsTable = std::vector<std::pair<std::string, std::variant<double, std::string>>>;

/// One physics variant of a design: which model of the scanned base, and the contact law.
struct Physics {
  std::string base;        ///< the base model's name (e.g. "flat_5mm")
  std::string base_scene;  ///< the scene of this base and contact law, settled with it (absolute path)
  double flatten_m = 0;    ///< how the base model was made: cut flat this far above its lowest point (unit: m)
  /// The law: rigid (restitution) or penalty (K_N, with K_S = K_N, and damping D); friction for both
  contact::ContactLaw law;

  bool penalty() const { return law.method == contact::ContactMethod::penalty; }
  /// One line for tables: "flat_5mm penalty K=1e+06 D=2 mu=0.60".
  std::string label() const;
  /// The scene's [physics] keys of the contact law: contact and, for the penalty model, its
  /// stiffnesses (K_S = K_N) and damping.
  PhysicsTable contact_law_table() const;
  /// contact_law_table with friction and, for rigid contact, restitution: the whole law.
  PhysicsTable physics_table() const;
};

/// The parameters every variant of a designed calibration sets (friction, restitution, damping,
/// scene): each law ignores the other's, and a job's variants must all set the same ones.
const std::vector<scenario::VariantKey>& physics_variant_keys();
/// A design's physics as the [[variant]] list of its job, in physics_variant_keys' order.
scenario::VariantSpace physics_variants(const std::vector<Physics>& physics);

/// A physics as the calibration documents state it (an ensemble member's or a parameter set's law
/// fields): base, flatten_base_m, contact, normal_stiffness_n_m1_5 and damping_s_m (penalty) or
/// restitution (rigid), friction.
io::Json physics_json(const Physics& p);
/// physics_json read back (base_scene empty). Throws InputError naming `file` for a missing,
/// unknown or out-of-range field.
Physics physics_from_json(const io::Json& j, const std::string& file);

}  // namespace rigid::shaketable
