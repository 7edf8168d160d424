#pragma once
/// What both contact models share: the bodies and their states, the cached world geometry, the
/// pairs that can touch and their narrow-phase state, the pedestals' motion and the rotation
/// integrator. The contact models' steppers (PenaltyStepper, RigidStepper) advance a WorldCore;
/// dynamics::World is their facade. No I/O, no allocation once the buffers have grown.
#include <string>
#include <vector>

#include "rigid/contact/contact.hpp"
#include "rigid/core/types.hpp"
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
  bool fixed = false;                   ///< true: a pedestal driven by the ground motion
  Vec3 position{0, 0, 0};               ///< world position of the centre of mass (unit: m)
  Quat orientation = Quat::Identity();  ///< body-to-world rotation
  Vec3 velocity{0, 0, 0};               ///< initial velocity (unit: m/s)
  Vec3 angular_velocity{0, 0, 0};       ///< initial angular velocity, world frame (unit: rad/s)
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
  /// Rigid model: the contact solve has converged when a sweep changes no velocity by more than
  /// this fraction of g dt, the velocity gravity adds in one step (and no angular velocity by more
  /// than that over the smallest block's bounding radius) (unit: 1).
  double solver_tolerance = 1e-7;
  /// Rigid model: sweeps of the contact solve before it gives up (SolverSettings::max_iterations);
  /// a step that reaches it is counted in StepStats::unconverged_steps.
  int solver_max_sweeps = 200;
};

/// Per-body kinematic state (world frame).
struct BodyState {
  Vec3 position{0, 0, 0};
  Quat orientation = Quat::Identity();
  Vec3 velocity{0, 0, 0};
  Vec3 angular_momentum{0, 0, 0};  ///< world frame (unit: kg m^2/s)
};

/// The narrow-phase state of one pair of contact pieces, kept across steps (what the contact
/// models keep per pair of their own is in their steppers).
struct PairContact {
  int a = 0, b = 0;  ///< body indices, a < b
  /// Which contact piece of each body (BodyDef::pieces; 0 for a body without pieces): a compound
  /// body touches another through one pair per two pieces.
  int piece_a = 0, piece_b = 0;
  Vec3 normal{0, 0, 1};  ///< last common-plane normal, from a to b
  contact::SupportHints hints;
  double overlap = 0;  ///< last overlap (unit: m); < 0 is a gap
  /// The last step's subcontact points. The rigid model also keeps open contacts within its
  /// speculative margin (SubcontactPoint::overlap < 0).
  std::vector<contact::SubcontactPoint> points;
  long tests = 0;  ///< narrow-phase tests of this pair so far
  /// Distance skin (WorldEffects::distance_skin): the bounding spheres were skin_gap + margin
  /// apart when the bodies' relative travels summed to skin_travel; < 0 = no skin.
  double skin_gap = -1;
  double skin_travel = 0;
};

/// Counters that tell what the stepper did (for reports and tests).
struct StepStats {
  long steps = 0;
  long pair_tests = 0;     ///< narrow-phase tests run
  long pairs_skipped = 0;  ///< pairs skipped by the bounding-sphere test
  long pairs_culled = 0;   ///< pairs skipped by the distance skin, without the sphere test
  long contact_steps = 0;  ///< pair evaluations with the blocks in contact
  long sliding_steps = 0;  ///< of those, evaluations where a subcontact reached mu F_n
  /// Rigid model: steps whose contact solve stopped at its sweep cap (StepSettings::
  /// solver_max_sweeps) without converging; their impulses are the last sweep's.
  long unconverged_steps = 0;
  int max_solver_sweeps = 0;  ///< rigid model: most sweeps one step's contact solve took
  long solver_solves = 0;     ///< rigid model: steps with a contact to solve
  long solver_sweeps = 0;     ///< rigid model: sweeps of those steps' contact solves, in all
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

/// The state both steppers advance. Plain data with the operations both need; its invariants
/// (world vertices and rotations follow the states) are kept by the steppers and World.
struct WorldCore {
  WorldCore(std::vector<BodyDef> bodies, const contact::ContactLaw& law, const StepSettings& settings);

  /// The convex piece k of body i's contact shape (the shape itself for a body without pieces).
  const geometry::ConvexPolyhedron& contact_piece(int i, int k) const {
    return defs[i].pieces.empty() ? defs[i].shape : defs[i].pieces[k];
  }
  /// World vertices of contact piece k of body i (body i's own for a body without pieces).
  const Vec3* piece_vertices(int i, int k) const {
    return defs[i].pieces.empty() ? world_vertices[i].data() : world_piece_vertices[i][k].data();
  }
  /// World angular velocity of body i (unit: rad/s).
  Vec3 angular_velocity(int i) const;
  /// Rotations and world vertices of every body from the states.
  void refresh_geometry();
  void update_world_vertices(int i);
  /// Adds `shift` to every world vertex of body i (outline and pieces).
  void shift_world_vertices(int i, const Vec3& shift);
  void shift_world_vertices_xy(int i, double dx, double dy);
  /// Moves the pedestals by dt at `ground_velocity`.
  void move_pedestals(double dt, const Vec3& ground_velocity);
  /// Whether the pair is too far apart to touch within `margin` (the bounding-sphere test and,
  /// with the distance skin, the travel since it was last found apart); clears its points when
  /// the spheres are apart.
  bool pair_apart(PairContact& p, double margin);
  /// Advances body i's orientation by dt with its angular momentum (StepSettings::rotation).
  void drift_rotation(int i, double dt);
  /// World::carry_with_ground, for the state both models share.
  void carry_with_ground(double t_end, const Vec3& displacement, const Vec3& v_start, const Vec3& v_end);
  double kinetic_energy() const;
  double potential_energy() const;

  std::vector<BodyDef> defs;
  std::vector<BodyState> states;
  std::vector<std::vector<Vec3>> world_vertices;
  std::vector<std::vector<std::vector<Vec3>>> world_piece_vertices;  ///< [body][piece]: compound bodies only
  std::vector<Mat3> rotations;
  std::vector<Vec3> contact_force;  ///< total contact force on each body in the last step (unit: N)
  std::vector<PairContact> pairs;
  std::vector<double> slip;
  std::vector<double> travel;  ///< path length of each body relative to the ground (unit: m)
  contact::ContactLaw law;
  StepSettings settings;
  StepStats stats;
  WorldEffects effects;
  long fixed_fixed_pairs = 0;
  double time = 0;
  double dt = 0;
  double pedestal_work = 0;
  double max_overlap = 0;
};

}  // namespace rigid::dynamics
