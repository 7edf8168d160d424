// The dry-run estimate of a job the test writes: its cell count and step count against the
// products computed here from the job's own numbers (objects x records x scales x rotations, and
// the fixed duration over the fixed step).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "rigid/job/cost_estimate.hpp"
#include "rigid/job/load.hpp"
#include "rigid/job/model.hpp"

namespace rigid::job {
namespace {

namespace fs = std::filesystem;

TEST(CostEstimate, CountsTheJobsCellsAndStepsAndMeasuresEachObject) {
  const fs::path dir = fs::temp_directory_path() / ("rigid_cost_estimate_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string src = RIGID_SOURCE_DIR;
  const fs::path path = dir / "job.toml";
  // 2 objects x 2 records x 3 scales x 3 rotations; every run 1.5 s at a 1 ms step
  std::ofstream(path) << "[campaign]\nscales = [0.1, 0.2, 0.4]\nrotations = 3\n\n"
                      << "[run]\nduration_s = 1.5\ndt_s = 0.001\n\n"
                      << "[[object]]\nscene = \"" << src << "/models/demo/block_a02.toml\"\n\n"
                      << "[[object]]\nscene = \"" << src << "/models/demo/block_a03.toml\"\n\n"
                      << "[[record]]\nmotion = \"" << src << "/waveforms/demo/stochastic_s1-X.AT2\"\n\n"
                      << "[[record]]\nmotion = \"" << src << "/waveforms/demo/stochastic_s2-X.AT2\"\n";
  const Job job = load_job(path.string());
  const CostEstimate e = estimate_cost(job, load_model(job));
  fs::remove_all(dir);

  EXPECT_EQ(e.cells_per_object, 2 * 3 * 3);
  EXPECT_EQ(e.cells, 2 * 2 * 3 * 3);
  EXPECT_DOUBLE_EQ(e.simulated_per_object_s, 18 * 1.5);
  EXPECT_DOUBLE_EQ(e.simulated_total_s(), 2 * 18 * 1.5);
  ASSERT_EQ(e.objects.size(), 2u);
  for (const ObjectCost& o : e.objects) {
    EXPECT_DOUBLE_EQ(o.dt_s, 0.001);
    EXPECT_NEAR(o.steps, 18 * 1.5 / 0.001, 1e-6);
    EXPECT_GT(o.seconds_per_step, 0);  // a probe ran
    EXPECT_DOUBLE_EQ(o.core_seconds, o.steps * o.seconds_per_step);
  }
  EXPECT_NEAR(e.steps(), 2 * 18 * 1.5 / 0.001, 1e-6);
  EXPECT_DOUBLE_EQ(e.probe_duration_s, kProbeDuration);
}

}  // namespace
}  // namespace rigid::job
