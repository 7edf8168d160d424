// A failed cell keeps its error text on its way to the cube: run_task stores the message of an
// exception raised inside the case, the journal (format RIGIDJ04) keeps it and the count of
// unconverged contact solves, and journals of the previous formats RIGIDJ03 (no count) and
// RIGIDJ02 (no message either), built here byte by byte from their documented layouts, are still
// read.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "rigid/campaign/journal.hpp"
#include "rigid/campaign/task.hpp"
#include "rigid/library/builders.hpp"

namespace rigid::campaign {
namespace {

namespace fs = std::filesystem;

std::string temp_path(const std::string& name) {
  return (fs::temp_directory_path() / ("rigid_failure_message_" + std::to_string(::getpid()) + "_" + name)).string();
}

// A job of one object and one record; cells are scaled to 0.3 g.
job::Job one_cell_job() {
  job::Job job;
  job::JobObject block;
  block.name = "block";
  job.objects.push_back(block);
  job::JobRecord r;
  r.name = "quiet";
  job.records.push_back(r);
  job.scales_g = {0.3};
  job.rotations = 1;
  return job;
}

TEST(FailureMessage, AnExceptionInACaseIsStoredWithTheResult) {
  motion::GroundMotion quiet;  // no acceleration: it cannot be scaled to 0.3 g
  quiet.dt = 0.01;
  quiet.x.assign(100, 0.0);
  const scenario::Model model(scenario::Engine::dem3d, {library::block_on_pedestal(0.2, 0.5, 0.4)}, {quiet},
                              scenario::RunSettings{});
  const TaskResult r = run_task(one_cell_job(), model, 0);
  EXPECT_EQ(r.outcome, static_cast<std::int32_t>(scenario::CellOutcome::failed));
  EXPECT_EQ(r.reason, static_cast<std::int32_t>(scenario::FailureReason::exception));
  EXPECT_NE(message_of(r).find("horizontal acceleration is zero"), std::string::npos) << message_of(r);
}

TEST(FailureMessage, LongMessagesAreCutToFit) {
  TaskResult r;
  set_message(r, std::string(1000, 'x'));
  EXPECT_EQ(message_of(r), std::string(kTaskMessageBytes - 1, 'x'));
  set_message(r, "short");
  EXPECT_EQ(message_of(r), "short");
}

TEST(FailureMessage, TheJournalKeepsMessages) {
  const std::string path = temp_path("v3.journal");
  const std::string key(64, 'a');
  TaskResult carried, appended;
  carried.task = 1;
  set_message(carried, "carried: bad, \"quoted\" text");
  appended.task = 2;
  set_message(appended, "appended");
  {
    Journal j(path, key, {carried});
    j.append(appended);
    j.flush();
  }
  const JournalContents c = read_journal(path, key, 10);
  ASSERT_EQ(c.results.size(), 2u);
  EXPECT_TRUE(c.problems.empty());
  EXPECT_EQ(message_of(c.results[0]), "carried: bad, \"quoted\" text");
  EXPECT_EQ(message_of(c.results[1]), "appended");
  fs::remove(path);
}

std::uint32_t crc(const unsigned char* p, std::size_t n) {
  return std::uint32_t(crc32(crc32(0L, Z_NULL, 0), p, uInt(n)));
}

// A journal of an older format, byte by byte as that format lays it out: magic, 64-byte key,
// CRC-32 of both; records of the first `result_bytes` bytes of a result, an 8-byte fingerprint
// (CRC-32 of each half of the key) and a CRC-32 of both. Tasks 3 and 4, overturned at 1.5 task s.
std::string write_old_journal(const std::string& magic, std::size_t result_bytes, const std::string& key,
                              const std::string& name) {
  const std::string head = magic + key;
  std::vector<unsigned char> bytes(head.begin(), head.end());
  auto append_crc = [&bytes](std::size_t from) {
    const std::uint32_t c = crc(bytes.data() + from, bytes.size() - from);
    const auto* p = reinterpret_cast<const unsigned char*>(&c);
    bytes.insert(bytes.end(), p, p + 4);
  };
  append_crc(0);
  const auto* k = reinterpret_cast<const unsigned char*>(key.data());
  const std::uint64_t print = (std::uint64_t{crc(k, 32)} << 32) | crc(k + 32, 32);
  for (std::int64_t task : {3, 4}) {
    TaskResult r;
    r.task = task;
    r.outcome = static_cast<std::int32_t>(scenario::CellOutcome::overturned);
    r.failure_time_s = 1.5 * double(task);
    set_message(r, "message of task " + std::to_string(task));
    r.unconverged_steps = 7;  // beyond every older format's records: must not be read back
    const std::size_t start = bytes.size();
    const auto* p = reinterpret_cast<const unsigned char*>(&r);
    bytes.insert(bytes.end(), p, p + result_bytes);
    const auto* f = reinterpret_cast<const unsigned char*>(&print);
    bytes.insert(bytes.end(), f, f + 8);
    append_crc(start);
  }
  const std::string path = temp_path(name);
  std::FILE* out = std::fopen(path.c_str(), "wb");
  if (!out) return path;
  std::fwrite(bytes.data(), 1, bytes.size(), out);
  std::fclose(out);
  return path;
}

TEST(FailureMessage, APreviousFormatJournalIsStillRead) {
  // RIGIDJ02: the 48 bytes of a result before its message
  const std::string key(64, 'b');
  const std::string path = write_old_journal("RIGIDJ02", 48, key, "v2.journal");
  const JournalContents c = read_journal(path, key, 10);
  ASSERT_EQ(c.results.size(), 2u);
  EXPECT_TRUE(c.problems.empty());
  EXPECT_FALSE(c.foreign);
  EXPECT_EQ(c.results[0].task, 3);
  EXPECT_EQ(c.results[1].failure_time_s, 6.0);
  EXPECT_EQ(message_of(c.results[1]), "");
  EXPECT_EQ(c.results[1].unconverged_steps, -1);
  fs::remove(path);
}

TEST(FailureMessage, AJournalWithoutTheSolverCountIsReadAsNotRecorded) {
  // RIGIDJ03: the 48 bytes and the 232-byte message, no count of unconverged contact solves
  const std::string key(64, 'c');
  const std::string path = write_old_journal("RIGIDJ03", 48 + kTaskMessageBytes, key, "v3.journal");
  const JournalContents c = read_journal(path, key, 10);
  ASSERT_EQ(c.results.size(), 2u);
  EXPECT_TRUE(c.problems.empty());
  EXPECT_FALSE(c.foreign);
  EXPECT_EQ(c.results[1].task, 4);
  EXPECT_EQ(c.results[1].failure_time_s, 6.0);
  EXPECT_EQ(message_of(c.results[1]), "message of task 4");
  EXPECT_EQ(c.results[0].unconverged_steps, -1) << "a count the format lacks is not recorded, not 0";
  fs::remove(path);
}

TEST(FailureMessage, TheSolverCountSurvivesTheJournal) {
  const std::string path = temp_path("count.journal");
  const std::string key(64, 'd');
  {
    Journal j(path, key);
    TaskResult r;
    r.task = 2;
    r.unconverged_steps = 12;
    j.append(r);
    j.flush();
  }
  const JournalContents c = read_journal(path, key, 10);
  ASSERT_EQ(c.results.size(), 1u);
  EXPECT_EQ(c.results[0].unconverged_steps, 12);
  fs::remove(path);
}

}  // namespace
}  // namespace rigid::campaign
