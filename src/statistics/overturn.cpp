// The overturning probability of an object (include/rigid/statistics/overturn.hpp).
#include "rigid/statistics/overturn.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rigid::statistics {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void require_size(std::size_t has, std::size_t expected, const char* what) {
  if (has != expected)
    throw std::invalid_argument(std::string(what) + " has " + std::to_string(has) + " values, expected " +
                                std::to_string(expected));
}

}  // namespace

std::vector<double> overturn_probability(std::span<const std::int8_t> outcome, const CellShape& shape) {
  require_size(outcome.size(), shape.cells(), "outcome");
  const std::size_t A = shape.rotations;
  std::vector<double> p(shape.record_scales(), kNaN);
  for (std::size_t rs = 0; rs < p.size(); ++rs) {
    int over = 0, known = 0;
    for (std::size_t a = 0; a < A; ++a) {
      const std::int8_t code = outcome[rs * A + a];
      if (code < 0 || code > static_cast<std::int8_t>(scenario::CellOutcome::failed))
        throw std::invalid_argument("outcome[" + std::to_string(rs * A + a) + "] = " + std::to_string(code) +
                                    " is not a CellOutcome");
      switch (counts_as(static_cast<scenario::CellOutcome>(code))) {
        case CountsAs::overturned:
          ++over;
          ++known;
          break;
        case CountsAs::not_overturned:
          ++known;
          break;
        case CountsAs::unknown:
          break;
      }
    }
    if (known > 0) p[rs] = static_cast<double>(over) / static_cast<double>(known);
  }
  return p;
}

std::vector<double> mean_over_records(std::span<const double> probability, const CellShape& shape) {
  require_size(probability.size(), shape.record_scales(), "probability");
  const std::size_t R = shape.records, S = shape.scales;
  std::vector<double> mean(S, kNaN);
  for (std::size_t s = 0; s < S; ++s) {
    double sum = 0.0;
    int known = 0;
    for (std::size_t r = 0; r < R; ++r) {
      if (std::isnan(probability[r * S + s])) continue;
      sum += probability[r * S + s];
      ++known;
    }
    if (known > 0) mean[s] = sum / known;
  }
  return mean;
}

}  // namespace rigid::statistics
