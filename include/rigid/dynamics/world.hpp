#pragma once
/// The rigid-block world: bodies, contacts and the time stepper. Translation by velocity Verlet;
/// rotation with angular momentum and a unit quaternion, by the symplectic splitting of Dullweber,
/// Leimkuhler & McLachlan (physics.md §8) or by RK4. Fixed blocks (pedestals) follow a prescribed
/// ground velocity. The state both contact models share is a WorldCore; each model steps it with
/// a stepper of its own (PenaltyStepper, RigidStepper). No I/O; no allocation inside step() once
/// the contact buffers have grown.
#include <variant>
#include <vector>

#include "rigid/contact/contact.hpp"
#include "rigid/core/types.hpp"
#include "rigid/dynamics/penalty_stepper.hpp"
#include "rigid/dynamics/rigid_stepper.hpp"
#include "rigid/dynamics/world_core.hpp"
#include "rigid/geometry/polyhedron.hpp"

namespace rigid::dynamics {

/// Critical explicit time step of the scene (physics.md §10), the smallest over the free blocks of
/// the limits of two modes, each four subcontacts acting on the block's effective mass
/// 1/m_eff = 1/m + r^2/I_min (r the bounding radius): the normal mode, a Hertz spring and damper
/// at the largest expected overlap d (the whole block striking one subcontact at 1 m/s, or resting
/// its weight on it), tangent stiffness 1.5 K_N sqrt(d) and damping D K_N d^1.5, whose
/// central-difference limit is (2/omega)(sqrt(1 + zeta^2) - zeta); and the shear mode of K_S, 2/omega.
double critical_time_step(const std::vector<BodyDef>& bodies, const contact::ContactLaw& law);

/// Time step of the rigid contact model (physics.md §12), from the geometry alone: `safety` / 50
/// of sqrt(r / g), r the smallest bounding radius of a free block, the time scale of its rocking
/// and falling (a rectangular block's 1/p is sqrt(4 R / 3 g)). For a 1 m block that is 1.9 ms at
/// safety 0.4 (the `fast` preset), the step ODE and Bullet use; it shrinks with the block.
double rigid_time_step(const std::vector<BodyDef>& bodies, double safety);

/// The step a World over these bodies takes: settings.dt when set, else the contact model's
/// automatic step: rigid_time_step, or for penalty contact safety x the smaller of
/// critical_time_step and rigid_time_step at safety 1 (a soft spring's long period does not let a
/// step coarser than the rigid model's resolve the rocking), stable for any stiffness.
double time_step(const std::vector<BodyDef>& bodies, const contact::ContactLaw& law, const StepSettings& settings);

/// The last step's contacts as a caller deciding about rest, sleep and stillness reads them: every
/// pair's normal and its loaded subcontacts (those that carried a positive normal force,
/// World::subcontact_load). Filled by World::summarize_contacts into the caller's buffers.
struct ContactSummary {
  struct Pair {
    int a = 0, b = 0;       ///< body indices, a < b
    Vec3 normal{0, 0, 1};   ///< common-plane normal, from a to b
    std::size_t first = 0;  ///< its loaded subcontacts are points[first, first + loaded)
    std::size_t loaded = 0;
  };
  struct Point {
    Vec3 position{0, 0, 0};  ///< world frame (unit: m)
    double load = 0;         ///< normal force (unit: N), > 0
  };
  std::vector<Pair> pairs;  ///< every pair, in the World's order
  std::vector<Point> points;
};

class World {
 public:
  World(std::vector<BodyDef> bodies, const contact::ContactLaw& law, const StepSettings& settings);

  /// Advances by dt. The fixed blocks move with the ground velocity, which goes linearly from
  /// ground_velocity_start (at t) to ground_velocity_end (at t + dt) (unit: m/s).
  void step(double dt, const Vec3& ground_velocity_start, const Vec3& ground_velocity_end);

  double time() const { return core_.time; }
  double dt() const { return core_.dt; }
  const std::vector<BodyDef>& bodies() const { return core_.defs; }
  const std::vector<BodyState>& states() const { return core_.states; }
  const std::vector<PairContact>& pairs() const { return core_.pairs; }
  const StepStats& stats() const { return core_.stats; }
  const StepSettings& settings() const { return core_.settings; }
  const contact::ContactLaw& law() const { return core_.law; }
  /// Normal force carried by subcontact k of pairs()[pair] in the last step (unit: N): K_N d^1.5
  /// for the penalty model (the elastic part), p_n / h for the rigid model; 0 for an open contact.
  double subcontact_load(std::size_t pair, std::size_t k) const;
  /// The last step's contacts, into `out` (its buffers are reused: no allocation once grown).
  void summarize_contacts(ContactSummary& out) const;

  /// World positions of body i's vertices (of its shape: the outline of a compound body) at the
  /// current time.
  const std::vector<Vec3>& world_vertices(int i) const { return core_.world_vertices[i]; }
  /// The convex piece k of body i's contact shape (the shape itself for a body without pieces).
  const geometry::ConvexPolyhedron& contact_piece(int i, int k) const { return core_.contact_piece(i, k); }
  /// World angular velocity of body i (unit: rad/s).
  Vec3 angular_velocity(int i) const { return core_.angular_velocity(i); }
  /// Kinetic energy of the free blocks (unit: J).
  double kinetic_energy() const { return core_.kinetic_energy(); }
  /// Gravitational potential energy of the free blocks, zero at z = 0 (unit: J).
  double potential_energy() const { return core_.potential_energy(); }
  /// Elastic energy stored in the contact springs (unit: J); 0 for rigid contacts.
  double elastic_energy() const;
  /// Work done on the free blocks by the moving fixed blocks since the start (unit: J).
  double pedestal_work() const { return core_.pedestal_work; }
  /// Frictional slip accumulated by each body (unit: m): the largest slip of its subcontacts in
  /// each step, summed over steps.
  const std::vector<double>& slip() const { return core_.slip; }
  /// Largest overlap of any subcontact in the last step (unit: m).
  double max_overlap() const { return core_.max_overlap; }
  /// Total contact force on body i in the last step (unit: N).
  const Vec3& contact_force(int i) const { return core_.contact_force[i]; }

  /// Recomputes the cached world data after states were edited from outside.
  void refresh();

  void set_effects(const WorldEffects& effects) { core_.effects = effects; }
  const WorldEffects& effects() const { return core_.effects; }
  /// Pairs of two fixed blocks: never tested, since pedestals cannot interact.
  long fixed_fixed_pairs() const { return core_.fixed_fixed_pairs; }

  /// Carries the whole scene rigidly with the ground from time() to t_end, without stepping: every
  /// body is translated by `displacement` (the integral of the ground velocity over the interval),
  /// the pedestals take v_end, the free blocks' velocity changes by v_end - v_start (so their
  /// velocity relative to the ground is kept), orientations, angular momenta, contact springs and
  /// forces stay as they are: nothing changes relative to the pedestals. For free blocks asleep
  /// on a quiet pedestal (scenario::run decides when that is sound). The pedestals' work on the
  /// blocks is that of carrying them: sum of m (|v_end|^2 - |v_start|^2) / 2 + m g displacement_z.
  void carry_with_ground(double t_end, const Vec3& displacement, const Vec3& v_start, const Vec3& v_end);

 private:
  WorldCore core_;
  std::variant<PenaltyStepper, RigidStepper> stepper_;
};

}  // namespace rigid::dynamics
