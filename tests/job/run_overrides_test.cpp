// The run settings a user may override: each bad value is refused with the one error it should
// get, naming the job file and line of the [run] key, or the command-line flag.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>

#include "rigid/core/error.hpp"
#include "rigid/job/load.hpp"
#include "rigid/job/run_overrides.hpp"
#include "rigid/scenario/accuracy.hpp"

namespace rigid::job {
namespace {

namespace fs = std::filesystem;

// 9 lines before [run], which is line 10; its first key is line 11
const char* kJob = R"([campaign]
scales = [0.1]

[[object]]
scene = "../models/demo/block_a02.toml"

[[record]]
motion = "../waveforms/demo/stochastic_s1-X.AT2"

[run]
)";

class RunSettingsInJob : public ::testing::Test {
 protected:
  void TearDown() override {
    if (!path_.empty()) fs::remove(path_);
  }
  Job load(const std::string& run_keys) {
    path_ = (fs::path(RIGID_SOURCE_DIR) / "jobs" / ("test_overrides_" + std::to_string(::getpid()) + ".toml")).string();
    std::ofstream(path_) << kJob << run_keys;
    return load_job(path_);
  }
  // the whole message: "FILE:LINE: problem"
  void expect_error(const std::string& run_keys, long line, const std::string& problem) {
    try {
      load(run_keys);
      ADD_FAILURE() << "accepted: " << run_keys;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), path_ + ":" + std::to_string(line) + ": " + problem);
    }
  }
  std::string path_;
};

TEST_F(RunSettingsInJob, Model) {
  expect_error("model = \"dem2d\"\n", 10, "model must be \"dem3d\" or \"rocking2d\", not \"dem2d\"");
}

TEST_F(RunSettingsInJob, Contact) {
  expect_error("contact = \"soft\"\n", 11, "contact must be \"rigid\" or \"penalty\"");
  expect_error("free_time_s = 1.0\ncontact = 3\n", 12, "contact must be \"rigid\" or \"penalty\"");
}

TEST_F(RunSettingsInJob, Effects) {
  expect_error("effects = \"some\"\n", 11, "effects must be \"auto\" or \"all\", not \"some\"");
  expect_error("effects = true\n", 11, "effects must be \"auto\" or \"all\", not a non-string");
}

TEST_F(RunSettingsInJob, Accuracy) {
  expect_error("accuracy = \"precise\"\n", 11, "accuracy must be fast, balanced or reference, not \"precise\"");
}

TEST_F(RunSettingsInJob, Integrator) {
  expect_error("integrator = \"euler\"\n", 10, "integrator must be \"splitting\" or \"rk4\"");
}

TEST_F(RunSettingsInJob, Numbers) {
  const std::string problem = "durations and dt must not be negative, safety must be positive";
  expect_error("duration_s = -1.0\n", 10, problem);
  expect_error("free_time_s = -0.5\n", 10, problem);
  expect_error("dt_s = -1e-4\n", 10, problem);
  expect_error("safety = 0.0\n", 10, problem);
}

TEST_F(RunSettingsInJob, SolverSettings) {
  // each bad value at its own key's line
  const std::string tolerance = "solver_tolerance must be a number in (0, 1), a fraction of g dt";
  const std::string sweeps = "solver_max_sweeps must be a whole number from 1 to 1e9";
  expect_error("solver_tolerance = 0.0\n", 11, tolerance);
  expect_error("solver_tolerance = -1e-7\n", 11, tolerance);
  expect_error("solver_tolerance = 2.0\n", 11, tolerance);
  expect_error("free_time_s = 1.0\nsolver_tolerance = nan\n", 12, "solver_tolerance must be a finite number");
  expect_error("solver_max_sweeps = 0\n", 11, sweeps);
  expect_error("solver_max_sweeps = 2.5\n", 11, sweeps);
  expect_error("free_time_s = 1.0\nsolver_max_sweeps = 1e12\n", 12, sweeps);
  expect_error("solver_max_sweeps = \"many\"\n", 11, "solver_max_sweeps must be a number");
}

TEST_F(RunSettingsInJob, SolverSettingsOverThePreset) {
  const Job job = load("accuracy = \"reference\"\nsolver_max_sweeps = 500\n");
  EXPECT_EQ(job.run.step.solver_max_sweeps, 500);
  EXPECT_EQ(job.run.step.solver_tolerance, scenario::find_accuracy_preset("reference")->solver_tolerance);
  const Job fast = load("solver_tolerance = 1e-9\n");
  EXPECT_EQ(fast.run.step.solver_tolerance, 1e-9);
  EXPECT_EQ(fast.run.step.solver_max_sweeps, scenario::find_accuracy_preset("fast")->solver_max_sweeps);
}

TEST_F(RunSettingsInJob, GoodValuesReachTheRunSettings) {
  const Job job = load(
      "model = \"rocking2d\"\ncontact = \"penalty\"\neffects = \"all\"\naccuracy = \"reference\"\n"
      "integrator = \"rk4\"\nduration_s = 4.0\nfree_time_s = 2.0\nsafety = 0.3\n");
  EXPECT_EQ(job.engine, scenario::Engine::rocking2d);
  ASSERT_TRUE(job.contact);
  EXPECT_EQ(*job.contact, contact::ContactMethod::penalty);
  EXPECT_FALSE(job.run.select_effects);
  EXPECT_EQ(job.accuracy, "reference");
  EXPECT_EQ(job.run.step.rotation, dynamics::RotationIntegrator::rk4);
  EXPECT_EQ(job.run.duration, 4.0);
  EXPECT_EQ(job.run.free_time, 2.0);
  EXPECT_EQ(job.run.step.safety, 0.3);
  EXPECT_EQ(job.run_line, 18);  // safety's line: where step errors point without dt_s
}

// On a command line the error names the flag the caller gave, with the values unquoted.
void expect_flag_error(Setting setting, const char* flag, const std::string& value, const std::string& message) {
  RunOverrides o;
  try {
    set_text_setting(o, setting, value, {"", 0, flag});
    ADD_FAILURE() << "accepted " << flag << " " << value;
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), message);
    EXPECT_TRUE(e.file().empty());
  }
}

TEST(RunSettingsOnCommandLine, EachSettingNamesItsFlag) {
  expect_flag_error(Setting::model, "--model", "3d", "--model must be dem3d or rocking2d");
  expect_flag_error(Setting::contact, "--contact", "soft", "--contact must be rigid or penalty");
  expect_flag_error(Setting::effects, "--effects", "none", "--effects must be auto or all");
  expect_flag_error(Setting::accuracy, "--accuracy", "precise", "--accuracy must be fast, balanced or reference");
  expect_flag_error(Setting::integrator, "--integrator", "euler", "--integrator must be splitting or rk4");
}

TEST(RunSettingsOnCommandLine, SolverFlagsNameThemselves) {
  for (const auto& [setting, flag, value, message] :
       {std::tuple{Setting::solver_tolerance, "--solver-tolerance", 0.0,
                   "--solver-tolerance must be a number in (0, 1), a fraction of g dt"},
        std::tuple{Setting::solver_tolerance, "--solver-tolerance", std::nan(""),
                   "--solver-tolerance must be a number in (0, 1), a fraction of g dt"},
        std::tuple{Setting::solver_max_sweeps, "--solver-max-sweeps", 10.5,
                   "--solver-max-sweeps must be a whole number from 1 to 1e9"}}) {
    RunOverrides o;
    try {
      set_number_setting(o, setting, value, flag);
      ADD_FAILURE() << "accepted " << flag << " " << value;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), message);
    }
  }
  RunOverrides o;
  set_number_setting(o, Setting::solver_max_sweeps, 1000, "--solver-max-sweeps");
  ASSERT_EQ(o.flags_given.size(), 1u);
  EXPECT_EQ(o.flags_given[0].second, "--solver-max-sweeps 1000");
  EXPECT_EQ(run_settings(o).step.solver_max_sweeps, 1000);
}

TEST(RunSettingsOnCommandLine, FlagsGivenAreKeptAsWritten) {
  RunOverrides o;
  set_text_setting(o, Setting::model, std::string("rocking2d"), {"", 0, "--model"});
  set_text_setting(o, Setting::contact, std::string("penalty"), {"", 0, "--contact"});
  ASSERT_EQ(o.flags_given.size(), 2u);
  EXPECT_EQ(o.flags_given[0].second, "--model rocking2d");
  EXPECT_EQ(o.flags_given[1].second, "--contact penalty");
}

TEST(RunSettings, CommandLineOverTheJobFile) {
  RunOverrides file, flags;
  file.engine = scenario::Engine::rocking2d;
  file.safety = 0.3;
  flags.engine = scenario::Engine::dem3d;
  const RunOverrides both = merged(file, flags);
  EXPECT_EQ(both.engine, scenario::Engine::dem3d);
  EXPECT_EQ(both.safety, 0.3);
}

TEST(RunSettings, ThePresetThenTheExplicitSettings) {
  // the reference preset's values, written out from scenario/accuracy.hpp's table
  const scenario::AccuracyPreset& reference = *scenario::find_accuracy_preset("reference");
  RunOverrides o;
  o.accuracy = "reference";
  o.dt = 2e-5;
  const scenario::RunSettings s = run_settings(o);
  EXPECT_EQ(s.step.dt, 2e-5);
  EXPECT_EQ(s.step.safety, reference.safety);
  EXPECT_EQ(s.rest_time, reference.rest_time);
  // the reference preset is the oracle: a tight contact solve with no practical cap
  EXPECT_LE(s.step.solver_tolerance, 1e-9);
  EXPECT_GE(s.step.solver_max_sweeps, 100000);
  // no preset named: the default one
  const scenario::RunSettings d = run_settings(RunOverrides{});
  EXPECT_EQ(d.step.safety, scenario::find_accuracy_preset(scenario::kDefaultAccuracy)->safety);
  EXPECT_TRUE(d.select_effects);
}

}  // namespace
}  // namespace rigid::job
