// The cube's statistics on plain arrays, against values worked by hand: a 2x2x2 outcome array
// (records x scales x rotations), its probabilities, their means over records and the binned
// fragility surface, with an empty bin and a record outside every bin.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "rigid/statistics/cells.hpp"
#include "rigid/statistics/fragility_surface.hpp"
#include "rigid/statistics/overturn.hpp"

namespace rigid::statistics {
namespace {

using O = scenario::CellOutcome;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::int8_t code(O o) { return static_cast<std::int8_t>(o); }

// [record][scale][rotation]
const std::vector<std::int8_t> kOutcome{
    code(O::survived), code(O::overturned),  // r0 s0: 1 of 2 known overturned -> 1/2
    code(O::inferred), code(O::overturned),  // r0 s1: inferred counts as overturned -> 2/2
    code(O::failed),   code(O::not_run),     // r1 s0: nothing known -> NaN
    code(O::survived), code(O::failed),      // r1 s1: failed left out, 0 of 1 -> 0
};
constexpr CellShape kShape{2, 2, 2};

void expect_same(const std::vector<double>& got, const std::vector<double>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (std::isnan(want[i]))
      EXPECT_TRUE(std::isnan(got[i])) << i << ": " << got[i];
    else
      EXPECT_EQ(got[i], want[i]) << i;
  }
}

TEST(CellShape, CountsRecordsTimesScalesTimesRotations) {
  EXPECT_EQ(kShape.cells(), 8u);
  EXPECT_EQ(kShape.record_scales(), 4u);
  EXPECT_EQ((CellShape{154, 12, 3}.cells()), 5544u);
  EXPECT_EQ((CellShape{0, 12, 3}.cells()), 0u);
}

TEST(Overturn, OverturnedAndInferredCountAsOverturnedSurvivedAsNotTheRestUnknown) {
  EXPECT_EQ(counts_as(O::overturned), CountsAs::overturned);
  EXPECT_EQ(counts_as(O::inferred), CountsAs::overturned);
  EXPECT_EQ(counts_as(O::survived), CountsAs::not_overturned);
  EXPECT_EQ(counts_as(O::not_run), CountsAs::unknown);
  EXPECT_EQ(counts_as(O::failed), CountsAs::unknown);
}

TEST(Overturn, ProbabilityOfATwoByTwoByTwoArray) {
  expect_same(overturn_probability(kOutcome, kShape), {0.5, 1.0, kNaN, 0.0});
}

TEST(Overturn, MeanOverRecordsLeavesOutUnknownRecords) {
  const std::vector<double> p = overturn_probability(kOutcome, kShape);
  // scale 0: record 1 unknown, so record 0's 0.5 alone; scale 1: (1 + 0) / 2
  expect_same(mean_over_records(p, kShape), {0.5, 0.5});
  // a scale no record knows is NaN
  expect_same(mean_over_records(std::vector<double>{kNaN, 0.25, kNaN, 0.75}, kShape), {kNaN, 0.5});
}

TEST(Overturn, WrongSizesAndCodesAreRefused) {
  EXPECT_THROW(overturn_probability(std::vector<std::int8_t>(7, code(O::survived)), kShape), std::invalid_argument);
  std::vector<std::int8_t> bad = kOutcome;
  bad[5] = 5;  // not a CellOutcome
  EXPECT_THROW(overturn_probability(bad, kShape), std::invalid_argument);
  bad[5] = -1;
  EXPECT_THROW(overturn_probability(bad, kShape), std::invalid_argument);
  EXPECT_THROW(mean_over_records(std::vector<double>(3, 0.0), kShape), std::invalid_argument);
}

TEST(FragilitySurface, MeansPerBinWithAnEmptyBinAndARecordOutsideEveryBin) {
  // probabilities [record][scale] of three records at two scales
  const std::vector<double> p{0.5,  1.0,   // record 0, PGV/PGA 0.05 s: bin 0
                              kNaN, 0.0,   // record 1, 0.07 s: bin 0, unknown at scale 0
                              1.0,  1.0};  // record 2, 0.40 s: above the last edge, in no bin
  const std::vector<double> pgv_pga{0.05, 0.07, 0.40};
  const std::vector<double> edges{0.0, 0.1, 0.2, 0.3};  // bins [0, 0.1), [0.1, 0.2) empty, [0.2, 0.3]
  const FragilitySurface f = fragility_surface(p, 2, pgv_pga, edges);
  ASSERT_EQ(f.bins(), 3u);
  EXPECT_EQ(f.edges_s, edges);
  // [scale][bin]: scale 0 bin 0 holds record 0 alone (record 1 unknown); scale 1 bin 0 (1 + 0) / 2
  expect_same(f.probability, {0.5, kNaN, kNaN, 0.5, kNaN, kNaN});
  EXPECT_EQ(f.count, (std::vector<std::int32_t>{1, 0, 0, 2, 0, 0}));
}

TEST(FragilitySurface, SizesAndEdgesAreChecked) {
  const std::vector<double> edges{0.0, 0.1};
  EXPECT_THROW(fragility_surface(std::vector<double>(3, 0.0), 2, std::vector<double>{0.05, 0.05}, edges),
               std::invalid_argument);
  EXPECT_THROW(fragility_surface(std::vector<double>(2, 0.0), 2, std::vector<double>{0.05}, std::vector<double>{0.1}),
               std::invalid_argument);
  EXPECT_NE(pgv_pga_edges_problem(std::vector<double>{0.0}).find("at least 2 edges"), std::string::npos);
  EXPECT_NE(pgv_pga_edges_problem(std::vector<double>{0.0, kNaN}).find("is NaN"), std::string::npos);
  EXPECT_NE(pgv_pga_edges_problem(std::vector<double>{0.0, 0.2, 0.2}).find("increase strictly"), std::string::npos);
  EXPECT_EQ(pgv_pga_edges_problem(default_pgv_pga_edges()), "");
}

TEST(FragilitySurface, BinsAreClosedBelowAndTheLastAlsoAbove) {
  const std::vector<double> e{0.0, 0.1, 0.2};
  EXPECT_EQ(pgv_pga_bin(e, 0.0), 0);
  EXPECT_EQ(pgv_pga_bin(e, 0.05), 0);
  EXPECT_EQ(pgv_pga_bin(e, 0.1), 1);
  EXPECT_EQ(pgv_pga_bin(e, 0.2), 1);
  EXPECT_EQ(pgv_pga_bin(e, 0.2000001), -1);
  EXPECT_EQ(pgv_pga_bin(e, -0.01), -1);
  EXPECT_EQ(pgv_pga_bin(e, kNaN), -1);
  const std::vector<double> d = default_pgv_pga_edges();
  ASSERT_EQ(d.size(), 10u);                // nine bins, physics.md §11
  EXPECT_EQ(pgv_pga_bin(d, 0.033309), 0);  // the smallest and largest PGV/PGA of the study's table
  EXPECT_EQ(pgv_pga_bin(d, 0.50236), 8);
  EXPECT_EQ(pgv_pga_bin(d, kInf), 8);
}

}  // namespace
}  // namespace rigid::statistics
