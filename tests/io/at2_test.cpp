// AT2 reader and writer: format variants, errors with file and line, round trip, sets, and every
// shared PEER record against its manifest (npts, dt, PGA).
#include "rigid/io/at2.hpp"

#include <gtest/gtest.h>

#include "support/manifest.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/json.hpp"

namespace fs = std::filesystem;

namespace rigid::io {
namespace {

const std::string kData = std::string(RIGID_SOURCE_DIR) + "/tests/data/at2/";
const std::vector<double> kValues = {0.001, -0.0025, 0.125, -0.5, 0.25, 0.0, 1.0e-5, -3.0e-4};

void expect_values(const At2Record& r) {
  ASSERT_EQ(r.values.size(), kValues.size()) << r.source;
  for (std::size_t i = 0; i < kValues.size(); ++i)
    EXPECT_DOUBLE_EQ(r.values[i], kValues[i]) << r.source << " value " << i;
}

// expects an InputError naming `file` and `line`
template <class F>
void expect_input_error(F f, const std::string& file, long line, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "no error for " << file;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file) << e.what();
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(At2Read, NgaKeywordHeaderWithCrlfAndShortLastLine) {
  const At2Record r = read_at2(kData + "nga_keyword_crlf.AT2");
  EXPECT_EQ(r.header_kind, At2Header::keyword);
  EXPECT_DOUBLE_EQ(r.dt, 0.01);
  EXPECT_EQ(r.component, "090");
  EXPECT_EQ(r.header.size(), 4u);
  expect_values(r);
  const motion::Component c = r.component_si();
  EXPECT_DOUBLE_EQ(c.acc[4], 0.25 * kGravity);
}

TEST(At2Read, OldPositionalHeader) {
  const At2Record r = read_at2(kData + "old_positional.AT2");
  EXPECT_EQ(r.header_kind, At2Header::positional);
  EXPECT_DOUBLE_EQ(r.dt, 0.02);
  EXPECT_EQ(r.component, "000 (CUE)");
  expect_values(r);
}

TEST(At2Read, LowercaseDtCrCrLfNoFinalNewline) {
  const At2Record r = read_at2(kData + "lowercase_dt_crcrlf.AT2");
  EXPECT_DOUBLE_EQ(r.dt, 0.005);
  expect_values(r);
}

TEST(At2Read, FortranExponentsAndThreeValuesPerLine) {
  // 1.0D-03, 1.25d-01, letter-less 1.0-005, a plain 0.0, sign-glued fields
  const At2Record r = read_at2(kData + "fortran_exponents.AT2");
  expect_values(r);
  const At2Record g = parse_at2(
      "t\ns, c\nACCELERATION IN UNITS OF G\nNPTS= 4, DT= 0.01\n"
      " -.1000E-02-.2000E-02  0.00300-0.00400\n",
      "glued", {});
  ASSERT_EQ(g.values.size(), 4u);
  EXPECT_DOUBLE_EQ(g.values[0], -0.001);
  EXPECT_DOUBLE_EQ(g.values[1], -0.002);
  EXPECT_DOUBLE_EQ(g.values[3], -0.004);
}

TEST(At2Read, HeaderlessNeedsExplicitDt) {
  expect_input_error([] { read_at2(kData + "headerless.AT2"); }, kData + "headerless.AT2", 1, "time step");
  At2ReadOptions o;
  o.dt = 0.005;
  const At2Record r = read_at2(kData + "headerless.AT2", o);
  EXPECT_EQ(r.header_kind, At2Header::none);
  EXPECT_DOUBLE_EQ(r.dt, 0.005);
  expect_values(r);
}

TEST(At2Read, ErrorsNameFileAndLine) {
  expect_input_error([] { read_at2(kData + "bad_npts.AT2"); }, kData + "bad_npts.AT2", 6,
                     "NPTS=10 in the header but 8 values");
  expect_input_error([] { read_at2(kData + "bad_value.AT2"); }, kData + "bad_value.AT2", 6, "NaN");
  expect_input_error([] { read_at2(kData + "bad_dt.AT2"); }, kData + "bad_dt.AT2", 4, "DT must be positive");
  expect_input_error([] { read_at2(kData + "no_header.AT2"); }, kData + "no_header.AT2", 0, "missing AT2 header");
  const std::string hdr = "t\ns, c\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 2, DT= 0.01\n";
  expect_input_error([&] { parse_at2(hdr + "0.1 abc\n", "m.AT2"); }, "m.AT2", 5, "non-numeric");
  expect_input_error([&] { parse_at2(hdr + "0.1 0.2 0.3\n", "m.AT2"); }, "m.AT2", 5, "more values than NPTS=2");
  expect_input_error([&] { parse_at2(hdr + "0.1 1e999\n", "m.AT2"); }, "m.AT2", 5, "range");
  expect_input_error([&] { parse_at2(hdr + "0.1 inf\n", "m.AT2"); }, "m.AT2", 5, "infinite");
  expect_input_error([] { parse_at2("", "e.AT2"); }, "e.AT2", 0, "empty");
  expect_input_error([] { parse_at2("t\ns, c\nVELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS= 1, DT= 0.01\n1\n", "v"); },
                     "v", 3, "not an acceleration");
  expect_input_error([] { read_at2(kData + "does_not_exist.AT2"); }, kData + "does_not_exist.AT2", 0, "cannot open");
}

TEST(At2Read, UnitsOtherThanG) {
  const At2Record r = parse_at2("t\ns, c\nACCELERATION TIME SERIES IN UNITS OF CM/S/S\nNPTS= 1, DT= 0.01\n981\n", "cm");
  EXPECT_DOUBLE_EQ(r.component_si().acc[0], 9.81);
}

TEST(At2Write, RoundTripIsExactToThePrintedPrecision) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  motion::Component c;
  c.dt = 0.005;
  c.label = "H1";
  for (int i = 0; i < 1003; ++i) c.acc.push_back(u(rng) * std::pow(10.0, double(i % 9) - 4.0));
  c.acc.push_back(0.0);
  for (const int digits : {7, 10, 17}) {
    At2WriteOptions o;
    o.digits = digits;
    const At2Record r = parse_at2(format_at2(c, o), "rt");
    ASSERT_EQ(r.values.size(), c.acc.size());
    EXPECT_EQ(r.dt, c.dt);
    EXPECT_EQ(r.component, "H1");
    for (std::size_t i = 0; i < c.acc.size(); ++i) {
      // printing the value read gives the same digits as printing the value written
      char a[64], b[64];
      std::snprintf(a, sizeof a, "%.*E", digits - 1, c.acc[i] / kGravity);
      std::snprintf(b, sizeof b, "%.*E", digits - 1, r.values[i]);
      ASSERT_STREQ(a, b) << i;
    }
    if (digits == 17) {
      // 17 significant digits identify a double: the g values come back bit for bit
      for (std::size_t i = 0; i < c.acc.size(); ++i) ASSERT_EQ(r.values[i], c.acc[i] / kGravity);
    }
  }
}

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("rigid_at2_test_" + std::to_string(std::random_device{}()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

motion::GroundMotion three_component(std::size_t n, double dt) {
  std::vector<motion::Component> c(3);
  for (int k = 0; k < 3; ++k) {
    c[k].dt = dt;
    c[k].label = std::string(1, char('X' + k));
    for (std::size_t i = 0; i < n; ++i) c[k].acc.push_back(std::sin(0.1 * double(i) * (k + 1)));
  }
  return motion::make_ground_motion("SET", c);
}

TEST(At2Sets, RigidNamingFindsSiblings) {
  TempDir d;
  const auto m = three_component(50, 0.01);
  const auto written = write_motion_set(m, (d.path / "SET").string());
  ASSERT_EQ(written.size(), 3u);
  const motion::GroundMotion r = read_motion_set((d.path / "SET-X.AT2").string());
  EXPECT_EQ(r.name, "SET");
  EXPECT_TRUE(r.has_y);
  EXPECT_TRUE(r.has_z);
  EXPECT_NEAR(r.z[7], m.z[7], 1e-6 * std::abs(m.z[7]));
  // horizontal-only set: without the -Z file
  fs::remove(d.path / "SET-Z.AT2");
  const motion::GroundMotion h = read_motion_set((d.path / "SET-X.AT2").string());
  EXPECT_TRUE(h.has_y);
  EXPECT_FALSE(h.has_z);
}

TEST(At2Sets, CommaListsAndExplicitRoles) {
  TempDir d;
  const auto m = three_component(40, 0.02);
  write_motion_set(m, (d.path / "R").string());
  const std::string x = (d.path / "R-X.AT2").string(), y = (d.path / "R-Y.AT2").string(),
                    z = (d.path / "R-Z.AT2").string();
  const auto a = read_motion_set(y + "," + x);  // order given: H1 = y file
  EXPECT_NEAR(a.x[5], m.y[5], 1e-6);
  EXPECT_FALSE(a.has_z);
  const auto b = read_motion_set("z=" + z + ",x=" + x);  // one horizontal and a vertical
  EXPECT_FALSE(b.has_y);
  EXPECT_TRUE(b.has_z);
  EXPECT_NEAR(b.z[5], m.z[5], 1e-6);
  SetFiles rel = resolve_set("x=R-X.AT2,y=R-Y.AT2", d.path.string());
  EXPECT_EQ(rel.x, x);
  EXPECT_EQ(rel.name, "R");
  EXPECT_THROW(resolve_set("a.AT2,,b.AT2"), InputError);
  EXPECT_THROW(resolve_set("q=a.AT2,b.AT2"), InputError);
  EXPECT_THROW(resolve_set("x=a.AT2,b.AT2"), InputError);
  EXPECT_THROW(resolve_set("a,b,c,d"), InputError);
}

TEST(At2Sets, UnequalLengthsNeedResampling) {
  TempDir d;
  motion::Component a{std::vector<double>(30, 0.1), 0.01, "1"};
  motion::Component b{std::vector<double>(28, 0.1), 0.01, "2"};
  write_at2((d.path / "a.AT2").string(), a);
  write_at2((d.path / "b.AT2").string(), b);
  const std::string spec = (d.path / "a.AT2").string() + "," + (d.path / "b.AT2").string();
  EXPECT_THROW(read_motion_set(spec), InputError);
  SetReadOptions o;
  o.align.resample = true;
  EXPECT_EQ(read_motion_set(spec, o).npts(), 30u);
}

TEST(At2Info, ReportHasIssueKeysPerSet) {
  TempDir d;
  write_motion_set(three_component(200, 0.01), (d.path / "S").string());
  const std::string j = motion_info_report((d.path / "S-X.AT2").string(), {}, {}, {}, /*json=*/true);
  EXPECT_EQ(j.find('\n'), std::string::npos);
  const Json parsed = Json::parse(j);
  EXPECT_TRUE(parsed.contains("gmroti50_pga_g"));
  ASSERT_EQ(parsed["components"].size(), 3u);
  EXPECT_EQ(parsed["components"][2]["axis"], "z");
  const std::string t = motion_info_report((d.path / "S-X.AT2").string(), {}, {}, {}, false);
  EXPECT_NE(t.find("GMRotI50"), std::string::npos);
}

// --- shared PEER records ---------------------------------------------------------------------

using rigid::test::read_manifest;

TEST(At2Shared, EveryRecordMatchesItsManifest) {
  const fs::path root = fs::path(RIGID_SHARED_DIR) / "waveforms";
  if (!fs::exists(root / "peer" / "manifest.csv")) GTEST_SKIP() << "no shared records at " << root;
  int checked = 0;
  double slowest = 0;
  for (const char* dir : {"peer", "peer_format_variants", "peer_headerless"}) {
    for (const auto& row : read_manifest(root / dir / "manifest.csv")) {
      const fs::path file = root / dir / row.at("file");
      At2ReadOptions o;
      if (std::string(dir) == "peer_headerless") o.dt = std::stod(row.at("dt_s"));
      const auto t0 = std::chrono::steady_clock::now();
      const At2Record r = read_at2(file.string(), o);
      slowest = std::max(slowest, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      EXPECT_EQ(r.values.size(), std::stoul(row.at("npts"))) << file;
      EXPECT_NEAR(r.dt, std::stod(row.at("dt_s")), 1e-9) << file;
      double pga = 0;
      for (double v : r.values) pga = std::max(pga, std::abs(v));
      // the manifest prints 6 significant digits
      EXPECT_NEAR(pga / std::stod(row.at("pga_g")), 1.0, 1e-5) << file;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 68 + 5 + 3);
  std::printf("read %d shared records; slowest read %.3f s\n", checked, slowest);
}

// Real NGA pairs whose horizontals differ by 1-34 samples at equal dt read without options, the
// shorter zero-padded and noted; the pair whose second component is 14 % shorter is refused
// unless resampling is asked for.
TEST(At2Shared, NearlyEqualPairsArePaddedAndAFarShorterOneIsRefused) {
  const fs::path peer = fs::path(RIGID_SHARED_DIR) / "waveforms" / "peer";
  if (!fs::exists(peer / "manifest.csv")) GTEST_SKIP() << "no shared records at " << peer;
  const auto pair = [&](const char* h1, const char* h2) { return (peer / h1).string() + "," + (peer / h2).string(); };
  const char* padded[][2] = {{"IMPVALL/RSN183_IMPVALL.H_H-E08140.AT2", "IMPVALL/RSN183_IMPVALL.H_H-E08230.AT2"},
                             {"IMPVALL/RSN181_IMPVALL.H_H-E06140.AT2", "IMPVALL/RSN181_IMPVALL.H_H-E06230.AT2"},
                             {"STELIAS/RSN1628_STELIAS_059V2090.AT2", "STELIAS/RSN1628_STELIAS_059V2180.AT2"},
                             {"FRIULI/RSN125_FRIULI.A_A-TMZ000.AT2", "FRIULI/RSN125_FRIULI.A_A-TMZ270.AT2"},
                             {"CHALFANT/RSN545_CHALFANT.B_B-BPL070.AT2", "CHALFANT/RSN545_CHALFANT.B_B-BPL160.AT2"}};
  for (const auto& p : padded) {
    const motion::GroundMotion m = read_motion_set(pair(p[0], p[1]));
    const At2Record a = read_at2((peer / p[0]).string()), b = read_at2((peer / p[1]).string());
    EXPECT_EQ(m.npts(), std::max(a.values.size(), b.values.size())) << p[0];
    EXPECT_NE(m.alignment.find("zero-padded"), std::string::npos) << p[0];
  }
  const std::string manjil = pair("MANJIL/RSN1633_MANJIL_ABBAR--L.AT2", "MANJIL/RSN1633_MANJIL_ABBAR--T.AT2");
  EXPECT_THROW(read_motion_set(manjil), InputError);
  SetReadOptions resample;
  resample.align.resample = true;
  EXPECT_NE(read_motion_set(manjil, resample).alignment.find("zero-padded to 2676"), std::string::npos);
}

TEST(At2Fuzz, RegressionInputsParseWithoutCrashing) {
  const fs::path dir = fs::path(RIGID_SOURCE_DIR) / "tests/data/at2/fuzz_regressions";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "no " << dir;
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const double dt : {0.0, 0.01}) {
      At2ReadOptions o;
      o.dt = dt;
      try {
        const At2Record r = parse_at2(bytes, e.path().filename().string(), o);
        EXPECT_GT(r.dt, 0.0);
        for (double v : r.values) EXPECT_TRUE(std::isfinite(v));
      } catch (const InputError&) {
      }
    }
    ++n;
  }
  std::printf("%d fuzz regression inputs\n", n);
}

}  // namespace
}  // namespace rigid::io
