#include "rigid/scenario/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rigid/geometry/polygon2d.hpp"

namespace rigid::scenario {

Vec3 GroundDrive::at(double t) const {
  if (velocity.empty()) return Vec3::Zero();
  if (t <= 0) return velocity.front();
  const double x = t / dt;
  const std::size_t k = static_cast<std::size_t>(x);
  if (k + 1 >= velocity.size()) return velocity.back();
  const double f = x - double(k);
  return (1 - f) * velocity[k] + f * velocity[k + 1];
}

Vec3 GroundDrive::displacement(double t0, double t1) const {
  Vec3 sum = Vec3::Zero();
  if (velocity.empty() || !(t1 > t0)) return sum;
  // constant velocity before the first sample and after the last
  if (t0 < 0) {
    const double b = std::min(t1, 0.0);
    sum += (b - t0) * velocity.front();
    t0 = b;
  }
  const double end = duration();
  if (t1 > end) {
    const double a = std::max(t0, end);
    sum += (t1 - a) * velocity.back();
    t1 = a;
  }
  if (!(t1 > t0)) return sum;
  // linear between samples: trapezoids are exact
  double a = t0;
  Vec3 va = at(t0);
  for (std::size_t j = static_cast<std::size_t>(t0 / dt) + 1; j < velocity.size() && double(j) * dt < t1; ++j) {
    const double b = double(j) * dt;
    sum += 0.5 * (b - a) * (va + velocity[j]);
    a = b;
    va = velocity[j];
  }
  sum += 0.5 * (t1 - a) * (va + at(t1));
  return sum;
}

GroundDrive ground_drive(const motion::GroundMotion& m) {
  const motion::GroundVelocity v = motion::ground_velocity(m);
  GroundDrive drive;
  drive.dt = v.dt;
  drive.velocity.resize(v.vx.size());
  for (std::size_t i = 0; i < v.vx.size(); ++i) drive.velocity[i] = Vec3(v.vx[i], v.vy[i], v.vz[i]);
  return drive;
}

double tilt(const Quat& initial, const Quat& current) {
  // initial vertical axis in body coordinates, carried to the world by the current pose
  const Vec3 axis = current * (initial.conjugate() * Vec3::UnitZ());
  return std::acos(std::clamp(axis.z(), -1.0, 1.0));
}

namespace {

bool at_rest(const dynamics::World& world, const RunSettings& s) {
  const auto& defs = world.bodies();
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) continue;
    if (world.states()[i].velocity.norm() > s.rest_speed) return false;
    if (world.angular_velocity(static_cast<int>(i)).norm() > s.rest_angular_speed) return false;
  }
  return true;
}

// At rest relative to the ground: the pedestals move with ground_velocity and do not rotate, so
// a block riding a coasting (or slowly moving) pedestal is at rest although its speed is not 0.
bool at_rest_relative(const dynamics::World& world, const Vec3& ground_velocity, double speed,
                      double angular_speed) {
  const auto& defs = world.bodies();
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) continue;
    if ((world.states()[i].velocity - ground_velocity).norm() > speed) return false;
    if (world.angular_velocity(static_cast<int>(i)).norm() > angular_speed) return false;
  }
  return true;
}

// Ground acceleration per interval of a drive (its velocity is linear between samples, so the
// acceleration is constant on each interval), with suffix maxima; zero outside the record.
class GroundAccelerationLevels {
 public:
  GroundAccelerationLevels() = default;
  explicit GroundAccelerationLevels(const GroundDrive& g) : dt_(g.dt) {
    for (std::size_t j = 0; j + 1 < g.velocity.size(); ++j) {
      const Vec3 a = (g.velocity[j + 1] - g.velocity[j]) / g.dt;
      horizontal_.push_back(std::hypot(a.x(), a.y()));
      vertical_.push_back(std::abs(a.z()));
    }
    suffix_h_ = horizontal_;
    suffix_z_ = vertical_;
    for (std::size_t j = suffix_h_.size(); j-- > 1;) {
      suffix_h_[j - 1] = std::max(suffix_h_[j - 1], suffix_h_[j]);
      suffix_z_[j - 1] = std::max(suffix_z_[j - 1], suffix_z_[j]);
    }
  }
  long count() const { return static_cast<long>(horizontal_.size()); }
  long interval(double t) const { return t <= 0 ? 0 : static_cast<long>(t / dt_); }
  double dt() const { return dt_; }
  // Whether interval j stays within the levels: horizontal at most level_h and at most `fraction`
  // of the quasi-static threshold ratio (g - |a_z|) (a downward ground acceleration lightens the
  // blocks, so the threshold falls with the effective gravity), vertical at most level_z and
  // fraction g.
  bool quiet(long j, double level_h, double level_z, double fraction, double ratio, double g) const {
    if (j < 0 || j >= count()) return true;
    return within(horizontal_[std::size_t(j)], vertical_[std::size_t(j)], level_h, level_z, fraction, ratio, g);
  }
  // The same for every interval from j to the end of the record (a sufficient test: the largest
  // horizontal against the smallest effective gravity).
  bool quiet_to_end(long j, double level_h, double level_z, double fraction, double ratio, double g) const {
    if (j < 0) j = 0;
    if (j >= count()) return true;
    return within(suffix_h_[std::size_t(j)], suffix_z_[std::size_t(j)], level_h, level_z, fraction, ratio, g);
  }

 private:
  static bool within(double ah, double az, double level_h, double level_z, double fraction, double ratio, double g) {
    return az <= level_z && az <= fraction * g && ah <= level_h && ah <= fraction * ratio * (g - az);
  }
  double dt_ = 1;
  std::vector<double> horizontal_, vertical_;  // |a_h|, |a_z| per interval (unit: m/s^2)
  std::vector<double> suffix_h_, suffix_z_;        // their maxima from each interval to the end
};

// Points of the support polygons and the scratch of their hull, reused from call to call.
struct SupportScratch {
  std::vector<geometry::Point2> points;
  std::vector<int> hull, order;
};

// Smallest distance from c to an edge of the convex hull of `scratch.points` (unit: m), 0 when c
// is outside it or the hull is degenerate.
double inner_distance(SupportScratch& scratch, const geometry::Point2& c) {
  geometry::convex_hull_2d(scratch.points, scratch.hull, scratch.order, 0.0);
  const auto& hull = scratch.hull;
  const auto& points = scratch.points;
  if (hull.size() < 3) return 0;
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const auto& a = points[hull[k]];
    const auto& b = points[hull[(k + 1) % hull.size()]];
    const double len = (b - a).norm();
    if (!(len > 0)) return 0;
    d = std::min(d, geometry::turn(a, b, c) / len);  // > 0 inside a counter-clockwise hull
  }
  return std::max(d, 0.0);
}

// The smallest quasi-static acceleration, as a fraction of the (effective) gravity, at which a
// free block could start to move: for each free block, rocking needs a/g > d/h (d: horizontal
// distance from its centroid to the nearest edge of the support polygon of its current
// subcontacts, h: centroid height above the lowest of them; physics.md §2, g tan(alpha) for a
// rectangular block), sliding needs a/g > tan(atan(mu) - theta) on contacts tilted by theta.
// Returns 0 when some free block does not rest on fixed blocks only (a stack: its threshold is
// not this simple), with `supported` false.
double quasi_static_ratio(const dynamics::World& world, double friction, SupportScratch& scratch,
                          bool& supported) {
  auto& points = scratch.points;
  const auto& defs = world.bodies();
  supported = true;
  double ratio = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) continue;
    points.clear();
    double lowest = std::numeric_limits<double>::infinity();
    double min_up = 1;  // smallest vertical component of the contact normals
    for (const auto& p : world.pairs()) {
      if (p.a != int(i) && p.b != int(i)) continue;
      // in contact: some subcontact loaded (the rigid model also keeps open ones near a contact)
      bool loaded = false;
      for (std::size_t k = 0; k < p.points.size() && !loaded; ++k) loaded = world.subcontact_load(p, k) > 0;
      if (!loaded) continue;
      const int other = p.a == int(i) ? p.b : p.a;
      if (!defs[other].fixed) {
        supported = false;
        return 0;
      }
      const double up = p.a == int(i) ? -p.normal.z() : p.normal.z();  // normal points a -> b
      min_up = std::min(min_up, up);
      for (std::size_t k = 0; k < p.points.size(); ++k) {
        if (!(world.subcontact_load(p, k) > 0)) continue;  // an open (rigid model) contact
        const auto& pt = p.points[k];
        points.emplace_back(pt.point.x(), pt.point.y());
        lowest = std::min(lowest, pt.point.z());
      }
    }
    const Vec3& c = world.states()[i].position;
    if (points.size() < 3 || !(min_up > 0)) return 0;
    const double h = c.z() - lowest;
    if (!(h > 0)) return 0;
    const double d = inner_distance(scratch, geometry::Point2(c.x(), c.y()));
    const double slope = std::atan(friction) - std::acos(std::min(min_up, 1.0));
    if (!(d > 0) || !(slope > 0)) return 0;
    ratio = std::min({ratio, d / h, std::tan(slope)});
  }
  return std::isfinite(ratio) ? ratio : 0.0;
}

// Contact signature of the free blocks: their loaded subcontacts in each pair. Unchanged from step
// to step while no block lifts a corner or gains a contact.
void contact_counts(const dynamics::World& world, std::vector<std::size_t>& out) {
  out.clear();
  for (const auto& p : world.pairs()) {
    std::size_t loaded = 0;
    for (std::size_t k = 0; k < p.points.size(); ++k) loaded += world.subcontact_load(p, k) > 0 ? 1 : 0;
    out.push_back(loaded);
  }
}

// Whether every loaded subcontact of every free block carries at least `fraction` of its block's
// mean subcontact load (World::subcontact_load: the elastic part K_N d^1.5 of the penalty model,
// physics.md §3, or the rigid model's normal impulse over the step). A rocking block unloads its
// heel corners to zero before they lift; an elastic vibration of the block on its contact
// springs, or a horizontal push, unloads them in proportion to its amplitude, the whole way at
// uplift.
bool corners_loaded(const dynamics::World& world, double fraction) {
  const auto& defs = world.bodies();
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (defs[i].fixed) continue;
    double least = std::numeric_limits<double>::infinity(), sum = 0;
    long count = 0;
    for (const auto& p : world.pairs()) {
      if ((p.a != int(i) && p.b != int(i)) || p.subs.empty()) continue;
      for (std::size_t k = 0; k < p.points.size(); ++k) {
        const double f = world.subcontact_load(p, k);
        if (!(f > 0)) continue;  // an open (rigid model) contact
        least = std::min(least, f);
        sum += f;
        ++count;
      }
    }
    if (count == 0 || !(least >= fraction * sum / double(count))) return false;
  }
  return true;
}

}  // namespace

RunOutcome run(const Scene& scene, const GroundDrive& ground, const RunSettings& settings) {
  dynamics::World world(scene.bodies, scene.law, settings.step);
  RunOutcome out;
  const double dt = world.dt();
  out.dt = dt;
  const double motion_end = ground.duration();
  const double duration = settings.duration > 0 ? settings.duration : motion_end + settings.free_time;
  const long steps = static_cast<long>(std::ceil(duration / dt - 1e-9));
  const auto& defs = scene.bodies;
  const long observe_every = std::max(1L, std::lround(settings.observe_interval / dt));
  // the first step boundary at or after the end of the motion
  long motion_end_step = std::max(0L, static_cast<long>(std::ceil(motion_end / dt)));
  while (double(motion_end_step) * dt < motion_end) ++motion_end_step;
  while (motion_end_step > 0 && double(motion_end_step - 1) * dt >= motion_end) --motion_end_step;

  // which effects this scene and motion call for (issue 6)
  const bool select = settings.select_effects;
  ActiveEffects& fx = out.effects;
  fx.selected = select;
  fx.vertical_motion = std::any_of(ground.velocity.begin(), ground.velocity.end(),
                                   [](const Vec3& v) { return v.z() != 0; });
  const long n = static_cast<long>(defs.size());
  fx.pairs_total = n * (n - 1) / 2;
  fx.pairs_fixed_fixed = world.fixed_fixed_pairs();
  dynamics::WorldEffects world_effects;
  world_effects.vertical_ground = !select || fx.vertical_motion;
  world_effects.distance_skin = select;
  world.set_effects(world_effects);
  const GroundAccelerationLevels acceleration = select ? GroundAccelerationLevels(ground) : GroundAccelerationLevels();
  SupportScratch support;
  std::vector<std::size_t> counts, last_counts;
  const double g = settings.step.gravity;

  // the lowest point of the pedestals, for the study's failure rule; without vertical motion
  // their z never changes, so it is found once
  auto lowest_fixed_point = [&] {
    double lowest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < defs.size(); ++i) {
      if (!defs[i].fixed) continue;
      for (const auto& v : world.world_vertices(static_cast<int>(i))) lowest = std::min(lowest, v.z());
    }
    return lowest;
  };
  const bool fixed_z_constant = select && !fx.vertical_motion;
  double lowest_fixed = lowest_fixed_point();

  double rest_since = -1;           // at rest (absolute speeds: the rule without effect selection)
  double relative_rest_since = -1;  // at rest relative to the ground, since
  double still_since = -1;          // still (see below), since
  double seen_h = 0, seen_z = 0;    // largest ground acceleration met so far (unit: m/s^2)
  long last_sliding = 0;
  long declined_interval = -1;      // drive interval where falling asleep was last declined
  bool done = false;
  long k = 0;
  if (settings.observer) settings.observer(world);
  while (k < steps && !done) {
    // Sleeping (with select_effects). While every free block rests on fixed blocks, the ground can
    // start a block rocking or sliding only beyond the quasi-static threshold `ratio` g
    // (physics.md §2; quasi_static_ratio). Free blocks then ride the ground rigidly over samples
    // the stepper jumps (World::carry_with_ground: relative state frozen, restored at the wake):
    //  - to the end of the motion, once they have been still for rest_time (no corner lifted or
    //    gained, none slipping, every corner keeping still_load_fraction of its mean load: not
    //    rocking, at most vibrating elastically well below uplift) and the rest of the record stays
    //    below sleep_wake_fraction (1/2) of the threshold and of the largest acceleration already
    //    met. A load applied suddenly overshoots a spring's static deflection at most twice, so no
    //    corner unloads and no larger elastic tilt comes (resonance of the block's rocking mode on
    //    its springs aside: README, Effect selection). The outcome is then decided, and the
    //    trajectory until then is the all-effects one.
    //  - while the ground is exactly still (zero acceleration), once they have been at rest by the
    //    run's own rule for rest_time. Not on a ground that moves at all: freezing a block at rest
    //    under weak shaking discards an elastic response that, measured on the validation subset,
    //    changed 2 of 960 outcomes when the strong part came.
    const double t = double(k) * dt;
    const bool at_rest_long = relative_rest_since >= 0 && t - relative_rest_since >= settings.rest_time;
    const bool still_long = still_since >= 0 && t - still_since >= settings.rest_time;
    if (select && (at_rest_long || still_long) && acceleration.interval(t) != declined_interval) {
      const long j0 = acceleration.interval(t);
      bool supported = false;
      const double ratio = quasi_static_ratio(world, scene.law.friction, support, supported);
      if (supported) fx.sleep_possible = true;
      const double f = settings.sleep_wake_fraction;
      long wake = -1;
      if (ratio > 0 && still_long && acceleration.quiet_to_end(j0, f * seen_h, f * seen_z, f, ratio, g)) {
        wake = steps;
      } else if (ratio > 0 && at_rest_long) {
        long j = j0;
        while (j < acceleration.count() && acceleration.quiet(j, 0, 0, f, ratio, g)) ++j;
        wake = j >= acceleration.count() ? steps : static_cast<long>(std::floor(double(j) * acceleration.dt() / dt));
      }
      if (wake <= k + 1) {
        declined_interval = j0;
      } else {
        ++fx.sleep_intervals;
        const long asleep_from = k;
        while (k < wake) {
          long target = std::min(wake, steps);
          if (k < motion_end_step) target = std::min(target, motion_end_step);
          if (settings.observer) target = std::min(target, (k / observe_every + 1) * observe_every);
          const double t0 = double(k) * dt, t1 = double(target) * dt;
          world.carry_with_ground(t1, ground.displacement(t0, t1), ground.at(t0), ground.at(t1));
          k = target;
          if (settings.observer && k % observe_every == 0) settings.observer(world);
          if (k >= motion_end_step) {
            // asleep, the motion over: nothing more can happen
            out.ended_at_rest = true;
            done = true;
            break;
          }
          if (k >= steps) break;
        }
        fx.steps_skipped += k - asleep_from;
        fx.asleep_s += double(k - asleep_from) * dt;
        out.simulated = double(k) * dt;
        if (!fixed_z_constant) lowest_fixed = lowest_fixed_point();
        continue;
      }
    }

    const double t0 = double(k) * dt;
    const double t1 = double(k + 1) * dt;
    const Vec3 ground_start = ground.at(t0);
    const Vec3 ground_end = ground.at(t1);
    world.step(dt, ground_start, ground_end);
    ++k;
    out.simulated = t1;
    if (settings.observer && k % observe_every == 0) settings.observer(world);
    out.max_overlap = std::max(out.max_overlap, world.max_overlap());

    if (!fixed_z_constant) lowest_fixed = lowest_fixed_point();
    for (std::size_t i = 0; i < defs.size(); ++i) {
      if (defs[i].fixed) continue;
      const auto& s = world.states()[i];
      if (!s.position.allFinite() || !s.orientation.coeffs().allFinite() ||
          !s.velocity.allFinite() || !s.angular_momentum.allFinite()) {
        out.finite = false;
        out.steps = world.stats().steps;
        return out;
      }
      const double a = tilt(defs[i].orientation, s.orientation);
      out.max_tilt = std::max(out.max_tilt, a);
      const bool failed = scene.failure.kind == FailureRule::Kind::below
                              ? s.position.z() < lowest_fixed
                              : a > scene.failure.tilt_angle;
      if (failed && !out.overturned) {
        out.overturned = true;
        out.failure_time = t1;
        out.failed_block = defs[i].name;
      }
    }
    if (out.overturned) break;
    if (select) {
      // the ground acceleration this step applied (unit: m/s^2)
      const Vec3 a = (ground_end - ground_start) / dt;
      const double ah = std::hypot(a.x(), a.y()), az = std::abs(a.z());
      seen_h = std::max(seen_h, ah);
      seen_z = std::max(seen_z, az);
      // still: no subcontact gained, lost or slipping, every one well loaded
      contact_counts(world, counts);
      const long sliding = world.stats().sliding_steps;
      if (counts == last_counts && sliding == last_sliding && corners_loaded(world, settings.still_load_fraction)) {
        if (still_since < 0) still_since = t1;
      } else {
        still_since = -1;
      }
      std::swap(counts, last_counts);
      last_sliding = sliding;
      // at rest relative to the (possibly coasting) pedestals; once the motion is over and the
      // blocks have rested for rest_time, nothing more can happen
      if (at_rest_relative(world, ground_end, settings.rest_speed, settings.rest_angular_speed)) {
        if (relative_rest_since < 0) relative_rest_since = t1;
        if (k >= motion_end_step && t1 - relative_rest_since >= settings.rest_time) {
          out.ended_at_rest = true;
          break;
        }
      } else {
        relative_rest_since = -1;
      }
    } else if (t1 >= motion_end && at_rest(world, settings)) {
      // after the motion, a scene at rest stays at rest: nothing more can happen
      if (rest_since < 0) rest_since = t1;
      if (t1 - rest_since >= settings.rest_time) {
        out.ended_at_rest = true;
        break;
      }
    } else {
      rest_since = -1;
    }
  }
  out.steps = world.stats().steps;
  for (std::size_t i = 0; i < defs.size(); ++i) {
    if (!defs[i].fixed) out.max_slip = std::max(out.max_slip, world.slip()[i]);
  }
  const auto& stats = world.stats();
  for (const auto& p : world.pairs()) fx.pairs_never_tested += p.tests == 0 ? 1 : 0;
  fx.pair_steps_culled = stats.pairs_skipped + stats.pairs_culled;
  fx.contact_steps = stats.contact_steps;
  fx.sliding_steps = stats.sliding_steps;
  fx.sliding = stats.sliding_steps > 0;
  fx.end = out.overturned ? ActiveEffects::End::failure
                          : out.ended_at_rest ? ActiveEffects::End::at_rest : ActiveEffects::End::full_duration;
  fx.time_saved_s = std::max(0.0, double(steps) * dt - out.simulated);
  if (settings.observer && k % observe_every != 0) settings.observer(world);
  return out;
}

Scene equilibrate(const Scene& scene, const dynamics::StepSettings& step, double max_time,
                  double local_damping) {
  dynamics::StepSettings s = step;
  s.local_damping = local_damping;
  dynamics::World world(scene.bodies, scene.law, s);
  RunSettings rest;
  const double dt = world.dt();
  double rest_since = -1;
  // settle until at rest for a while, checked with tight thresholds
  rest.rest_speed = 1e-6;
  rest.rest_angular_speed = 1e-6;
  for (double t = 0; t < max_time; t += dt) {
    world.step(dt, Vec3::Zero(), Vec3::Zero());
    if (at_rest(world, rest)) {
      if (rest_since < 0) rest_since = t;
      if (t - rest_since > 0.2) break;
    } else {
      rest_since = -1;
    }
  }
  Scene out = scene;
  for (std::size_t i = 0; i < out.bodies.size(); ++i) {
    if (out.bodies[i].fixed) continue;
    out.bodies[i].position = world.states()[i].position;
    out.bodies[i].orientation = world.states()[i].orientation;
    out.bodies[i].velocity.setZero();
    out.bodies[i].angular_velocity.setZero();
  }
  return out;
}

}  // namespace rigid::scenario
