// The journal as the campaign's durability layer (src/campaign/checkpointer.cpp): a checkpoint is a
// flush and an fsync of what was appended, through a duplicated descriptor so the fsync needs no
// lock; a reset after a cube rewrite is written beside the journal in use (start_reset, while
// results are still appended to the old one), then completed with what arrived meanwhile and
// renamed (finish_reset). Until the rename the old journal, a superset, stays whole.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "rigid/campaign/journal.hpp"

namespace rigid::campaign {
namespace {

namespace fs = std::filesystem;

const std::string kKey(64, 'a');

std::string temp_path(const std::string& name) {
  return (fs::temp_directory_path() / ("rigid_journal_" + std::to_string(::getpid()) + "_" + name)).string();
}

TaskResult result(long task) {
  TaskResult r;
  r.task = task;
  r.outcome = 1;
  r.max_tilt_deg = 0.5 * double(task);
  return r;
}

std::vector<long> tasks_in(const std::string& path) {
  std::vector<long> out;
  for (const TaskResult& r : read_journal(path, kKey, 100).results) out.push_back(r.task);
  return out;
}

TEST(Journal, SyncedAppendsAreReadBackAndCounted) {
  const std::string path = temp_path("sync");
  Journal j(path, kKey, {result(1)});
  const std::uint64_t empty = j.bytes() - Journal::record_bytes();
  j.append(result(2));
  j.append(result(3));
  j.sync(j.flush_and_duplicate());
  EXPECT_EQ(j.bytes(), empty + 3 * Journal::record_bytes());
  EXPECT_EQ(fs::file_size(path), j.bytes());
  EXPECT_EQ(tasks_in(path), (std::vector<long>{1, 2, 3}));
  fs::remove(path);
}

TEST(Journal, ATwoStepResetKeepsTheOldJournalUntilTheRenameAndAddsWhatArrivedMeanwhile) {
  const std::string path = temp_path("reset");
  Journal j(path, kKey);
  for (long t : {1, 2, 3}) j.append(result(t));
  j.flush();
  // the cube now holds 1 and 2; 3 arrived after its snapshot
  Journal::File fresh = j.start_reset({result(3)});
  j.append(result(4));  // arrives while the new journal is written
  j.flush();
  EXPECT_EQ(tasks_in(path), (std::vector<long>{1, 2, 3, 4})) << "the old journal stays whole";
  const TaskResult late = result(4);
  j.finish_reset(std::move(fresh), &late, 1);
  EXPECT_EQ(tasks_in(path), (std::vector<long>{3, 4}));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  j.append(result(5));  // appends go on to the new file
  j.flush();
  EXPECT_EQ(tasks_in(path), (std::vector<long>{3, 4, 5}));
  EXPECT_EQ(fs::file_size(path), j.bytes());
  fs::remove(path);
}

}  // namespace
}  // namespace rigid::campaign
