// A job file's calibrated [[object]] (calibration = "FILE"): the calibration's distinct member
// scenes become the variant axis, each weighted by its members' share of the weight (worked by
// hand below), the object's scene is the calibration's own when left out, and the combinations
// a job refuses name the job file's line. The calibration files are written by
// write_calibration_document, as the shake-table workflow writes them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "rigid/core/error.hpp"
#include "rigid/io/calibration_document.hpp"
#include "rigid/io/job_file.hpp"
#include "rigid/io/provenance.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

class JobCalibration : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rigid_job_calibration_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "cal");
    for (const char* scene : {"cal/rock.toml", "cal/soft.toml", "other.toml"}) std::ofstream(dir_ / scene) << "\n";
    fs::copy_file(fs::path(RIGID_SOURCE_DIR) / "waveforms/demo/mp_pulse_1s-X.AT2", dir_ / "r.AT2");
    // members: rock 0.5 + 0.25 = 0.75, soft 0.25 (weights need not sum to 1)
    write_calibration_document((dir_ / "cal/rock.calibration.json").string(), Json::parse(R"({
      "scene": "rock.toml", "parameters": {"friction": {"value": 0.9}}, "in_sample": {"log_score": 0.4},
      "ensemble": [{"scene": "rock.toml", "rotations_deg": [150, 160], "weight": 1.0, "lapse": 0.1},
                   {"scene": "soft.toml", "rotations_deg": [160], "weight": 0.5, "lapse": 0.0},
                   {"scene": "rock.toml", "rotations_deg": [170], "weight": 0.5, "lapse": 0.05}]})"),
                               "rigid test");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string job(const std::string& objects, const std::string& extra = "") {
    const fs::path path = dir_ / "job.toml";
    std::ofstream(path) << "[campaign]\nscales = [0.1, 0.2]\n"
                        << objects << extra << "[[record]]\nmotion = \"r.AT2\"\n";
    return path.string();
  }

  long refused_line(const std::string& objects, const std::string& extra = "") {
    try {
      read_job_file(job(objects, extra));
    } catch (const InputError& e) {
      EXPECT_EQ(fs::path(e.file()).filename(), "job.toml") << e.what();
      return e.line();
    }
    ADD_FAILURE() << "accepted: " << objects << extra;
    return -1;
  }

  fs::path dir_;
};

TEST_F(JobCalibration, MembersAreTheVariantsWeightedByTheirShare) {
  const JobFile f = read_job_file(job("[[object]]\nname = \"sp\"\ncalibration = \"cal/rock.calibration.json\"\n"));
  ASSERT_EQ(f.objects.size(), 1u);
  EXPECT_TRUE(fs::equivalent(f.objects[0].scene, dir_ / "cal/rock.toml"));  // the calibration's own scene
  ASSERT_EQ(f.variants.count(), 2);
  EXPECT_EQ(f.variants.method, "calibration");
  ASSERT_EQ(f.variants.keys.size(), 1u);
  EXPECT_EQ(f.variants.keys[0], scenario::VariantKey::scene);
  EXPECT_TRUE(fs::equivalent(f.variants.variants[0][0].text, dir_ / "cal/rock.toml"));
  EXPECT_TRUE(fs::equivalent(f.variants.variants[1][0].text, dir_ / "cal/soft.toml"));
  ASSERT_TRUE(f.calibration);
  ASSERT_EQ(f.calibration->weights.size(), 2u);
  EXPECT_DOUBLE_EQ(f.calibration->weights[0], 0.75);
  EXPECT_DOUBLE_EQ(f.calibration->weights[1], 0.25);
  EXPECT_EQ(f.calibration->sha256, file_sha256((dir_ / "cal/rock.calibration.json").string()));
  EXPECT_EQ(f.calibration->line, 3);
  const Json summary = Json::parse(f.calibration->summary_json);
  EXPECT_EQ(summary["parameters"]["friction"]["value"], 0.9);
  EXPECT_EQ(summary["rigid_version"], rigid_version());
  EXPECT_FALSE(summary.contains("ensemble"));
}

TEST_F(JobCalibration, TheCalibrationsOwnSceneMayBeNamed) {
  const JobFile f =
      read_job_file(job("[[object]]\nscene = \"cal/rock.toml\"\ncalibration = \"cal/rock.calibration.json\"\n"));
  EXPECT_EQ(f.variants.count(), 2);
}

TEST_F(JobCalibration, RefusedCombinationsNameTheJobLine) {
  const std::string calibrated = "[[object]]\ncalibration = \"cal/rock.calibration.json\"\n";  // lines 3-4
  EXPECT_EQ(refused_line("[[object]]\nscene = \"other.toml\"\ncalibration = \"cal/rock.calibration.json\"\n"), 3);
  EXPECT_EQ(refused_line(calibrated + calibrated), 5);
  EXPECT_EQ(refused_line(calibrated + "[[object]]\nscene = \"other.toml\"\n"), 3);
  EXPECT_EQ(refused_line(calibrated, "[sweep]\nmethod = \"lhs\"\ncount = 2\nfriction = [0.4, 0.9]\n"), 5);
  EXPECT_EQ(refused_line(calibrated, "[[variant]]\nfriction = 0.4\n"), 5);
  EXPECT_EQ(refused_line("[[object]]\ncalibration = \"cal/none.calibration.json\"\n"), 3);
}

TEST_F(JobCalibration, AnEditedCalibrationIsRefusedUnderTheObjectsLine) {
  const fs::path file = dir_ / "cal/rock.calibration.json";
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("\"weight\": 0.5"), 13, "\"weight\": 5.0");
  std::ofstream(file) << text;
  try {
    read_job_file(job("[[object]]\ncalibration = \"cal/rock.calibration.json\"\n"));
    ADD_FAILURE() << "an edited calibration was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(e.problem().find("checksum"), std::string::npos) << e.what();
    EXPECT_NE(e.problem().find("rock.calibration.json"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rigid::io
