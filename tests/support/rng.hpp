#pragma once
// The seeded stream for test inputs: the engine's SplitMix64 (std:: distributions differ between
// standard libraries).
#include <cstdint>
#include <vector>

#include "rigid/core/rng.hpp"
#include "rigid/core/types.hpp"

namespace rigid::test {

using Rng = rigid::SplitMix64;

/// N points uniformly distributed in the unit ball (rejection from the cube [-1, 1]^3), seeded.
inline std::vector<Vec3> unit_ball_points(std::uint64_t seed, int n) {
  Rng rng{seed};
  std::vector<Vec3> pts;
  while (static_cast<int>(pts.size()) < n) {
    const Vec3 u(2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1);
    if (u.squaredNorm() <= 1) pts.push_back(u);
  }
  return pts;
}

}  // namespace rigid::test
