#pragma once
/// A run's time history (scenario::History) as one CSV table, one row per frame: what
/// `rigid run --history` writes and `--plot` hands to rigidpy's figure (rigidpy/simulation.py
/// reads it into the Dataset rigidpy.run returns). Columns: `time_s`; the table's
/// `table_displacement_m:X`, `table_velocity_m_s:X`, `table_acceleration_m_s2:X` (X = x, y, z);
/// per free block B `tilt_deg:B`, `slip_m:B`, `contacts:B`, `base_height_m:B` (the same in
/// every row: scenario::History), `position_m:X:B`,
/// `orientation:Q:B` (Q = w, x, y, z), `contact_force_n:X:B`.
#include <ostream>

#include "rigid/scenario/history.hpp"

namespace rigid::io {

void write_history_csv(std::ostream& out, const scenario::History& history);

}  // namespace rigid::io
