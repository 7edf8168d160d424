#include "rigid/io/history_csv.hpp"

#include <string>
#include <vector>

#include "rigid/core/types.hpp"
#include "rigid/io/csv.hpp"

namespace rigid::io {

void write_history_csv(std::ostream& out, const scenario::History& h) {
  static const char* const kAxes[] = {"x", "y", "z"};
  static const char* const kQuaternion[] = {"w", "x", "y", "z"};
  CsvWriter csv(out);
  std::vector<std::string> header{"time_s"};
  for (const char* table : {"table_displacement_m", "table_velocity_m_s", "table_acceleration_m_s2"}) {
    for (const char* a : kAxes) header.push_back(std::string(table) + ":" + a);
  }
  for (const std::string& b : h.blocks) {
    header.push_back("tilt_deg:" + b);
    header.push_back("slip_m:" + b);
    header.push_back("contacts:" + b);
    header.push_back("base_height_m:" + b);
    for (const char* a : kAxes) header.push_back(std::string("position_m:") + a + ":" + b);
    for (const char* q : kQuaternion) header.push_back(std::string("orientation:") + q + ":" + b);
    for (const char* a : kAxes) header.push_back(std::string("contact_force_n:") + a + ":" + b);
  }
  csv.row(header);
  const std::size_t blocks = h.blocks.size();
  for (std::size_t f = 0; f < h.frames(); ++f) {
    csv.field(h.time_s[f]);
    for (const auto* table : {&h.table_displacement_m, &h.table_velocity_m_s, &h.table_acceleration_m_s2}) {
      for (std::size_t a = 0; a < 3; ++a) csv.field((*table)[3 * f + a]);
    }
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t k = f * blocks + b;
      csv.field(h.tilt_rad[k] * 180.0 / kPi).field(h.slip_m[k]).field(h.contacts[k]).field(h.base_height_m[b]);
      for (std::size_t a = 0; a < 3; ++a) csv.field(h.position_m[3 * k + a]);
      for (std::size_t q = 0; q < 4; ++q) csv.field(h.orientation[4 * k + q]);
      for (std::size_t a = 0; a < 3; ++a) csv.field(h.contact_force_n[3 * k + a]);
    }
    csv.end_row();
  }
}

}  // namespace rigid::io
