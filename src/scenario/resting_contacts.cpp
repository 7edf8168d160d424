#include "resting_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rigid::scenario {
namespace {

// Smallest distance from c to an edge of the convex hull of `scratch.points` (unit: m), 0 when c
// is outside it or the hull is degenerate.
double inner_distance(SupportScratch& scratch, const geometry::Point2& c) {
  geometry::convex_hull_2d(scratch.points, scratch.hull, scratch.order, 0.0);
  const auto& hull = scratch.hull;
  const auto& points = scratch.points;
  if (hull.size() < 3) return 0;
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const auto& a = points[std::size_t(hull[k])];
    const auto& b = points[std::size_t(hull[(k + 1) % hull.size()])];
    const double len = (b - a).norm();
    if (!(len > 0)) return 0;
    d = std::min(d, geometry::turn(a, b, c) / len);  // > 0 inside a counter-clockwise hull
  }
  return std::max(d, 0.0);
}

bool within(double ah, double az, double level_h, double level_z, double fraction, double ratio, double g) {
  return az <= level_z && az <= fraction * g && ah <= level_h && ah <= fraction * ratio * (g - az);
}

bool touches(const dynamics::ContactSummary::Pair& p, int body) { return p.a == body || p.b == body; }

}  // namespace

bool at_rest(const dynamics::World& world, double speed, double angular_speed) {
  return at_rest_relative(world, Vec3::Zero(), speed, angular_speed);
}

bool at_rest_relative(const dynamics::World& world, const Vec3& ground_velocity, double speed, double angular_speed) {
  const auto& defs = world.bodies();
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) continue;
    if ((world.states()[i].velocity - ground_velocity).norm() > speed) return false;
    if (world.angular_velocity(static_cast<int>(i)).norm() > angular_speed) return false;
  }
  return true;
}

DriveAcceleration::DriveAcceleration(const GroundDrive& g) : dt_(g.dt) {
  for (std::size_t j = 0; j + 1 < g.velocity.size(); ++j) {
    const Vec3 a = (g.velocity[j + 1] - g.velocity[j]) / g.dt;
    horizontal_.push_back(std::hypot(a.x(), a.y()));
    vertical_.push_back(std::abs(a.z()));
  }
  suffix_h_ = horizontal_;
  suffix_z_ = vertical_;
  for (std::size_t j = suffix_h_.size(); j-- > 1;) {
    suffix_h_[j - 1] = std::max(suffix_h_[j - 1], suffix_h_[j]);
    suffix_z_[j - 1] = std::max(suffix_z_[j - 1], suffix_z_[j]);
  }
}

bool DriveAcceleration::quiet(long j, double level_h, double level_z, double fraction, double ratio, double g) const {
  if (j < 0 || j >= count()) return true;
  return within(horizontal_[std::size_t(j)], vertical_[std::size_t(j)], level_h, level_z, fraction, ratio, g);
}

bool DriveAcceleration::quiet_to_end(long j, double level_h, double level_z, double fraction, double ratio,
                                     double g) const {
  if (j < 0) j = 0;
  if (j >= count()) return true;
  return within(suffix_h_[std::size_t(j)], suffix_z_[std::size_t(j)], level_h, level_z, fraction, ratio, g);
}

double quasi_static_ratio(const dynamics::World& world, const dynamics::ContactSummary& contacts, double friction,
                          SupportScratch& scratch, bool& supported) {
  const auto& defs = world.bodies();
  supported = true;
  double ratio = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) continue;
    scratch.points.clear();
    double lowest = std::numeric_limits<double>::infinity();
    double min_up = 1;  // smallest vertical component of the contact normals
    for (const auto& p : contacts.pairs) {
      if (!touches(p, int(i)) || p.loaded == 0) continue;
      const int other = p.a == int(i) ? p.b : p.a;
      if (!defs[other].fixed) {
        supported = false;
        return 0;
      }
      const double up = p.a == int(i) ? -p.normal.z() : p.normal.z();  // normal points a -> b
      min_up = std::min(min_up, up);
      for (std::size_t k = p.first; k < p.first + p.loaded; ++k) {
        const Vec3& x = contacts.points[k].position;
        scratch.points.emplace_back(x.x(), x.y());
        lowest = std::min(lowest, x.z());
      }
    }
    const Vec3& c = world.states()[i].position;
    if (scratch.points.size() < 3 || !(min_up > 0)) return 0;
    const double h = c.z() - lowest;
    if (!(h > 0)) return 0;
    const double d = inner_distance(scratch, geometry::Point2(c.x(), c.y()));
    const double slope = std::atan(friction) - std::acos(std::min(min_up, 1.0));
    if (!(d > 0) || !(slope > 0)) return 0;
    ratio = std::min({ratio, d / h, std::tan(slope)});
  }
  return std::isfinite(ratio) ? ratio : 0.0;
}

void loaded_counts(const dynamics::ContactSummary& contacts, std::vector<std::size_t>& out) {
  out.clear();
  for (const auto& p : contacts.pairs) out.push_back(p.loaded);
}

bool corners_loaded(const dynamics::World& world, const dynamics::ContactSummary& contacts, double fraction) {
  const auto& defs = world.bodies();
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) continue;
    double least = std::numeric_limits<double>::infinity(), sum = 0;
    long count = 0;
    for (const auto& p : contacts.pairs) {
      if (!touches(p, int(i))) continue;
      for (std::size_t k = p.first; k < p.first + p.loaded; ++k) {
        const double f = contacts.points[k].load;
        least = std::min(least, f);
        sum += f;
        ++count;
      }
    }
    if (count == 0 || !(least >= fraction * sum / double(count))) return false;
  }
  return true;
}

}  // namespace rigid::scenario
