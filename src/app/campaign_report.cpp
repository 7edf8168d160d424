#include "campaign_report.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numeric>

#include "rigid/campaign/log.hpp"
#include "rigid/job/cost_estimate.hpp"

namespace rigid::app {
namespace {

namespace fs = std::filesystem;

// A scene that `rigid model import` wrote (NAME.toml with NAME.import.json beside it): a scanned
// rock, whose default rigid contact is not a measured physics.
bool is_imported_scan(const std::string& scene) {
  fs::path report(scene);
  report.replace_extension(".import.json");
  std::error_code ec;
  return fs::is_regular_file(report, ec);
}

// Where the object's physics comes from, one line: its calibration, or for a scanned rock on the
// default physics that it has none and how it could take one.
void print_physics_note(const io::Cube& cube) {
  if (cube.calibration) {
    const io::CubeCalibration& c = *cube.calibration;
    std::string weights;
    for (double w : c.weights) {
      char text[32];
      std::snprintf(text, sizeof text, "%.3g", w);
      weights += (weights.empty() ? "" : ", ") + std::string(text);
    }
    std::printf("physics: calibrated, %s (%zu member scenes, weights %s; headings random as for any field rock)\n",
                c.path.c_str(), c.weights.size(), weights.c_str());
    return;
  }
  for (std::size_t o = 0; o < cube.objects.size(); ++o) {
    const io::ObjectCube& oc = cube.objects[o];
    if (oc.variant > 0 || !is_imported_scan(oc.scene)) continue;
    fs::path beside(oc.scene);
    beside.replace_extension(".calibration.json");
    std::error_code ec;
    const std::string how = fs::is_regular_file(beside, ec)
                                ? "calibration = \"" + beside.string() + "\" (beside it)"
                                : "calibration = \".../NAME.calibration.json\" from `rigid shaketable calibrate` "
                                  "(its shake-table tests) or `rigid shaketable transfer CALIBRATION.json " +
                                      oc.scene + " --out DIR/NAME` (another rock's)";
    std::printf("note: %s is a scanned rock on uncalibrated default physics; its [[object]] can take %s\n",
                oc.name.c_str(), how.c_str());
  }
}

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

// One report: cells settled out of all cells (a denominator fixed for the whole run; a cell the
// stop rule infers counts as settled), the simulation rate since this run started and the time
// left at that rate for the cells still to simulate.
void print_progress(const campaign::ProgressReport& p, bool bar, const std::string& label) {
  const std::string lead = label.empty() ? "" : label + ": ";
  const double rate = p.elapsed_s > 0 ? double(p.done - p.done_at_start) / p.elapsed_s : 0.0;
  const double eta = p.remaining == 0 ? 0.0 : rate > 0 ? double(p.remaining) / rate : NAN;
  const double share = p.total > 0 ? double(p.settled) / double(p.total) : 1.0;
  if (bar) {
    const int width = 30;
    const int filled = std::clamp(int(width * share), 0, width);
    std::fprintf(stderr, "\r%s[%s%s] %ld/%ld cells (%.0f %%)  %.2f sim/s  ETA %s  failures %ld   ", lead.c_str(),
                 std::string(std::size_t(filled), '#').c_str(), std::string(std::size_t(width - filled), '.').c_str(),
                 p.settled, p.total, 100 * share, rate, format_duration(eta).c_str(), p.failures);
    if (p.final) std::fprintf(stderr, "\n");
  } else {
    campaign::log_status(
        "{}{}/{} cells settled ({:.0f} %; inferred cells count as settled), {} left to simulate, "
        "{:.2f} sim/s, ETA {}, failures {}",
        lead, p.settled, p.total, 100 * share, p.remaining, rate, format_duration(eta), p.failures);
  }
  std::fflush(stderr);
}

// Whether a person watches stderr: a terminal, or, for a rank that mpirun started, the terminal of
// mpirun itself (Open MPI relays the ranks' stderr through a pipe, which is never a terminal, while
// the user sees mpirun's). On another node the parent is Open MPI's daemon, whose stderr is no
// terminal: plain log lines there.
bool person_watches_stderr() {
  if (isatty(STDERR_FILENO)) return true;
  if (std::getenv("OMPI_COMM_WORLD_SIZE") == nullptr) return false;
  const std::string parent_stderr = "/proc/" + std::to_string(getppid()) + "/fd/2";
  const int fd = open(parent_stderr.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool terminal = isatty(fd) != 0;
  close(fd);
  return terminal;
}

// Tasks and core-hours of each object (and variant): what each row of the cube will cost. Many
// variants are summarised per object (least, median, most) rather than listed.
void print_object_costs(const job::Job& job, const job::CostEstimate& e) {
  constexpr int kListed = 40;
  std::printf("%-28s %10s %12s\n", "object", "tasks", "core-hours");
  if (int(job.objects.size()) <= kListed) {
    for (std::size_t o = 0; o < job.objects.size(); ++o) {
      std::printf("%-28s %10ld %12.3g\n", job.objects[o].label().c_str(), e.cells_per_object,
                  e.objects[o].core_seconds / 3600.0);
    }
    return;
  }
  const int V = job.variant_count();
  for (int b = 0; b < job.base_objects(); ++b) {
    std::vector<double> hours;
    for (int v = 0; v < V; ++v) hours.push_back(e.objects[std::size_t(b) * V + v].core_seconds / 3600.0);
    std::sort(hours.begin(), hours.end());
    std::printf("%-28s %10ld %12.3g  per variant: least %.3g, median %.3g, most %.3g core-hours (%d variants)\n",
                job.objects[std::size_t(b) * V].name.c_str(), e.cells_per_object * V,
                std::accumulate(hours.begin(), hours.end(), 0.0), hours.front(), hours[hours.size() / 2], hours.back(),
                V);
  }
}

}  // namespace

void attach_progress(campaign::CampaignOptions& options, const std::string& mode, double log_interval,
                     const std::string& label) {
  if (mode == "none") return;
  const bool bar = mode == "bar" || (mode == "auto" && person_watches_stderr());
  options.progress_interval = bar ? 0.25 : log_interval;
  options.on_progress = [bar, label](const campaign::ProgressReport& p) { print_progress(p, bar, label); };
}

void print_summary(const io::Cube& cube, const std::string& output) {
  std::printf("\nfragility cube: %s\n", std::filesystem::absolute(output).string().c_str());
  std::printf("overturning probability (mean over records; inferred cells count as overturned)\n");
  const std::size_t S = cube.scales_g.size();
  const std::size_t stride = (S + 15) / 16;             // at most 16 columns: every k-th scale of a long list
  const int width = cube.variants.count > 0 ? 24 : 20;  // room for "rock [v12]"
  std::printf("%-*s", width, "object \\ scale (g)");
  for (std::size_t s = 0; s < S; s += stride) std::printf("%7.3g", cube.scales_g[s]);
  std::printf("\n");
  if (stride > 1) std::printf("(every %zu-th scale of %zu)\n", stride, S);
  for (const auto& oc : cube.objects) {
    const std::vector<double> mean = io::mean_overturn_probability(cube, oc);  // per scale
    std::printf("%-*s", width, io::object_label(oc).c_str());                  // "rock [v3]" with variants
    for (std::size_t s = 0; s < S; s += stride) {
      if (std::isnan(mean[s])) {
        std::printf("%7s", "-");
      } else {
        std::printf("%7.2f", mean[s]);
      }
    }
    std::printf("\n");
  }
  print_physics_note(cube);
}

void print_failures(const io::Cube& cube) {
  const std::size_t S = cube.scales_g.size(), A = std::size_t(cube.rotations);
  constexpr int kListed = 10;
  int failed = 0;
  for (const auto& oc : cube.objects) {
    for (std::size_t i = 0; i < oc.outcome.size(); ++i) {
      if (static_cast<scenario::CellOutcome>(oc.outcome[i]) != scenario::CellOutcome::failed) continue;
      if (++failed == 1)
        std::printf("\nfailed cells (not counted above; the cube keeps failure_reason and failure_message):\n");
      if (failed > kListed) continue;
      const std::size_t r = i / (S * A), s = (i / A) % S, a = i % A;
      const std::string message = i < oc.failure_message.size() ? oc.failure_message[i] : std::string();
      std::printf("  %s, record %s, %.3g g, rotation %zu: %s\n", io::object_label(oc).c_str(),
                  cube.records[r].name.c_str(), cube.scales_g[s], a,
                  message.empty() ? "(no message)" : message.c_str());
    }
  }
  if (failed > kListed) std::printf("  ... and %d more (rigid export cells lists every cell)\n", failed - kListed);
}

void print_unconverged(const io::Cube& cube, int solver_max_sweeps) {
  long cells = 0, simulated = 0, steps = 0;
  for (const auto& oc : cube.objects) {
    for (const std::int32_t n : oc.unconverged_steps) {
      if (n < 0) continue;
      ++simulated;
      if (n == 0) continue;
      ++cells;
      steps += n;
    }
  }
  if (cells == 0) return;
  // one line: the count is a diagnostic of the rigid contact solver (docs/cube.md), not an error;
  // what such a step costs the answer, and where that is measured, goes with it
  std::printf(
      "\ncontact solver: %ld steps in %ld of %ld cells stopped at its %d-sweep cap; such a step keeps the last "
      "sweep's impulses, a small force error in that step (per cell: unconverged_steps; what it does to the "
      "outcomes: docs/accuracy.md, \"Convergence of the contact solve\"; --solver-max-sweeps raises the cap)\n",
      steps, cells, simulated, solver_max_sweeps);
}

int print_dry_run(const job::Job& job, const scenario::Model& model) {
  const job::CostEstimate e = job::estimate_cost(job, model);
  const long cells = e.cells;
  if (job.variants.count() > 0) {
    std::printf("job %s: %d objects x %d variants x %zu records x %zu scales x %d rotations = %ld tasks\n",
                job.path.c_str(), job.base_objects(), job.variant_count(), job.records.size(), job.scales_g.size(),
                job.rotations, cells);
  } else {
    std::printf("job %s: %zu objects x %zu records x %zu scales x %d rotations = %ld tasks\n", job.path.c_str(),
                job.objects.size(), job.records.size(), job.scales_g.size(), job.rotations, cells);
  }
  const double wall = e.core_seconds();
  std::printf(
      "at most %.4g s simulated, %.4g time steps; about %s of one core (%.3g core-hours) if every task ran to its "
      "end\n",
      e.simulated_total_s(), e.steps(), format_duration(wall).c_str(), wall / 3600.0);
  print_object_costs(job, e);
  std::printf("wall time if the ranks share the work evenly (one rank hands out tasks and simulates too):");
  for (int ranks : {2, 64, 500}) std::printf("  %d ranks %s", ranks, format_duration(wall / ranks).c_str());
  std::printf("\n(overturned runs stop early and the stop rule skips scales, so the real cost is lower)\n");
  return 0;
}

}  // namespace rigid::app
