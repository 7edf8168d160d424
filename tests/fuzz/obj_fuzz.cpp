// libFuzzer target of the OBJ reader (assimp): malformed vertex and face lines must be refused as
// input, never crash. Seeds: tests/data/obj. CI runs it for a fixed time (setup.sh sanitize).
#include "mesh_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz_mesh_reader(data, size, "fuzz.obj");
}
