#pragma once
// SplitMix64: a portable, seeded random stream for test inputs (std:: distributions differ
// between standard libraries).
#include <cstdint>

namespace rigid::test {

struct Rng {
  std::uint64_t s;
  /// Uniform on [0, 1).
  double uniform() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
};

}  // namespace rigid::test
