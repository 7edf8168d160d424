#include "rigid/shaketable/physics.hpp"

#include <cmath>
#include <cstdio>

#include "rigid/core/error.hpp"
#include "rigid/io/calibration_ensemble.hpp"
#include "rigid/shaketable/calibrate.hpp"

namespace rigid::shaketable {

std::string Physics::label() const {
  char text[160];
  if (penalty()) {
    std::snprintf(text, sizeof text, "%s penalty K=%.3g D=%g mu=%.2f", base.c_str(), law.normal_stiffness, law.damping,
                  law.friction);
  } else {
    std::snprintf(text, sizeof text, "%s rigid e=%.2f mu=%.2f", base.c_str(), law.restitution, law.friction);
  }
  return text;
}

PhysicsTable Physics::contact_law_table() const {
  PhysicsTable t;
  t.emplace_back("contact", contact::contact_method_name(law.method));
  if (penalty()) {
    t.emplace_back("normal_stiffness", law.normal_stiffness);
    t.emplace_back("shear_stiffness", law.normal_stiffness);
    t.emplace_back("damping", law.damping);
  }
  return t;
}

PhysicsTable Physics::physics_table() const {
  PhysicsTable t = contact_law_table();
  t.emplace_back("friction", law.friction);
  if (!penalty()) t.emplace_back("restitution", law.restitution);
  return t;
}

const std::vector<scenario::VariantKey>& physics_variant_keys() {
  using scenario::VariantKey;
  // in the catalogue's order, the order the job reader gives them back in
  static const std::vector<VariantKey> keys{VariantKey::friction, VariantKey::restitution, VariantKey::damping,
                                            VariantKey::scene};
  return keys;
}

scenario::VariantSpace physics_variants(const std::vector<Physics>& physics) {
  scenario::VariantSpace space;
  space.method = "list";
  space.keys = physics_variant_keys();
  for (const Physics& p : physics) {
    scenario::VariantValue scene;
    scene.text = p.base_scene;
    space.variants.push_back({{p.law.friction, "", {}}, {p.law.restitution, "", {}}, {p.law.damping, "", {}}, scene});
  }
  return space;
}

io::Json physics_json(const Physics& p) {
  io::Json j;
  j["base"] = p.base;
  j["flatten_base_m"] = p.flatten_m;
  j["contact"] = contact::contact_method_name(p.law.method);
  if (p.penalty()) {
    j["normal_stiffness_n_m1_5"] = p.law.normal_stiffness;
    j["damping_s_m"] = p.law.damping;
  } else {
    j["restitution"] = p.law.restitution;
  }
  j["friction"] = p.law.friction;
  return j;
}

Physics physics_from_json(const io::Json& m, const std::string& file) {
  Physics p;
  if (!m.contains("contact") || !m["contact"].is_string() ||
      !contact::parse_contact_method(m["contact"].get<std::string>(), p.law.method))
    throw InputError(file, 0, "ensemble member without a contact law it names");
  p.flatten_m = io::member_number(m, "flatten_base_m", file);
  if (!(p.flatten_m >= 0 && p.flatten_m < 0.1))
    throw InputError(file, 0, "ensemble member with flatten_base_m outside [0, 0.1) m");
  p.base = base_name(p.flatten_m);
  if (p.penalty()) {
    p.law.normal_stiffness = io::member_number(m, "normal_stiffness_n_m1_5", file);
    p.law.damping = io::member_number(m, "damping_s_m", file);
    if (!(p.law.normal_stiffness > 0) || !(p.law.damping >= 0))
      throw InputError(file, 0, "ensemble member with a stiffness <= 0 or a negative damping");
  } else {
    p.law.restitution = io::member_number(m, "restitution", file);
    if (!(p.law.restitution >= 0 && p.law.restitution <= 1))
      throw InputError(file, 0, "ensemble member with a restitution outside [0, 1]");
  }
  p.law.friction = io::member_number(m, "friction", file);
  if (!(p.law.friction > 0)) throw InputError(file, 0, "ensemble member with a friction <= 0");
  return p;
}

}  // namespace rigid::shaketable
