#include "rigid/shaketable/physics.hpp"

#include <cstdio>

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

}  // namespace rigid::shaketable
