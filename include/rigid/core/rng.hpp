#pragma once
/// SplitMix64 (Steele, Lea & Flood 2014): a seeded 64-bit generator that gives the same stream on
/// every platform, unlike the distributions of <random>. The finaliser alone hashes a word (campaign
/// rotations, synthetic-motion seeds); the stream feeds the rock library's shapes and test inputs.
#include <cstdint>

namespace rigid {

/// The SplitMix64 step: adds the golden-ratio increment to x and mixes the bits of the sum.
constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// Top 53 bits of a word as a double in [0, 1).
constexpr double unit_interval(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

/// The SplitMix64 stream: the n-th output is splitmix64(seed + (n - 1) * increment).
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    const std::uint64_t out = splitmix64(state_);
    state_ += 0x9E3779B97F4A7C15ull;
    return out;
  }
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return unit_interval(next()); }
  /// Uniform in [-1, 1).
  double symmetric() { return 2.0 * uniform() - 1.0; }

 private:
  std::uint64_t state_;
};

}  // namespace rigid
