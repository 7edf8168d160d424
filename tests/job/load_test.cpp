// Job files: a good job loads with its defaults, and every kind of bad job is refused before any
// work starts with the file, line and problem.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "rigid/core/error.hpp"
#include "rigid/job/job.hpp"
#include "rigid/job/load.hpp"

namespace rigid::job {
namespace {

namespace fs = std::filesystem;

class JobFile : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    const fs::path dir = fs::path(RIGID_SOURCE_DIR) / "jobs";
    path_ = (dir / ("test_job_" + std::to_string(::getpid()) + ".toml")).string();
    std::ofstream(path_) << text;
    return path_;
  }
  void TearDown() override {
    if (!path_.empty()) fs::remove(path_);
  }
  void expect_error(const std::string& text, const std::string& fragment, long line = -1) {
    try {
      load_job(write(text));
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      if (line >= 0) {
        EXPECT_EQ(e.line(), line) << e.what();
      }
    }
  }
  std::string path_;
};

const char* kGood = R"([campaign]
scales = "0.1:0.5:0.1"

[[object]]
scene = "../models/demo/block_a02.toml"

[[record]]
motion = "../waveforms/demo/stochastic_s1-X.AT2"
)";

// a lab recording written beside the job (the job resolves it relative to itself)
const char* kLabJob = R"([campaign]
scales = "as recorded"

[[object]]
scene = "../models/demo/block_a02.toml"

[[record]]
lab = "test_lab_recording.txt"

[lab]
channel = "displacement"
displacement_unit = "mm"
band_hz = [0.2, 20.0]
filter_order = 2
acceleration_column = "Acceleration [g]"
)";

TEST_F(JobFile, ALabRecordAsRecordedReadsItsFormatFromTheLabTable) {
  const fs::path recording = fs::path(RIGID_SOURCE_DIR) / "jobs" / "test_lab_recording.txt";
  std::ofstream(recording) << "t\ta\td\n0\t0\t0\n";
  const auto job = load_job(write(kLabJob));
  fs::remove(recording);
  EXPECT_TRUE(job.as_recorded());
  ASSERT_EQ(job.scales_g.size(), 1u);
  ASSERT_EQ(job.records.size(), 1u);
  EXPECT_TRUE(job.records[0].lab);
  EXPECT_EQ(job.records[0].name, "test_lab_recording");
  EXPECT_EQ(fs::path(job.records[0].spec).filename(), "test_lab_recording.txt");
  EXPECT_EQ(job.lab_format.channel, motion::LabChannel::displacement);
  EXPECT_EQ(job.lab_format.displacement_unit, "mm");
  EXPECT_EQ(job.lab_format.acceleration.name, "Acceleration [g]");
  EXPECT_EQ(job.lab_format.processing.order, 2);
  EXPECT_DOUBLE_EQ(job.lab_format.processing.low_hz, 0.2);
  EXPECT_DOUBLE_EQ(job.lab_format.processing.high_hz, 20.0);
}

TEST_F(JobFile, ABadLabTableOrLabRecordIsRefusedAtItsLine) {
  std::string job = kLabJob;
  expect_error(job, "lab recording not found", 7);
  const std::string unused = std::string(kGood) + "[lab]\nchannel = \"acceleration\"\n";
  expect_error(unused, "no [[record]] has lab", 9);
}

TEST_F(JobFile, GoodJobLoadsWithTheStudysDefaults) {
  const auto job = load_job(write(kGood));
  ASSERT_EQ(job.scales_g.size(), 5u);
  EXPECT_NEAR(job.scales_g.back(), 0.5, 1e-12);
  EXPECT_EQ(job.rotations, 2);
  EXPECT_EQ(job.stop_after, 10);
  EXPECT_EQ(job.records.at(0).name, "stochastic_s1");
  EXPECT_EQ(job.objects.at(0).name, "block_a02");
  EXPECT_EQ(job.hash.size(), 64u);  // hex SHA-256
}

// A range's scales are the doubles the decimals start + i * step parse to (the compiler's reading
// of the literals is the oracle), so xarray's sel(scale=0.3) finds them; the simulations keep the
// float sums start + i * step the campaigns ran with before.
TEST_F(JobFile, RangeScalesAreTheStatedDecimalsAndDriveWithTheFloatSums) {
  const auto with = [&](const std::string& range) {
    std::string t = kGood;
    t.replace(t.find("0.1:0.5:0.1"), 11, range);
    return load_job(write(t));
  };
  const auto demo = with("0.1:1.0:0.1");
  const std::vector<double> stated{0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
  EXPECT_EQ(demo.scales_g, stated);
  ASSERT_EQ(demo.drive_scales_g.size(), stated.size());
  for (std::size_t i = 0; i < stated.size(); ++i) EXPECT_EQ(demo.drive_scale_g(i), 0.1 + double(i) * 0.1) << i;
  EXPECT_NE(demo.drive_scale_g(2), 0.3);  // 0.30000000000000004: the sum differs, the coordinate does not
  EXPECT_EQ(with("1e-1:3e-1:1e-1").scales_g, (std::vector<double>{0.1, 0.2, 0.3}));
  EXPECT_EQ(with("0.25:1:0.25").scales_g, (std::vector<double>{0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(with("0.2:2.0:0.2").scales_g, (std::vector<double>{0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6, 1.8, 2.0}));
  EXPECT_EQ(with("0.05:0.2:0.05").scales_g, (std::vector<double>{0.05, 0.1, 0.15, 0.2}));
  EXPECT_EQ(with("0.1:0.35:0.1").scales_g, (std::vector<double>{0.1, 0.2, 0.3}));  // stop off the grid
  // a list is taken as written, and drives as written
  std::string listed = kGood;
  listed.replace(listed.find("\"0.1:0.5:0.1\""), 13, "[0.3, 0.7]");
  const auto list = load_job(write(listed));
  EXPECT_EQ(list.scales_g, (std::vector<double>{0.3, 0.7}));
  EXPECT_EQ(list.drive_scale_g(0), 0.3);
}

TEST_F(JobFile, RecordAlignIsResampleOrAutoWithItsLine) {
  std::string t = kGood + std::string("align = \"resample\"\n");
  EXPECT_TRUE(load_job(write(t)).records.at(0).resample);
  EXPECT_FALSE(load_job(write(kGood)).records.at(0).resample);
  expect_error(kGood + std::string("align = \"stretch\"\n"), "align", 9);
  expect_error(kGood + std::string("align = 5\n"), "align", 9);
}

TEST_F(JobFile, UnknownKeyIsRefusedWithItsLine) {
  std::string t = kGood;
  t.insert(t.find("scales"), "rotatons = 3\n");
  expect_error(t, "rotatons", 2);
}

TEST_F(JobFile, MissingSceneIsRefused) {
  std::string t = kGood;
  t.replace(t.find("block_a02.toml"), 14, "nothere.toml");
  expect_error(t, "nothere.toml");
}

TEST_F(JobFile, AbsentOptionalObjectIsLeftOutWithANoteThatEntersTheHash) {
  const std::string extra = "[[object]]\nname = \"scan\"\nscene = \"../models/absent/none.toml\"\noptional = true\n";
  std::string text = kGood;
  text.insert(text.find("[[record]]"), extra);
  const Job with_absent = load_job(write(text));
  ASSERT_EQ(with_absent.objects.size(), 1u);
  ASSERT_EQ(with_absent.notes.size(), 1u);
  EXPECT_NE(with_absent.notes[0].find("none.toml"), std::string::npos) << with_absent.notes[0];
  // the same job without the optional object is another job: a resume between them is refused
  EXPECT_NE(with_absent.hash, load_job(write(kGood)).hash);
  // an optional object that exists is loaded; a non-optional absent one is an error
  std::string present = kGood;
  present.insert(present.find("[[record]]"),
                 "[[object]]\nname = \"again\"\nscene = \"../models/demo/block_a03.toml\"\noptional = true\n");
  EXPECT_EQ(load_job(write(present)).objects.size(), 2u);
  std::string required = text;
  required.replace(required.find("optional = true"), 15, "optional = false");
  expect_error(required, "scene file not found");
  std::string typo = text;
  typo.replace(typo.find("optional = true"), 15, "optional = 1");
  expect_error(typo, "optional");
}

TEST_F(JobFile, MissingMotionIsRefused) {
  std::string t = kGood;
  t.replace(t.find("stochastic_s1-X"), 15, "no_such_record-X");
  expect_error(t, "no_such_record-X.AT2");
}

// The checkpoint interval must be a positive number of seconds and the grace period a number of
// seconds >= 0, by one rule for the job file (refused at its [campaign] line) and the flags.
TEST_F(JobFile, CheckpointIntervalAndGraceFollowOneRule) {
  const std::string good = kGood;
  const auto with = [&](const std::string& line) {
    return "[campaign]\n" + line + "\n" + good.substr(good.find('\n') + 1);
  };
  expect_error(with("checkpoint_interval_s = 0.0"), "checkpoint_interval_s must be a positive number of seconds", 1);
  // a value that is no finite number is the reader's to refuse, at its own line
  expect_error(with("checkpoint_interval_s = inf"), "checkpoint_interval_s must be a finite number", 2);
  expect_error(with("grace_s = -1.0"), "grace_s must be a number of seconds >= 0", 1);
  expect_error(with("grace_s = nan"), "grace_s must be a finite number", 2);
  const Job zero_grace = load_job(write(with("grace_s = 0.0")));
  EXPECT_EQ(zero_grace.grace_s, 0.0);
  const Job tiny = load_job(write(with("checkpoint_interval_s = 0.001")));
  EXPECT_EQ(tiny.checkpoint_interval_s, 0.001);
  EXPECT_FALSE(checkpoint_interval_problem(-1.0).empty());
  EXPECT_FALSE(checkpoint_interval_problem(std::nan("")).empty());
  EXPECT_TRUE(grace_problem(0.0).empty());
  EXPECT_FALSE(grace_problem(-0.5).empty());
}

TEST_F(JobFile, EmptyScaleListIsRefused) {
  std::string t = kGood;
  t.replace(t.find("\"0.1:0.5:0.1\""), 13, "[]");
  expect_error(t, "empty", 2);
}

TEST_F(JobFile, NonIncreasingScalesAreRefused) {
  std::string t = kGood;
  t.replace(t.find("\"0.1:0.5:0.1\""), 13, "[0.1, 0.3, 0.2]");
  expect_error(t, "increasing", 2);
}

TEST_F(JobFile, MalformedTomlNamesTheLine) {
  std::string t = kGood;
  t.insert(t.find("[[object]]"), "scales = = 1\n");
  expect_error(t, "", 4);
}

// kGood has 8 lines; a [sweep] appended starts on line 9
TEST_F(JobFile, SweepExpandsEveryObjectIntoItsVariants) {
  const std::string t = std::string(kGood) + "\n[[object]]\nname = \"b\"\nscene = \"../models/demo/block_a03.toml\"\n" +
                        "\n[sweep]\ncount = 4\nfriction = [0.4, 0.8]\nrestitution = { values = [0.0, 0.2] }\n";
  const auto job = load_job(write(t));
  ASSERT_EQ(job.variants.count(), 4);
  EXPECT_EQ(job.variants.method, "lhs");
  EXPECT_EQ(job.variants.seed, job.seed);  // the campaign's seed unless [sweep] gives one
  ASSERT_EQ(job.objects.size(), 8u);       // 2 objects x 4 variants, object-major
  EXPECT_EQ(job.base_objects(), 2);
  EXPECT_EQ(job.objects[5].name, "b");
  EXPECT_EQ(job.objects[5].variant, 1);
  EXPECT_EQ(job.objects[5].base, 1);
  EXPECT_EQ(job.objects[5].label(), "b [v1]");
  for (const auto& row : job.variants.variants) {
    EXPECT_GE(row[0].number, 0.4);
    EXPECT_LE(row[0].number, 0.8);
    EXPECT_TRUE(row[1].number == 0.0 || row[1].number == 0.2);
  }
}

TEST_F(JobFile, VariantTablesAndGrid) {
  const auto list = load_job(write(std::string(kGood) + "[[variant]]\nfriction = 0.5\ncontact = \"penalty\"\n"
                                                        "[[variant]]\nfriction = 0.7\ncontact = \"rigid\"\n"));
  ASSERT_EQ(list.variants.count(), 2);
  EXPECT_EQ(list.variants.method, "list");
  EXPECT_EQ(list.variants.variants[1][0].number, 0.7);
  EXPECT_EQ(list.variants.variants[0][1].text, "penalty");
  const auto grid =
      load_job(write(std::string(kGood) + "[sweep]\nmethod = \"grid\"\nlevels = 3\nfriction = [0.4, 0.8]\n"
                                          "size_scale = { values = [0.9, 1.1] }\n"));
  EXPECT_EQ(grid.variants.count(), 6);
}

TEST_F(JobFile, AlternativeScenesReplaceTheObjectsScenePerVariant) {
  const auto job = load_job(write(std::string(kGood) +
                                  "[sweep]\nmethod = \"grid\"\n"
                                  "scene = [\"../models/demo/block_a02.toml\", \"../models/demo/block_a03.toml\"]\n"));
  ASSERT_EQ(job.objects.size(), 2u);
  EXPECT_EQ(fs::path(job.objects[0].simulated_scene()).filename(), "block_a02.toml");
  EXPECT_EQ(fs::path(job.objects[1].simulated_scene()).filename(), "block_a03.toml");
  EXPECT_EQ(job.objects[1].scene, job.objects[0].scene);  // the cube's group names the object's own
  EXPECT_EQ(job.objects[1].name, "block_a02");            // still the [[object]]'s name: one group in the cube
  // another [[object]] makes the alternative ambiguous
  expect_error(std::string(kGood) + "[[object]]\nname = \"b\"\nscene = \"../models/demo/block_a03.toml\"\n" +
                   "[sweep]\nmethod = \"grid\"\nscene = [\"../models/demo/block_a03.toml\"]\n",
               "exactly one [[object]]", 14);
}

TEST_F(JobFile, BadSweepsAreRefusedAtTheirLine) {
  const std::string job = kGood;
  expect_error(job + "[sweep]\ncount = 4\nfriction = [-0.2, 0.8]\n", "friction must be greater than 0", 11);
  expect_error(job + "[sweep]\ncount = 4\nfriction = [0.8, 0.8]\n", "friction: the range [0.8, 0.8] is empty", 11);
  expect_error(job + "[sweep]\ncount = 4\nviscosity = [0.1, 0.2]\n", "unknown parameter 'viscosity' in [sweep]", 11);
  expect_error(job + "[sweep]\ncount = 4\n", "[sweep] varies no parameter", 9);
  expect_error(job + "[sweep]\nfriction = [0.4, 0.8]\n", "needs count", 9);
  expect_error(job + "[sweep]\ncount = 0\nfriction = [0.4, 0.8]\n", "count must be an integer", 10);
  expect_error(job + "[sweep]\ncount = 4\nrestitution = [0.0, 1.5]\n", "restitution must not be greater than 1", 11);
  expect_error(job + "[sweep]\ncount = 4\nfriction = { values = [] }\n", "the list of values is empty", 11);
  expect_error(job + "[sweep]\ncount = 4\ncontact = [\"rigid\", \"soft\"]\n",
               "contact must be \"rigid\" or \"penalty\"", 11);
  expect_error(job + "[sweep]\nmethod = \"sobol\"\ncount = 4\nfriction = [0.4, 0.8]\n", "method must be", 10);
  expect_error(job + "[sweep]\ncount = 4\nfriction = [0.4, nan]\n", "friction must be a finite number", 11);
  expect_error(job + "[sweep]\ncount = 4\nscene = [\"no_such_scene.toml\"]\n", "scene: file not found", 11);
  expect_error(job + "[[variant]]\nfriction = 0.5\n[[variant]]\nrestitution = 0.1\n", "the same parameters", 11);
  expect_error(job + "[[variant]]\nfriction = 0.5\n[sweep]\ncount = 2\nfriction = [0.4, 0.8]\n", "not both");
}

TEST_F(JobFile, VariantsCountTowardsTheCellLimit) {
  std::string t = kGood;
  t.replace(t.find("\"0.1:0.5:0.1\""), 13, "\"0.001:1.0:0.001\"\nrotations = 1000");
  expect_error(t + "[sweep]\ncount = 20\nfriction = [0.4, 0.8]\n", "more than 1e7");
}

}  // namespace
}  // namespace rigid::job
