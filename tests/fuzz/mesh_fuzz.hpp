#pragma once
// The body of the PLY and OBJ fuzz targets: bytes -> read_mesh_from_memory under a name with the
// format's extension. Only rigid::InputError may escape the reader; anything else (a crash, a
// sanitizer report, another exception) is a bug. What the soup is (closed, finite) is for the
// geometry checks, which the STL target covers.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "rigid/core/error.hpp"
#include "rigid/io/mesh_import.hpp"

inline int fuzz_mesh_reader(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const rigid::geometry::TriangleSoup soup = rigid::io::read_mesh_from_memory(bytes, name);
    (void)soup;
  } catch (const rigid::InputError&) {
  }
  return 0;
}
