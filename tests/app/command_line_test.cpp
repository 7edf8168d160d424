// The command line's own rules on a CLI11 app made here (src/app/command_line.hpp,
// old_spellings.hpp, nearest_name.hpp): old spellings with a unit change give the exact values of
// the new spelling and one note; misspellings get the nearest name. The whole executable's
// behaviour: tests/app/cli_vocabulary_test.py.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "command_line.hpp"
#include "nearest_name.hpp"
#include "old_spellings.hpp"

namespace rigid::app {
namespace {

struct Parsed {
  std::vector<double> depths_m;
  std::string error;  // usage_problem of a failed parse
  std::string notes;  // what went to stderr
};

// `rigid import --flatten-base M,...` with the old spelling `--flatten-mm MM,...`.
Parsed parse(std::vector<std::string> args) {
  Parsed p;
  CommandLine app{"test"};
  CLI::App* cmd = app.add_subcommand("import", "");
  CLI::Option* depths = cmd->add_option("--flatten-base", p.depths_m, "")->delimiter(',');
  add_old_spelling(*cmd, *depths, {"--flatten-mm", "m", value_divided_by(1000)});
  args.insert(args.begin(), {"rigid", "import"});
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  testing::internal::CaptureStderr();
  try {
    app.parse(int(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    p.error = usage_problem(app, e);
  }
  p.notes = testing::internal::GetCapturedStderr();
  return p;
}

TEST(OldSpelling, MillimetresGiveTheMetresOfTheNewSpellingExactly) {
  const Parsed old = parse({"--flatten-mm", "0,2.5,5,9,12.7"});
  const Parsed now = parse({"--flatten-base", "0,0.0025,0.005,0.009,0.0127"});
  EXPECT_EQ(old.error, "");
  EXPECT_EQ(old.depths_m, now.depths_m);  // bit for bit: the decimal texts are the oracle
  EXPECT_EQ(old.notes,
            "rigid: note: --flatten-mm is now --flatten-base (in m); the old spelling goes in the next release\n");
  EXPECT_EQ(now.notes, "");
}

TEST(OldSpelling, BothSpellingsAreAUsageErrorWithoutTheNote) {
  const Parsed p = parse({"--flatten-base", "0.005", "--flatten-mm", "5"});
  EXPECT_EQ(p.error,
            "--flatten-mm: is the old spelling of --flatten-base; give only --flatten-base (see rigid import --help)");
  EXPECT_EQ(p.notes, "");
}

TEST(OldSpelling, IsNoSuggestion) {
  // one edit from the hidden --flatten-mm, four from --flatten-base: the current name is suggested
  const Parsed p = parse({"--flatten-mn", "5"});
  EXPECT_EQ(p.error, "unknown option '--flatten-mn'; did you mean '--flatten-base'? (see rigid import --help)");
}

TEST(NearestName, EditDistanceCountsSwapsAsOneEdit) {
  EXPECT_EQ(edit_distance("campain", "campaign"), 1u);
  EXPECT_EQ(edit_distance("imoprt", "import"), 1u);
  EXPECT_EQ(edit_distance("", "run"), 3u);
  EXPECT_EQ(edit_distance("plot", "plot"), 0u);
}

TEST(NearestName, SuggestsOnlyWhatIsNearEnough) {
  const std::vector<std::string> commands{"run", "settle", "inspect", "campaign", "plot", "model", "motion"};
  EXPECT_EQ(nearest_name("campain", commands), "campaign");
  EXPECT_EQ(nearest_name("camp", commands), "campaign");  // begun, and nothing else begins so
  EXPECT_EQ(nearest_name("mo", commands), "");            // model and motion both begin so
  EXPECT_EQ(nearest_name("frobnicate", commands), "");
  EXPECT_EQ(nearest_name("rnu", commands), "run");
}

}  // namespace
}  // namespace rigid::app
