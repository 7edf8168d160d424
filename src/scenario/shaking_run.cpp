// scenario::run: one shaking run of a scene, in stages -- sleep (carry blocks at rest with a quiet
// ground instead of stepping), step, failure, rest -- over the contact summary the World publishes.
#include <algorithm>
#include <cmath>
#include <limits>

#include "resting_contacts.hpp"
#include "rigid/scenario/scene.hpp"

namespace rigid::scenario {
namespace {

class ShakingRun {
 public:
  ShakingRun(const Scene& scene, const GroundDrive& ground, const RunSettings& settings);
  RunOutcome run();

 private:
  enum class Verdict { go_on, non_finite, failed };
  bool sleep();
  void step();
  Verdict check_failure();
  bool check_rest();
  void finish();
  // the steps taken and how their contact solves went, from the World's counters
  void count_steps();
  double lowest_fixed_point() const;
  void observe_on_cadence() {
    if (settings_.observer && k_ % observe_every_ == 0) settings_.observer(world_);
  }

  const Scene& scene_;
  const GroundDrive& ground_;
  const RunSettings& settings_;
  dynamics::World world_;
  RunOutcome out_;
  const double dt_;
  const double motion_end_;
  long steps_ = 0;
  long observe_every_ = 1;
  long motion_end_step_ = 0;  // the first step boundary at or after the end of the motion
  const bool select_;
  bool fixed_z_constant_ = false;  // no vertical motion: the pedestals' lowest point never moves
  DriveAcceleration acceleration_;
  dynamics::ContactSummary contacts_;
  SupportScratch support_;
  std::vector<std::size_t> counts_, last_counts_;
  double lowest_fixed_ = 0;
  double rest_since_ = -1;           // at rest (absolute speeds: the rule without effect selection)
  double relative_rest_since_ = -1;  // at rest relative to the ground, since
  double still_since_ = -1;          // still (see check_rest), since
  double seen_h_ = 0, seen_z_ = 0;   // largest ground acceleration met so far (unit: m/s^2)
  long last_sliding_ = 0;
  long declined_interval_ = -1;  // drive interval where falling asleep was last declined
  bool done_ = false;
  long k_ = 0;                                        // steps taken or slept through
  Vec3 ground_start_{0, 0, 0}, ground_end_{0, 0, 0};  // ground velocity over the last step
};

ShakingRun::ShakingRun(const Scene& scene, const GroundDrive& ground, const RunSettings& settings)
    : scene_(scene),
      ground_(ground),
      settings_(settings),
      world_(scene.bodies, scene.law, settings.step),
      dt_(world_.dt()),
      motion_end_(ground.duration()),
      select_(settings.select_effects) {
  out_.dt_s = dt_;
  const double duration = settings.duration > 0 ? settings.duration : motion_end_ + settings.free_time;
  steps_ = static_cast<long>(std::ceil(duration / dt_ - 1e-9));
  observe_every_ = std::max(1L, std::lround(settings.observe_interval / dt_));
  motion_end_step_ = std::max(0L, static_cast<long>(std::ceil(motion_end_ / dt_)));
  while (double(motion_end_step_) * dt_ < motion_end_) ++motion_end_step_;
  while (motion_end_step_ > 0 && double(motion_end_step_ - 1) * dt_ >= motion_end_) --motion_end_step_;

  // which effects this scene and motion call for: skipping work whose result is known saves time
  ActiveEffects& fx = out_.effects;
  fx.selected = select_;
  fx.vertical_motion =
      std::any_of(ground.velocity.begin(), ground.velocity.end(), [](const Vec3& v) { return v.z() != 0; });
  const long n = static_cast<long>(scene.bodies.size());
  fx.pairs_total = n * (n - 1) / 2;
  fx.pairs_fixed_fixed = world_.fixed_fixed_pairs();
  dynamics::WorldEffects world_effects;
  world_effects.vertical_ground = !select_ || fx.vertical_motion;
  world_effects.distance_skin = select_;
  world_.set_effects(world_effects);
  if (select_) acceleration_ = DriveAcceleration(ground);
  fixed_z_constant_ = select_ && !fx.vertical_motion;
  lowest_fixed_ = lowest_fixed_point();
}

// The lowest point of the pedestals, for the study's failure rule.
double ShakingRun::lowest_fixed_point() const {
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scene_.bodies.size(); ++i) {
    if (!scene_.bodies[i].fixed) continue;
    for (const auto& v : world_.world_vertices(static_cast<int>(i))) lowest = std::min(lowest, v.z());
  }
  return lowest;
}

RunOutcome ShakingRun::run() {
  if (settings_.observer) settings_.observer(world_);
  while (k_ < steps_ && !done_) {
    if (sleep()) continue;
    step();
    const Verdict v = check_failure();
    if (v == Verdict::non_finite) return out_;
    if (v == Verdict::failed || check_rest()) break;
  }
  finish();
  return out_;
}

// Sleeping (with select_effects). While every free block rests on fixed blocks, the ground can
// start a block rocking or sliding only beyond the quasi-static threshold `ratio` g (physics.md
// §2; quasi_static_ratio). Free blocks then ride the ground rigidly over samples the stepper jumps
// (World::carry_with_ground: relative state frozen, restored at the wake):
//  - to the end of the motion, once they have been still for rest_time (no corner lifted or
//    gained, none slipping, every corner keeping still_load_fraction of its mean load: not
//    rocking, at most vibrating elastically well below uplift) and the rest of the record stays
//    below sleep_wake_fraction (1/2) of the threshold and of the largest acceleration already met.
//    A load applied suddenly overshoots a spring's static deflection at most twice, so no corner
//    unloads and no larger elastic tilt comes (resonance of the block's rocking mode on its
//    springs aside: docs/performance.md, "Effect selection, measured"). The outcome is then decided, and the trajectory
//    until then is the all-effects one.
//  - while the ground is exactly still (zero acceleration), once they have been at rest by the
//    run's own rule for rest_time. Not on a ground that moves at all: freezing a block at rest
//    under weak shaking discards an elastic response that, measured on the validation subset,
//    changed 2 of 960 outcomes when the strong part came.
// True when it slept (k_ advanced without steps).
bool ShakingRun::sleep() {
  if (!select_) return false;
  const double t = double(k_) * dt_;
  const bool at_rest_long = relative_rest_since_ >= 0 && t - relative_rest_since_ >= settings_.rest_time;
  const bool still_long = still_since_ >= 0 && t - still_since_ >= settings_.rest_time;
  if (!(at_rest_long || still_long) || acceleration_.interval(t) == declined_interval_) return false;
  const long j0 = acceleration_.interval(t);
  bool supported = false;
  world_.summarize_contacts(contacts_);
  const double ratio = quasi_static_ratio(world_, contacts_, scene_.law.friction, support_, supported);
  ActiveEffects& fx = out_.effects;
  if (supported) fx.sleep_possible = true;
  const double f = settings_.sleep_wake_fraction;
  const double g = settings_.step.gravity;
  long wake = -1;
  if (ratio > 0 && still_long && acceleration_.quiet_to_end(j0, f * seen_h_, f * seen_z_, f, ratio, g)) {
    wake = steps_;
  } else if (ratio > 0 && at_rest_long) {
    long j = j0;
    while (j < acceleration_.count() && acceleration_.quiet(j, 0, 0, f, ratio, g)) ++j;
    wake = j >= acceleration_.count() ? steps_ : static_cast<long>(std::floor(double(j) * acceleration_.dt() / dt_));
  }
  if (wake <= k_ + 1) {
    declined_interval_ = j0;
    return false;
  }
  ++fx.sleep_intervals;
  const long asleep_from = k_;
  while (k_ < wake) {
    long target = std::min(wake, steps_);
    if (k_ < motion_end_step_) target = std::min(target, motion_end_step_);
    if (settings_.observer) target = std::min(target, (k_ / observe_every_ + 1) * observe_every_);
    const double t0 = double(k_) * dt_, t1 = double(target) * dt_;
    world_.carry_with_ground(t1, ground_.displacement(t0, t1), ground_.at(t0), ground_.at(t1));
    k_ = target;
    observe_on_cadence();
    if (k_ >= motion_end_step_) {
      // asleep, the motion over: nothing more can happen
      out_.ended_at_rest = true;
      done_ = true;
      break;
    }
    if (k_ >= steps_) break;
  }
  fx.steps_skipped += k_ - asleep_from;
  fx.asleep_s += double(k_ - asleep_from) * dt_;
  out_.simulated_s = double(k_) * dt_;
  if (!fixed_z_constant_) lowest_fixed_ = lowest_fixed_point();
  return true;
}

void ShakingRun::step() {
  const double t0 = double(k_) * dt_;
  const double t1 = double(k_ + 1) * dt_;
  ground_start_ = ground_.at(t0);
  ground_end_ = ground_.at(t1);
  world_.step(dt_, ground_start_, ground_end_);
  ++k_;
  out_.simulated_s = t1;
  observe_on_cadence();
  out_.max_overlap_m = std::max(out_.max_overlap_m, world_.max_overlap());
}

ShakingRun::Verdict ShakingRun::check_failure() {
  if (!fixed_z_constant_) lowest_fixed_ = lowest_fixed_point();
  const auto& defs = scene_.bodies;
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) continue;
    const auto& s = world_.states()[i];
    if (!s.position.allFinite() || !s.orientation.coeffs().allFinite() || !s.velocity.allFinite() ||
        !s.angular_momentum.allFinite()) {
      out_.finite = false;
      count_steps();
      return Verdict::non_finite;
    }
    const double a = tilt(defs[i].orientation, s.orientation);
    out_.max_tilt_rad = std::max(out_.max_tilt_rad, a);
    const bool failed = scene_.failure.kind == FailureRule::Kind::below ? s.position.z() < lowest_fixed_
                                                                        : a > scene_.failure.tilt_angle;
    if (failed && !out_.overturned) {
      out_.overturned = true;
      out_.failure_time_s = out_.simulated_s;
      out_.failed_block = defs[i].name;
    }
  }
  return out_.overturned ? Verdict::failed : Verdict::go_on;
}

// True when the run can end: the motion is over and the blocks have rested for rest_time.
bool ShakingRun::check_rest() {
  const double t1 = out_.simulated_s;
  if (!select_) {
    if (t1 >= motion_end_ && at_rest(world_, settings_.rest_speed, settings_.rest_angular_speed)) {
      // after the motion, a scene at rest stays at rest: nothing more can happen
      if (rest_since_ < 0) rest_since_ = t1;
      if (t1 - rest_since_ >= settings_.rest_time) {
        out_.ended_at_rest = true;
        return true;
      }
    } else {
      rest_since_ = -1;
    }
    return false;
  }
  // the ground acceleration this step applied (unit: m/s^2)
  const Vec3 a = (ground_end_ - ground_start_) / dt_;
  seen_h_ = std::max(seen_h_, std::hypot(a.x(), a.y()));
  seen_z_ = std::max(seen_z_, std::abs(a.z()));
  // still: no subcontact gained, lost or slipping, every one well loaded
  world_.summarize_contacts(contacts_);
  loaded_counts(contacts_, counts_);
  const long sliding = world_.stats().sliding_steps;
  if (counts_ == last_counts_ && sliding == last_sliding_ &&
      corners_loaded(world_, contacts_, settings_.still_load_fraction)) {
    if (still_since_ < 0) still_since_ = t1;
  } else {
    still_since_ = -1;
  }
  std::swap(counts_, last_counts_);
  last_sliding_ = sliding;
  // at rest relative to the (possibly coasting) pedestals; once the motion is over and the blocks
  // have rested for rest_time, nothing more can happen
  if (at_rest_relative(world_, ground_end_, settings_.rest_speed, settings_.rest_angular_speed)) {
    if (relative_rest_since_ < 0) relative_rest_since_ = t1;
    if (k_ >= motion_end_step_ && t1 - relative_rest_since_ >= settings_.rest_time) {
      out_.ended_at_rest = true;
      return true;
    }
  } else {
    relative_rest_since_ = -1;
  }
  return false;
}

void ShakingRun::count_steps() {
  const auto& stats = world_.stats();
  out_.steps = stats.steps;
  out_.unconverged_steps = stats.unconverged_steps;
  out_.max_solver_sweeps = stats.max_solver_sweeps;
  out_.solver_solves = stats.solver_solves;
  out_.solver_sweeps = stats.solver_sweeps;
}

void ShakingRun::finish() {
  count_steps();
  for (std::size_t i = 0; i < scene_.bodies.size(); ++i) {
    if (!scene_.bodies[i].fixed) out_.max_slip_m = std::max(out_.max_slip_m, world_.slip()[i]);
  }
  const auto& stats = world_.stats();
  ActiveEffects& fx = out_.effects;
  for (const auto& p : world_.pairs()) fx.pairs_never_tested += p.tests == 0 ? 1 : 0;
  fx.pair_steps_culled = stats.pairs_skipped + stats.pairs_culled;
  fx.contact_steps = stats.contact_steps;
  fx.sliding_steps = stats.sliding_steps;
  fx.sliding = stats.sliding_steps > 0;
  fx.end = out_.overturned      ? ActiveEffects::End::failure
           : out_.ended_at_rest ? ActiveEffects::End::at_rest
                                : ActiveEffects::End::full_duration;
  fx.time_saved_s = std::max(0.0, double(steps_) * dt_ - out_.simulated_s);
  if (settings_.observer && k_ % observe_every_ != 0) settings_.observer(world_);
}

}  // namespace

RunOutcome run(const Scene& scene, const GroundDrive& ground, const RunSettings& settings) {
  return ShakingRun(scene, ground, settings).run();
}

}  // namespace rigid::scenario
