// The CSV writer and reader (io/csv.hpp) and the lab test list read through them
// (io/lab_tests.hpp): names that need quoting survive a round trip, byte-order marks and unknown
// outcomes are read, what cannot be read names its line.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "rigid/core/error.hpp"
#include "rigid/io/csv.hpp"
#include "rigid/io/lab_tests.hpp"

namespace rigid::io {
namespace {

const std::vector<std::string> kNames = {
    "plain", "a, comma", "\"quoted\"", "a \"b\", c", "two\nlines", "crlf\r\nend", std::string(700, 'x') + ",\"",
    "",      " padded "};

long error_line(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.line();
  }
  return -1;
}

TEST(Csv, FieldQuotesOnlyWhatNeedsIt) {
  EXPECT_EQ(csv_field("plain"), "plain");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("a\nb"), "\"a\nb\"");
  EXPECT_EQ(csv_number(0.1), "0.1");
  EXPECT_EQ(csv_number(std::nan("")), "");
}

TEST(Csv, WriterRoundTripsEveryName) {
  for (const char* end : {"\n", "\r\n"}) {
    std::ostringstream out;
    CsvWriter csv(out, end);
    csv.row({"name", "n", "x"});
    long n = 0;
    for (const std::string& name : kNames) csv.field(name).field(n++).fixed(1e300, 2).end_row();
    const std::vector<CsvRow> rows = parse_csv(out.str(), "t.csv");
    ASSERT_EQ(rows.size(), kNames.size() + 1);
    for (std::size_t k = 0; k < kNames.size(); ++k) {
      ASSERT_EQ(rows[k + 1].fields.size(), 3u) << k;
      EXPECT_EQ(rows[k + 1].fields[0], kNames[k]) << k;
      EXPECT_EQ(rows[k + 1].fields[1], std::to_string(k));
      EXPECT_EQ(rows[k + 1].fields[2].size(), 301u + 3u);  // 1e300 with two decimals
    }
  }
}

TEST(Csv, ReaderNamesTheLineOfAnOpenQuote) {
  EXPECT_EQ(error_line([] { parse_csv("a,b\n1,\"x\n2,3\n", "t.csv"); }), 2);
  EXPECT_EQ(error_line([] { parse_csv("a,b\n1,\"x\"y\n", "t.csv"); }), 2);
}

TEST(LabTests, QuotedNamesRoundTripThroughTheWriter) {
  std::ostringstream out;
  CsvWriter csv(out, "\r\n");
  out << "\xEF\xBB\xBF";  // Excel's byte-order mark
  csv.row({"test_no", "record", "pgv_over_pga_s", "pga_g", "file", "overturned"});
  for (std::size_t k = 0; k < kNames.size(); ++k) {
    if (kNames[k].empty()) continue;  // an empty record name means the file's stem
    csv.field(long(k + 1)).field(kNames[k]).field(0.1).field(0.2).field("m.txt").field(k % 2 ? "1" : "0").end_row();
  }
  const LabTestList list = parse_lab_tests(out.str(), "t.csv", "/d");
  std::size_t t = 0;
  for (const std::string& name : kNames) {
    if (name.empty()) continue;
    ASSERT_LT(t, list.tests.size());
    EXPECT_EQ(list.tests[t].record, name);
    EXPECT_EQ(list.tests[t].file, "/d/m.txt");
    ++t;
  }
  EXPECT_EQ(t, list.tests.size());
  EXPECT_TRUE(list.has_outcomes);
  EXPECT_NO_THROW(require_outcomes(list, "fits the outcomes"));
}

TEST(LabTests, UnknownOutcomesAreReadAndRefusedWhereRequired) {
  const std::string text = "# a hold-out list\ntest_no,file,overturned\n1,a.txt,1\n2,b.txt,?\n3,c.txt,\n4,d.txt,0\n";
  const LabTestList list = parse_lab_tests(text, "t.csv", "");
  ASSERT_EQ(list.tests.size(), 4u);
  EXPECT_TRUE(list.outcome_column);
  EXPECT_FALSE(list.has_outcomes);
  EXPECT_FALSE(list.tests[1].overturned);
  EXPECT_FALSE(list.tests[2].overturned);
  EXPECT_EQ(*list.tests[3].overturned, 0);
  EXPECT_EQ(error_line([&] { require_outcomes(list, "calibration fits the observed outcomes"); }), 4);
  const LabTestList none = parse_lab_tests("\ntest_no,file\n1,a.txt\n", "t.csv", "");
  EXPECT_EQ(error_line([&] { require_outcomes(none, "fits the outcomes"); }), 2);
  EXPECT_EQ(error_line([] { parse_lab_tests("test_no,file,overturned\n1,a.txt,yes\n", "t.csv", ""); }), 2);
}

}  // namespace
}  // namespace rigid::io
