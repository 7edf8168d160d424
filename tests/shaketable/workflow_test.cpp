// The shake-table workflow's parts without MPI: the typed physics and the designed job it becomes,
// the calibration file's ensemble and its one probability rule, the staged design, the PGA grid
// and the outcome grid read back from a cube. Oracles: values worked by hand, and the project's
// own job reader for what the writer wrote.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>

#include "rigid/calibration/outcome_model.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/job_file.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/provenance.hpp"
#include "rigid/shaketable/calibrate.hpp"
#include "rigid/shaketable/calibration_document.hpp"
#include "rigid/shaketable/ensemble.hpp"
#include "rigid/shaketable/fragility.hpp"
#include "rigid/shaketable/physics.hpp"

namespace fs = std::filesystem;
using namespace rigid;
using shaketable::Physics;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rigid_shaketable_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

Physics penalty(double k, double d, double mu) {
  Physics p;
  p.base = "flat_5mm";
  p.base_scene = "/scenes/flat_5mm_k" + std::to_string(int(k)) + ".toml";
  p.law.method = contact::ContactMethod::penalty;
  p.law.normal_stiffness = k;
  p.law.damping = d;
  p.law.friction = mu;
  return p;
}

}  // namespace

TEST(ShaketablePhysics, LabelsAndSceneTablesSayTheLawInUse) {
  const Physics soft = penalty(5e5, 4, 0.9);
  EXPECT_EQ(soft.label(), "flat_5mm penalty K=5e+05 D=4 mu=0.90");
  const shaketable::PhysicsTable t = soft.physics_table();
  ASSERT_EQ(t.size(), 5u);  // contact, K_N, K_S = K_N, D, friction: no restitution for springs
  EXPECT_EQ(std::get<std::string>(t[0].second), "penalty");
  EXPECT_EQ(std::get<double>(t[1].second), 5e5);
  EXPECT_EQ(std::get<double>(t[2].second), 5e5);
  Physics rigid;
  rigid.base = "flat_0mm";
  rigid.law.restitution = 0.5;
  EXPECT_EQ(rigid.label(), "flat_0mm rigid e=0.50 mu=0.60");
  const shaketable::PhysicsTable r = rigid.physics_table();
  ASSERT_EQ(r.size(), 3u);  // contact, friction, restitution
  EXPECT_EQ(std::get<std::string>(r[0].second), "rigid");
  EXPECT_EQ(r[2].first, "restitution");
}

TEST(ShaketableEnsemble, MembersAverageTheOneRuleByWeight) {
  // the rule worked by hand: lapse/2 + (1 - lapse) x share
  EXPECT_DOUBLE_EQ(calibration::member_probability(2.0 / 3.0, 0.1), 0.05 + 0.9 * 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(calibration::member_probability(0.0, 0.2), 0.1);
  const fs::path dir = scratch("ensemble");
  write(dir / "rock.toml", "# a scene; the ensemble names its own\n");
  write(dir / "member_v2.toml", "# another member's scene\n");
  shaketable::write_calibration_document((dir / "rock.calibration.json").string(), io::Json::parse(R"({"ensemble": [
      {"scene": "rock.toml", "weight": 3, "lapse": 0.1, "rotations_deg": [-10, 0, 10]},
      {"scene": "member_v2.toml", "weight": 1, "lapse": 0, "rotations_deg": [0]}]})"),
                                         "rigid test");
  const shaketable::Ensemble e = shaketable::load_ensemble((dir / "rock.toml").string());
  ASSERT_EQ(e.scenes.size(), 2u);
  EXPECT_EQ(e.rotations_deg, (std::vector<double>{-10, 0, 10}));
  ASSERT_EQ(e.members.size(), 2u);
  EXPECT_EQ(e.members[0].rotations, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(e.members[1].rotations, (std::vector<int>{1}));
  // member 0 overturns at -10 and 0 deg (share 2/3), member 1 at its one heading
  const auto overturned = [](int variant, int rotation) { return variant == 1 || rotation < 2; };
  EXPECT_NEAR(e.probability(overturned), 0.75 * (0.05 + 0.9 * 2.0 / 3.0) + 0.25 * 1.0, 1e-15);
  EXPECT_NEAR(e.probability(overturned, false), 0.75 * 2.0 / 3.0 + 0.25, 1e-15);
  // a field campaign weights each scene by its members' share: 3 of 4, 1 of 4
  EXPECT_EQ(e.scene_weights(), (std::vector<double>{0.75, 0.25}));

  // its designed job: one object, the scenes as variants, the headings as rotation angles
  const io::JobFile job = shaketable::ensemble_job((dir / "rock.toml").string(), e, shaketable::lab_input(""));
  ASSERT_EQ(job.variants.count(), 2);
  EXPECT_EQ(job.variants.variants[1][0].text, (dir / "member_v2.toml").string());
  EXPECT_EQ(job.rotation_angles_deg, e.rotations_deg);
  fs::remove_all(dir);
}

TEST(ShaketableEnsemble, ASceneWithoutCalibrationIsItselfAtHeadingZero) {
  const fs::path dir = scratch("alone");
  const shaketable::Ensemble e = shaketable::load_ensemble((dir / "rock.toml").string());
  EXPECT_TRUE(e.json.empty());
  EXPECT_EQ(e.rotations_deg, std::vector<double>{0.0});
  EXPECT_EQ(e.probability([](int, int) { return true; }), 1.0);
  write(dir / "rock.toml", "# scene\n");
  shaketable::write_calibration_document((dir / "rock.calibration.json").string(),
                                         io::Json::parse(R"({"ensemble": [{"scene": "rock.toml", "weight": -1,
                                             "lapse": 0, "rotations_deg": [0]}]})"),
                                         "rigid test");
  EXPECT_THROW(shaketable::load_ensemble((dir / "rock.toml").string()), InputError);
  fs::remove_all(dir);
}

namespace {

// The message of the InputError `f` throws ("" when it throws none).
std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CalibrationDocument, AWholeUneditedDocumentReadsBackWithItsEnvelope) {
  const fs::path dir = scratch("document");
  const std::string file = (dir / "a.calibration.json").string();
  shaketable::write_calibration_document(file, io::Json::parse(R"({"ensemble": [1, 2.5e-7]})"), "rigid 'a b'");
  const io::Json j = shaketable::read_calibration_document(file);
  EXPECT_EQ(j["format"], "rigid calibration");
  EXPECT_EQ(j["format_version"], shaketable::kCalibrationFormatVersion);
  EXPECT_EQ(j["command_line"], "rigid 'a b'");
  EXPECT_EQ(j["ensemble"][1].get<double>(), 2.5e-7);
  // the checksum is SHA-256 of the document without it, compact: sha256sum of that line by hand
  io::Json without = j;
  without.erase("sha256");
  EXPECT_EQ(j["sha256"], io::sha256_hex(io::json_line(without)));
  fs::remove_all(dir);
}

TEST(CalibrationDocument, EditedTruncatedOrOtherVersionsAreRefusedByName) {
  const fs::path dir = scratch("refused");
  const std::string file = (dir / "a.calibration.json").string();
  shaketable::write_calibration_document(file, io::Json::parse(R"({"weight": 0.25})"), "rigid test");
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto read = [&] { shaketable::read_calibration_document(file); };
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const auto at = t.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    write(file, t.replace(at, from.size(), to));
  };
  with("0.25", "0.35");  // an edit by hand
  EXPECT_NE(refusal(read).find("checksum"), std::string::npos) << refusal(read);
  write(file, text.substr(0, text.size() / 2));  // cut short
  EXPECT_NE(refusal(read).find("truncated"), std::string::npos) << refusal(read);
  with("\"format_version\": 2", "\"format_version\": 3");
  EXPECT_NE(refusal(read).find("version 3"), std::string::npos) << refusal(read);
  write(file, R"({"ensemble": []})");  // a file of the old, unversioned kind
  EXPECT_NE(refusal(read).find("not a calibration file"), std::string::npos) << refusal(read);
  EXPECT_NE(refusal([&] {
              shaketable::read_calibration_document((dir / "none.json").string());
            }).find("no such calibration file"),
            std::string::npos);
  EXPECT_NE(refusal(read).find(file), std::string::npos);  // names the file
  fs::remove_all(dir);
}

TEST(CalibrationDocument, CommandLinesQuoteWhatTheShellWouldSplit) {
  const char* argv[] = {"rigid", "shaketable", "calibrate", "my scan.ply", "--out", "it's"};
  EXPECT_EQ(shaketable::command_line_text(6, argv), "rigid shaketable calibrate 'my scan.ply' --out 'it'\\''s'");
}

TEST(ShaketableDesign, TheDesignedJobReadsBackAsItsPhysicsAndWindows) {
  const fs::path dir = scratch("design");
  // a scene and two recordings the reader can find
  write(dir / "rock.toml", "# scene\n");
  write(dir / "Test001.txt", "t\n");
  write(dir / "Test002.txt.gz", "t\n");
  write(dir / "format.toml", "[lab]\nheader_lines = 3\nband_hz = [0.2, 20.0]\ndelimiter = \"comma\"\n");
  shaketable::LabInput lab = shaketable::lab_input((dir / "format.toml").string());
  io::JobFile job = shaketable::designed_job((dir / "rock.toml").string(), lab);
  std::vector<Physics> physics{penalty(5e5, 4, 0.6), penalty(5e5, 4, 0.9)};
  for (Physics& p : physics) p.base_scene = (dir / "rock.toml").string();
  job.variants = shaketable::physics_variants(physics);
  job.records = {shaketable::lab_record((dir / "Test001.txt").string(), 1.5, 7.25),
                 shaketable::lab_record((dir / "Test002.txt.gz").string(), 0, 2)};
  job.rotation_angles_deg = {100, 110, 120};
  io::write_job_file((dir / "stage.toml").string(), job, "a comment\nof two lines");

  const io::JobFile back = io::read_job_file((dir / "stage.toml").string());
  EXPECT_EQ(back.seed, 1u);
  EXPECT_EQ(back.stop_after, 0);
  EXPECT_EQ(back.scales_g, std::vector<double>{io::kAsRecordedScale});
  EXPECT_EQ(back.rotation_angles_deg, job.rotation_angles_deg);
  ASSERT_EQ(back.objects.size(), 1u);
  EXPECT_EQ(back.objects[0].name, "rock");
  ASSERT_EQ(back.variants.count(), 2);
  ASSERT_EQ(back.variants.keys, shaketable::physics_variant_keys());
  EXPECT_EQ(back.variants.variants[1][0].number, 0.9);  // friction
  EXPECT_EQ(back.variants.variants[1][1].number, 0.0);  // restitution
  EXPECT_EQ(back.variants.variants[1][2].number, 4.0);  // damping
  EXPECT_EQ(back.variants.variants[1][3].text, physics[1].base_scene);
  ASSERT_EQ(back.records.size(), 2u);
  EXPECT_TRUE(back.records[0].lab);
  EXPECT_EQ(back.records[0].name, "Test001");
  EXPECT_EQ(back.records[0].start, 1.5);
  EXPECT_EQ(back.records[0].end, 7.25);
  EXPECT_EQ(back.records[1].name, "Test002");
  EXPECT_EQ(back.lab_format.header_lines, 3);
  EXPECT_EQ(back.lab_format.processing.low_hz, 0.2);
  EXPECT_EQ(back.lab_format.processing.high_hz, 20.0);
  EXPECT_EQ(back.lab_format.delimiter, motion::LabDelimiter::comma);
  ASSERT_TRUE(back.run.free_time_s);
  EXPECT_EQ(*back.run.free_time_s, 5.0);
  std::ifstream in(dir / "stage.toml");
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "# a comment");
  fs::remove_all(dir);
}

TEST(ShaketableDesign, AFormatFileWithoutLabTableIsRefused) {
  const fs::path dir = scratch("format");
  write(dir / "typo.toml", "[labb]\nheader_lines = 3\n");
  write(dir / "empty.toml", "");
  EXPECT_THROW(shaketable::lab_input((dir / "typo.toml").string()), InputError);
  EXPECT_THROW(shaketable::lab_input((dir / "empty.toml").string()), InputError);
  fs::remove_all(dir);
}

TEST(ShaketableDesign, StageTwoRefinesTheBestVariantAroundItsBestHeading) {
  // stage 1: rigid and one penalty law over a ring of 12 headings; 6 tests. The penalty variant
  // at heading 120 deg reproduces the observed outcomes exactly, the rigid one never overturns.
  shaketable::CalibrationSettings s;
  s.damping = {4, 2};
  s.friction = {0.6, 0.9};
  s.keep = 1;
  const std::map<double, std::string> bases{{0.005, "/b/flat_5mm.toml"}};
  s.contact_models = {{contact::ContactMethod::rigid, 0}, {contact::ContactMethod::penalty, 5e5}};
  const std::vector<Physics> stage1 = shaketable::first_stage_physics(bases, s);
  ASSERT_EQ(stage1.size(), 2u);
  EXPECT_EQ(stage1[0].base, "flat_5mm");
  EXPECT_FALSE(stage1[0].penalty());
  EXPECT_EQ(stage1[1].law.normal_stiffness, 5e5);
  EXPECT_EQ(stage1[1].law.damping, 4);  // the first value in stage 1
  const std::vector<int> observed{1, 0, 1, 1, 0, 0};
  calibration::OutcomeGrid grid(2, 6, shaketable::heading_ring(12));
  for (int t = 0; t < 6; ++t) {
    for (int h = 0; h < 12; ++h) grid.set(1, t, h, h == 4 ? observed[std::size_t(t)] == 1 : t == 0);
  }
  const shaketable::SecondStage second = shaketable::second_stage_design(grid, observed, stage1, s);
  EXPECT_EQ(second.headings_deg, (std::vector<double>{100, 110, 120, 130, 140}));
  ASSERT_EQ(second.physics.size(), 4u);  // 2 dampings x 2 frictions of the penalty law
  for (const Physics& p : second.physics) EXPECT_TRUE(p.penalty());
  EXPECT_EQ(second.physics[1].law.damping, 4);
  EXPECT_EQ(second.physics[1].law.friction, 0.9);
  EXPECT_EQ(second.physics[2].law.damping, 2);
  ASSERT_EQ(second.kept.size(), 1u);
}

TEST(ShaketableDesign, SettingsOutsideTheirRangesNameTheirFlag) {
  shaketable::CalibrationSettings s;
  s.out = "cal/rock";
  EXPECT_NO_THROW(shaketable::check_settings(s));
  const auto message = [](const shaketable::CalibrationSettings& bad) {
    try {
      shaketable::check_settings(bad);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  shaketable::CalibrationSettings bad = s;
  bad.flatten_base_m = {0.2};
  EXPECT_NE(message(bad).find("--flatten-base"), std::string::npos);
  bad = s;
  bad.tilt_deg = 90;
  EXPECT_NE(message(bad).find("--tilt-rule"), std::string::npos);
  bad = s;
  bad.headings = 3;
  EXPECT_NE(message(bad).find("--headings"), std::string::npos);
  EXPECT_EQ(shaketable::parse_contact_choice("rigid")->method, contact::ContactMethod::rigid);
  EXPECT_EQ(shaketable::parse_contact_choice("5e5")->normal_stiffness, 5e5);
  EXPECT_FALSE(shaketable::parse_contact_choice("1e4"));
  EXPECT_FALSE(shaketable::parse_contact_choice("5e5x"));
  EXPECT_FALSE(shaketable::parse_contact_choice("nan"));
  EXPECT_EQ(shaketable::base_name(0.005), "flat_5mm");
}

TEST(ShaketableFragility, ThePgaGridIsGeometricInFourDigits) {
  const std::vector<double> g = shaketable::pga_grid(0.02, 0.5, 10);
  EXPECT_EQ(g.front(), 0.02);
  EXPECT_GE(g.back(), 0.5);
  EXPECT_LT(g[g.size() - 2], 0.5);
  for (std::size_t i = 1; i < g.size(); ++i) {
    EXPECT_NEAR(g[i] / g[i - 1], std::pow(10.0, 0.1), 1e-3);
    const double digits = std::pow(10.0, 3 - std::floor(std::log10(g[i])));
    EXPECT_NEAR(std::round(g[i] * digits), g[i] * digits, 1e-9);  // 4 significant digits
  }
}

TEST(ShaketableCube, TheOutcomeGridIsTheCubesCellsByVariantTestHeading) {
  io::Cube cube;
  cube.records.resize(2);
  cube.records[0].name = "Test001";
  cube.records[1].name = "Test002";
  cube.scales_g = {io::kAsRecordedScale};
  cube.rotations = 3;
  const auto over = std::int8_t(io::CellOutcome::overturned), stood = std::int8_t(io::CellOutcome::survived);
  cube.objects.resize(2);
  cube.objects[0].outcome = {over, stood, stood, stood, stood, over};
  cube.objects[1].outcome = {stood, stood, stood, over, over, over};
  const calibration::OutcomeGrid grid = shaketable::outcome_grid(cube, {0, 10, 20});
  EXPECT_TRUE(grid.overturned(0, 0, 0));
  EXPECT_FALSE(grid.overturned(0, 0, 1));
  EXPECT_TRUE(grid.overturned(0, 1, 2));
  EXPECT_TRUE(grid.overturned(1, 1, 0));
  EXPECT_FALSE(grid.overturned(1, 0, 2));
  cube.objects[1].outcome[4] = std::int8_t(io::CellOutcome::not_run);
  EXPECT_THROW(shaketable::outcome_grid(cube, {0, 10, 20}), InputError);
  EXPECT_THROW(shaketable::outcome_grid(cube, {0, 10}), InputError);
}
