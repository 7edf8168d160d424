#pragma once
/// The shape of one object's cells: records x scales x rotations, stored row-major
/// [record][scale][rotation] (the rotation fastest). The one place the per-object cell count is
/// computed: the cube's arrays (io) and the job's cell grid (job) both ask here.
#include <cstddef>

namespace rigid::statistics {

struct CellShape {
  std::size_t records = 0, scales = 0, rotations = 0;
  /// Cells of one object.
  constexpr std::size_t cells() const { return records * scales * rotations; }
  /// (record, scale) pairs of one object: the size of a per-(record, scale) result.
  constexpr std::size_t record_scales() const { return records * scales; }
};

}  // namespace rigid::statistics
