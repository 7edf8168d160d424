#include "rigid/job/cells.hpp"

#include <initializer_list>

#include "rigid/core/rng.hpp"

namespace rigid::job {

Cell CellGrid::cell(long t) const {
  Cell c;
  c.rotation = static_cast<int>(t % rotations);
  t /= rotations;
  c.scale = static_cast<int>(t % scales);
  t /= scales;
  c.record = static_cast<int>(t % records);
  c.object = static_cast<int>(t / records);
  return c;
}

long CellGrid::task(const Cell& c) const {
  return ((long(c.object) * records + c.record) * scales + c.scale) * rotations + c.rotation;
}

double rotation_angle_deg(std::uint64_t seed, const Cell& c) {
  std::uint64_t h = splitmix64(seed);
  for (int v : {c.object, c.record, c.scale, c.rotation}) h = splitmix64(h ^ static_cast<std::uint64_t>(v));
  return 360.0 * unit_interval(h);
}

}  // namespace rigid::job
