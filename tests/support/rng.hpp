#pragma once
// The seeded stream for test inputs: the engine's SplitMix64 (std:: distributions differ between
// standard libraries).
#include "rigid/core/rng.hpp"

namespace rigid::test {

using Rng = rigid::SplitMix64;

}  // namespace rigid::test
