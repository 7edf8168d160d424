// Bad input through the real command line: every case must end with exit status 2 and one line
// on stderr naming the file (and line or facet) and the problem; never a crash or a hang.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

struct Result {
  int status;
  std::string err;
};

Result run_rigid(const std::string& args) {
  const fs::path err_file = fs::temp_directory_path() / ("rigid_bad_input_" + std::to_string(::getpid()) + ".err");
  const std::string cmd =
      "timeout 60 " + std::string(RIGID_BINARY_DIR) + "/bin/rigid " + args + " > /dev/null 2> " + err_file.string();
  const int raw = std::system(cmd.c_str());
  std::ifstream in(err_file);
  std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  fs::remove(err_file);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, err};
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rigid_bad_input_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    write("cube.stl", cube_ascii());
    write("top.stl", cube_ascii(2.0, 1.0));  // a block standing on the cube
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  static std::string cube_ascii(double top = 1.0, double bottom = 0.0) {
    const double v[8][3] = {{0, 0, bottom}, {1, 0, bottom}, {1, 1, bottom}, {0, 1, bottom},
                            {0, 0, top},    {1, 0, top},    {1, 1, top},    {0, 1, top}};
    const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                          {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    std::string s = "solid cube\n";
    for (const auto& t : f) {
      s += " facet normal 0 0 0\n  outer loop\n";
      for (int k : t) {
        s += "   vertex " + std::to_string(v[k][0]) + " " + std::to_string(v[k][1]) + " " + std::to_string(v[k][2]) +
             "\n";
      }
      s += "  endloop\n endfacet\n";
    }
    return s + "endsolid cube\n";
  }
  // expects exit 2 and a single stderr line containing every fragment
  void expect_error(const std::string& args, std::initializer_list<std::string> fragments) {
    const Result r = run_rigid(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("rigid: error: ", 0), 0u) << r.err;
    for (const auto& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << "missing '" << f << "' in " << r.err;
  }
  fs::path dir_;
};

TEST_F(BadInput, MissingSceneFile) {
  expect_error("run " + (dir_ / "none.model").string(), {"none.model", "not found"});
}

TEST_F(BadInput, MissingStlNamesModelLine) {
  const auto m = write("a.model", "block cube.stl\n1 0 0 0\nblock missing.stl\n0 0 0 0\n");
  expect_error("run " + m, {"a.model:3", "missing.stl"});
}

TEST_F(BadInput, MalformedModelNumber) {
  const auto m = write("a.model", "block cube.stl\n1 0 0 0\nblock top.stl\n0 x 0 0\n");
  expect_error("run " + m, {"a.model:4", "'x'"});
}

TEST_F(BadInput, NanVelocityInModel) {
  const auto m = write("a.model", "block cube.stl\n1 0 0 0\nblock top.stl\n0 nan 0 0\n");
  expect_error("run " + m, {"a.model:4"});
}

TEST_F(BadInput, NonPositiveDensity) {
  const auto m = write("a.model", "block cube.stl\n1 0 0 0\nblock top.stl\n0 0 0 0\n-2600 1e8 1e8 0.6 2\n");
  expect_error("run " + m, {"a.model:5", "density"});
}

TEST_F(BadInput, EmptyStl) {
  write("empty.stl", "");
  const auto m = write("a.model", "block cube.stl\n1 0 0 0\nblock empty.stl\n0 0 0 0\n");
  expect_error("run " + m, {"empty.stl"});
}

TEST_F(BadInput, TruncatedBinaryStl) {
  std::string bin(84 + 25, '\0');
  bin[80] = 2;  // claims two facets, holds half of one
  write("trunc.stl", bin);
  const auto m = write("a.model", "block cube.stl\n1 0 0 0\nblock trunc.stl\n0 0 0 0\n");
  expect_error("run " + m, {"trunc.stl"});
}

TEST_F(BadInput, OpenMeshNamesFacet) {
  std::string s = cube_ascii();
  const auto cut = s.find(" facet", s.find("endfacet"));  // drop the second facet
  s.erase(cut, s.find("endfacet", cut) + 9 - cut);
  write("open.stl", s);
  const auto m = write("a.model", "block cube.stl\n1 0 0 0\nblock open.stl\n0 0 0 0\n");
  expect_error("run " + m, {"open.stl", "facet"});
}

TEST_F(BadInput, UnknownTomlKey) {
  const auto t =
      write("a.toml", "model_text = \"block cube.stl 1 0 0 0 block top.stl 0 0 0 0\"\n[physics]\nfrction = 0.5\n");
  expect_error("run " + t, {"a.toml:3", "frction"});
}

TEST_F(BadInput, NegativeTimeStep) {
  const auto m = write("a.model", "block cube.stl\n1 0 0 0\nblock top.stl\n0 0 0 0\n");
  expect_error("run " + m + " --dt -1", {"--dt"});
}

TEST_F(BadInput, MalformedAt2) {
  const auto m = write("a.model", "block cube.stl\n1 0 0 0\nblock top.stl\n0 0 0 0\n");
  const auto a = write("rec-X.AT2", "PEER\nx\nACCELERATION IN G\nNPTS=    3, DT=   0.01 SEC\n0.1 zz 0.3\n");
  expect_error("run " + m + " --motion " + a, {"rec-X.AT2:5"});
}

// Command-line usage errors of every kind CLI11 reports: the same one-line format, exit 2.
class UsageError : public ::testing::TestWithParam<const char*> {};

TEST_P(UsageError, ExitsTwoWithOneLine) {
  const Result r = run_rigid(GetParam());
  EXPECT_EQ(r.status, 2) << GetParam() << ": " << r.err;
  EXPECT_EQ(r.err.rfind("rigid: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

INSTANTIATE_TEST_SUITE_P(Kinds, UsageError,
                         ::testing::Values("frobnicate",                       // unknown subcommand
                                           "run",                              // missing positional
                                           "run a.model --no-such-option",     // unknown option
                                           "bench --repeat x",                 // not a number
                                           "bench --repeat 0",                 // out of range
                                           "run a.model --motion",             // option without value
                                           "motion",                           // subcommand required
                                           "campaign a.toml b.toml c.toml"));  // extra positionals

TEST(BareCommand, PrintsHelpAndSucceeds) {
  const std::string cmd = std::string(RIGID_BINARY_DIR) + "/bin/rigid > /dev/null 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 0);
}

}  // namespace
