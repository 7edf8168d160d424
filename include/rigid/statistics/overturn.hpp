#pragma once
/// The overturning probability of an object from its cells' outcomes: which outcomes count, the
/// fraction over rotations and the mean over records. Pure functions on plain arrays, so the cube
/// writer (io), the campaign's summary and the tests share one rule; the Python copy of the same
/// rule is src/python/rigidpy/outcomes.py.
#include <cstdint>
#include <span>
#include <vector>

#include "rigid/scenario/case.hpp"
#include "rigid/statistics/cells.hpp"

namespace rigid::statistics {

/// How the overturning probability counts a cell.
enum class CountsAs { overturned, not_overturned, unknown };

/// The rule: overturned and inferred cells count as overturned (the stop rule infers overturning
/// above scales where every rotation overturned), survived as not; not-run and failed cells are
/// unknown (a failed simulation says nothing about the rock).
constexpr CountsAs counts_as(scenario::CellOutcome outcome) {
  switch (outcome) {
    case scenario::CellOutcome::overturned:
    case scenario::CellOutcome::inferred:
      return CountsAs::overturned;
    case scenario::CellOutcome::survived:
      return CountsAs::not_overturned;
    case scenario::CellOutcome::not_run:
    case scenario::CellOutcome::failed:
      break;
  }
  return CountsAs::unknown;
}

/// Overturning probability per (record, scale), row-major [record][scale]: over the rotations of
/// that (record, scale), overturned cells / known cells (counts_as), NaN where no cell is known.
/// `outcome` holds CellOutcome codes, shape.cells() of them, [record][scale][rotation]. Throws
/// std::invalid_argument when its size does not match the shape or a code is not a CellOutcome.
std::vector<double> overturn_probability(std::span<const std::int8_t> outcome, const CellShape& shape);

/// Per scale (shape.scales values): the mean, in record order, of the probabilities [record][scale]
/// (shape.record_scales() of them, as overturn_probability returns) that are known (not NaN);
/// NaN where none is. Throws std::invalid_argument when the size does not match the shape.
std::vector<double> mean_over_records(std::span<const double> probability, const CellShape& shape);

}  // namespace rigid::statistics
