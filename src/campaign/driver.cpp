// MPI master/worker. Rank 0's main thread does all MPI, checkpoints and progress while a second
// thread simulates tasks from the same plan, so on 2 ranks both cores simulate. Workers ask for
// tasks with the results of their last batch. Every result is journalled at once and the cube is
// rewritten atomically every checkpoint interval.
#include "rigid/campaign/driver.hpp"

#include <mpi.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "rigid/campaign/journal.hpp"
#include "rigid/campaign/output_lock.hpp"
#include "rigid/campaign/plan.hpp"
#include "rigid/campaign/runner.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/at2.hpp"
#include "rigid/io/job_file.hpp"
#include "rigid/io/provenance.hpp"
#include "rigid/dynamics/world.hpp"
#include "rigid/scenario/rocking_parameters.hpp"
#include "rigid/scenario/scene.hpp"

#if !defined(RIGID_VERSION) || !defined(RIGID_GIT_HASH)
#error "the build defines RIGID_VERSION and RIGID_GIT_HASH"
#endif

namespace rigid::campaign {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kTagResults = 1;  // worker -> master: results of the last batch, and a request
constexpr int kTagTasks = 2;    // master -> worker: task ids
constexpr int kTagStop = 3;     // master -> worker: no more work

volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_stop_signal(int sig) { g_stop_signal = sig; }

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  for (int s : {SIGTERM, SIGINT, SIGUSR1}) sigaction(s, &sa, nullptr);
}

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string format_duration(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--";
  const long t = std::lround(s);
  char buf[32];
  if (t >= 3600) {
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%ld:%02ld", t / 60, t % 60);
  }
  return buf;
}

// SHA-256 of everything a cell depends on besides the code: the settings (job text with the
// command-line overrides, accuracy preset), the job file, the record list, every object's files
// and every record's motion files. Rank 0 reads them once more after loading them.
struct Inputs {
  io::Digests job;                    // (settings), job file, record list
  std::vector<io::Digests> objects;   // per object: scene, model, STLs, state
  std::vector<io::Digests> records;   // per record: motion files
  std::string combined;               // over the contents only: the same files elsewhere match
};

Inputs collect_inputs(const scenario::Job& job, const TaskRunner& runner) {
  Inputs in;
  in.job.push_back({"(settings)", io::sha256_hex(io::job_settings_text(job))});
  in.job.push_back({job.path, io::file_sha256(job.path)});
  if (!job.record_list.empty()) in.job.push_back({job.record_list, io::file_sha256(job.record_list)});
  for (std::size_t o = 0; o < job.objects.size(); ++o) in.objects.push_back(io::digest_files(runner.scene(int(o)).files));
  for (const auto& r : job.records) {
    const io::SetFiles set = io::resolve_set(r.spec);
    std::vector<std::string> files;
    for (const std::string* f : {&set.x, &set.y, &set.z}) {
      if (!f->empty()) files.push_back(*f);
    }
    in.records.push_back(io::digest_files(files));
  }
  std::string all;
  const auto add = [&all](const char* what, const io::Digests& d) {
    all += std::string(what) + " " + std::to_string(d.size()) + "\n";
    for (const auto& f : d) all += f.sha256 + "\n";
  };
  add("job", in.job);
  for (const auto& d : in.objects) add("object", d);
  for (const auto& d : in.records) add("record", d);
  in.combined = io::sha256_hex(all);
  return in;
}

// An object's full physics and run settings as one JSON object: its own contact model and law,
// density, failure rule and the time step its runs take, with the job's run settings.
std::string physics_json(const scenario::Scene& scene, const scenario::Job& job) {
  const auto& law = scene.law;
  const bool tilt = scene.failure.kind == scenario::FailureRule::Kind::tilt;
  char physics[1536];
  std::snprintf(physics, sizeof physics,
                "{\"contact\": \"%s\", \"restitution\": %.17g, \"normal_stiffness\": %.17g, \"shear_stiffness\": %.17g, \"friction\": %.17g, "
                "\"damping\": %.17g, \"density\": %.17g, \"failure_rule\": \"%s\", \"failure_tilt_deg\": %.17g, "
                "\"step_s\": %.17g, \"dt_s\": %.17g, \"safety\": %.17g, \"integrator\": \"%s\", "
                "\"duration_s\": %.17g, \"free_time_s\": %.17g, \"stop_after\": %d, \"accuracy\": \"%s\", "
                "\"rest_speed_m_s\": %.17g, \"rest_angular_speed_rad_s\": %.17g, \"rest_time_s\": %.17g, "
                "\"effects\": \"%s\"}",
                contact::contact_model_name(law.model), law.restitution, law.normal_stiffness,
                law.shear_stiffness, law.friction, law.damping, scene.density, tilt ? "tilt" : "below",
                tilt ? scene.failure.tilt_angle * 180.0 / kPi : 0.0, dynamics::time_step(scene.bodies, law, job.run.step),
                job.run.step.dt, job.run.step.safety,
                job.run.step.rotation == dynamics::RotationIntegrator::rk4 ? "rk4" : "splitting",
                job.run.duration, job.run.free_time, job.stop_after, job.accuracy.c_str(), job.run.rest_speed,
                job.run.rest_angular_speed, job.run.rest_time, job.run.select_effects ? "auto" : "all");
  return physics;
}

// Builds the cube from the plan's state (caller holds the plan lock).
io::Cube make_cube(const scenario::Job& job, const TaskRunner& runner, const Inputs& inputs, const Plan& plan) {
  io::Cube cube;
  cube.records = runner.records();
  for (std::size_t r = 0; r < cube.records.size(); ++r) cube.records[r].inputs = io::format_digests(inputs.records[r]);
  cube.job_inputs = io::format_digests(inputs.job);
  cube.inputs_sha256 = inputs.combined;
  cube.scales_g = job.scales_g;
  cube.rotations = job.rotations;
  cube.job_text = job.text;
  cube.job_hash = job.hash;
  cube.software_version = RIGID_VERSION " (" RIGID_GIT_HASH ")";
  cube.seed = job.seed;
  cube.physics_json = physics_json(runner.scene(0), job);  // object 0's, as before per-object records
  const std::vector<std::int8_t> outcome = plan.final_outcomes();
  const std::vector<bool> kept = plan.kept_mask();
  const long per_object = long(job.records.size()) * long(job.scales_g.size()) * job.rotations;
  const double nan = std::nan("");
  for (std::size_t o = 0; o < job.objects.size(); ++o) {
    io::ObjectCube oc;
    oc.name = job.objects[o].name;
    oc.scene = job.objects[o].scene;
    oc.inputs = io::format_digests(inputs.objects[o]);
    oc.physics_json = physics_json(runner.scene(int(o)), job);
    if (const auto rocking = scenario::rocking_parameters(runner.scene(int(o)))) {
      oc.alpha_rad = rocking->alpha;
      oc.p_rad_s = rocking->p;
    }
    for (long i = 0; i < per_object; ++i) {
      const long t = long(o) * per_object + i;
      const TaskResult& r = plan.results()[t];
      oc.outcome.push_back(outcome[t]);
      oc.rotation_deg.push_back(cell_rotation_deg(job, plan.cell(t)));
      oc.failure_time_s.push_back(kept[t] ? r.failure_time_s : nan);
      oc.max_tilt_deg.push_back(kept[t] ? r.max_tilt_deg : nan);
      oc.max_slip_m.push_back(kept[t] ? r.max_slip_m : nan);
      oc.wall_s.push_back(kept[t] ? r.wall_s : nan);
      oc.failure_reason.push_back(kept[t] ? r.reason : 0);
    }
    cube.objects.push_back(std::move(oc));
  }
  return cube;
}

InputError changed_file(const std::string& file) {
  return InputError(file, 0, "changed since the campaign started (resume refused; --force starts anew)");
}

// Why the cube's results must not be resumed with these inputs, or nothing when they may.
std::optional<InputError> input_change(const io::Cube& old, const scenario::Job& job, const Inputs& now) {
  const io::Digests old_job = io::parse_digests(old.job_inputs);
  if (old.job_hash != job.hash) {
    // the same job file edited is named; another job file or other command-line settings name the output
    if (old_job.size() >= 2 && old_job[1].path == now.job[1].path && old_job[1].sha256 != now.job[1].sha256) {
      return changed_file(job.path);
    }
    return InputError(job.output, 0,
                      "was written by a different job file, accuracy preset or command-line settings (hash " + old.job_hash + ", now " + job.hash +
                          "); use --force to start a new campaign over it, or another --out");
  }
  if (old.inputs_sha256.empty()) {
    std::fprintf(stderr, "rigid campaign: warning: %s was written before input hashes were stored; its scenes and "
                 "records are not checked for changes\n", job.output.c_str());
    return std::nullopt;
  }
  if (old.inputs_sha256 == now.combined) return std::nullopt;
  if (auto f = io::first_changed(old_job, now.job)) return changed_file(*f);
  for (std::size_t o = 0; o < now.objects.size() && o < old.objects.size(); ++o) {
    if (auto f = io::first_changed(io::parse_digests(old.objects[o].inputs), now.objects[o])) return changed_file(*f);
  }
  for (std::size_t r = 0; r < now.records.size() && r < old.records.size(); ++r) {
    if (auto f = io::first_changed(io::parse_digests(old.records[r].inputs), now.records[r])) return changed_file(*f);
  }
  return changed_file(job.output);  // a digest that matches no file list: the cube itself was altered
}

// Results already on disk: the cube's simulated cells, then the journal, whose results are
// returned (the new journal carries them until the first checkpoint). With changed inputs it
// refuses, touching neither the cube nor the journal, unless `force`, which starts anew.
std::vector<TaskResult> restore(const std::string& output, const scenario::Job& job, const Inputs& inputs, Plan& plan,
                                bool force) {
  const std::string journal = output + ".journal";
  const bool have_cube = fs::exists(output);
  if (have_cube) {
    const io::Cube old = io::read_cube(output);
    if (std::optional<InputError> change = input_change(old, job, inputs)) {
      if (!force) throw *change;
      fs::remove(output);
      fs::remove(journal);
      return {};
    }
    const long per_object = long(job.records.size()) * long(job.scales_g.size()) * job.rotations;
    for (std::size_t o = 0; o < old.objects.size() && o < job.objects.size(); ++o) {
      const auto& oc = old.objects[o];
      for (long i = 0; i < per_object && i < long(oc.outcome.size()); ++i) {
        const auto v = static_cast<io::CellOutcome>(oc.outcome[i]);
        if (v != io::CellOutcome::survived && v != io::CellOutcome::overturned && v != io::CellOutcome::failed) continue;
        TaskResult r;
        r.task = long(o) * per_object + i;
        r.outcome = oc.outcome[i];
        r.reason = oc.failure_reason[i];
        r.failure_time_s = oc.failure_time_s[i];
        r.max_tilt_deg = oc.max_tilt_deg[i];
        r.max_slip_m = oc.max_slip_m[i];
        r.wall_s = oc.wall_s[i];
        plan.restore(r);
      }
    }
  } else if (force) {
    fs::remove(journal);
  }
  JournalContents kept = read_journal(journal, inputs.combined, plan.size());
  if (kept.foreign) {
    // without a cube to name the changed file, the journal itself is the evidence
    if (!have_cube) throw changed_file(journal);
    kept.problems.push_back(journal + ": written for other inputs; ignored");
  }
  for (const std::string& p : kept.problems) std::fprintf(stderr, "rigid campaign: warning: %s\n", p.c_str());
  for (const TaskResult& r : kept.results) plan.restore(r);
  return std::move(kept.results);
}

class Progress {
 public:
  Progress(const std::string& mode, double log_interval, long total)
      : log_interval_(log_interval), total_(total), start_(Clock::now()), last_(start_) {
    bar_ = mode == "bar" || (mode == "auto" && isatty(STDERR_FILENO));
    quiet_ = mode == "none";
  }
  bool due() const { return !quiet_ && seconds_since(last_) >= (bar_ ? 0.25 : log_interval_); }
  void update(long done_now, long remaining, long failures, long done_at_start, bool final = false) {
    if (quiet_) return;
    if (!final && !due()) return;
    last_ = Clock::now();
    const double elapsed = seconds_since(start_);
    const double rate = elapsed > 0 ? double(done_now - done_at_start) / elapsed : 0.0;
    const double eta = rate > 0 ? double(remaining) / rate : NAN;
    const long shown_total = done_now + remaining;
    if (bar_) {
      const int width = 30;
      const int filled = shown_total > 0 ? int(width * double(done_now) / double(shown_total)) : width;
      std::fprintf(stderr, "\r[%s%s] %ld/%ld tasks  %.1f sim/s  ETA %s  failures %ld   ",
                   std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), done_now,
                   shown_total, rate, format_duration(eta).c_str(), failures);
      if (final) std::fprintf(stderr, "\n");
    } else {
      std::fprintf(stderr, "rigid campaign: %ld/%ld tasks done (%ld of the %ld cells left to simulate), %.2f sim/s, ETA %s, failures %ld\n",
                   done_now, shown_total, remaining, total_, rate, format_duration(eta).c_str(), failures);
    }
    std::fflush(stderr);
  }

 private:
  double log_interval_;
  long total_;
  Clock::time_point start_, last_;
  bool bar_ = false, quiet_ = false;
};

void print_summary(const scenario::Job& job, const io::Cube& cube, const std::string& output) {
  std::printf("\nfragility cube: %s\n", fs::absolute(output).string().c_str());
  std::printf("overturning probability (mean over records; inferred cells count as overturned)\n");
  std::printf("%-20s", "object \\ scale (g)");
  for (std::size_t s = 0; s < job.scales_g.size(); s += (job.scales_g.size() + 15) / 16) {
    std::printf("%7.3g", job.scales_g[s]);
  }
  std::printf("\n");
  const std::size_t R = job.records.size(), S = job.scales_g.size(), A = std::size_t(job.rotations);
  // at most 16 columns: every k-th scale of a long list
  const std::size_t stride = (S + 15) / 16;
  if (stride > 1) std::printf("(every %zu-th scale of %zu)\n", stride, S);
  for (const auto& oc : cube.objects) {
    std::printf("%-20s", oc.name.c_str());
    for (std::size_t s = 0; s < S; s += stride) {
      double sum = 0;
      int known = 0;
      for (std::size_t r = 0; r < R; ++r) {
        int over = 0, n = 0;
        for (std::size_t k = 0; k < A; ++k) {
          const auto v = static_cast<io::CellOutcome>(oc.outcome[(r * S + s) * A + k]);
          if (v == io::CellOutcome::overturned || v == io::CellOutcome::inferred) ++over, ++n;
          if (v == io::CellOutcome::survived) ++n;
        }
        if (n > 0) {
          sum += double(over) / n;
          ++known;
        }
      }
      if (known > 0) {
        std::printf("%7.2f", sum / known);
      } else {
        std::printf("%7s", "-");
      }
    }
    std::printf("\n");
  }
}

int dry_run(const scenario::Job& job, const TaskRunner& runner) {
  const long cells = long(job.objects.size()) * long(job.records.size()) * long(job.scales_g.size()) * job.rotations;
  double simulated = 0;
  for (std::size_t r = 0; r < job.records.size(); ++r) simulated += runner.simulated_time(int(r));
  simulated *= double(job.objects.size()) * double(job.scales_g.size()) * job.rotations;
  // measure this machine's step cost on each object at rest
  double steps = 0, wall = 0;
  for (std::size_t o = 0; o < job.objects.size(); ++o) {
    const scenario::Scene& scene = runner.scene(int(o));
    dynamics::World world(scene.bodies, scene.law, job.run.step);
    const auto start = Clock::now();
    for (int k = 0; k < 2000; ++k) world.step(world.dt(), Vec3::Zero(), Vec3::Zero());
    const double per_step = seconds_since(start) / 2000.0;
    double object_sim = 0;
    for (std::size_t r = 0; r < job.records.size(); ++r) object_sim += runner.simulated_time(int(r));
    object_sim *= double(job.scales_g.size()) * job.rotations;
    steps += object_sim / world.dt();
    wall += object_sim / world.dt() * per_step;
  }
  std::printf("job %s: %zu objects x %zu records x %zu scales x %d rotations = %ld tasks\n", job.path.c_str(),
              job.objects.size(), job.records.size(), job.scales_g.size(), job.rotations, cells);
  std::printf("at most %.4g s simulated, %.4g time steps; about %s of one core if every task ran to its end\n",
              simulated, steps, format_duration(wall).c_str());
  std::printf("(overturned runs stop early and the stop rule skips scales, so the real cost is lower)\n");
  return 0;
}

// What follows an InputError's "FILE: " prefix, when FILE is `file`.
std::string reason_of(const std::exception& e, const std::string& file) {
  const std::string what = e.what();
  const std::string prefix = file + ": ";
  return what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
}

struct Master {
  Master(const scenario::Job& j, const CampaignOptions& o, const TaskRunner& r, const Inputs& in, int n)
      : job(j), options(o), runner(r), inputs(in), output(j.output), ranks(n) {}

  const scenario::Job& job;
  const CampaignOptions& options;
  const TaskRunner& runner;
  const Inputs& inputs;
  std::string output;
  int ranks = 1;

  std::mutex mutex;  // guards plan, journal and failure
  Plan* plan = nullptr;
  std::unique_ptr<Journal> journal;
  bool journal_ok = false;
  // The first failed write, as printed. A failure ends the campaign, not the process: dispatch
  // stops, every rank is told to stop, the local thread is joined, and the last good cube and the
  // journal stay as they were (both are only ever replaced by a rename).
  std::string failure;
  std::atomic<bool> stopping{false};
  std::atomic<bool> local_done{false};
  double mean_wall = 0.05;  // running mean task wall time, for batch sizes (unit: s)
  long remote_tasks = 0, remote_messages = 0;  // handed to other ranks

  std::vector<TaskResult> since_snapshot;  // results not in the cube being written

  // caller holds the mutex
  void fail(const std::string& message) {
    if (failure.empty()) failure = message;
    stopping = true;
  }
  void journal_failed(const std::exception& e) {
    journal_ok = false;
    fail(std::string(e.what()) + " (the cube and the journal keep what was written; run again to resume)");
  }
  void flush_journal() {
    if (!journal_ok) return;
    try {
      journal->flush();
    } catch (const std::exception& e) {
      journal_failed(e);
    }
  }

  void record(const TaskResult& r) {
    plan->complete(r);
    since_snapshot.push_back(r);
    mean_wall = 0.9 * mean_wall + 0.1 * r.wall_s;
    // after a failed cube write the journal still takes results: they are kept for the resume
    if (!journal_ok) return;
    try {
      journal->append(r);
    } catch (const std::exception& e) {
      journal_failed(e);
    }
  }

  // the master's own simulations, on a second thread that never calls MPI; with --noop on
  // several ranks it stays idle, so the run measures what the master alone can hand out
  void local_worker() {
    const bool idle = options.noop && ranks > 1;
    for (;;) {
      if (idle) break;
      std::optional<long> t;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (stopping || plan->finished()) break;
        t = plan->next();
      }
      if (!t) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        continue;
      }
      const TaskResult r = runner.run(*t, plan->cell(*t), options.noop);
      std::lock_guard<std::mutex> lock(mutex);
      record(r);
    }
    local_done = true;
  }

  // tasks for one request: about a quarter second of work, fewer near the end
  std::vector<std::int64_t> batch() {
    const long left = plan->size() - plan->done() - plan->in_flight();
    const long want = std::clamp(long(0.25 / std::max(mean_wall, 1e-6)), 1L,
                                 std::max(1L, std::min(256L, left / (2L * ranks))));
    std::vector<std::int64_t> ids;
    while (long(ids.size()) < want) {
      const auto t = plan->next();
      if (!t) break;
      ids.push_back(*t);
    }
    return ids;
  }

  // Writes the cube, then restarts the journal. False after a failure (recorded in `failure`);
  // nothing is written once one has happened.
  bool checkpoint() {
    io::Cube cube;
    {
      std::lock_guard<std::mutex> lock(mutex);
      flush_journal();
      if (!failure.empty()) return false;
      cube = make_cube(job, runner, inputs, *plan);
      since_snapshot.clear();
    }
    try {
      io::write_cube(output, cube);  // to OUT.tmp, renamed over OUT: the previous cube stays on failure
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      fail(output + ": checkpoint failed: " + reason_of(e, output) +
           " (results kept in the journal; run again to resume)");
      return false;
    }
    std::lock_guard<std::mutex> lock(mutex);
    // the cube now holds everything but what arrived while it was written: journal only that
    try {
      journal->reset(since_snapshot);
    } catch (const std::exception& e) {
      journal_failed(e);  // the old journal, a superset, is still in place
      return false;
    }
    return true;
  }

  // carried: the old journal's results, kept in the new one until the first checkpoint
  int run(const std::vector<TaskResult>& carried) {
    const long total = plan->size();
    const long done_at_start = plan->done();
    const auto started = Clock::now();
    try {
      journal = std::make_unique<Journal>(output + ".journal", inputs.combined, carried);
      journal_ok = true;
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      journal_failed(e);
    }
    // the restored results go into the cube at once, which also proves the output writable; on a
    // failure the loop below only tells the workers to stop
    if (checkpoint()) {
      std::fprintf(stderr, "rigid campaign: %ld tasks, %ld already done, %d ranks, output %s\n", plan->size(),
                   plan->done(), ranks, job.output.c_str());
    }
    Progress progress(options.progress, options.log_interval, total);
    std::thread local([this] { local_worker(); });
    std::vector<int> waiting;  // worker ranks whose request is unanswered
    int active_workers = ranks - 1;
    auto last_checkpoint = Clock::now();
    std::optional<Clock::time_point> stop_since;
    const double checkpoint_interval = options.checkpoint_interval > 0 ? options.checkpoint_interval : job.checkpoint_interval;
    const double grace = options.grace >= 0 ? options.grace : job.grace;
    bool abandoned = false;
    std::vector<TaskResult> inbox;
    for (;;) {
      bool busy = false;
      int flag = 0;
      MPI_Status status;
      // answer every pending request
      while (MPI_Iprobe(MPI_ANY_SOURCE, kTagResults, MPI_COMM_WORLD, &flag, &status) == MPI_SUCCESS && flag) {
        busy = true;
        int bytes = 0;
        MPI_Get_count(&status, MPI_BYTE, &bytes);
        inbox.resize(std::size_t(bytes) / sizeof(TaskResult));
        MPI_Recv(inbox.data(), bytes, MPI_BYTE, status.MPI_SOURCE, kTagResults, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& r : inbox) record(r);
        flush_journal();
        waiting.push_back(status.MPI_SOURCE);
      }
      if (g_stop_signal && !stopping) {
        stopping = true;
        stop_since = Clock::now();
        std::fprintf(stderr, "\nrigid campaign: signal %d: no new tasks; waiting up to %g s for %ld in flight\n",
                     int(g_stop_signal), grace, plan->in_flight());
      }
      // hand out work, or stop workers that will get none
      for (auto it = waiting.begin(); it != waiting.end();) {
        std::vector<std::int64_t> ids;
        bool stop = false;
        {
          std::lock_guard<std::mutex> lock(mutex);
          if (!stopping) ids = batch();
          stop = ids.empty() && (stopping || plan->finished());
        }
        if (!ids.empty()) {
          MPI_Send(ids.data(), int(ids.size()), MPI_INT64_T, *it, kTagTasks, MPI_COMM_WORLD);
          remote_tasks += long(ids.size());
          ++remote_messages;
          it = waiting.erase(it);
        } else if (stop) {
          MPI_Send(nullptr, 0, MPI_INT64_T, *it, kTagStop, MPI_COMM_WORLD);
          --active_workers;
          it = waiting.erase(it);
        } else {
          ++it;  // nothing to give now: tasks in flight may unblock more
        }
      }
      {
        std::lock_guard<std::mutex> lock(mutex);
        flush_journal();
        if (progress.due()) progress.update(plan->done(), plan->remaining(), plan->failures(), done_at_start);
      }
      if (seconds_since(last_checkpoint) >= checkpoint_interval) {
        checkpoint();
        last_checkpoint = Clock::now();
      }
      bool all_done;
      {
        std::lock_guard<std::mutex> lock(mutex);
        all_done = active_workers == 0 && local_done && (stopping || plan->finished());
      }
      if (all_done) break;
      if (stopping && !stop_since) stop_since = Clock::now();  // stopped by a failed write
      if (stopping && seconds_since(*stop_since) > grace) {
        abandoned = true;
        break;
      }
      if (!busy) std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    if (abandoned) {
      // in-flight work is given up: checkpoint what is done, then end every rank
      stopping = true;
      const bool written = checkpoint();
      std::fprintf(stderr, "rigid campaign: grace period over; %ld tasks abandoned (redone on resume)\n", plan->in_flight());
      if (!written) {
        std::lock_guard<std::mutex> lock(mutex);  // the local thread may still be recording
        std::fprintf(stderr, "rigid: error: %s\n", failure.c_str());
      }
      std::fflush(stderr);
      MPI_Abort(MPI_COMM_WORLD, written ? kExitInterrupted : kExitIoFailure);
    }
    local.join();
    checkpoint();
    io::Cube cube;
    {
      std::lock_guard<std::mutex> lock(mutex);
      progress.update(plan->done(), plan->remaining(), plan->failures(), done_at_start, true);
      if (!failure.empty()) {
        std::fprintf(stderr, "rigid: error: %s\n", failure.c_str());
        return kExitIoFailure;
      }
      cube = make_cube(job, runner, inputs, *plan);
    }
    if (ranks > 1) {
      std::fprintf(stderr, "rigid campaign: %ld tasks sent to %d worker ranks in %ld messages (%.0f tasks/s over %.2f s)\n",
                   remote_tasks, ranks - 1, remote_messages, double(remote_tasks) / seconds_since(started), seconds_since(started));
    }
    if (stopping) {
      std::fprintf(stderr, "rigid campaign: stopped; checkpoint written to %s; run the same command to resume\n",
                   output.c_str());
      return kExitInterrupted;
    }
    print_summary(job, cube, output);
    fs::remove(output + ".journal");
    return 0;
  }
};

void worker_loop(const scenario::Job& job, const TaskRunner& runner, bool noop) {
  std::vector<TaskResult> results;
  std::vector<std::int64_t> ids;
  const int records = int(job.records.size()), scales = int(job.scales_g.size());
  for (;;) {
    MPI_Send(results.data(), int(results.size() * sizeof(TaskResult)), MPI_BYTE, 0, kTagResults, MPI_COMM_WORLD);
    results.clear();
    MPI_Status status;
    MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_INT64_T, &count);
    ids.resize(std::size_t(count));
    MPI_Recv(ids.data(), count, MPI_INT64_T, 0, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (status.MPI_TAG == kTagStop) break;
    for (std::int64_t t : ids) results.push_back(runner.run(t, cell_of(t, records, scales, job.rotations), noop));
  }
}

}  // namespace

int run_campaign(int& argc, char**& argv, const CampaignOptions& options) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  install_signal_handlers();

  // every rank reads the job and its inputs; only rank 0 reports problems
  scenario::Job job;
  std::unique_ptr<TaskRunner> runner;
  int ok = 1;
  std::string error;
  try {
    job = io::load_job(options.job);
    if (!options.output.empty()) job.output = options.output;
    if (!options.model.empty()) {
      if (options.model != "dem3d" && options.model != "rocking2d") {
        throw InputError("", 0, "--model must be dem3d or rocking2d");
      }
      // the override is part of what the cube holds: a resume with another model is refused
      job.model = options.model;
      job.text += "\n# command line: --model " + options.model + "\n";
      job.hash = io::text_hash(job.text);
    }
    if (!options.contact.empty()) {
      contact::ContactModel model;
      if (!contact::parse_contact_model(options.contact, model)) {
        throw InputError("", 0, "--contact must be rigid or penalty");
      }
      // like --model: part of the job text, so of its hash, and a resume with the other model is refused
      job.contact = options.contact;
      job.text += "\n# command line: --contact " + options.contact + "\n";
      job.hash = io::text_hash(job.text);
    }
    if (!options.effects.empty() && options.effects != "auto" && options.effects != "all") {
      throw InputError("", 0, "--effects must be auto or all");
    }
    if (!options.effects.empty() && (options.effects == "auto") != job.run.select_effects) {
      // like --model: part of the job text, so of its hash, and a resume with the other choice is refused
      job.run.select_effects = options.effects == "auto";
      job.text += "\n# command line: --effects " + options.effects + "\n";
      job.hash = io::text_hash(job.text);
    }
    if (!options.accuracy.empty()) {
      const scenario::AccuracyPreset* preset = scenario::find_accuracy_preset(options.accuracy);
      if (!preset) throw InputError("", 0, "--accuracy must be " + scenario::accuracy_preset_list());
      // the preset enters the job hash (io::job_hash), so a resume with another preset is refused
      job.accuracy = preset->name;
      scenario::apply_accuracy(*preset, job.accuracy_overrides, job.run);
    }
    job.hash = io::job_hash(job);
    runner = std::make_unique<TaskRunner>(job);
  } catch (const InputError& e) {
    ok = 0;
    error = e.what();
  }
  int all_ok = 0;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (!all_ok) {
    MPI_Finalize();
    if (rank == 0 && !ok) throw InputError("", 0, error);
    if (rank == 0) throw InputError(options.job, 0, "another rank could not read the job's inputs");
    return 2;
  }

  int status = 0;
  if (rank == 0) {
    Plan plan(int(job.objects.size()), int(job.records.size()), int(job.scales_g.size()), job.rotations,
              job.stop_after, [&] {
                std::vector<double> cost;
                for (std::size_t r = 0; r < job.records.size(); ++r) cost.push_back(runner->simulated_time(int(r)));
                return cost;
              }());
    int go = 1;
    std::string problem;
    std::unique_ptr<OutputLock> lock;  // held until this function returns or throws
    Inputs inputs;
    std::vector<TaskResult> carried;
    try {
      if (options.dry_run) {
        go = 0;
      } else {
        io::silence_hdf5_errors();  // our one-line messages say what failed
        if (fs::path(job.output).has_parent_path()) {
          std::error_code ec;
          fs::create_directories(fs::path(job.output).parent_path(), ec);
          if (ec) throw InputError(job.output, 0, "cannot create its directory: " + ec.message());
        }
        lock = std::make_unique<OutputLock>(job.output);
        inputs = collect_inputs(job, *runner);
        carried = restore(job.output, job, inputs, plan, options.force);
      }
    } catch (const InputError& e) {
      go = -1;
      problem = e.what();
    }
    MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (go == -1) {
      MPI_Finalize();
      throw InputError("", 0, problem);
    }
    if (go == 0) {
      status = dry_run(job, *runner);
    } else {
      Master master(job, options, *runner, inputs, ranks);
      master.plan = &plan;
      status = master.run(carried);
    }
  } else {
    int go = 0;
    MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (go == 1) worker_loop(job, *runner, options.noop);
    status = go == -1 ? 2 : 0;
  }
  MPI_Finalize();
  return status;
}

}  // namespace rigid::campaign
