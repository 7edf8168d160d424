#pragma once
/// STL mesh files, ASCII and binary, to and from triangle soups (unit: m, as stored in the file).
/// Facets are numbered from 0 in file order, the same numbering geometry errors use.
#include <string>
#include <string_view>

#include "rigid/geometry/polyhedron.hpp"

namespace rigid::io {

/// Reads an ASCII or binary STL file. The format is detected from the content, not the "solid"
/// prefix alone: a file whose size is 84 + 50 n for the facet count n in its header and which is
/// not plain "solid ..." text is binary. ASCII keywords are case-insensitive, any whitespace and
/// CRLF line ends are accepted, and facet normals are optional and ignored (recomputed from the
/// vertices). Throws rigid::InputError(path, line, what): line is the ASCII line, or 0 with
/// "facet N: ..." for binary files and whole-file problems (missing, empty, truncated, no facets,
/// malformed or NaN/infinite numbers).
geometry::TriangleSoup read_stl(const std::string& path);

/// Parses STL content already in memory, exactly as read_stl does; `name` labels the errors.
geometry::TriangleSoup read_stl_from_memory(std::string_view bytes, const std::string& name);

/// Writes a binary STL. Coordinates are rounded to single precision (the format's float32), and
/// the header never starts with "solid". Throws std::invalid_argument for a coordinate that is
/// not finite or exceeds the float range or for more than 2^32 - 1 facets, and
/// rigid::InputError(path, 0, ...) when the file cannot be written.
void write_stl_binary(const std::string& path, const geometry::TriangleSoup& soup);

/// Writes an ASCII STL with the shortest decimal that round-trips each double, so reading it back
/// gives the soup bit for bit. Facet normals are computed from the vertices (0 0 0 when
/// degenerate). Throws std::invalid_argument for a non-finite coordinate and
/// rigid::InputError(path, 0, ...) when the file cannot be written.
void write_stl_ascii(const std::string& path, const geometry::TriangleSoup& soup,
                     const std::string& solid_name = "rigid");

}  // namespace rigid::io
