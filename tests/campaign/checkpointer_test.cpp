// The campaign's checkpoints without MPI (campaign/checkpointer, campaign/checkpoint_writer):
// results fed to a Checkpointer are journalled, compacted into the cube from the shadow plan by
// the writer thread, and read back by the campaign's own resume (campaign::restore). The oracle
// throughout is what was fed in: every result handed over must come back unchanged (from the
// journal byte for byte, whatever fields TaskResult has; from the cube value by value), and a
// failed write must leave the previous checkpoint readable with nothing computed lost.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "rigid/campaign/checkpoint_writer.hpp"
#include "rigid/campaign/checkpointer.hpp"
#include "rigid/campaign/journal.hpp"
#include "rigid/campaign/session.hpp"
#include "rigid/io/cube.hpp"
#include "rigid/library/builders.hpp"

namespace rigid::campaign {
namespace {

namespace fs = std::filesystem;

constexpr auto kSurvived = static_cast<std::int32_t>(scenario::CellOutcome::survived);
constexpr auto kOverturned = static_cast<std::int32_t>(scenario::CellOutcome::overturned);
constexpr auto kFailed = static_cast<std::int32_t>(scenario::CellOutcome::failed);
constexpr auto kInferred = static_cast<std::int8_t>(scenario::CellOutcome::inferred);
constexpr auto kNotRun = static_cast<std::int8_t>(scenario::CellOutcome::not_run);

// A fresh directory per test, removed after it.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(fs::temp_directory_path() / ("rigid_checkpointer_" + std::to_string(::getpid()) + "_" + name)) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

// A campaign of one block, one record, `scales` scales and `rotations` rotations, written to
// `output`: what make_cube and restore need, built in memory.
struct Campaign {
  Campaign(const std::string& output, int scales, int rotations, int stop_after)
      : model(scenario::Engine::dem3d, {library::block_on_pedestal(0.2, 0.5, 0.4)}, {quiet_motion()},
              scenario::RunSettings{}) {
    job.output = output;
    job.hash = "test-job";
    job::JobObject block;
    block.name = "block";
    job.objects.push_back(block);
    job::JobRecord r;
    r.name = "quiet";
    job.records.push_back(r);
    for (int s = 0; s < scales; ++s) job.scales_g.push_back(0.1 * (s + 1));
    job.rotations = rotations;
    job.stop_after = stop_after;
    io::RecordMeta meta;
    meta.name = "quiet";
    records.push_back(meta);
    inputs.job = {{"(settings)", std::string(64, '1')}};
    inputs.objects = {{}};
    inputs.records = {{}};
    inputs.combined = std::string(64, 'c');
  }
  static motion::GroundMotion quiet_motion() {
    motion::GroundMotion m;
    m.dt = 0.01;
    m.x.assign(100, 0.0);
    return m;
  }
  Plan plan() const { return Plan(1, 1, int(job.scales_g.size()), job.rotations, job.stop_after, {1.0}); }
  CampaignContext context() const { return {job, model, records, inputs}; }
  Checkpointer::CubeOf cube_of() const {
    return [this](const Plan& p) { return make_cube(context(), p); };
  }
  // Cube and journal read back as a resume reads them.
  Plan resumed() const {
    Plan p = plan();
    restore(job.output, job, inputs, p, false, OutputRemedies{});
    return p;
  }
  long size() const { return long(job.scales_g.size()) * job.rotations; }

  job::Job job;
  scenario::Model model;
  std::vector<io::RecordMeta> records;
  Inputs inputs;
};

// A result whose every value is its own (so a mix-up between tasks shows).
TaskResult result(long task, std::int32_t outcome = kSurvived) {
  TaskResult r;
  std::memset(static_cast<void*>(&r), 0, sizeof r);  // padding too: results are compared byte for byte
  r.task = task;
  r.outcome = outcome;
  r.wall_s = 0.001 * double(task + 1);
  if (outcome == kFailed) {
    r.reason = static_cast<std::int32_t>(scenario::FailureReason::exception);
    r.failure_time_s = std::nan("");
    r.max_tilt_deg = std::nan("");
    r.max_slip_m = std::nan("");
    set_message(r, "task " + std::to_string(task) + " threw");
  } else {
    r.failure_time_s = outcome == kOverturned ? 1.0 + 0.25 * double(task) : std::nan("");
    r.max_tilt_deg = 0.5 + double(task);
    r.max_slip_m = 1e-3 * double(task);
  }
  return r;
}

bool same_bytes(const TaskResult& a, const TaskResult& b) { return std::memcmp(&a, &b, sizeof(TaskResult)) == 0; }

// Equal doubles, NaN equal to NaN.
bool same_value(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

// Every result of `fed` is in the plan's results as fed.
void expect_in_plan(const Plan& plan, const std::vector<TaskResult>& fed) {
  for (const TaskResult& r : fed) {
    const TaskResult& got = plan.results()[std::size_t(r.task)];
    EXPECT_TRUE(same_bytes(got, r)) << "task " << r.task << " came back changed";
  }
}

// The cell of each fed result in the cube holds its values; every other cell is not run.
void expect_cube_holds(const io::Cube& cube, const std::vector<TaskResult>& fed, long cells) {
  ASSERT_EQ(cube.objects.size(), 1u);
  const io::ObjectCube& oc = cube.objects[0];
  ASSERT_EQ(long(oc.outcome.size()), cells);
  std::map<long, TaskResult> by_task;
  for (const TaskResult& r : fed) by_task[r.task] = r;
  for (long t = 0; t < cells; ++t) {
    const auto it = by_task.find(t);
    if (it == by_task.end()) {
      EXPECT_EQ(oc.outcome[t], kNotRun) << "cell " << t;
      continue;
    }
    const TaskResult& r = it->second;
    EXPECT_EQ(oc.outcome[t], r.outcome) << "cell " << t;
    EXPECT_TRUE(same_value(oc.failure_time_s[t], r.failure_time_s)) << "cell " << t;
    EXPECT_TRUE(same_value(oc.max_tilt_deg[t], r.max_tilt_deg)) << "cell " << t;
    EXPECT_TRUE(same_value(oc.max_slip_m[t], r.max_slip_m)) << "cell " << t;
    EXPECT_EQ(oc.wall_s[t], r.wall_s) << "cell " << t;
    EXPECT_EQ(oc.failure_reason[t], r.reason) << "cell " << t;
    EXPECT_EQ(oc.failure_message[t], message_of(r)) << "cell " << t;
  }
}

// Copies the file's bytes as they are at one instant (nothing when it does not exist).
std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<TaskResult> journal_of(const Campaign& c) {
  return read_journal(c.job.output + ".journal", c.inputs.combined, c.size()).results;
}

std::vector<TaskResult> results(long from, long to) {
  std::vector<TaskResult> out;
  for (long t = from; t < to; ++t) out.push_back(result(t, t % 5 == 4 ? kFailed : kSurvived));
  return out;
}

TEST(Checkpointer, JournalsEveryResultAndAResumeReplaysThem) {
  const TempDir dir("journal");
  const Campaign c(dir.file("cube.h5"), 4, 3, 0);
  const std::vector<TaskResult> fed = results(0, 7);
  std::atomic<bool> stop{false};
  Checkpointer ck(c.job.output, c.inputs.combined, c.plan(), c.cube_of(), {}, stop);
  ck.record(fed);
  ck.flush();
  const std::vector<TaskResult> journal = journal_of(c);
  ASSERT_EQ(journal.size(), fed.size());
  for (std::size_t i = 0; i < fed.size(); ++i) EXPECT_TRUE(same_bytes(journal[i], fed[i])) << "record " << i;
  EXPECT_FALSE(fs::exists(c.job.output)) << "no cube before the first rewrite";
  const Plan resumed = c.resumed();
  EXPECT_EQ(resumed.done(), long(fed.size()));
  expect_in_plan(resumed, fed);
  EXPECT_TRUE(ck.failure().empty());
  EXPECT_FALSE(stop);
}

TEST(Checkpointer, CarriedResultsStayInTheJournalUntilTheFirstRewrite) {
  const TempDir dir("carried");
  const Campaign c(dir.file("cube.h5"), 4, 3, 0);
  const std::vector<TaskResult> carried = results(0, 3);
  Plan restored = c.plan();
  for (const TaskResult& r : carried) restored.restore(r);
  std::atomic<bool> stop{false};
  Checkpointer ck(c.job.output, c.inputs.combined, restored, c.cube_of(), carried, stop);
  ASSERT_EQ(journal_of(c).size(), carried.size());
  ASSERT_TRUE(ck.rewrite()) << ck.failure();
  expect_cube_holds(io::read_cube(c.job.output), carried, c.size());
  EXPECT_TRUE(journal_of(c).empty()) << "the cube holds the carried results now";
}

TEST(Checkpointer, ARewriteMovesTheSnapshotIntoTheCubeAndKeepsTheRestInTheJournal) {
  const TempDir dir("rewrite");
  const Campaign c(dir.file("cube.h5"), 4, 3, 0);
  const std::vector<TaskResult> first = results(0, 5), second = results(5, 9);
  std::atomic<bool> stop{false};
  Checkpointer ck(c.job.output, c.inputs.combined, c.plan(), c.cube_of(), {}, stop);
  ck.record(first);
  ASSERT_TRUE(ck.rewrite()) << ck.failure();
  expect_cube_holds(io::read_cube(c.job.output), first, c.size());
  EXPECT_TRUE(journal_of(c).empty());
  ck.record(second);
  ck.sync();
  expect_cube_holds(io::read_cube(c.job.output), first, c.size());  // unchanged until the next rewrite
  ASSERT_EQ(journal_of(c).size(), second.size());
  const Plan resumed = c.resumed();
  EXPECT_EQ(resumed.done(), long(first.size() + second.size()));
  expect_in_plan(resumed, first);
  expect_in_plan(resumed, second);
  const CheckpointStats s = ck.stats();
  EXPECT_EQ(s.rewrites, 1);
  EXPECT_EQ(s.syncs, 1);
}

// The stop rule (plan.hpp): after `stop_after` consecutive scales overturned at every rotation,
// the record's higher scales are inferred, and a result simulated there before the rule applied
// is not kept.
TEST(Checkpointer, TheShadowPlanInfersCellsByTheStopRule) {
  const TempDir dir("stop_rule");
  const Campaign c(dir.file("cube.h5"), 4, 2, 1);  // cells: scale * 2 + rotation
  std::atomic<bool> stop{false};
  Checkpointer ck(c.job.output, c.inputs.combined, c.plan(), c.cube_of(), {}, stop);
  const std::vector<TaskResult> fed = {result(0, kSurvived), result(1, kOverturned), result(2, kOverturned),
                                       result(3, kOverturned), result(6, kSurvived)};
  ck.record(fed);
  ASSERT_TRUE(ck.rewrite()) << ck.failure();
  const io::Cube cube = io::read_cube(c.job.output);
  const io::ObjectCube& oc = cube.objects[0];
  // scale 0 mixed, scale 1 fully overturned: scales 2 and 3 inferred, cell 6's result dropped
  EXPECT_EQ(oc.outcome, (std::vector<std::int8_t>{1, 2, 2, 2, kInferred, kInferred, kInferred, kInferred}));
  for (long t : {4, 5, 6, 7}) EXPECT_TRUE(std::isnan(oc.max_tilt_deg[t])) << "cell " << t;
  for (long t : {0, 1, 2, 3}) EXPECT_EQ(oc.max_tilt_deg[t], fed[t].max_tilt_deg) << "cell " << t;
}

bool wait_for(const std::function<bool()>& done) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!done()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

// Results arrive on one thread while the writer thread rewrites the cube and a reader copies the
// cube file whenever it likes: every copy is a complete cube whose cells hold what was fed.
TEST(CheckpointWriter, RewritesOnItsThreadWhileResultsArriveAndReadersSeeCompleteCubes) {
  const TempDir dir("writer");
  const Campaign c(dir.file("cube.h5"), 20, 10, 0);
  const std::vector<TaskResult> fed = results(0, c.size());
  std::atomic<bool> stop{false};
  Checkpointer ck(c.job.output, c.inputs.combined, c.plan(), c.cube_of(), {}, stop);
  std::vector<std::string> copies;
  {
    CheckpointWriter writer(ck);
    std::atomic<bool> producing{true};
    std::atomic<long> recorded{0};
    std::thread producer([&] {
      for (const TaskResult& r : fed) {
        ck.record({&r, 1});
        ++recorded;
        if (r.task % 2 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      producing = false;
    });
    std::thread reader([&] {
      while (producing || copies.size() < 3) {
        if (std::string b = bytes_of(c.job.output); !b.empty() && copies.size() < 40) copies.push_back(std::move(b));
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
    });
    for (int round = 0; producing || round < 3; ++round) {
      writer.request(round % 2 == 0, true);
      if (!wait_for([&] { return !writer.rewrite_pending(); })) {
        ADD_FAILURE() << "the writer thread is stuck";
        break;
      }
      // between rewrites, the cube and the journal hold every result recorded so far, also
      // those that arrived while the rewrite restarted the journal
      const long n = recorded;
      ck.flush();
      expect_in_plan(c.resumed(), std::vector<TaskResult>(fed.begin(), fed.begin() + n));
    }
    producer.join();
    reader.join();
    writer.stop();
  }
  ASSERT_TRUE(ck.rewrite()) << ck.failure();  // the final one, on this thread
  EXPECT_GE(ck.stats().rewrites, 4);
  EXPECT_GE(ck.stats().syncs, 1);
  std::map<long, TaskResult> by_task;
  for (const TaskResult& r : fed) by_task[r.task] = r;
  ASSERT_FALSE(copies.empty());
  const std::string copy_path = dir.file("copy.h5");
  for (const std::string& bytes : copies) {
    std::ofstream(copy_path, std::ios::binary) << bytes;
    const io::Cube copy = io::read_cube(copy_path);  // throws on a partial file
    std::vector<TaskResult> held;
    for (long t = 0; t < c.size(); ++t) {
      if (copy.objects[0].outcome[t] != kNotRun) held.push_back(by_task.at(t));
    }
    expect_cube_holds(copy, held, c.size());
  }
  expect_cube_holds(io::read_cube(c.job.output), fed, c.size());
  EXPECT_TRUE(journal_of(c).empty());
  EXPECT_FALSE(stop);
}

TEST(Checkpointer, AnUnwritableOutputIsAFailureNotACrash) {
  const TempDir dir("unwritable");
  const std::string not_a_directory = dir.file("file");
  std::ofstream(not_a_directory) << "x";
  const Campaign c(not_a_directory + "/cube.h5", 4, 3, 0);
  std::atomic<bool> stop{false};
  Checkpointer ck(c.job.output, c.inputs.combined, c.plan(), c.cube_of(), {}, stop);
  EXPECT_TRUE(stop) << "dispatch is told to stop";
  EXPECT_NE(ck.failure().find(c.job.output + ".journal"), std::string::npos) << ck.failure();
  const std::vector<TaskResult> fed = results(0, 3);
  ck.record(fed);
  ck.flush();
  ck.sync();
  EXPECT_FALSE(ck.rewrite());
  EXPECT_EQ(bytes_of(not_a_directory), "x");
}

// Files larger than `bytes` cannot be written (EFBIG, as on a full disk) while it lives.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    getrlimit(RLIMIT_FSIZE, &previous_);
    rlimit limit = previous_;
    limit.rlim_cur = bytes;
    ok_ = setrlimit(RLIMIT_FSIZE, &limit) == 0;
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &previous_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  bool ok() const { return ok_; }

 private:
  rlimit previous_{};
  void (*previous_handler_)(int) = nullptr;
  bool ok_ = false;
};

TEST(Checkpointer, ACubeWriteThatFailsMidwayLeavesThePreviousCheckpointAndLosesNothing) {
  const TempDir dir("cube_fails");
  const Campaign c(dir.file("cube.h5"), 8, 4, 0);
  const std::vector<TaskResult> first = results(0, 6), second = results(6, 12), third = results(12, 14);
  std::atomic<bool> stop{false};
  Checkpointer ck(c.job.output, c.inputs.combined, c.plan(), c.cube_of(), {}, stop);
  ck.record(first);
  ASSERT_TRUE(ck.rewrite()) << ck.failure();
  const std::string good = bytes_of(c.job.output);
  ck.record(second);
  ck.sync();
  const std::uintmax_t journal_bytes = fs::file_size(c.job.output + ".journal");
  const rlim_t limit = rlim_t(good.size() / 2);
  ASSERT_LT(journal_bytes + 4 * Journal::record_bytes(), limit) << "the journal must still fit under the limit";
  {
    const FileSizeLimit small(limit);
    ASSERT_TRUE(small.ok());
    EXPECT_FALSE(ck.rewrite()) << "the new cube is larger than the limit";
    ck.record(third);  // still journalled after the failed cube write
    ck.flush();
  }
  EXPECT_TRUE(stop);
  EXPECT_NE(ck.failure().find("checkpoint failed"), std::string::npos) << ck.failure();
  EXPECT_EQ(bytes_of(c.job.output), good) << "the previous cube is untouched";
  EXPECT_FALSE(fs::exists(c.job.output + ".tmp")) << "the partial cube is removed";
  expect_cube_holds(io::read_cube(c.job.output), first, c.size());
  EXPECT_FALSE(ck.rewrite()) << "nothing is written after a failure";
  EXPECT_EQ(bytes_of(c.job.output), good);
  const Plan resumed = c.resumed();
  EXPECT_EQ(resumed.done(), long(first.size() + second.size() + third.size()));
  expect_in_plan(resumed, first);
  expect_in_plan(resumed, second);
  expect_in_plan(resumed, third);
}

TEST(Checkpointer, AJournalWriteThatFailsStopsTheCampaignAndKeepsWhatWasWritten) {
  const TempDir dir("journal_fails");
  const Campaign c(dir.file("cube.h5"), 8, 4, 0);
  const std::vector<TaskResult> first = results(0, 4), second = results(4, 8), late = results(8, 32);
  std::atomic<bool> stop{false};
  Checkpointer ck(c.job.output, c.inputs.combined, c.plan(), c.cube_of(), {}, stop);
  ck.record(first);
  ASSERT_TRUE(ck.rewrite()) << ck.failure();
  const std::string good = bytes_of(c.job.output);
  ck.record(second);
  ck.sync();
  const std::uintmax_t journal_bytes = fs::file_size(c.job.output + ".journal");
  {
    const FileSizeLimit tight(rlim_t(journal_bytes + Journal::record_bytes() / 2));
    ASSERT_TRUE(tight.ok());
    ck.record(late);
    ck.flush();
  }
  EXPECT_TRUE(stop);
  EXPECT_NE(ck.failure().find("journal write failed"), std::string::npos) << ck.failure();
  EXPECT_FALSE(ck.rewrite());
  EXPECT_EQ(bytes_of(c.job.output), good) << "the cube is untouched";
  const Plan resumed = c.resumed();
  expect_in_plan(resumed, first);
  expect_in_plan(resumed, second);  // synced before the failure
}

}  // namespace
}  // namespace rigid::campaign
