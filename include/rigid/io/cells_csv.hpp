#pragma once
/// The cube's cells as one CSV table, for spreadsheet and pandas users (`rigid export cells`).
#include <ostream>

#include "rigid/io/cube.hpp"

namespace rigid::io {

/// Writes a header and one row per cell, objects in job order (with variants: each base object's
/// variants in order), then [record][scale][rotation]: object, variant (the variant index; this
/// column only in a cube with variants), record, scale_g, rotation (index), rotation_deg, outcome
/// (name), failure_time_s, max_tilt_deg, max_slip_m, failure_reason (name), failure_message,
/// unconverged_steps (steps whose contact solve stopped at its sweep cap; empty when not recorded).
/// Numbers are written as the shortest text that reads back as the same double, NaN as an empty
/// field; fields are quoted as RFC 4180 says (a field with a comma, quote or line break in double
/// quotes, quotes doubled) and lines end in CRLF.
void write_cells_csv(std::ostream& out, const Cube& cube);

}  // namespace rigid::io
