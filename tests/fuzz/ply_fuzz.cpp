// libFuzzer target of the PLY reader (the structure check, then assimp): malformed headers,
// counts, list lengths and corner indices must be refused as input, never crash or allocate for
// the declared counts. Seeds: tests/data/ply. CI runs it for a fixed time (setup.sh sanitize).
#include "mesh_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz_mesh_reader(data, size, "fuzz.ply");
}
