#pragma once
/// The rigid-block world: bodies, contacts and the time stepper. Translation by velocity Verlet;
/// rotation with angular momentum and a unit quaternion, by the symplectic splitting of Dullweber,
/// Leimkuhler & McLachlan (physics.md §8) or by RK4. Fixed blocks (pedestals) follow a prescribed
/// ground velocity. No I/O; no allocation inside step() once the contact buffers have grown.
#include <string>
#include <vector>

#include "rigid/contact/contact.hpp"
#include "rigid/core/types.hpp"
#include "rigid/dynamics/contact_solver.hpp"
#include "rigid/geometry/polyhedron.hpp"

namespace rigid::dynamics {

/// One block of a scene.
struct BodyDef {
  std::string name;
  geometry::ConvexPolyhedron shape;  ///< body frame: centroid origin, principal axes
  /// A compound body's contact shape: convex pieces in `shape`'s body frame (a scanned rock's
  /// hull or convex decomposition, geometry::build_compound). Empty: the contact shape is `shape`.
  /// With pieces, `shape` still gives the mass, the inertia and the outline (the pieces' convex
  /// hull) that everything but contact uses (failure rule, bounds, trajectories).
  std::vector<geometry::ConvexPolyhedron> pieces;
  bool fixed = false;                ///< true: a pedestal driven by the ground motion
  Vec3 position{0, 0, 0};            ///< world position of the centre of mass (unit: m)
  Quat orientation = Quat::Identity();  ///< body-to-world rotation
  Vec3 velocity{0, 0, 0};            ///< initial velocity (unit: m/s)
  Vec3 angular_velocity{0, 0, 0};    ///< initial angular velocity, world frame (unit: rad/s)
  /// Centre of mass minus the mesh's centroid, body frame (unit: m): zero for a uniform block
  /// (scenario::offset_centre_of_mass). Saved states keep the centroid's pose, so one settled
  /// state serves every offset.
  Vec3 centre_of_mass_offset{0, 0, 0};
};

/// How orientations are advanced.
enum class RotationIntegrator {
  /// Splitting into exact rotations about the principal axes (Dullweber, Leimkuhler & McLachlan
  /// 1997; the quaternion form of NO_SQUISH): 2nd order, symplectic, conserves angular momentum
  /// exactly when torque-free, one force evaluation per step.
  splitting,
  /// Classical RK4 on the quaternion with the angular momentum held over the step.
  rk4,
};

/// Stepper settings.
struct StepSettings {
  /// Time step (unit: s); 0 = automatic, `safety` times the critical step (stable_time_step).
  double dt = 0;
  /// Fraction of the critical step 2/omega_max used by the automatic step (unit: 1). The
  /// estimate already lumps four subcontacts and the lever arm into omega_max; 0.2 keeps the
  /// rocking, sliding and impact cases of the test suite stable with margin.
  double safety = 0.2;
  RotationIntegrator rotation = RotationIntegrator::splitting;
  /// Itasca local damping coefficient alpha (physics.md §9): 0 while shaking, ~0.8 to settle.
  double local_damping = 0;
  /// Gravitational acceleration (unit: m/s^2), along -z.
  double gravity = kGravity;
};

/// Critical explicit time step of the scene, 2/omega_max, where omega_max^2 bounds the stiffest
/// contact mode of the lightest free block: four subcontacts of stiffness k acting at the block's
/// bounding radius r, omega^2 = 4 k (1/m + r^2/I_min), with k the larger of K_S and the Hertz
/// tangent stiffness 1.5 K_N sqrt(d) at the indentation d of a 1 m/s impact (physics.md §10).
double critical_time_step(const std::vector<BodyDef>& bodies, const contact::ContactLaw& law);

/// Time step of the rigid contact model (physics.md §12), from the geometry alone: `safety` / 50
/// of sqrt(r / g), r the smallest bounding radius of a free block, the time scale of its rocking
/// and falling (a rectangular block's 1/p is sqrt(4 R / 3 g)). For a 1 m block that is 1.9 ms at
/// safety 0.4 (the `fast` preset), the step ODE and Bullet use; it shrinks with the block.
double rigid_time_step(const std::vector<BodyDef>& bodies, double safety);

/// The step a World over these bodies takes: settings.dt when set, else the contact model's
/// automatic step (rigid_time_step, or safety x critical_time_step for penalty contact).
double time_step(const std::vector<BodyDef>& bodies, const contact::ContactLaw& law, const StepSettings& settings);

/// Per-body kinematic state (world frame).
struct BodyState {
  Vec3 position{0, 0, 0};
  Quat orientation = Quat::Identity();
  Vec3 velocity{0, 0, 0};
  Vec3 angular_momentum{0, 0, 0};  ///< world frame (unit: kg m^2/s)
};

/// Contact bookkeeping of one pair of blocks, kept across steps.
struct PairContact {
  int a = 0, b = 0;                      ///< body indices, a < b
  /// Which contact piece of each body (BodyDef::pieces; 0 for a body without pieces): a compound
  /// body touches another through one pair per two pieces.
  int piece_a = 0, piece_b = 0;
  /// Penalty model: the weight of each subcontact's springs, min(1, 4 / n) for a patch of n
  /// subcontacts counted by depth, n = sum (d_i / d_max)^1.5 (World::compute_forces): a patch is
  /// never stiffer than four subcontacts at its deepest indentation.
  double stiffness_weight = 1;
  Vec3 normal{0, 0, 1};                  ///< last common-plane normal, from a to b
  contact::SupportHints hints;
  double overlap = 0;                    ///< last overlap (unit: m); < 0 is a gap
  struct Sub {
    int key;
    Vec3 shear_force;                    ///< on b (unit: N); penalty model
    double normal_impulse = 0;           ///< on b over the last step (unit: N s); rigid model
  };
  /// Rigid model: the friction impulse of the pair's contact patch on b over the last step,
  /// along the plane (unit: N s) and twisting about the normal (unit: N m s).
  Vec3 friction_impulse{0, 0, 0};
  double twist_impulse = 0;
  /// Persistent subcontacts (double-buffered); subs[k] belongs to points[k]. The rigid model
  /// also keeps open contacts within its speculative margin (SubcontactPoint::overlap < 0).
  std::vector<Sub> subs, next_subs;
  std::vector<contact::SubcontactPoint> points;  ///< the last step's subcontact points
  long tests = 0;                        ///< narrow-phase tests of this pair so far
  /// Distance skin (WorldEffects::distance_skin): the bounding spheres were skin_gap + margin
  /// apart when the bodies' relative travels summed to skin_travel; < 0 = no skin.
  double skin_gap = -1;
  double skin_travel = 0;
};

/// The last step's contacts as a caller deciding about rest, sleep and stillness reads them: every
/// pair's normal and its loaded subcontacts (those that carried a positive normal force,
/// World::subcontact_load). Filled by World::summarize_contacts into the caller's buffers.
struct ContactSummary {
  struct Pair {
    int a = 0, b = 0;            ///< body indices, a < b
    Vec3 normal{0, 0, 1};        ///< common-plane normal, from a to b
    std::size_t first = 0;       ///< its loaded subcontacts are points[first, first + loaded)
    std::size_t loaded = 0;
  };
  struct Point {
    Vec3 position{0, 0, 0};      ///< world frame (unit: m)
    double load = 0;             ///< normal force (unit: N), > 0
  };
  std::vector<Pair> pairs;       ///< every pair, in the World's order
  std::vector<Point> points;
};

/// Counters that tell what the stepper did (for reports and tests).
struct StepStats {
  long steps = 0;
  long pair_tests = 0;       ///< narrow-phase tests run
  long pairs_skipped = 0;    ///< pairs skipped by the bounding-sphere test
  long pairs_culled = 0;     ///< pairs skipped by the distance skin, without the sphere test
  long contact_steps = 0;    ///< pair evaluations with the blocks in contact
  long sliding_steps = 0;    ///< of those, evaluations where a subcontact reached mu F_n
};

/// Optional work of the stepper (simulate only the effects a scene calls for, docs/engine.md). The
/// defaults do all of it; each switch skips only work whose result is known in advance, so
/// results do not change (see each).
struct WorldEffects {
  /// The ground moves vertically. false: the pedestals' z is not updated, which is exact when the
  /// caller guarantees that every z velocity it passes to step() is exactly 0 (z + dt * 0 = z).
  bool vertical_ground = true;
  /// Verlet-style skin on the bounding-sphere test: a pair found apart by a gap is not looked at
  /// again until the two bodies' travel relative to the ground (the pedestals have none) adds up
  /// to that gap. The sphere distance cannot shrink by more than that travel, so no pair the
  /// sphere test would have tested is skipped.
  bool distance_skin = false;
};

class World {
 public:
  World(std::vector<BodyDef> bodies, const contact::ContactLaw& law, const StepSettings& settings);

  /// Advances by dt. The fixed blocks move with the ground velocity, which goes linearly from
  /// ground_velocity_start (at t) to ground_velocity_end (at t + dt) (unit: m/s).
  void step(double dt, const Vec3& ground_velocity_start, const Vec3& ground_velocity_end);

  double time() const { return time_; }
  double dt() const { return dt_; }
  const std::vector<BodyDef>& bodies() const { return defs_; }
  const std::vector<BodyState>& states() const { return states_; }
  std::vector<BodyState>& mutable_states() { return states_; }
  const std::vector<PairContact>& pairs() const { return pairs_; }
  const StepStats& stats() const { return stats_; }
  const StepSettings& settings() const { return settings_; }
  StepSettings& mutable_settings() { return settings_; }
  const contact::ContactLaw& law() const { return law_; }
  /// Normal force carried by subcontact k of a pair in the last step (unit: N): K_N d^1.5 for
  /// the penalty model (the elastic part), p_n / h for the rigid model; 0 for an open contact.
  double subcontact_load(const PairContact& pair, std::size_t k) const;
  /// The last step's contacts, into `out` (its buffers are reused: no allocation once grown).
  void summarize_contacts(ContactSummary& out) const;
  /// Sweeps the rigid contact solver needed in the last step, and whether it converged.
  const SolverResult& last_solve() const { return last_solve_; }

  /// World positions of body i's vertices (of its shape: the outline of a compound body) at the
  /// current time.
  const std::vector<Vec3>& world_vertices(int i) const { return world_vertices_[i]; }
  /// The convex piece k of body i's contact shape (the shape itself for a body without pieces).
  const geometry::ConvexPolyhedron& contact_piece(int i, int k) const {
    return defs_[i].pieces.empty() ? defs_[i].shape : defs_[i].pieces[k];
  }
  /// World angular velocity of body i (unit: rad/s).
  Vec3 angular_velocity(int i) const;
  /// Kinetic energy of the free blocks (unit: J).
  double kinetic_energy() const;
  /// Gravitational potential energy of the free blocks, zero at z = 0 (unit: J).
  double potential_energy() const;
  /// Elastic energy stored in the contact springs (unit: J).
  double elastic_energy() const;
  /// Work done on the free blocks by the moving fixed blocks since the start (unit: J).
  double pedestal_work() const { return pedestal_work_; }
  /// Frictional slip accumulated by each body (unit: m): the largest slip of its subcontacts in
  /// each step, summed over steps.
  const std::vector<double>& slip() const { return slip_; }
  /// Largest overlap of any subcontact in the last step (unit: m).
  double max_overlap() const { return max_overlap_; }
  /// Total contact force on body i in the last force evaluation (unit: N).
  const Vec3& contact_force(int i) const { return contact_force_[i]; }

  /// Recomputes the cached world data after states were edited from outside.
  void refresh();

  void set_effects(const WorldEffects& effects) { effects_ = effects; }
  const WorldEffects& effects() const { return effects_; }
  /// Pairs of two fixed blocks: never tested, since pedestals cannot interact.
  long fixed_fixed_pairs() const { return fixed_fixed_pairs_; }

  /// Carries the whole scene rigidly with the ground from time() to t_end, without stepping: every
  /// body is translated by `displacement` (the integral of the ground velocity over the interval),
  /// the pedestals take v_end, the free blocks' velocity changes by v_end - v_start (so their
  /// velocity relative to the ground is kept), orientations, angular momenta, contact springs and
  /// forces stay as they are: nothing changes relative to the pedestals. For free blocks asleep
  /// on a quiet pedestal (scenario::run decides when that is sound). The pedestals' work on the
  /// blocks is that of carrying them: sum of m (|v_end|^2 - |v_start|^2) / 2 + m g displacement_z.
  void carry_with_ground(double t_end, const Vec3& displacement, const Vec3& v_start, const Vec3& v_end);

 private:
  void update_world_vertices(int i);
  /// World vertices of contact piece k of body i (body i's own for a body without pieces).
  const Vec3* piece_vertices(int i, int k) const {
    return defs_[i].pieces.empty() ? world_vertices_[i].data() : piece_vertices_[i][k].data();
  }
  /// Adds `shift` to every world vertex of body i (outline and pieces).
  void shift_world_vertices(int i, const Vec3& shift);
  void shift_world_vertices_xy(int i, double dx, double dy);
  void move_pedestals(double dt, const Vec3& ground_velocity);
  /// Whether the pair is too far apart to touch within `margin` (the bounding-sphere test and,
  /// with the distance skin, the travel since it was last found apart).
  bool pair_apart(PairContact& p, double margin);
  void step_penalty(double dt, const Vec3& ground_velocity_start, const Vec3& ground_velocity_end);
  void step_rigid(double dt, const Vec3& ground_velocity_start, const Vec3& ground_velocity_end);
  void collect_rigid_rows(double dt, const Vec3& ground_velocity);
  void merge_piece_patches();
  void compute_forces(double dt);
  void drift_rotation(int i, double dt);

  std::vector<BodyDef> defs_;
  std::vector<BodyState> states_;
  std::vector<std::vector<Vec3>> world_vertices_;
  std::vector<std::vector<std::vector<Vec3>>> piece_vertices_;  ///< [body][piece]: compound bodies only
  std::vector<Mat3> rotations_;
  std::vector<Vec3> forces_, torques_, contact_force_;
  std::vector<PairContact> pairs_;
  std::vector<double> slip_;
  contact::ContactLaw law_;
  StepSettings settings_;
  StepStats stats_;
  WorldEffects effects_;
  std::vector<double> travel_;  ///< path length of each body relative to the ground (unit: m)
  long fixed_fixed_pairs_ = 0;
  double time_ = 0;
  double dt_ = 0;
  double pedestal_work_ = 0;
  double max_overlap_ = 0;
  // rigid model scratch (sized once, reused every step)
  std::vector<ContactRow> rows_;
  std::vector<FrictionPatch> patches_;
  /// The pairs of each patch: patch j's rows are those of pairs member_pairs_[member_begin_[j]] ..
  /// member_pairs_[member_begin_[j + 1] - 1], in that order (one pair unless pieces merged).
  std::vector<int> member_begin_, member_pairs_;
  bool has_compound_ = false;  ///< some body has several contact pieces
  std::vector<ContactRow> merged_rows_;
  std::vector<FrictionPatch> merged_patches_;
  std::vector<int> merged_members_, merged_begin_;
  std::vector<char> patch_taken_;
  Vec3 pedestal_velocity_{0, 0, 0};  ///< the pedestals' mean velocity over the last step
  std::vector<SolverBody> solver_bodies_, pseudo_bodies_;
  std::vector<SolverBody> free_bodies_, solver_scratch_;  ///< velocities before the solve (local damping)
  SolverResult last_solve_;
};

}  // namespace rigid::dynamics
