#include "rigid/campaign/driver.hpp"

#include <mpi.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rigid/campaign/log.hpp"
#include "rigid/campaign/output_lock.hpp"
#include "rigid/campaign/stop_signal.hpp"
#include "rigid/campaign/task.hpp"
#include "rigid/campaign/transport.hpp"
#include "rigid/core/error.hpp"
#include "rigid/job/model.hpp"

namespace rigid::campaign {
namespace {

namespace fs = std::filesystem;

// What every rank loads: the job and the model its cases run on.
struct Loaded {
  job::Job job;
  std::unique_ptr<scenario::Model> model;
};

// Loads on every rank; true on all ranks only if every rank succeeded. Rank 0 throws the error.
bool load_everywhere(const CampaignOptions& options, int rank, Loaded& loaded) {
  int ok = 1;
  std::string error;
  try {
    loaded.job = load_campaign_job(options);
    if (rank == 0) {
      for (const std::string& note : loaded.job.notes) log_status("note: {}", note);
    }
    loaded.model = std::make_unique<scenario::Model>(job::load_model(loaded.job));
  } catch (const InputError& e) {
    ok = 0;
    error = e.what();
  }
  int all_ok = 0;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (all_ok) return true;
  if (rank == 0 && !ok) throw InputError("", 0, error);
  if (rank == 0) throw InputError(options.job, 0, "another rank could not read the job's inputs");
  return false;
}

Plan make_plan(const job::Job& job, const scenario::Model& model) {
  std::vector<double> cost;  // longest records first within a scale
  for (int r = 0; r < model.records(); ++r) cost.push_back(model.simulated_time(r));
  return Plan(int(job.objects.size()), int(job.records.size()), int(job.scales_g.size()), job.rotations, job.stop_after,
              std::move(cost));
}

// Rank 0: lock the output, digest the inputs, restore what is on disk, then run as master.
// Every outcome is broadcast to the workers first: go (1), dry run (0) or refused (-1).
CampaignResult run_rank0(const CampaignOptions& options, const Loaded& loaded, int ranks) {
  const job::Job& job = loaded.job;
  Plan plan = make_plan(job, *loaded.model);
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
      lock = std::make_unique<OutputLock>(job.output, options.remedies.other_output);
      inputs = collect_inputs(job, *loaded.model);
      carried = restore(job.output, job, inputs, plan, options.force, options.remedies);
    }
  } catch (const InputError& e) {
    go = -1;
    problem = e.what();
  }
  MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (go == -1) throw InputError("", 0, problem);
  CampaignResult result;
  result.output = job.output;
  if (go == 0) {
    result.status = options.on_dry_run ? options.on_dry_run(job, *loaded.model) : 0;
    return result;
  }
  const std::vector<io::RecordMeta> records = job::record_metadata(job, *loaded.model);
  const CampaignContext context{job, *loaded.model, records, inputs};
  MasterResult master = run_master(context, options, plan, carried, ranks);
  result.status = master.status;
  result.cube = std::move(master.cube);
  result.solver_max_sweeps = job.run.step.solver_max_sweeps;
  return result;
}

}  // namespace

MpiSession::MpiSession(int& argc, char**& argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
  install_stop_signal_handlers();
}

MpiSession::~MpiSession() { MPI_Finalize(); }

CampaignResult run_campaign(const MpiSession& session, const CampaignOptions& options) {
  Loaded loaded;
  if (!load_everywhere(options, session.rank(), loaded)) return {2, std::nullopt, "", 0};
  CampaignResult result;
  if (session.rank() == 0) {
    result = run_rank0(options, loaded, session.ranks());
  } else {
    int go = 0;
    MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (go == 1) {
      worker_loop([&](std::int64_t t) { return run_task(loaded.job, *loaded.model, t, options.noop); });
    }
    result.status = go == -1 ? 2 : 0;
  }
  return result;
}

CampaignResult run_campaign(int& argc, char**& argv, const CampaignOptions& options) {
  const MpiSession session(argc, argv);
  return run_campaign(session, options);
}

namespace {

// Rank 0's string on every rank.
std::string broadcast(const std::string& text) {
  long size = long(text.size());
  MPI_Bcast(&size, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  std::string out = text;
  out.resize(std::size_t(size));
  MPI_Bcast(out.data(), int(size), MPI_CHAR, 0, MPI_COMM_WORLD);
  return out;
}

}  // namespace

CampaignResult run_campaign_sequence(const MpiSession& session,
                                     const std::function<std::optional<CampaignOptions>(const CampaignResult*)>& next) {
  CampaignResult last;
  bool first = true;
  for (;;) {
    // 1: run the options broadcast next, 0: done, -1: rank 0's `next` failed
    int go = 0;
    std::optional<CampaignOptions> options;
    std::string problem;
    if (session.rank() == 0) {
      try {
        options = next(first ? nullptr : &last);
        go = options ? 1 : 0;
      } catch (const InputError& e) {
        go = -1;
        problem = e.what();
      }
    }
    MPI_Bcast(&go, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (go == -1) {
      if (session.rank() == 0) throw InputError("", 0, problem);
      return {2, std::nullopt, "", 0};
    }
    if (go == 0) return last;
    if (session.rank() != 0) options.emplace();
    options->job = broadcast(options->job);
    options->output = broadcast(options->output);
    last = run_campaign(session, *options);
    first = false;
    // a refused campaign: rank 0 has thrown, workers got 2 (run_campaign), no one broadcasts
    if (session.rank() != 0 && last.status == 2) return last;
    int status = last.status;
    MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (status != 0) {
      last.status = status;
      return last;
    }
  }
}

}  // namespace rigid::campaign
