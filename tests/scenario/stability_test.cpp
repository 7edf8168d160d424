// Hard cases stay numerically stable (CTest label `stability`, from the file name). Every case is
// built in code and stepped here, step by step, by one checker that asserts after EVERY step:
//
//  * finite: every position, orientation, velocity and angular momentum is finite;
//  * unit quaternions: | |q| - 1 | <= 1e-12 for the stored orientation of every block;
//  * bounded penetration: for every pair in contact, the deepest subcontact indentation (what the
//    contact forces see; World::max_overlap is their maximum over all pairs) is below 1 % of the
//    pair's size, the smaller of the two blocks' sizes, where the size of a block is its smallest
//    width across its own faces (min over its faces of the extent of its vertices along the face
//    normal: a box's shortest edge, a slab's or wedge's thickness). The common-plane overlap
//    (PairContact::overlap) is not used: along a normal tilted by a few 1e-5 rad it measures the
//    large block's lever (1e-5 m for a pebble on a 10 m pedestal), not a penetration;
//  * energy balance: E(t) - E(0) <= W(t) + tol, where E = kinetic + gravitational potential +
//    elastic energy of the contact springs (World::elastic_energy), W = World::pedestal_work (the
//    work the moving pedestals did on the free blocks) and tol = 1e-3 M g L, M the total free mass
//    and L the largest extent of any free block. Contact damping and friction only remove energy,
//    so the stored-plus-mechanical energy can never exceed what the pedestals put in; 1e-3 M g L
//    leaves room for the bounded O(dt^2) energy error of the explicit integrator only;
//
// and, running the case a second time, determinism: the two final states are bit-identical.
// The printed line per case gives the step, the largest overlap / size, the smallest energy margin
// (tol + W - (E - E0)) as a fraction of tol, and the wall time of one run.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "rigid/library/builders.hpp"
#include "support/rng.hpp"

namespace rigid {
namespace {

using dynamics::BodyDef;
using geometry::convex_hull;

constexpr double kDensity = 2600;

// ---------------------------------------------------------------------------------------------
// scene building

BodyDef hull_body(const std::string& name, const std::vector<Vec3>& points, bool fixed) {
  return library::body_from_soup(name, convex_hull(points), kDensity, fixed);
}

BodyDef box(const std::string& name, const Vec3& lo, const Vec3& hi, bool fixed) {
  return library::box_body(name, lo, hi, kDensity, fixed);
}

// the 8 corners of the box [lo, hi]
std::vector<Vec3> box_points(const Vec3& lo, const Vec3& hi) {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i) {
    p.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  }
  return p;
}

// Size of a block: its smallest width across its own faces, min over faces f of
// (max - min of n_f . v over its vertices) (unit: m): the shortest edge of a box, the thickness of
// a slab or wedge (an upper bound of the true minimum width, exact for boxes and prisms).
double smallest_width(const BodyDef& body) {
  double out = std::numeric_limits<double>::infinity();
  for (const auto& f : body.shape.faces) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec3& v : body.shape.vertices) {
      lo = std::min(lo, f.normal.dot(v));
      hi = std::max(hi, f.normal.dot(v));
    }
    out = std::min(out, hi - lo);
  }
  return out;
}

// largest extent of a block along its principal axes (unit: m)
double largest_extent(const BodyDef& body) {
  double out = 0;
  for (int axis = 0; axis < 3; ++axis) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec3& v : body.shape.vertices) {
      lo = std::min(lo, v[axis]);
      hi = std::max(hi, v[axis]);
    }
    out = std::max(out, hi - lo);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// ground motions: analytic velocities sampled into a GroundDrive

scenario::GroundDrive sampled(double duration, double sample_dt, const std::function<Vec3(double)>& v) {
  scenario::GroundDrive drive;
  drive.dt = sample_dt;
  const long n = std::lround(duration / sample_dt);
  drive.velocity.reserve(static_cast<std::size_t>(n + 1));
  for (long i = 0; i <= n; ++i) drive.velocity.push_back(v(double(i) * sample_dt));
  return drive;
}

// one-sine acceleration pulse a(t) = A sin(2 pi (t - t0) / T) on [t0, t0 + T] (A in m/s^2)
Vec3 one_sine(double t, double amplitude, double period, const Vec3& direction, double t0 = 0) {
  const double s = t - t0;
  if (s <= 0 || s >= period) return Vec3::Zero();
  return amplitude * period / (2 * kPi) * (1 - std::cos(2 * kPi * s / period)) * direction;
}

// harmonic velocity of peak acceleration `amplitude` (m/s^2) at `frequency` (Hz), switched on and
// off by half-cosine ramps of one period each, so the velocity starts and ends at zero
Vec3 sine(double t, double amplitude, double frequency, const Vec3& direction, double t0, double t1, double phase = 0) {
  if (t <= t0 || t >= t1) return Vec3::Zero();
  const double period = 1.0 / frequency;
  double envelope = 1;
  if (t - t0 < period) envelope = 0.5 * (1 - std::cos(kPi * (t - t0) / period));
  if (t1 - t < period) envelope = std::min(envelope, 0.5 * (1 - std::cos(kPi * (t1 - t) / period)));
  const double w = 2 * kPi * frequency;
  return envelope * amplitude / w * std::sin(w * (t - t0) + phase) * direction;
}

// ---------------------------------------------------------------------------------------------
// the checker

struct Case {
  std::string name;
  std::vector<BodyDef> bodies;
  contact::ContactLaw law;
  dynamics::StepSettings step;  // dt = 0: the automatic step
  scenario::GroundDrive ground;
  double duration = 1;  // unit: s
  /// Stop once a free block's centroid is below the lowest vertex of every fixed block (the
  /// study's failure rule): it has fallen off and only free fall is left.
  bool stop_when_fallen = true;
};

struct Outcome {
  long steps = 0;
  double dt = 0;
  double simulated = 0;
  double max_overlap_ratio = 0;  ///< largest overlap / size of its pair
  double max_overlap = 0;        ///< largest World::max_overlap() (unit: m)
  double min_energy_margin = 0;  ///< smallest (tol + W - (E - E0)) / tol
  double energy_tol = 0;         ///< unit: J
  double pedestal_work = 0;      ///< at the end (unit: J)
  double max_quat_error = 0;
  std::size_t max_subcontacts = 0;  ///< most subcontacts of one pair at once
  double wall = 0;                  ///< unit: s
  bool fell = false;
  std::vector<dynamics::BodyState> final_states;
};

// Steps the case and checks every step; gtest failures (fatal) stop it at the first violation.
void run_checked(const Case& c, Outcome& out) {
  const auto start = std::chrono::steady_clock::now();
  dynamics::World world(c.bodies, c.law, c.step);
  const auto& defs = world.bodies();
  const std::size_t n = defs.size();
  std::vector<double> size(n);
  double free_mass = 0, free_length = 0;
  for (std::size_t i = 0; i < n; ++i) {
    size[i] = smallest_width(defs[i]);
    if (defs[i].fixed) continue;
    free_mass += defs[i].shape.mass;
    free_length = std::max(free_length, largest_extent(defs[i]));
  }
  const double tol = 1e-3 * free_mass * world.settings().gravity * free_length;
  out.energy_tol = tol;
  const double dt = world.dt();
  out.dt = dt;
  const double e0 = world.kinetic_energy() + world.potential_energy() + world.elastic_energy();
  const long steps = static_cast<long>(std::ceil(c.duration / dt - 1e-9));
  out.min_energy_margin = std::numeric_limits<double>::infinity();

  for (long k = 0; k < steps; ++k) {
    const double t0 = double(k) * dt, t1 = double(k + 1) * dt;
    world.step(dt, c.ground.at(t0), c.ground.at(t1));
    out.steps = k + 1;
    out.simulated = t1;
    const auto& states = world.states();

    // finite, unit quaternions
    for (std::size_t i = 0; i < n; ++i) {
      const auto& s = states[i];
      ASSERT_TRUE(s.position.allFinite() && s.orientation.coeffs().allFinite() && s.velocity.allFinite() &&
                  s.angular_momentum.allFinite())
          << c.name << ": block " << defs[i].name << " not finite at t = " << t1;
      const double q_error = std::abs(s.orientation.norm() - 1.0);
      out.max_quat_error = std::max(out.max_quat_error, q_error);
      ASSERT_LE(q_error, 1e-12) << c.name << ": |q| of " << defs[i].name << " at t = " << t1;
    }

    // penetration, pair by pair, against the smaller block's size
    for (const auto& p : world.pairs()) {
      if (p.overlap <= 0) continue;
      double deepest = 0;
      for (const auto& pt : p.points) deepest = std::max(deepest, pt.overlap);
      out.max_subcontacts = std::max(out.max_subcontacts, p.points.size());
      const double ratio = deepest / std::min(size[p.a], size[p.b]);
      out.max_overlap_ratio = std::max(out.max_overlap_ratio, ratio);
      ASSERT_LT(ratio, 0.01) << c.name << ": overlap " << deepest << " m between " << defs[p.a].name << " and "
                             << defs[p.b].name << " at t = " << t1;
    }
    out.max_overlap = std::max(out.max_overlap, world.max_overlap());

    // energy balance
    const double e = world.kinetic_energy() + world.potential_energy() + world.elastic_energy();
    const double margin = (tol + world.pedestal_work() - (e - e0)) / tol;
    out.min_energy_margin = std::min(out.min_energy_margin, margin);
    ASSERT_GE(margin, 0.0) << c.name << ": energy " << e - e0 << " J above the start exceeds the "
                           << "pedestal work " << world.pedestal_work() << " J + tol " << tol << " J at t = " << t1;

    if (c.stop_when_fallen) {
      double lowest_fixed = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < n; ++i) {
        if (!defs[i].fixed) continue;
        for (const Vec3& v : world.world_vertices(static_cast<int>(i))) {
          lowest_fixed = std::min(lowest_fixed, v.z());
        }
      }
      bool fell = false;
      for (std::size_t i = 0; i < n; ++i) fell |= !defs[i].fixed && states[i].position.z() < lowest_fixed;
      if (fell) {
        out.fell = true;
        break;
      }
    }
  }
  out.pedestal_work = world.pedestal_work();
  out.final_states = world.states();
  out.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool bit_identical(const std::vector<dynamics::BodyState>& a, const std::vector<dynamics::BodyState>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto& x = a[i];
    const auto& y = b[i];
    if (std::memcmp(x.position.data(), y.position.data(), 3 * sizeof(double)) != 0 ||
        std::memcmp(x.orientation.coeffs().data(), y.orientation.coeffs().data(), 4 * sizeof(double)) != 0 ||
        std::memcmp(x.velocity.data(), y.velocity.data(), 3 * sizeof(double)) != 0 ||
        std::memcmp(x.angular_momentum.data(), y.angular_momentum.data(), 3 * sizeof(double)) != 0) {
      return false;
    }
  }
  return true;
}

// Runs the case twice: all per-step checks on the first run, bit-identical final states.
Outcome check_one_model(const Case& c) {
  Outcome first, second;
  run_checked(c, first);
  if (::testing::Test::HasFatalFailure()) return first;
  run_checked(c, second);
  if (::testing::Test::HasFatalFailure()) return first;
  EXPECT_EQ(first.steps, second.steps) << c.name;
  EXPECT_TRUE(bit_identical(first.final_states, second.final_states)) << c.name << ": two runs of the same case differ";
  EXPECT_EQ(std::memcmp(&first.pedestal_work, &second.pedestal_work, sizeof(double)), 0) << c.name;
  std::printf(
      "%-22s dt %.3g s, %ld steps, %.3g s%s; max overlap/size %.3g (%.3g m); energy margin "
      "min %.3f of tol %.3g J (pedestal work %.4g J); |q|-1 max %.2g; up to %zu subcontacts; "
      "wall %.2f s per run\n",
      c.name.c_str(), first.dt, first.steps, first.simulated, first.fell ? " (fell off)" : "", first.max_overlap_ratio,
      first.max_overlap, first.min_energy_margin, first.energy_tol, first.pedestal_work, first.max_quat_error,
      first.max_subcontacts, first.wall);
  return first;
}

// The case as given (the penalty model), then with the rigid contact model at its own automatic
// step (physics.md §12): every check holds for both.
Outcome check_case(const Case& c) {
  const Outcome penalty = check_one_model(c);
  if (::testing::Test::HasFatalFailure()) return penalty;
  Case rigid = c;
  rigid.name += " [rigid]";
  rigid.law.method = contact::ContactMethod::rigid;
  rigid.step.dt = 0;
  check_one_model(rigid);
  return penalty;
}

// settled rectangular block on a pedestal (the study's set-up), width 2b, height 2h
std::vector<BodyDef> settled_block(double b, double h, double depth, const contact::ContactLaw& law,
                                   double margin = 0.02, double pedestal_height = 0.2) {
  const scenario::Scene s = library::block_on_pedestal(b, h, depth, law, kDensity, margin, pedestal_height);
  return scenario::equilibrate(s, dynamics::StepSettings{}).bodies;
}

// ---------------------------------------------------------------------------------------------
// the cases

// A very slender block, alpha = 0.05 rad (1 m tall, 5 cm wide), settled, then a one-sine pulse
// well above its quasi-static uplift (g tan 0.05 = 0.05 g): it rocks on 2.5 cm half-widths.
TEST(Stability, SlenderBlockAlpha005) {
  Case c;
  c.name = "slender alpha 0.05";
  const double h = 0.5, b = h * std::tan(0.05);
  c.bodies = settled_block(b, h, 0.5, c.law);
  c.ground = sampled(1.0, 1e-3, [](double t) -> Vec3 { return one_sine(t, 0.15 * kGravity, 0.5, Vec3::UnitX()); });
  c.duration = 4.0;
  check_case(c);
}

// Five blocks stacked with a growing overhang towards a wall: the whole stack's centroid lies
// beyond its base, so it leans on the wall through the top block. Starts exactly touching (face-
// face contacts), settles under gravity, then is shaken towards and away from the wall.
TEST(Stability, FiveBlockLeaningStackAgainstWall) {
  Case c;
  c.name = "leaning stack";
  c.bodies.push_back(box("floor", Vec3(-1.0, -0.5, -0.2), Vec3(0, 0.5, 0), true));
  c.bodies.push_back(box("wall", Vec3(0, -0.5, 0), Vec3(0.2, 0.5, 1.2), true));
  const double s = 0.06;  // overhang of each block over the one below, towards the wall
  for (int k = 0; k < 5; ++k) {
    const double x = -0.1 - s * (4 - k);
    c.bodies.push_back(
        box("block" + std::to_string(k), Vec3(x - 0.1, -0.15, 0.2 * k), Vec3(x + 0.1, 0.15, 0.2 * k + 0.2), false));
  }
  c.ground = sampled(4.0, 1e-3, [](double t) -> Vec3 { return sine(t, 0.2 * kGravity, 3.0, Vec3::UnitX(), 0.5, 3.5); });
  c.duration = 4.0;
  check_case(c);
}

// A block on a pedestal whose top slopes at 35 degrees, steeper than the friction angle (31
// degrees): alone it would slide. A small free wedge (3-4.4 cm thick, 0.8 kg) is jammed between
// its downhill face and a fixed ledge whose uphill face leans 8 degrees away, and holds it. Four
// exactly coplanar face-face contacts on a slope (block-slope, block-wedge, wedge-slope,
// wedge-ledge), starting exactly touching; then shaken along the fall line.
TEST(Stability, BlockOnSlopeHeldByWedge) {
  Case c;
  c.name = "slope and wedge";
  const double beta = 35 * kPi / 180, gamma = 8 * kPi / 180;
  const Vec3 u(std::cos(beta), 0, -std::sin(beta));  // downhill along the slope
  const Vec3 w(std::sin(beta), 0, std::cos(beta));   // slope normal
  const Vec3 y = Vec3::UnitY();
  auto at = [&](double su, double sy, double sw) { return Vec3(su * u + sy * y + sw * w); };
  std::vector<Vec3> pedestal;
  for (double su : {-0.6, 0.6}) {
    for (double sy : {-0.4, 0.4}) {
      pedestal.push_back(at(su, sy, 0));
      pedestal.push_back(at(su, sy, 0) - Vec3(0, 0, 0.5));
    }
  }
  // block 0.3 x 0.3 x 0.3 on the slope, its downhill face at u = 0
  std::vector<Vec3> block;
  for (double su : {-0.3, 0.0}) {
    for (double sy : {-0.15, 0.15}) {
      for (double sw : {0.0, 0.3}) block.push_back(at(su, sy, sw));
    }
  }
  // wedge between u = 0 and the ledge face u = 0.03 + sw tan(gamma), 0.1 high, 0.2 wide
  const double gap = 0.03, height = 0.1, t = std::tan(gamma);
  std::vector<Vec3> wedge, ledge;
  for (double sy : {-0.1, 0.1}) {
    for (double sw : {0.0, height}) {
      wedge.push_back(at(0, sy, sw));
      wedge.push_back(at(gap + sw * t, sy, sw));
    }
  }
  for (double sy : {-0.3, 0.3}) {
    for (double sw : {0.0, 0.12}) {
      ledge.push_back(at(gap + sw * t, sy, sw));
      ledge.push_back(at(gap + 0.2, sy, sw));
    }
  }
  c.bodies.push_back(hull_body("pedestal", pedestal, true));
  c.bodies.push_back(hull_body("ledge", ledge, true));
  c.bodies.push_back(hull_body("block", block, false));
  c.bodies.push_back(hull_body("wedge", wedge, false));
  c.ground = sampled(3.0, 1e-3, [&](double t) -> Vec3 { return sine(t, 0.1 * kGravity, 2.0, u, 0.5, 2.5); });
  c.duration = 3.0;
  const Outcome out = check_case(c);
  if (HasFatalFailure()) return;
  const double moved = (out.final_states[2].position - c.bodies[2].position).norm();
  std::printf("slope and wedge: the block moved %.3g m\n", moved);
  EXPECT_LT(moved, 0.005) << "the wedge should hold the block (the scene is not what it says)";
}

// Exactly coplanar face-face contact: a block whose footprint is the pedestal's top face (margin
// 0: the faces coincide, edges and corners too), starting exactly touching, shaken diagonally.
TEST(Stability, ExactlyCoplanarFaceFace) {
  Case c;
  c.name = "coplanar face-face";
  const scenario::Scene s = library::block_on_pedestal(0.15, 0.3, 0.3, c.law, kDensity, 0.0);
  c.bodies = s.bodies;
  const Vec3 diagonal = Vec3(1, 1, 0).normalized();
  c.ground = sampled(3.0, 1e-3, [&](double t) -> Vec3 {
    return sine(t, 0.4 * kGravity, 2.5, diagonal, 0.2, 2.6) + sine(t, 0.1 * kGravity, 4.0, Vec3::UnitZ(), 0.2, 2.6);
  });
  c.duration = 3.0;
  check_case(c);
}

// Crossing edge-edge contact: a free bar of flat rhombic section (faces 20 degrees off the
// horizontal), edge down along y, balanced exactly on a fixed square bar, edge up along x: a point
// contact between two crossing edges. It tips 20 degrees onto a face lying across the fixed edge
// (an edge-face contact whose ends are edge crossings) and rocks there.
TEST(Stability, CrossingEdgeEdge) {
  Case c;
  c.name = "crossing edge-edge";
  const double a = 0.05, half = 0.3, w = 0.08, h = w * std::tan(20 * kPi / 180);
  std::vector<Vec3> fixed_bar, free_bar;
  for (double s : {-half, half}) {
    for (const auto& q : {Vec3(0, 0, 0), Vec3(0, a, -a), Vec3(0, 0, -2 * a), Vec3(0, -a, -a)}) {
      fixed_bar.push_back(q + Vec3(s, 0, 0));
    }
    for (const auto& q : {Vec3(0, 0, 0), Vec3(w, 0, h), Vec3(0, 0, 2 * h), Vec3(-w, 0, h)}) {
      free_bar.push_back(q + Vec3(0, s, 0));
    }
  }
  c.bodies.push_back(box("floor", Vec3(-1, -1, -2 * a - 0.2), Vec3(1, 1, -2 * a), true));
  c.bodies.push_back(hull_body("fixed bar", fixed_bar, true));
  c.bodies.push_back(hull_body("free bar", free_bar, false));
  c.ground = sampled(3.0, 1e-3,
                     [](double t) -> Vec3 { return one_sine(t, 0.05 * kGravity, 0.3, Vec3(1, 0.5, 0).normalized()); });
  c.duration = 3.0;
  check_case(c);
}

// Vertex on vertex: a block whose underside is a shallow pyramid (11 degrees) stands on its apex
// exactly on the apex of a fixed pedestal roofed by a shallow pyramid (6 degrees): a vertex-vertex
// contact surrounded by nearly parallel faces. It tips until an underside face meets a roof face
// (17 degrees, a gentle landing) and rocks there.
TEST(Stability, VertexOnVertex) {
  Case c;
  c.name = "vertex on vertex";
  std::vector<Vec3> roof{Vec3(0, 0, 0)}, top{Vec3(0, 0, 0)};
  for (double x : {-0.4, 0.4}) {
    for (double y : {-0.4, 0.4}) {
      roof.emplace_back(x, y, -0.04);
      roof.emplace_back(x, y, -0.3);
      top.emplace_back(0.375 * x, 0.375 * y, 0.03);
      top.emplace_back(0.375 * x, 0.375 * y, 0.25);
    }
  }
  c.bodies.push_back(hull_body("roofed pedestal", roof, true));
  c.bodies.push_back(hull_body("pointed block", top, false));
  c.ground = sampled(3.0, 1e-3,
                     [](double t) -> Vec3 { return one_sine(t, 0.05 * kGravity, 0.3, Vec3(1, 0.3, 0).normalized()); });
  c.duration = 3.0;
  check_case(c);
}

// A 1 cm cube (2.6 g) on a 10 m x 1 m x 0.1 m pedestal (2,600 kg: mass ratio 1e6, size ratio
// 1,000), shaken horizontally and vertically.
TEST(Stability, CentimetreBlockOnTenMetrePedestal) {
  Case c;
  c.name = "1 cm on 10 m";
  c.bodies.push_back(box("pedestal", Vec3(-5, -0.5, -0.1), Vec3(5, 0.5, 0), true));
  c.bodies.push_back(box("pebble", Vec3(-0.005, -0.005, 0), Vec3(0.005, 0.005, 0.01), false));
  ASSERT_NEAR(c.bodies[0].shape.mass / c.bodies[1].shape.mass, 1e6, 1e-3);
  c.ground = sampled(0.5, 1e-3, [](double t) -> Vec3 {
    return sine(t, 0.3 * kGravity, 5.0, Vec3::UnitX(), 0.05, 0.5) +
           sine(t, 0.2 * kGravity, 7.0, Vec3::UnitZ(), 0.05, 0.5);
  });
  c.duration = 0.5;
  check_case(c);
}

// Very stiff contacts, K_N = K_S = 1e11 (1,000 times the study's), with the automatic step: the
// peer block (1 m tall, alpha 0.2) rocked by a one-sine pulse.
TEST(Stability, VeryStiffContactsAutomaticStep) {
  Case c;
  c.name = "K = 1e11";
  c.law.normal_stiffness = c.law.shear_stiffness = 1e11;
  const double h = 0.5, b = h * std::tan(0.2);
  c.bodies = library::block_on_pedestal(b, h, 0.5, c.law).bodies;
  c.ground = sampled(2.0, 1e-3, [](double t) -> Vec3 { return one_sine(t, 0.25 * kGravity, 0.5, Vec3::UnitX(), 0.2); });
  c.duration = 2.0;
  check_case(c);
}

// 10 g shaking: a stocky 0.4 m block (it slides, friction 0.6, rather than rocks) on a 0.4 m
// thick pedestal under 10 g horizontal harmonic shaking in x and in y (10 and 7 Hz) and 0.5 g
// vertical (13 Hz). It chatters (hops of ~1 mm, tilts up to 0.01 rad) and slides 0.2 m, past the
// pedestal's edge: the pedestal's edge then runs under its base (edge-crossing subcontacts).
TEST(Stability, TenGShaking) {
  Case c;
  c.name = "10 g";
  c.bodies = settled_block(0.2, 0.2, 0.4, c.law, 0.2, 0.4);
  c.ground = sampled(3.0, 5e-4, [](double t) -> Vec3 {
    return sine(t, 10 * kGravity, 10.0, Vec3::UnitX(), 0.0, 2.5) +
           sine(t, 10 * kGravity, 7.0, Vec3::UnitY(), 0.0, 2.5, 1.0) +
           sine(t, 0.5 * kGravity, 13.0, Vec3::UnitZ(), 0.0, 2.5, 2.0);
  });
  c.duration = 3.0;
  const Outcome out = check_case(c);
  if (HasFatalFailure()) return;
  const Vec3 slid =
      (out.final_states[1].position - out.final_states[0].position) - (c.bodies[1].position - c.bodies[0].position);
  std::printf(
      "10 g: the block slid (%.3f, %.3f) m on the pedestal (its edge is 0.2 m beyond the "
      "block's)\n",
      slid.x(), slid.y());
}

// A 300 s run: a stocky 0.4 m block under a long low-level motion (sum of 24 harmonics of random
// phase, 0.5-12 Hz, about 0.1 g peak horizontally), with the automatic step.
TEST(Stability, ThreeHundredSecondRun) {
  Case c;
  c.name = "300 s";
  c.bodies = settled_block(0.2, 0.2, 0.4, c.law);
  struct Harmonic {
    double w, phase;
    Vec3 amplitude;  // velocity amplitude (unit: m/s)
  };
  std::vector<Harmonic> harmonics;
  test::Rng random{20261122};  // the random-phase motion
  for (int k = 0; k < 24; ++k) {
    const double f = 0.5 + 11.5 * random.uniform();
    const double w = 2 * kPi * f;
    const double a = 0.012 * kGravity;  // each harmonic's acceleration amplitude
    harmonics.push_back({w, 2 * kPi * random.uniform(),
                         Vec3(a / w * random.uniform(), a / w * random.uniform(), 0.3 * a / w * random.uniform())});
  }
  c.ground = sampled(300.0, 2e-3, [&](double t) -> Vec3 {
    const double ramp = std::min({1.0, t / 2.0, (300.0 - t) / 2.0});
    Vec3 v = Vec3::Zero();
    for (const auto& h : harmonics) v += std::sin(h.w * t + h.phase) * h.amplitude;
    return ramp * v;
  });
  c.duration = 300.0;
  check_case(c);
}

// Nearly degenerate meshes. (a) Slivers: a 0.4 x 0.4 x 0.6 box with every edge and corner
// chamfered by 1 micrometre (the hull of its 24 corner points moved 1e-6 m inward along each
// axis): 12 bevel faces 1.4e-6 m wide and 0.4-0.6 m long, split into sliver triangles of aspect
// ratio ~4e5, 8 corner facets 1.4e-6 m across, and bases whose corners are pairs of vertices
// 1.4e-6 m apart; it rocks and slides on a pedestal.
TEST(Stability, DegenerateMeshSlivers) {
  Case c;
  c.name = "slivers";
  const double chamfer = 1e-6;
  std::vector<Vec3> points;
  for (const Vec3& corner : box_points(Vec3(-0.2, -0.2, 0), Vec3(0.2, 0.2, 0.6))) {
    const Vec3 inward(corner.x() > 0 ? -1 : 1, corner.y() > 0 ? -1 : 1, corner.z() > 0.3 ? -1 : 1);
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 p = corner;
      p[axis] += chamfer * inward[axis];
      points.push_back(p);
    }
  }
  const geometry::TriangleSoup soup = convex_hull(points);
  double worst_aspect = 0;
  for (const auto& t : soup) {
    const double longest = std::max({(t.b - t.a).norm(), (t.c - t.b).norm(), (t.a - t.c).norm()});
    const double area2 = (t.b - t.a).cross(t.c - t.a).norm();
    worst_aspect = std::max(worst_aspect, longest * longest / area2);
  }
  std::printf("slivers: %zu facets, worst aspect (longest edge / height) %.3g\n", soup.size(), worst_aspect);
  ASSERT_GT(worst_aspect, 1e5) << "the mesh should have slivers";
  c.bodies.push_back(box("pedestal", Vec3(-0.3, -0.3, -0.2), Vec3(0.3, 0.3, 0), true));
  c.bodies.push_back(library::body_from_soup("sliver block", soup, kDensity, false));
  c.ground = sampled(3.0, 1e-3, [](double t) -> Vec3 {
    return sine(t, 0.45 * kGravity, 2.0, Vec3(1, 0.4, 0).normalized(), 0.3, 2.8);
  });
  c.duration = 3.0;
  check_case(c);
}

// (b) Nearly coplanar facets: a 0.4 x 0.4 x 0.6 block whose base is an 11 x 11 grid sagging
// 10 micrometres in the middle (a convex bowl): 200 base facets whose normals differ by 1e-5 to
// 1e-4 rad (above the 1e-6 rad merge angle), so dozens of base vertices touch the pedestal at once.
TEST(Stability, DegenerateMeshNearlyCoplanarFacets) {
  Case c;
  c.name = "nearly coplanar";
  std::vector<Vec3> points;
  const double a = 0.2, sag = 1e-5;
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j <= 10; ++j) {
      const double x = -a + 0.04 * i, y = -a + 0.04 * j;
      points.emplace_back(x, y, sag * (x * x + y * y) / (a * a));
    }
  }
  for (double x : {-a, a}) {
    for (double y : {-a, a}) points.emplace_back(x, y, 0.6);
  }
  const geometry::TriangleSoup soup = convex_hull(points);
  c.bodies.push_back(box("pedestal", Vec3(-0.3, -0.3, -0.2), Vec3(0.3, 0.3, 0), true));
  c.bodies.push_back(library::body_from_soup("bowl block", soup, kDensity, false));
  std::printf("nearly coplanar: %zu facets, %zu faces after merging, %zu vertices\n", soup.size(),
              c.bodies[1].shape.faces.size(), c.bodies[1].shape.vertices.size());
  ASSERT_GT(c.bodies[1].shape.faces.size(), 100u) << "the base facets should stay separate";
  c.ground = sampled(3.0, 1e-3, [](double t) -> Vec3 {
    return sine(t, 0.45 * kGravity, 2.0, Vec3(1, 0.4, 0).normalized(), 0.3, 2.8);
  });
  c.duration = 3.0;
  check_case(c);
}

// (c) 10,000 facets: the hull of 5,002 points spread over an ellipsoid (0.3 x 0.2 x 0.12 m
// semi-axes) by a Fibonacci lattice, lying on a pedestal and rocked.
TEST(Stability, DegenerateMeshTenThousandFacets) {
  Case c;
  c.name = "10,000 facets";
  const int n = 5002;
  std::vector<Vec3> points;
  const double golden = kPi * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = golden * i;
    points.emplace_back(0.3 * r * std::cos(phi), 0.2 * r * std::sin(phi), 0.12 * z + 0.12);
  }
  const geometry::TriangleSoup soup = convex_hull(points);
  ASSERT_EQ(soup.size(), 10000u);
  c.bodies.push_back(box("pedestal", Vec3(-0.5, -0.4, -0.2), Vec3(0.5, 0.4, 0), true));
  c.bodies.push_back(library::body_from_soup("ellipsoid", soup, kDensity, false));
  c.ground = sampled(
      3.0, 1e-3, [](double t) -> Vec3 { return sine(t, 0.3 * kGravity, 1.5, Vec3(1, 0.5, 0).normalized(), 0.3, 2.7); });
  c.duration = 3.0;
  check_case(c);
}

}  // namespace
}  // namespace rigid
