#pragma once
/// The cells of a job: (object, record, scale, rotation), numbered row-major with the object
/// slowest and the rotation fastest. The task number of a cell, the cell of a task number and
/// the cell count all come from CellGrid, for the plan, the cube, the journal and the estimate.
#include <cstddef>
#include <cstdint>

#include "rigid/statistics/cells.hpp"

namespace rigid::job {

/// Coordinates of a cell.
struct Cell {
  int object = 0, record = 0, scale = 0, rotation = 0;
};

struct CellGrid {
  int objects = 0, records = 0, scales = 0, rotations = 0;
  /// Cells of one object: records x scales x rotations (statistics::CellShape, the one count the
  /// cube's arrays use too).
  long per_object() const {
    return static_cast<long>(statistics::CellShape{static_cast<std::size_t>(records), static_cast<std::size_t>(scales),
                                                   static_cast<std::size_t>(rotations)}
                                 .cells());
  }
  /// Every cell of the grid, as a double: a job too large to count in a long is still measured.
  double size_estimate() const { return double(objects) * double(records) * double(scales) * double(rotations); }
  long size() const { return long(objects) * per_object(); }
  Cell cell(long task) const;
  long task(const Cell& c) const;
};

/// Rotation of the horizontals for a cell (unit: deg, in [0, 360)): SplitMix64 applied to the
/// job seed and the cell coordinates in turn, so any cell's angle is computed on its own.
double rotation_angle_deg(std::uint64_t seed, const Cell& cell);

}  // namespace rigid::job
