#include "rigid/scenario/history.hpp"

#include <algorithm>
#include <cmath>

#include "rigid/scenario/scene.hpp"

namespace rigid::scenario {

Vec3 HistoryRecorder::acceleration_at(double t) const {
  const std::size_t n = motion_.npts();
  if (n == 0 || motion_.dt <= 0 || t < 0 || t > motion_.duration()) return Vec3::Zero();
  const double u = t / motion_.dt;
  const std::size_t k = std::min(n - 1, static_cast<std::size_t>(std::floor(u)));
  const std::size_t k1 = std::min(n - 1, k + 1);
  const double w = u - double(k);
  const auto at = [&](const std::vector<double>& a) { return a.empty() ? 0.0 : (1 - w) * a[k] + w * a[k1]; };
  return {at(motion_.x), at(motion_.y), at(motion_.z)};
}

void HistoryRecorder::record(const dynamics::World& world) {
  const auto& defs = world.bodies();
  const auto& states = world.states();
  if (history_.time_s.empty()) {
    for (std::size_t i = 0; i < defs.size(); ++i) {
      if (!defs[i].fixed) {
        free_.push_back(int(i));
        history_.blocks.push_back(defs[i].name);
        double lowest = states[i].position.z();
        for (const Vec3& v : world.world_vertices(int(i))) lowest = std::min(lowest, v.z());
        history_.base_height_m.push_back(states[i].position.z() - lowest);
      } else if (table_ < 0) {
        table_ = int(i);
        table_start_ = states[i].position;
      }
    }
  }
  History& h = history_;
  h.time_s.push_back(world.time());
  // loaded subcontacts per body, from the contact summary the run's own stages read
  world.summarize_contacts(summary_);
  std::vector<int> loaded(defs.size(), 0);
  for (const auto& pair : summary_.pairs) {
    loaded[std::size_t(pair.a)] += int(pair.loaded);
    loaded[std::size_t(pair.b)] += int(pair.loaded);
  }
  for (int i : free_) {
    const auto& s = states[std::size_t(i)];
    h.tilt_rad.push_back(tilt(defs[std::size_t(i)].orientation, s.orientation));
    h.slip_m.push_back(world.slip()[std::size_t(i)]);
    h.position_m.insert(h.position_m.end(), {s.position.x(), s.position.y(), s.position.z()});
    const Quat& q = s.orientation;
    h.orientation.insert(h.orientation.end(), {q.w(), q.x(), q.y(), q.z()});
    h.contacts.push_back(loaded[std::size_t(i)]);
    const Vec3& f = world.contact_force(i);
    h.contact_force_n.insert(h.contact_force_n.end(), {f.x(), f.y(), f.z()});
  }
  const Vec3 d = table_ < 0 ? Vec3::Zero() : Vec3(states[std::size_t(table_)].position - table_start_);
  const Vec3 v = table_ < 0 ? Vec3::Zero() : states[std::size_t(table_)].velocity;
  h.table_displacement_m.insert(h.table_displacement_m.end(), {d.x(), d.y(), d.z()});
  h.table_velocity_m_s.insert(h.table_velocity_m_s.end(), {v.x(), v.y(), v.z()});
  const Vec3 a = acceleration_at(world.time());
  h.table_acceleration_m_s2.insert(h.table_acceleration_m_s2.end(), {a.x(), a.y(), a.z()});
}

}  // namespace rigid::scenario
