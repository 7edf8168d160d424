#pragma once
// A cube of the study's layout (154 records x 20 scales x 2 rotations = 6,160 cells per object;
// more cells = more objects, as variants would add) with realistic contents, for the benchmarks.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "rigid/core/rng.hpp"
#include "rigid/io/cube.hpp"

namespace rigid_bench {

constexpr int kRecords = 154, kScales = 20, kRotations = 2;
constexpr std::int64_t kCellsPerObject = std::int64_t(kRecords) * kScales * kRotations;

inline rigid::io::Cube study_layout_cube(std::int64_t cells) {
  rigid::io::Cube cube;
  cube.rotations = kRotations;
  for (int s = 1; s <= kScales; ++s) cube.scales_g.push_back(0.1 * s);
  for (int r = 0; r < kRecords; ++r) {
    rigid::io::RecordMeta m;
    m.name = "record_" + std::to_string(r);
    m.source = "waveforms/" + m.name + "-X.AT2";
    m.end_s = 20;
    m.gmroti_pga_g = 0.3;
    m.gmroti_pgv_cm_s = 30 + r % 40;
    m.pgv_pga_s = m.gmroti_pgv_cm_s / (m.gmroti_pga_g * 980.665);
    cube.records.push_back(m);
  }
  rigid::SplitMix64 rng(7);
  const std::int64_t objects = std::max<std::int64_t>(1, (cells + kCellsPerObject - 1) / kCellsPerObject);
  for (std::int64_t o = 0; o < objects; ++o) {
    rigid::io::ObjectCube obj;
    obj.name = "object_" + std::to_string(o);
    obj.scene = obj.name + ".toml";
    for (std::int64_t c = 0; c < kCellsPerObject; ++c) {
      const auto scale = (c / kRotations) % kScales;
      const bool over = rng.uniform() < double(scale) / kScales;
      obj.outcome.push_back(over ? 2 : 1);
      obj.rotation_deg.push_back(360 * rng.uniform());
      obj.failure_time_s.push_back(over ? 10 * rng.uniform() : std::numeric_limits<double>::quiet_NaN());
      obj.max_tilt_deg.push_back(over ? 90.0 : 5 * rng.uniform());
      obj.max_slip_m.push_back(0.01 * rng.uniform());
      obj.wall_s.push_back(0.1 * rng.uniform());
      obj.failure_reason.push_back(0);
      obj.failure_message.emplace_back();
    }
    cube.objects.push_back(std::move(obj));
  }
  return cube;
}

}  // namespace rigid_bench
