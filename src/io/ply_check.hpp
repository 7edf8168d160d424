#pragma once
// The structure of a PLY file checked before assimp reads it: assimp's PLY reader trusts the
// header (a truncated body, a face index out of range, a list count past the data or a missing
// end_header crash it; a header declaring 2e9 vertices makes it allocate for them). Private to
// rigid_io.
#include <string>
#include <string_view>

namespace rigid::io {

/// Throws rigid::InputError(name, line, problem) unless `bytes` is a PLY file (ASCII, binary
/// little or big endian) whose header ends with end_header, declares a `vertex` element with
/// scalar x, y, z and a `face` element with a vertex_indices (or vertex_index) list, whose element
/// counts fit in the file's size, and whose body holds every record the header declares, each
/// face with at least three corners, every corner an index of a declared vertex. Line numbers are
/// given for the header and for ASCII bodies. Works in one pass over the bytes, allocating nothing
/// in proportion to the declared counts. Returns the canonical file the importer then reads: the
/// same format, a header of only the vertices' x, y, z and the faces' corner list (their own
/// types, no comments), and each record cut to those fields, copied byte for byte. Whatever else
/// the file holds (colours, normals, other elements, unusual spacing) the importer never sees: on
/// such inputs the check and assimp's reader disagreed, and assimp crashed (fuzzer finds).
std::string check_ply(std::string_view bytes, const std::string& name);

}  // namespace rigid::io
