// libFuzzer entry point for the AT2 reader (and the measures of what it accepts).
// Build by hand (not part of the CMake test suite), e.g. from the repository root:
//   clang++-14 -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -Iinclude \
//     -I/usr/include/eigen3 tests/fuzz/at2_fuzz.cpp src/io/at2.cpp src/motion/*.cpp \
//     -o /tmp/at2_fuzz
//   /tmp/at2_fuzz -max_total_time=300 -max_len=4096 /tmp/at2_corpus tests/data/at2
// Inputs that crashed once are kept in tests/data/at2/fuzz_regressions/ (io_at2_test parses each).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "rigid/core/error.hpp"
#include "rigid/io/at2.hpp"
#include "rigid/motion/measures.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  // the first byte chooses whether a headerless dt is given
  rigid::io::At2ReadOptions options;
  options.dt = (data[0] & 1) ? 0.01 : 0.0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    const rigid::io::At2Record r = rigid::io::parse_at2(text, "fuzz", options);
    if (r.values.size() >= 2 && r.values.size() < 4096) {
      // what the reader accepts must be usable downstream without crashing
      const auto m = rigid::motion::make_ground_motion("fuzz", {r.component_si(), r.component_si()});
      (void)rigid::motion::motion_info(m);
    }
  } catch (const rigid::InputError&) {
  }
  return 0;
}
