// The cell numbering of a job: task number <-> (object, record, scale, rotation), checked against
// the grid enumerated by nested loops (object slowest, rotation fastest).
#include <gtest/gtest.h>

#include "rigid/job/cells.hpp"
#include "rigid/job/job.hpp"

namespace rigid::job {
namespace {

TEST(CellGrid, NumbersTheGridRowMajor) {
  for (const CellGrid grid : {CellGrid{3, 4, 5, 2}, CellGrid{1, 1, 1, 1}, CellGrid{2, 1, 7, 3}}) {
    long t = 0;
    for (int o = 0; o < grid.objects; ++o) {
      for (int r = 0; r < grid.records; ++r) {
        for (int s = 0; s < grid.scales; ++s) {
          for (int k = 0; k < grid.rotations; ++k, ++t) {
            const Cell c = grid.cell(t);
            EXPECT_EQ(c.object, o);
            EXPECT_EQ(c.record, r);
            EXPECT_EQ(c.scale, s);
            EXPECT_EQ(c.rotation, k);
            EXPECT_EQ(grid.task({o, r, s, k}), t);
          }
        }
      }
      EXPECT_EQ(grid.per_object() * (o + 1), t);
    }
    EXPECT_EQ(grid.size(), t);
    EXPECT_EQ(grid.size_estimate(), double(t));
  }
}

TEST(CellGrid, AJobsGridCountsItsObjectsRecordsScalesAndRotations) {
  Job job;
  job.objects.resize(6);
  job.records.resize(2);
  job.scales_g = {0.1, 0.2, 0.3};
  job.rotations = 4;
  const CellGrid grid = job.cells();
  EXPECT_EQ(grid.objects, 6);
  EXPECT_EQ(grid.records, 2);
  EXPECT_EQ(grid.scales, 3);
  EXPECT_EQ(grid.rotations, 4);
  EXPECT_EQ(grid.size(), 6 * 2 * 3 * 4);
}

TEST(OneCellJob, ItsOneCaseIsTheRecordAsItIs) {
  const Job job = one_cell_job(RunOverrides{});
  EXPECT_EQ(job.cells().size(), 1);
  const scenario::Case c = case_of(job, Cell{});
  EXPECT_EQ(c.object, 0);
  EXPECT_EQ(c.record, 0);
  EXPECT_EQ(c.target_pga_g, 0.0);  // 0 = no scaling
  EXPECT_EQ(c.rotation_deg, 0.0);
}

}  // namespace
}  // namespace rigid::job
