// The binned fragility surface (include/rigid/statistics/fragility_surface.hpp).
#include "rigid/statistics/fragility_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rigid::statistics {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

std::vector<double> default_pgv_pga_edges() { return {0.0, 0.06, 0.08, 0.10, 0.12, 0.15, 0.20, 0.25, 0.35, kInf}; }

std::string pgv_pga_edges_problem(std::span<const double> e) {
  if (e.size() < 2) return "pgv_pga_edges_s needs at least 2 edges (has " + std::to_string(e.size()) + ")";
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (std::isnan(e[i])) return "pgv_pga_edges_s[" + std::to_string(i) + "] is NaN";
    if (i > 0 && !(e[i] > e[i - 1])) return "pgv_pga_edges_s must increase strictly (edge " + std::to_string(i) + ")";
  }
  return {};
}

int pgv_pga_bin(std::span<const double> edges_s, double pgv_pga_s) {
  if (edges_s.size() < 2 || std::isnan(pgv_pga_s)) return -1;
  if (pgv_pga_s < edges_s.front() || pgv_pga_s > edges_s.back()) return -1;
  const auto above = std::upper_bound(edges_s.begin(), edges_s.end(), pgv_pga_s);
  const int bins = static_cast<int>(edges_s.size()) - 1;
  return std::min(static_cast<int>(above - edges_s.begin()) - 1, bins - 1);
}

FragilitySurface fragility_surface(std::span<const double> probability, std::size_t scales,
                                   std::span<const double> record_pgv_pga_s, std::span<const double> edges_s) {
  if (std::string p = pgv_pga_edges_problem(edges_s); !p.empty()) throw std::invalid_argument(p);
  const std::size_t R = record_pgv_pga_s.size(), S = scales;
  if (probability.size() != R * S)
    throw std::invalid_argument("probability has " + std::to_string(probability.size()) + " values, expected " +
                                std::to_string(R * S) + " (records x scales)");
  FragilitySurface f;
  f.edges_s.assign(edges_s.begin(), edges_s.end());
  const std::size_t B = f.bins();
  std::vector<double> sum(S * B, 0.0);
  f.count.assign(S * B, 0);
  for (std::size_t r = 0; r < R; ++r) {
    const int b = pgv_pga_bin(f.edges_s, record_pgv_pga_s[r]);
    if (b < 0) continue;
    for (std::size_t s = 0; s < S; ++s) {
      const double v = probability[r * S + s];
      if (std::isnan(v)) continue;
      sum[s * B + static_cast<std::size_t>(b)] += v;
      ++f.count[s * B + static_cast<std::size_t>(b)];
    }
  }
  f.probability.assign(S * B, kNaN);
  for (std::size_t i = 0; i < S * B; ++i) {
    if (f.count[i] > 0) f.probability[i] = sum[i] / f.count[i];
  }
  return f;
}

}  // namespace rigid::statistics
