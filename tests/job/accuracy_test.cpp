// The [run] accuracy key of job files: a preset sets the numerical settings, the explicit keys
// override it, an unknown name is refused with its line, and the preset enters the job hash.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "rigid/core/error.hpp"
#include "rigid/io/provenance.hpp"
#include "rigid/job/load.hpp"

namespace rigid::job {
namespace {

namespace fs = std::filesystem;

class JobAccuracy : public ::testing::Test {
 protected:
  job::Job load(const std::string& run_table) {
    const fs::path dir = fs::path(RIGID_SOURCE_DIR) / "jobs";
    path_ = (dir / ("test_job_accuracy_" + std::to_string(::getpid()) + ".toml")).string();
    std::ofstream(path_)
        << "[campaign]\nscales = \"0.1:0.5:0.1\"\n\n[[object]]\nscene = \"../models/demo/block_a02.toml\"\n\n"
           "[[record]]\nmotion = \"../waveforms/demo/stochastic_s1-X.AT2\"\n\n"
        << run_table;
    return load_job(path_);
  }
  void TearDown() override {
    if (!path_.empty()) fs::remove(path_);
  }
  std::string path_;
};

const scenario::AccuracyPreset& preset(const char* name) { return *scenario::find_accuracy_preset(name); }

TEST_F(JobAccuracy, NoKeyMeansTheDefaultPreset) {
  const auto job = load("[run]\nfree_time_s = 5.0\n");
  EXPECT_EQ(job.accuracy, scenario::kDefaultAccuracy);
  const auto& p = preset(scenario::kDefaultAccuracy);
  EXPECT_EQ(job.run.step.safety, p.safety);
  EXPECT_EQ(job.run.rest_speed, p.rest_speed);
  EXPECT_EQ(job.run.rest_time, p.rest_time);
  const auto no_run = load("");
  EXPECT_EQ(no_run.accuracy, scenario::kDefaultAccuracy);
  EXPECT_EQ(no_run.run.step.safety, p.safety);
}

TEST_F(JobAccuracy, EachPresetSetsItsValues) {
  for (const char* name : {"fast", "balanced", "reference"}) {
    const auto job = load(std::string("[run]\naccuracy = \"") + name + "\"\n");
    const auto& p = preset(name);
    EXPECT_EQ(job.accuracy, name);
    EXPECT_EQ(job.run.step.safety, p.safety) << name;
    EXPECT_EQ(job.run.step.rotation, p.rotation) << name;
    EXPECT_EQ(job.run.step.dt, 0.0) << name;
    EXPECT_EQ(job.run.rest_speed, p.rest_speed) << name;
    EXPECT_EQ(job.run.rest_angular_speed, p.rest_angular_speed) << name;
    EXPECT_EQ(job.run.rest_time, p.rest_time) << name;
  }
}

TEST_F(JobAccuracy, ExplicitKeysOverrideThePreset) {
  const auto job = load("[run]\naccuracy = \"reference\"\nsafety = 0.3\nintegrator = \"rk4\"\n");
  EXPECT_EQ(job.run.step.safety, 0.3);
  EXPECT_EQ(job.run.step.rotation, dynamics::RotationIntegrator::rk4);
  EXPECT_EQ(job.run.rest_speed, preset("reference").rest_speed);
  ASSERT_TRUE(job.overrides.safety);
  ASSERT_TRUE(job.overrides.integrator);
  EXPECT_FALSE(job.overrides.dt);
  const auto fixed = load("[run]\naccuracy = \"fast\"\ndt_s = 1e-5\n");
  EXPECT_EQ(fixed.run.step.dt, 1e-5);
  EXPECT_EQ(fixed.run.rest_time, preset("fast").rest_time);
}

TEST_F(JobAccuracy, UnknownPresetIsRefusedWithItsLine) {
  for (const char* bad : {"accuracy = \"precise\"\n", "accuracy = 3\n", "accuracy = \"\"\n"}) {
    try {
      load(std::string("[run]\nfree_time_s = 5.0\n") + bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), 12) << e.what();
      EXPECT_NE(std::string(e.what()).find("fast, balanced or reference"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path_), std::string::npos) << e.what();
    }
  }
}

TEST_F(JobAccuracy, ThePresetEntersTheHash) {
  // balanced hashes the text alone (the cubes written before the presets keep their hash)
  const auto balanced = load("[run]\naccuracy = \"balanced\"\n");
  EXPECT_EQ(balanced.hash, io::sha256_hex(balanced.text));
  const auto fast = load("[run]\naccuracy = \"fast\"\n");
  EXPECT_NE(fast.hash, io::sha256_hex(fast.text));
  // the same text under another preset (as --accuracy does) hashes differently
  Job other = fast;
  other.accuracy = "reference";
  EXPECT_NE(job_hash(other), fast.hash);
  other.accuracy = "fast";
  EXPECT_EQ(job_hash(other), fast.hash);
}

TEST(JobHash, IsTheSha256OfTheSettingsAndKnowsTheOlderHash) {
  // the published digests of "a": SHA-256 and FNV-1a 64
  Job job;
  job.text = "a";
  job.accuracy = "balanced";
  EXPECT_EQ(job_hash(job), "ca978112ca1bbdcafac231b39a23dc4da786eff8147c4e72b9807785afee48bb");
  EXPECT_EQ(legacy_job_hash(job), "af63dc4c8601ec8c");
}

}  // namespace
}  // namespace rigid::job
