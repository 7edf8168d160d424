#pragma once
/// The binned fragility surface P(overturn | PGA, PGV/PGA) of one object (physics.md §11): the
/// PGV/PGA bins (their edges, which bin a record falls in) and the per-bin means of the
/// overturning probability (statistics/overturn.hpp). No I/O: the cube writer stores the result.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rigid::statistics {

/// The default PGV/PGA bin edges (unit: s): ten edges, nine bins,
/// {0, 0.06, 0.08, 0.10, 0.12, 0.15, 0.20, 0.25, 0.35, inf}. Round numbers chosen so that the
/// study's 154 records (PGV/PGA 0.033-0.50 s, the study's table,
/// ../shared/docs/table3_6_records.tsv) fall 13-24 per bin: narrow bins where the records are
/// dense (0.06-0.15 s), wide ones in the tails.
std::vector<double> default_pgv_pga_edges();

/// Why edges cannot bin (fewer than 2, a NaN, not strictly increasing), one message naming
/// pgv_pga_edges_s; empty when they can.
std::string pgv_pga_edges_problem(std::span<const double> edges_s);

/// Bin of a PGV/PGA value (unit: s): i such that edges_s[i] <= v < edges_s[i + 1], the last bin
/// also holding v == edges_s.back(); -1 when v is NaN or outside the edges.
int pgv_pga_bin(std::span<const double> edges_s, double pgv_pga_s);

struct FragilitySurface {
  std::vector<double> edges_s;      ///< PGV/PGA bin edges used (unit: s); bins() = size - 1
  std::vector<double> probability;  ///< [scale][bin]: mean probability, NaN for empty bins
  std::vector<std::int32_t> count;  ///< [scale][bin]: number of records contributing
  std::size_t bins() const { return edges_s.empty() ? 0 : edges_s.size() - 1; }
};

/// For every scale and PGV/PGA bin: the mean, in record order, of the probabilities
/// [record][scale] (`scales` per record, as overturn_probability returns) of the records whose
/// PGV/PGA (record_pgv_pga_s, one per record) falls in the bin and whose probability at that scale
/// is known (not NaN); NaN and a count of 0 for a bin without any. A record in no bin counts
/// nowhere. Throws std::invalid_argument when the sizes disagree or the edges cannot bin.
FragilitySurface fragility_surface(std::span<const double> probability, std::size_t scales,
                                   std::span<const double> record_pgv_pga_s, std::span<const double> edges_s);

}  // namespace rigid::statistics
