// Record lists (table TSV, .ABF) and the comparison of the study's tabulated GMRotI50 values with
// the values computed from the shared PEER files (docs/ground-motions.md, "The study's table against the shared
// records").
#include "rigid/io/record_list.hpp"

#include <gtest/gtest.h>

#include "support/manifest.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "rigid/core/error.hpp"

namespace fs = std::filesystem;

namespace rigid::io {
namespace {

const fs::path kShared = fs::path(RIGID_SHARED_DIR);

TEST(RecordTable, ParsesTheStudyTable) {
  const fs::path p = kShared / "docs" / "table3_6_records.tsv";
  if (!fs::exists(p)) GTEST_SKIP() << "no shared table at " << p;
  const RecordList l = read_record_list(p.string());
  ASSERT_EQ(l.records.size(), 154u);
  EXPECT_TRUE(l.pga_scales_g.empty());
  const RecordEntry& first = l.records.front();
  EXPECT_EQ(first.earthquake, "St Elias, Alaska");
  EXPECT_EQ(first.year, 1979);
  EXPECT_EQ(first.file, "059v2-X.AT2");
  EXPECT_DOUBLE_EQ(first.start, 13.7903);
  EXPECT_DOUBLE_EQ(first.gmroti_pgv_cm_s, 34.2635);
  int empty_quake = 0;
  for (const auto& e : l.records) {
    empty_quake += e.earthquake.empty();
    // the last column is PGV / (PGA g) with g = 980.665 cm/s^2 (physics.md §1), 5 digits
    EXPECT_NEAR(e.gmroti_pgv_cm_s / (e.gmroti_pga_g * 980.665) / e.pgv_pga_s, 1.0, 2e-4) << e.file;
  }
  EXPECT_EQ(empty_quake, 1);  // the TCU128 row has no earthquake name
}

TEST(RecordTable, MalformedLinesNameTheLine) {
  EXPECT_THROW(parse_record_table("A\t1999\t7\tx.AT2\t1\n", "t.tsv"), InputError);
  try {
    parse_record_table("# c\nA\t1999\t7\tx.AT2\t1\t2\t0.1\t10\t0.1\nB\t1999\t7\ty.AT2\tabc\t2\n", "t.tsv");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.file(), "t.tsv");
  }
  EXPECT_THROW(parse_record_table("A\t1999\t7\tx.AT2\t5\t2\n", "t.tsv"), InputError);
  // header line and explicit mapping of PEER files in the file column
  const RecordList l = parse_record_table(
      "earthquake\tyear\tM\tfile\tstart\tend\tpga\tpgv\tratio\n"
      "Chi-Chi\t1999\t7.62\tx=RSN1_E.AT2,y=RSN1_N.AT2,z=RSN1_V.AT2\t0\t10\t\t\t\n",
      "t.tsv");
  ASSERT_EQ(l.records.size(), 1u);
  EXPECT_EQ(l.records[0].file, "x=RSN1_E.AT2,y=RSN1_N.AT2,z=RSN1_V.AT2");
  EXPECT_TRUE(std::isnan(l.records[0].gmroti_pga_g));
  EXPECT_EQ(resolve_set(l.records[0].file).z, "RSN1_V.AT2");
}

TEST(RecordTable, OptionalAlignColumn) {
  const RecordList l = parse_record_table(
      "A\t1999\t7\tx.AT2\t0\t10\t\t\t\tresample\n"
      "B\t1999\t7\ty.AT2\t0\t10\t\t\t\tauto\n"
      "C\t1999\t7\tz.AT2\t0\t10\n",
      "t.tsv");
  ASSERT_EQ(l.records.size(), 3u);
  EXPECT_TRUE(l.records[0].resample);
  EXPECT_FALSE(l.records[1].resample);
  EXPECT_FALSE(l.records[2].resample);
  try {
    parse_record_table("A\t1999\t7\tx.AT2\t0\t10\t\t\t\tstretch\n", "t.tsv");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 1);
    EXPECT_NE(std::string(e.what()).find("align"), std::string::npos);
  }
  EXPECT_THROW(parse_record_table("A\t1999\t7\tx.AT2\t0\t10\t\t\t\t\textra\n", "t.tsv"), InputError);
}

TEST(RecordAbf, ParsesScalesDeprecatedZeroAndRecords) {
  const RecordList l =
      parse_abf("0.1 0.2, 0.3\r\n0\r\nCHY028-X.AT2\r\n# comment\r\nA.AT2,B.AT2 1.5 12.25\r\n", "b.abf");
  EXPECT_EQ(l.pga_scales_g, (std::vector<double>{0.1, 0.2, 0.3}));
  ASSERT_EQ(l.records.size(), 2u);
  EXPECT_EQ(l.records[0].file, "CHY028-X.AT2");
  EXPECT_TRUE(std::isinf(l.records[0].end));
  EXPECT_EQ(l.records[1].file, "A.AT2,B.AT2");
  EXPECT_DOUBLE_EQ(l.records[1].start, 1.5);
  EXPECT_DOUBLE_EQ(l.records[1].end, 12.25);
  EXPECT_EQ(l.records[1].line, 5);
  EXPECT_THROW(parse_abf("0.1\n1\nX.AT2\n", "b.abf"), InputError);     // line 2 must be 0
  EXPECT_THROW(parse_abf("0.1 -2\n0\nX.AT2\n", "b.abf"), InputError);  // negative scale
  EXPECT_THROW(parse_abf("0.1\n0\nX.AT2 1\n", "b.abf"), InputError);   // start without end
  EXPECT_THROW(parse_abf("", "b.abf"), InputError);
}

// --- the study's table vs the shared records --------------------------------------------------

struct SharedSet {
  std::string table_name;
  std::map<std::string, std::string> files;  // H1, H2, V -> path
};

std::map<std::string, SharedSet> shared_sets(const fs::path& dir) {
  std::map<std::string, SharedSet> sets;
  for (auto& row : rigid::test::read_manifest(dir / "manifest.csv")) {
    if (row["table3_6_name"].empty()) continue;
    SharedSet& s = sets[row["table3_6_name"]];
    s.table_name = row["table3_6_name"];
    s.files[row["component"]] = (dir / row["file"]).string();
  }
  return sets;
}

TEST(TableComparison, ComputedVsTabulatedGmroti) {
  const fs::path peer = kShared / "waveforms" / "peer";
  const fs::path table = kShared / "docs" / "table3_6_records.tsv";
  if (!fs::exists(peer / "manifest.csv") || !fs::exists(table))
    GTEST_SKIP() << "no shared records or table under " << kShared;
  std::map<std::string, RecordEntry> rows;
  for (const auto& e : read_record_list(table.string()).records) rows[e.file] = e;

  // outliers explained in docs/ground-motions.md, each with the evidence checked below
  const std::set<std::string> explained = {"059v2-X.AT2", "CHY074-X.AT2", "H_E06-X.AT2", "DZC-X.AT2",
                                           "GBZ-X.AT2",   "H_EMO-X.AT2",  "CHY104-X.AT2"};
  SetReadOptions o;
  o.align.resample = true;  // some horizontals differ by a few samples: zero-pad (same dt)
  int n = 0, pga_ok = 0, pgv_ok = 0;
  std::printf("%-14s %8s %8s %7s | %8s %8s %7s | %8s %8s | %8s %8s\n", "record", "tab PGA", "GMRotI", "diff%",
              "tab PGV", "GMRotI", "diff%", "GMRotD", "GMRotD v", "win PGA", "win PGV");
  for (const auto& [name, set] : shared_sets(peer)) {
    ASSERT_TRUE(rows.count(name)) << name;
    ASSERT_TRUE(set.files.count("H1") && set.files.count("H2")) << name;
    const RecordCheck c = check_record(rows[name], o, set.files.at("H1") + "," + set.files.at("H2"));
    std::printf("%-14s %8.4f %8.4f %+7.1f | %8.2f %8.2f %+7.1f | %8.4f %8.2f | %8.4f %8.2f%s\n", name.c_str(),
                c.entry.gmroti_pga_g, c.gmroti_pga_g, 100 * c.pga_rel_diff, c.entry.gmroti_pgv_cm_s, c.gmroti_pgv_cm_s,
                100 * c.pgv_rel_diff, c.gmrotd_pga_g, c.gmrotd_pgv_cm_s, c.window_gmroti_pga_g,
                c.window_gmroti_pgv_cm_s, explained.count(name) ? "  (explained outlier)" : "");
    ++n;
    const bool a = std::abs(c.pga_rel_diff) <= 0.03, v = std::abs(c.pgv_rel_diff) <= 0.10;
    pga_ok += a;
    pgv_ok += v;
    if (!explained.count(name)) {
      EXPECT_TRUE(a) << name << " PGA " << c.pga_rel_diff;
      EXPECT_TRUE(v) << name << " PGV " << c.pgv_rel_diff;
    }
    // the evidence quoted in docs/ground-motions.md
    if (name == "059v2-X.AT2") {
      EXPECT_LT(c.entry.gmroti_pga_g, c.rotd0_pga_g);  // below any
    }
    if (name == "CHY074-X.AT2") {
      EXPECT_GT(c.entry.gmroti_pga_g, c.rotd100_pga_g);  // above any
    }
    if (name == "H_E06-X.AT2") {
      EXPECT_LT(c.entry.gmroti_pga_g, c.gm_min_pga_g);
    }
    if (name == "CHY104-X.AT2") {
      EXPECT_GT(c.entry.gmroti_pga_g, c.gm_max_pga_g);  // above GM at every angle
    }
    if (name == "H_EMO-X.AT2") {
      EXPECT_NEAR(c.gmrotd_pga_g / c.entry.gmroti_pga_g, 1.0, 0.005);
    }
    if (name == "GBZ-X.AT2") {
      EXPECT_LT(std::abs(c.gmrotd_pga_g / c.entry.gmroti_pga_g - 1), 0.04);
    }
  }
  std::printf("%d records: %d PGAs within 3%%, %d PGVs within 10%%\n", n, pga_ok, pgv_ok);
  EXPECT_EQ(n, 16);
  EXPECT_GE(pga_ok * 2, n);      // most PGAs within 3%
  EXPECT_GE(pgv_ok * 4, n * 3);  // at least three quarters of PGVs within 10%
}

}  // namespace
}  // namespace rigid::io
