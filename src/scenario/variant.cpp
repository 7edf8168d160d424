#include "rigid/scenario/variant.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "rigid/core/rng.hpp"

namespace rigid::scenario {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The seeded word of (seed, parameter, variant, purpose): every value is computed on its own.
std::uint64_t draw(std::uint64_t seed, std::size_t parameter, int variant, int purpose) {
  std::uint64_t h = splitmix64(seed);
  for (std::uint64_t v : {std::uint64_t(parameter), std::uint64_t(variant), std::uint64_t(purpose)})
    h = splitmix64(h ^ v);
  return h;
}

// The value at probability u in [0, 1] of a range (uniform or log-uniform).
double range_value(const VariantDomain& d, double u) {
  if (d.log_spacing) return std::exp(std::log(d.low) + u * (std::log(d.high) - std::log(d.low)));
  return d.low + u * (d.high - d.low);
}

}  // namespace

const std::vector<VariantParameterInfo>& variant_catalogue() {
  static const std::vector<VariantParameterInfo> catalogue{
      {VariantKey::friction, "friction", "1", "Coulomb friction coefficient mu", false, 0, true, kInf},
      {VariantKey::restitution, "restitution", "1", "normal restitution of the rigid contact model", false, 0, false,
       1},
      {VariantKey::damping, "damping", "s m-1", "hysteretic damping D of the penalty contact model", false, 0, false,
       kInf},
      {VariantKey::normal_stiffness, "normal_stiffness", "N m-1.5", "normal stiffness K_N of the penalty contact model",
       false, 0, true, kInf},
      {VariantKey::shear_stiffness, "shear_stiffness", "N m-1", "shear stiffness K_S of the penalty contact model",
       false, 0, true, kInf},
      {VariantKey::contact, "contact", "", "contact model (rigid or penalty)", true, 0, false, 0},
      {VariantKey::density, "density_kg_m3", "kg m-3", "density of every block", false, 0, true, kInf},
      {VariantKey::com_offset_x, "com_offset_x_m", "m", "centre-of-mass offset of every free block along its mesh x",
       false, -kInf, false, kInf},
      {VariantKey::com_offset_y, "com_offset_y_m", "m", "centre-of-mass offset of every free block along its mesh y",
       false, -kInf, false, kInf},
      {VariantKey::com_offset_z, "com_offset_z_m", "m", "centre-of-mass offset of every free block along its mesh z",
       false, -kInf, false, kInf},
      {VariantKey::size_scale, "size_scale", "1", "geometric similitude factor of the whole scene about its origin",
       false, 0, true, kInf},
      {VariantKey::scene, "scene", "", "alternative scene file of the object (another model of the same rock)", true, 0,
       false, 0},
  };
  return catalogue;
}

const VariantParameterInfo* find_variant_parameter(std::string_view name) {
  for (const VariantParameterInfo& p : variant_catalogue()) {
    if (name == p.name) return &p;
  }
  return nullptr;
}

const VariantParameterInfo& variant_parameter(VariantKey key) {
  for (const VariantParameterInfo& p : variant_catalogue()) {
    if (p.key == key) return p;
  }
  throw std::logic_error("variant parameter missing from the catalogue");
}

std::string variant_parameter_list() {
  std::string s;
  const auto& c = variant_catalogue();
  for (std::size_t i = 0; i < c.size(); ++i)
    s += (i == 0 ? "" : i + 1 == c.size() ? " or " : ", ") + std::string(c[i].name);
  return s;
}

std::optional<std::string> variant_value_problem(const VariantParameterInfo& info, double v) {
  if (!std::isfinite(v)) return "must be a finite number";
  if (info.lowest_open && !(v > info.lowest)) return "must be greater than " + std::to_string(int(info.lowest));
  if (!info.lowest_open && v < info.lowest) return "must not be less than " + std::to_string(int(info.lowest));
  if (v > info.highest) return "must not be greater than " + std::to_string(int(info.highest));
  return std::nullopt;
}

VariantSpace latin_hypercube(const std::vector<VariantDomain>& domains, int count, std::uint64_t seed) {
  if (count < 1) throw std::invalid_argument("a Latin hypercube needs at least one variant");
  VariantSpace space;
  space.method = "lhs";
  space.seed = seed;
  space.variants.assign(std::size_t(count), std::vector<VariantValue>(domains.size()));
  for (std::size_t j = 0; j < domains.size(); ++j) {
    const VariantDomain& d = domains[j];
    space.keys.push_back(d.key);
    // the stratum of each variant: variants sorted by a seeded key, rank = stratum
    std::vector<int> order(static_cast<std::size_t>(count));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return draw(seed, j, a, 0) < draw(seed, j, b, 0); });
    for (int stratum = 0; stratum < count; ++stratum) {
      const int v = order[std::size_t(stratum)];
      const double u = (stratum + unit_interval(draw(seed, j, v, 1))) / count;
      VariantValue& out = space.variants[std::size_t(v)][j];
      if (!d.values.empty()) {
        out = d.values[std::min(d.values.size() - 1, std::size_t(u * double(d.values.size())))];
      } else {
        out.number = range_value(d, u);
      }
    }
  }
  return space;
}

double grid_size(const std::vector<VariantDomain>& domains, int levels) {
  double n = 1;
  for (const VariantDomain& d : domains) n *= d.values.empty() ? double(levels) : double(d.values.size());
  return n;
}

VariantSpace grid_design(const std::vector<VariantDomain>& domains, int levels) {
  if (levels < 1) throw std::invalid_argument("a grid needs at least one level");
  std::vector<std::vector<VariantValue>> axes;
  VariantSpace space;
  space.method = "grid";
  for (const VariantDomain& d : domains) {
    space.keys.push_back(d.key);
    std::vector<VariantValue> axis = d.values;
    if (axis.empty()) {
      for (int i = 0; i < levels; ++i)
        axis.push_back({range_value(d, levels == 1 ? 0.5 : double(i) / (levels - 1)), "", std::nullopt});
    }
    axes.push_back(std::move(axis));
  }
  const long total = long(grid_size(domains, levels));
  for (long n = 0; n < total; ++n) {
    std::vector<VariantValue> row(axes.size());
    long rest = n;
    for (std::size_t j = axes.size(); j-- > 0;) {  // the last parameter varies fastest
      row[j] = axes[j][std::size_t(rest % long(axes[j].size()))];
      rest /= long(axes[j].size());
    }
    space.variants.push_back(std::move(row));
  }
  return space;
}

void scale_body(dynamics::BodyDef& body, double s) {
  const auto scale_shape = [s](geometry::ConvexPolyhedron& p, bool with_mass) {
    for (Vec3& v : p.vertices) v *= s;
    for (geometry::Face& f : p.faces) f.offset *= s;
    p.bounding_radius *= s;
    p.bounding_centre *= s;
    p.translation *= s;
    p.volume *= s * s * s;
    if (with_mass) {
      p.mass *= s * s * s;
      p.inertia *= s * s * s * s * s;
    }
  };
  scale_shape(body.shape, true);
  for (geometry::ConvexPolyhedron& piece : body.pieces) scale_shape(piece, false);
  body.position *= s;
  body.centre_of_mass_offset *= s;
}

const VariantValue* variant_value(const VariantSpace& space, int v, VariantKey key) {
  for (std::size_t j = 0; j < space.keys.size(); ++j) {
    if (space.keys[j] == key) return &space.variants.at(std::size_t(v))[j];
  }
  return nullptr;
}

std::string variant_scene(const VariantSpace& space, int v) {
  const VariantValue* scene = variant_value(space, v, VariantKey::scene);
  return scene ? scene->text : "";
}

void apply_variant(const VariantSpace& space, int v, Scene& scene) {
  const auto value = [&](VariantKey key) { return variant_value(space, v, key); };
  if (const VariantValue* s = value(VariantKey::size_scale)) {
    for (dynamics::BodyDef& body : scene.bodies) scale_body(body, s->number);
  }
  if (const VariantValue* rho = value(VariantKey::density)) {
    const double factor = rho->number / scene.density;
    for (dynamics::BodyDef& body : scene.bodies) {
      body.shape.mass *= factor;
      body.shape.inertia *= factor;
    }
    scene.density = rho->number;
  }
  Vec3 offset = Vec3::Zero();
  const VariantKey axes[3] = {VariantKey::com_offset_x, VariantKey::com_offset_y, VariantKey::com_offset_z};
  bool moved = false;
  for (int i = 0; i < 3; ++i) {
    if (const VariantValue* d = value(axes[i])) {
      offset[i] = d->number;
      moved = true;
    }
  }
  if (moved) {
    for (dynamics::BodyDef& body : scene.bodies) {
      if (!body.fixed) offset_centre_of_mass(body, offset);
    }
  }
  contact::ContactLaw& law = scene.law;
  if (const VariantValue* m = value(VariantKey::contact)) {
    if (!m->method) throw std::invalid_argument("contact variant \"" + m->text + "\" was not parsed");
    law.method = *m->method;
  }
  for (const auto& [key, field] :
       {std::pair{VariantKey::friction, &law.friction}, std::pair{VariantKey::restitution, &law.restitution},
        std::pair{VariantKey::damping, &law.damping}, std::pair{VariantKey::normal_stiffness, &law.normal_stiffness},
        std::pair{VariantKey::shear_stiffness, &law.shear_stiffness}}) {
    if (const VariantValue* x = value(key)) *field = x->number;
  }
}

}  // namespace rigid::scenario
