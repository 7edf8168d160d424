// The cube's cells as CSV (include/rigid/io/cells_csv.hpp).
#include "rigid/io/cells_csv.hpp"

#include "rigid/io/csv.hpp"

#include <string>
#include <vector>

namespace rigid::io {
namespace {

/// A cell's count of unconverged contact solves; empty when not recorded (-1, or a cube written
/// before the count existed), as a NaN is.
std::string csv_unconverged(const ObjectCube& o, std::size_t i) {
  if (o.unconverged_steps.empty() || o.unconverged_steps[i] < 0) return {};
  return std::to_string(o.unconverged_steps[i]);
}

}  // namespace

void write_cells_csv(std::ostream& out, const Cube& cube) {
  // the variant column only when the cube has variants: tables of other cubes stay as they were
  const bool variants = cube.variants.count > 0;
  std::vector<std::string> header{"object",       "record",         "scale_g",         "rotation",
                                  "rotation_deg", "outcome",        "failure_time_s",  "max_tilt_deg",
                                  "max_slip_m",   "failure_reason", "failure_message", "unconverged_steps"};
  if (variants) header.insert(header.begin() + 1, "variant");
  CsvWriter csv(out, "\r\n");
  csv.row(header);
  const std::size_t S = cube.scales_g.size(), A = static_cast<std::size_t>(cube.rotations);
  for (const ObjectCube& o : cube.objects) {
    for (std::size_t r = 0; r < cube.records.size(); ++r) {
      for (std::size_t s = 0; s < S; ++s) {
        for (std::size_t a = 0; a < A; ++a) {
          const std::size_t i = (r * S + s) * A + a;
          std::vector<std::string> row{o.name,
                                       cube.records[r].name,
                                       csv_number(cube.scales_g[s]),
                                       std::to_string(a),
                                       csv_number(o.rotation_deg[i]),
                                       outcome_name(o.outcome[i]),
                                       csv_number(o.failure_time_s[i]),
                                       csv_number(o.max_tilt_deg[i]),
                                       csv_number(o.max_slip_m[i]),
                                       failure_reason_name(o.failure_reason[i]),
                                       o.failure_message.empty() ? std::string() : o.failure_message[i],
                                       csv_unconverged(o, i)};
          if (variants) row.insert(row.begin() + 1, std::to_string(o.variant));
          csv.row(row);
        }
      }
    }
  }
}

}  // namespace rigid::io
