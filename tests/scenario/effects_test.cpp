// Effect selection (RunSettings::select_effects): a run that simulates only the effects
// its scene and motion call for gives the answers of the run that simulates all of them, and the
// report says what was skipped. Oracles: the all-effects run, rigid-block statics (g tan(alpha),
// physics.md §2), exact integrals of piecewise-linear velocities, the energy balance.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <vector>

#include "rigid/core/error.hpp"
#include "rigid/job/load.hpp"
#include "rigid/library/builders.hpp"

namespace rigid {
namespace {

constexpr double kHalfHeight = 0.5;  // 1 m tall blocks (m)
constexpr double kDepth = 0.5;       // (m)
constexpr double kSample = 0.005;    // record time step (s)

// A rectangular block of slenderness alpha on its pedestal, settled (physics.md §11 set-up).
const scenario::Scene& settled_block(double alpha) {
  static std::vector<std::pair<double, scenario::Scene>> cache;
  for (const auto& [a, s] : cache) {
    if (a == alpha) return s;
  }
  const auto s = library::block_on_pedestal(kHalfHeight * std::tan(alpha), kHalfHeight, kDepth);
  cache.emplace_back(alpha, scenario::equilibrate(s, dynamics::StepSettings{}));
  return cache.back().second;
}

// Ground velocity sampled every kSample s, the trapezoid integral of the acceleration a(t).
scenario::GroundDrive drive_from(double duration, const std::function<Vec3(double)>& a) {
  scenario::GroundDrive d;
  d.dt = kSample;
  const long n = std::lround(duration / kSample) + 1;
  d.velocity.assign(n, Vec3::Zero());
  for (long i = 1; i < n; ++i) {
    d.velocity[i] = d.velocity[i - 1] + 0.5 * kSample * (a((i - 1) * kSample) + a(i * kSample));
  }
  return d;
}

// One full sine of acceleration amplitude `amplitude_g` (in g) and period `period` along x from t0,
// on a ground otherwise still, except for a faint 3 Hz hum of `hum_g` from hum_from on.
std::function<Vec3(double)> pulse(double amplitude_g, double period, double t0, double hum_g, double hum_from = 0) {
  return [=](double t) {
    double ax = t >= hum_from ? hum_g * kGravity * std::sin(2 * kPi * 3.0 * (t - hum_from)) : 0.0;
    if (t >= t0 && t <= t0 + period) ax += amplitude_g * kGravity * std::sin(2 * kPi * (t - t0) / period);
    return Vec3(ax, 0, 0);
  };
}

scenario::RunOutcome run(const scenario::Scene& scene, const scenario::GroundDrive& drive, bool select,
                         scenario::RunSettings settings = {}) {
  settings.select_effects = select;
  return scenario::run(scene, drive, settings);
}

constexpr double kAlpha = 0.2;  // tan(alpha) = 0.2027; one-sine threshold at T = 0.5 s ~ 0.26 g

TEST(Effects, QuietStretchesSleepAndGiveTheSameAnswer) {
  // Still for 4 s, then a one-sine pulse of 0.42 g that rocks a block of alpha 0.3 (uplift near
  // g tan(alpha) = 0.31 g) without toppling it, then still again to 20 s.
  const auto drive = drive_from(20.0, pulse(0.42, 0.5, 4.0, 0.0));
  const auto& scene = settled_block(0.3);
  const auto all = run(scene, drive, false);
  const auto sel = run(scene, drive, true);
  ASSERT_FALSE(all.overturned);
  EXPECT_FALSE(sel.overturned);
  EXPECT_GT(all.max_tilt_rad, 0.02) << "the pulse must make the block rock (elastic tilt is ~1e-3 rad)";
  EXPECT_NEAR(sel.max_tilt_rad, all.max_tilt_rad, 0.01 * all.max_tilt_rad);
  EXPECT_FALSE(all.effects.selected);
  EXPECT_EQ(all.effects.sleep_intervals, 0);
  EXPECT_EQ(all.effects.steps_skipped, 0);
  EXPECT_TRUE(sel.effects.selected);
  EXPECT_TRUE(sel.effects.sleep_possible);
  // asleep before the pulse (still for 4 s) and after the block settles again
  EXPECT_GE(sel.effects.sleep_intervals, 2);
  EXPECT_GT(sel.effects.asleep_s, 10.0);
  EXPECT_LT(double(sel.steps), 0.5 * double(all.steps));
  EXPECT_EQ(sel.effects.steps_skipped, std::lround(sel.effects.asleep_s / sel.dt_s));
}

TEST(Effects, ABlockThatToppplesStillTopplesAtTheSameTimeAfterAQuietStart) {
  const auto drive = drive_from(12.0, pulse(0.42, 0.5, 4.0, 0.0));
  const auto& scene = settled_block(kAlpha);
  const auto all = run(scene, drive, false);
  const auto sel = run(scene, drive, true);
  ASSERT_TRUE(all.overturned);
  ASSERT_TRUE(sel.overturned);
  ASSERT_TRUE(all.failure_time_s && sel.failure_time_s);
  EXPECT_GT(*all.failure_time_s, 4.0);
  // within 1 % of the pulse period
  EXPECT_NEAR(*sel.failure_time_s, *all.failure_time_s, 0.005);
  EXPECT_GT(sel.effects.asleep_s, 2.5) << "the quiet start must be slept through";
  EXPECT_EQ(sel.effects.end, scenario::ActiveEffects::End::failure);
  EXPECT_NEAR(sel.effects.time_saved_s, 12.0 + 5.0 - *sel.failure_time_s, 2 * sel.dt_s);
}

TEST(Effects, NoSleepOnAMovingGroundBeforeTheOutcomeIsDecided) {
  // a faint hum from the start: the block is at rest, but the ground moves, so it stays awake and
  // the toppling run is the all-effects run bit for bit
  const auto drive = drive_from(12.0, pulse(0.40, 0.5, 4.0, 0.001));
  const auto& scene = settled_block(kAlpha);
  const auto all = run(scene, drive, false);
  const auto sel = run(scene, drive, true);
  ASSERT_TRUE(all.overturned && sel.overturned);
  EXPECT_EQ(std::memcmp(&*all.failure_time_s, &*sel.failure_time_s, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&all.max_tilt_rad, &sel.max_tilt_rad, sizeof(double)), 0);
  EXPECT_EQ(sel.effects.sleep_intervals, 0);
  EXPECT_EQ(sel.steps, all.steps);
}

TEST(Effects, VerticalWorkOnlyWithAVerticalComponent) {
  const auto& scene = settled_block(kAlpha);
  scenario::RunSettings s;
  s.duration = 0.2;
  const auto flat = run(scene, drive_from(1.0, pulse(0.05, 0.5, 0.0, 0)), true, s);
  EXPECT_FALSE(flat.effects.vertical_motion);
  const auto with_z = run(scene, drive_from(1.0, [](double t) { return Vec3(0, 0, 0.01 * std::sin(5 * t)); }), true, s);
  EXPECT_TRUE(with_z.effects.vertical_motion);
}

TEST(Effects, SelectionIsExactBeforeAnyBlockSleeps) {
  // A block dropped from 0.4 m (bounding spheres apart at first: the skin culls the pair), onto a
  // pedestal shaken horizontally: no vertical work, skin, slip bookkeeping, none may change a bit.
  scenario::Scene scene = library::block_on_pedestal(0.1, 0.5, 0.5);
  scene.bodies[1].position.z() += 0.4;
  const auto drive = drive_from(1.5, [](double t) { return Vec3(3.0 * std::sin(9 * t), 2.0 * std::cos(7 * t), 0); });
  scenario::RunSettings s;
  s.rest_time = 1e9;  // no sleeping, no early end
  std::vector<dynamics::BodyState> frames[2];
  scenario::RunOutcome out[2];
  for (int k = 0; k < 2; ++k) {
    s.observer = [&frames, k](const dynamics::World& w) { frames[k].push_back(w.states()[1]); };
    out[k] = run(scene, drive, k == 1, s);
  }
  ASSERT_EQ(frames[0].size(), frames[1].size());
  for (std::size_t f = 0; f < frames[0].size(); ++f) {
    const auto &x = frames[0][f], &y = frames[1][f];
    ASSERT_EQ(std::memcmp(x.position.data(), y.position.data(), 3 * sizeof(double)), 0) << "frame " << f;
    ASSERT_EQ(std::memcmp(x.orientation.coeffs().data(), y.orientation.coeffs().data(), 4 * sizeof(double)), 0)
        << "frame " << f;
    ASSERT_EQ(std::memcmp(x.velocity.data(), y.velocity.data(), 3 * sizeof(double)), 0) << "frame " << f;
    ASSERT_EQ(std::memcmp(x.angular_momentum.data(), y.angular_momentum.data(), 3 * sizeof(double)), 0)
        << "frame " << f;
  }
  EXPECT_EQ(std::memcmp(&out[0].max_tilt_rad, &out[1].max_tilt_rad, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&out[0].max_slip_m, &out[1].max_slip_m, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&out[0].max_overlap_m, &out[1].max_overlap_m, sizeof(double)), 0);
  EXPECT_GT(out[1].max_slip_m, 0) << "the test should exercise sliding";
  EXPECT_TRUE(out[1].effects.sliding);
  EXPECT_GT(out[1].effects.pair_steps_culled, 100) << "the falling block's pair should be culled";
  EXPECT_EQ(out[1].steps, out[0].steps);
}

TEST(Effects, FixedFixedPairsAreNeverTestedAndFarPairsAreCulled) {
  // two blocks on two pedestals 10 m apart: 6 pairs, 1 fixed-fixed, 3 always far apart
  const scenario::Scene& one = settled_block(kAlpha);
  scenario::Scene scene = one;
  for (auto body : one.bodies) {
    body.name += "_far";
    body.position.x() += 10.0;
    scene.bodies.push_back(body);
  }
  const auto drive = drive_from(8.0, pulse(0.22, 0.5, 3.0, 0.0));
  const auto all = run(scene, drive, false);
  const auto sel = run(scene, drive, true);
  for (const auto* r : {&all, &sel}) {
    EXPECT_EQ(r->effects.pairs_total, 6);
    EXPECT_EQ(r->effects.pairs_fixed_fixed, 1);
    EXPECT_EQ(r->effects.pairs_never_tested, 3);
  }
  EXPECT_GT(sel.effects.pair_steps_culled, 3 * sel.steps - 10);
  EXPECT_EQ(sel.overturned, all.overturned);
  EXPECT_NEAR(sel.max_tilt_rad, all.max_tilt_rad, 0.01 * all.max_tilt_rad);
  EXPECT_GT(sel.effects.sleep_intervals, 0) << "two blocks, each on its own pedestal, may sleep";
}

TEST(Effects, ARestingBlockIsAwakeBeforeTheGroundReachesGTanAlpha) {
  // Still for 2 s, then the acceleration ramps to 0.95 g tan(alpha) at 6 s and holds: the block
  // sleeps while it is still, and must be awake well before the quasi-static uplift acceleration.
  const double limit = kGravity * std::tan(kAlpha);
  auto accel = [limit](double t) { return Vec3(t < 2.0 ? 0.0 : std::min(t - 2.0, 4.0) / 4.0 * 0.95 * limit, 0, 0); };
  const auto drive = drive_from(8.0, accel);
  scenario::RunSettings s;
  s.free_time = 0;
  s.observe_interval = 0.01;
  std::vector<std::pair<double, long>> frames;  // (time, steps computed so far)
  s.observer = [&frames](const dynamics::World& w) { frames.emplace_back(w.time(), w.stats().steps); };
  const auto r = run(settled_block(kAlpha), drive, true, s);
  EXPECT_FALSE(r.overturned);
  bool slept = false;
  for (std::size_t f = 1; f < frames.size(); ++f) {
    const double t0 = frames[f - 1].first, t1 = frames[f].first;
    const bool stepped = frames[f].second > frames[f - 1].second;
    if (t1 < 2.0 && !stepped) slept = true;
    if (accel(t0).x() >= 0.6 * limit) {
      ASSERT_TRUE(stepped) << "asleep from " << t0 << " to " << t1 << " s at " << accel(t0).x() / limit
                           << " g tan(alpha)";
    }
  }
  EXPECT_TRUE(slept) << "the block should sleep on the still ground";
}

TEST(Effects, PedestalWorkWhileAsleepKeepsTheEnergyBalance) {
  // A gentle push (0.01 g for 0.5 s), then a steady 0.004 g: the block falls asleep and is
  // carried. The pedestal's work on a carried block is that of the force m (a_ground + g z) along
  // the ground's path, so E = kinetic + potential + elastic - pedestal work changes only by
  // m v_rel . dv_ground, v_rel the frozen velocity relative to the ground.
  const auto drive = drive_from(4.0, [](double t) {
    return Vec3(t < 0.5 ? 0.0 : t < 1.0 ? 0.01 * kGravity : 0.004 * kGravity, 0, 0);
  });
  scenario::RunSettings s;
  s.free_time = 0;
  s.observe_interval = 0.05;
  struct Frame {
    long steps;
    double energy;
    Vec3 block_velocity, ground_velocity;
  };
  std::vector<Frame> frames;
  s.observer = [&frames](const dynamics::World& w) {
    frames.push_back({w.stats().steps,
                      w.kinetic_energy() + w.potential_energy() + w.elastic_energy() - w.pedestal_work(),
                      w.states()[1].velocity, w.states()[0].velocity});
  };
  const auto& scene = settled_block(kAlpha);
  const auto r = run(scene, drive, true, s);
  ASSERT_GT(r.effects.asleep_s, 1.0);
  const double m = scene.bodies[1].shape.mass;
  int compared = 0;
  for (std::size_t f = 1; f < frames.size(); ++f) {
    if (frames[f].steps != frames[f - 1].steps) continue;  // stepped: not asleep
    ++compared;
    const Vec3 relative = frames[f - 1].block_velocity - frames[f - 1].ground_velocity;
    EXPECT_LT((frames[f].block_velocity - frames[f].ground_velocity - relative).norm(), 1e-12) << "frame " << f;
    const double expected = m * relative.dot(frames[f].ground_velocity - frames[f - 1].ground_velocity);
    EXPECT_NEAR(frames[f].energy - frames[f - 1].energy, expected, 1e-9) << "frame " << f;
  }
  EXPECT_GT(compared, 10);
  EXPECT_GT(frames.back().ground_velocity.x(), 0.1) << "the block must have been carried";
}

TEST(Effects, RunEndsWhenAtRestOnACoastingPedestal) {
  // The ground ends moving at 0.05 m/s: the all-effects rule (absolute speeds) never sees rest
  // and runs the free time out; the relative rule ends once the motion is over.
  const auto drive = drive_from(4.0, [](double t) { return Vec3(t >= 1.0 && t < 2.0 ? 0.05 : 0.0, 0, 0); });
  const auto& scene = settled_block(kAlpha);
  const auto all = run(scene, drive, false);
  const auto sel = run(scene, drive, true);
  EXPECT_FALSE(all.ended_at_rest);
  EXPECT_NEAR(all.simulated_s, 9.0, 2 * all.dt_s);
  EXPECT_TRUE(sel.ended_at_rest);
  EXPECT_EQ(sel.effects.end, scenario::ActiveEffects::End::at_rest);
  EXPECT_LE(sel.simulated_s, 4.0 + 0.5 + 2 * sel.dt_s);
  EXPECT_NEAR(sel.effects.time_saved_s, 9.0 - sel.simulated_s, 2 * sel.dt_s);
  EXPECT_EQ(sel.overturned, all.overturned);
}

TEST(Effects, StacksDoNotSleep) {
  // a block on a block: no simple threshold, so no sleeping, but the run still ends at rest
  scenario::Scene scene;
  scene.bodies.push_back(library::box_body("pedestal", Vec3(-0.4, -0.4, -0.2), Vec3(0.4, 0.4, 0), 2600, true));
  scene.bodies.push_back(library::box_body("lower", Vec3(-0.3, -0.3, 0), Vec3(0.3, 0.3, 0.3), 2600, false));
  scene.bodies.push_back(library::box_body("upper", Vec3(-0.2, -0.2, 0.3), Vec3(0.2, 0.2, 0.6), 2600, false));
  scene = scenario::equilibrate(scene, dynamics::StepSettings{});
  const auto r = run(scene, drive_from(3.0, [](double) { return Vec3::Zero(); }), true);
  EXPECT_FALSE(r.effects.sleep_possible);
  EXPECT_EQ(r.effects.sleep_intervals, 0);
  EXPECT_TRUE(r.ended_at_rest);
  EXPECT_FALSE(r.overturned);
}

TEST(Effects, TwoRunsAreBitIdentical) {
  const auto drive = drive_from(10.0, pulse(0.24, 0.5, 3.0, 0.002));
  const auto& scene = settled_block(kAlpha);
  const auto a = run(scene, drive, true);
  const auto b = run(scene, drive, true);
  EXPECT_EQ(std::memcmp(&a.max_tilt_rad, &b.max_tilt_rad, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&a.max_slip_m, &b.max_slip_m, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&a.simulated_s, &b.simulated_s, sizeof(double)), 0);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.effects.steps_skipped, b.effects.steps_skipped);
  EXPECT_EQ(a.overturned, b.overturned);
}

TEST(Effects, GroundDisplacementIsTheExactIntegral) {
  // velocity samples of t^2 every 0.1 s; the integral of the linear interpolation, by a fine
  // midpoint sum of at(t), before, inside and after the record (constant outside it)
  scenario::GroundDrive d;
  d.dt = 0.1;
  for (int i = 0; i <= 20; ++i) d.velocity.emplace_back(std::pow(0.1 * i, 2), -0.5 * i, 0.25);
  auto fine = [&d](double t0, double t1) {
    const int n = 200000;
    Vec3 sum = Vec3::Zero();
    for (int i = 0; i < n; ++i) sum += d.at(t0 + (i + 0.5) * (t1 - t0) / n);
    return Vec3(sum * (t1 - t0) / n);
  };
  for (const auto& [t0, t1] :
       std::vector<std::pair<double, double>>{{0.0, 2.0}, {0.03, 0.07}, {0.123, 1.777}, {-0.5, 0.35}, {1.5, 3.25}}) {
    EXPECT_LT((d.displacement(t0, t1) - fine(t0, t1)).norm(), 1e-8) << t0 << " " << t1;
  }
  EXPECT_EQ(d.displacement(1.0, 1.0), Vec3::Zero());
}

TEST(Effects, JobFileChoosesEffectsAndRefusesUnknownValues) {
  namespace fs = std::filesystem;
  const fs::path path =
      fs::path(RIGID_SOURCE_DIR) / "jobs" / ("test_effects_job_" + std::to_string(::getpid()) + ".toml");
  const std::string head =
      "[campaign]\nscales = \"0.1:0.2:0.1\"\n\n[[object]]\nscene = \"../models/demo/block_a02.toml\"\n\n"
      "[[record]]\nmotion = \"../waveforms/demo/stochastic_s1-X.AT2\"\n\n[run]\n";
  auto load = [&](const std::string& run) {
    std::ofstream(path) << head << run;
    return job::load_job(path.string());
  };
  EXPECT_TRUE(load("free_time_s = 5.0\n").run.select_effects);
  EXPECT_TRUE(load("effects = \"auto\"\n").run.select_effects);
  EXPECT_FALSE(load("effects = \"all\"\n").run.select_effects);
  try {
    load("free_time_s = 5.0\neffects = \"some\"\n");
    ADD_FAILURE() << "effects = \"some\" was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 12) << e.what();
    EXPECT_NE(std::string(e.what()).find("effects"), std::string::npos) << e.what();
  }
  fs::remove(path);
}

}  // namespace
}  // namespace rigid
