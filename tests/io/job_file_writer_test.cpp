// write_job_file against its mirror: every shipped job file read, written and read again gives
// the same settings, objects, variants, records, [lab] and [run] (the reader is the oracle).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "rigid/core/error.hpp"
#include "rigid/io/job_file.hpp"

namespace fs = std::filesystem;
using namespace rigid;

namespace {

void expect_same(const io::JobFile& a, const io::JobFile& b, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(fs::absolute(a.output).lexically_normal(), fs::absolute(b.output).lexically_normal());
  EXPECT_EQ(a.scales_g, b.scales_g);
  EXPECT_EQ(a.drive_scales_g, b.drive_scales_g);
  EXPECT_EQ(a.rotations, b.rotations);
  EXPECT_EQ(a.rotation_angles_deg, b.rotation_angles_deg);
  EXPECT_EQ(a.stop_after, b.stop_after);
  EXPECT_EQ(a.checkpoint_interval_s, b.checkpoint_interval_s);
  EXPECT_EQ(a.grace_s, b.grace_s);
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    EXPECT_EQ(a.objects[i].name, b.objects[i].name);
    EXPECT_EQ(fs::absolute(a.objects[i].scene).lexically_normal(), fs::absolute(b.objects[i].scene).lexically_normal());
    EXPECT_EQ(a.objects[i].state.empty(), b.objects[i].state.empty());
  }
  ASSERT_EQ(a.variants.count(), b.variants.count());
  EXPECT_EQ(a.variants.keys, b.variants.keys);
  for (int v = 0; v < a.variants.count(); ++v) {
    for (std::size_t k = 0; k < a.variants.keys.size(); ++k) {
      EXPECT_EQ(a.variants.variants[std::size_t(v)][k].number, b.variants.variants[std::size_t(v)][k].number);
      EXPECT_EQ(a.variants.variants[std::size_t(v)][k].method, b.variants.variants[std::size_t(v)][k].method);
    }
  }
  ASSERT_EQ(a.records.size(), b.records.size());
  for (std::size_t i = 0; i < a.records.size(); ++i) {
    EXPECT_EQ(a.records[i].name, b.records[i].name);
    EXPECT_EQ(a.records[i].spec, b.records[i].spec);
    EXPECT_EQ(a.records[i].lab, b.records[i].lab);
    EXPECT_EQ(a.records[i].start, b.records[i].start);
    EXPECT_EQ(a.records[i].end, b.records[i].end);
    EXPECT_EQ(a.records[i].earthquake, b.records[i].earthquake);
    EXPECT_EQ(a.records[i].listed_pga_g, b.records[i].listed_pga_g);
    EXPECT_EQ(a.records[i].resample, b.records[i].resample);
  }
  EXPECT_EQ(a.record_list, b.record_list);
  const auto text = [](const std::optional<io::RunText>& t) { return t && t->text ? *t->text : std::string("-"); };
  EXPECT_EQ(text(a.run.model), text(b.run.model));
  EXPECT_EQ(text(a.run.contact), text(b.run.contact));
  EXPECT_EQ(text(a.run.accuracy), text(b.run.accuracy));
  EXPECT_EQ(text(a.run.effects), text(b.run.effects));
  EXPECT_EQ(a.run.duration_s, b.run.duration_s);
  EXPECT_EQ(a.run.free_time_s, b.run.free_time_s);
  EXPECT_EQ(a.run.dt_s, b.run.dt_s);
  EXPECT_EQ(a.run.safety, b.run.safety);
}

}  // namespace

TEST(JobFileWriter, EveryShippedJobReadsBackTheSame) {
  const fs::path out = fs::temp_directory_path() / ("rigid_job_writer_" + std::to_string(::getpid()));
  fs::create_directories(out);
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(RIGID_SOURCE_DIR) / "jobs")) {
    if (entry.path().extension() != ".toml") continue;
    io::JobFile first;
    try {
      first = io::read_job_file(entry.path().string());
    } catch (const InputError&) {
      continue;  // a job over ../shared when it is absent
    }
    const std::string copy = (out / entry.path().filename()).string();
    io::write_job_file(copy, first, "written back");
    const io::JobFile second = io::read_job_file(copy);
    expect_same(first, second, entry.path().filename().string());
    ++checked;
  }
  EXPECT_GE(checked, 3);
  fs::remove_all(out);
}

TEST(JobFileWriter, ARangeOfScalesKeepsItsStatedDecimalsAndItsSums) {
  const fs::path dir = fs::temp_directory_path() / ("rigid_job_range_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "rock.toml") << "# scene\n";
  std::ofstream(dir / "a-X.AT2") << "x\n";
  std::ofstream(dir / "job.toml")
      << "[campaign]\nscales = \"0.1:1.0:0.1\"\nrotations = 3\ncheckpoint_interval_s = 5\n"
         "[[object]]\nscene = \"rock.toml\"\n[[record]]\nmotion = \"a-X.AT2\"\nstart = 2.0\n"
         "name = \"mine\"\nalign = \"resample\"\n[run]\naccuracy = \"fast\"\ndt_s = 1e-4\n";
  const io::JobFile first = io::read_job_file((dir / "job.toml").string());
  ASSERT_EQ(first.scales_g.size(), 10u);
  EXPECT_EQ(first.scales_g[2], 0.3);
  EXPECT_NE(first.drive_scales_g[2], 0.3);  // 0.30000000000000004: the sums the range drives
  io::write_job_file((dir / "copy.toml").string(), first);
  expect_same(first, io::read_job_file((dir / "copy.toml").string()), "range");
  fs::remove_all(dir);
}
