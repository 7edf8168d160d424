#pragma once
/// The penalty contact model's time step (physics.md §8-11): velocity Verlet over the forces of
/// Hertz normal springs and incremental shear springs at each subcontact, with Itasca local
/// damping. Owns what only this model keeps: the accumulated shear force of every subcontact, each
/// pair's stiffness weight and the bodies' forces and torques.
#include <vector>

#include "rigid/dynamics/world_core.hpp"

namespace rigid::dynamics {

class PenaltyStepper {
 public:
  explicit PenaltyStepper(const WorldCore& world);

  /// Advances `world` by dt (World::step).
  void step(WorldCore& world, double dt, const Vec3& ground_velocity_start, const Vec3& ground_velocity_end);
  /// Forces and torques of the current state (dt: the step the shear springs stretch over; 0 when
  /// the state was set from outside).
  void compute_forces(WorldCore& world, double dt);
  /// Normal force of subcontact k of pair `pair` in the last step (unit: N): the elastic part
  /// K_N d^1.5, weighted; 0 for an open contact.
  double subcontact_load(const WorldCore& world, std::size_t pair, std::size_t k) const;
  /// Elastic energy stored in the contact springs (unit: J).
  double elastic_energy(const WorldCore& world) const;

 private:
  /// The springs of one pair, kept across steps.
  struct PairSprings {
    /// The weight of each subcontact's springs, min(1, 4 / n) for a patch of n subcontacts counted
    /// by depth, n = sum (d_i / d_max)^1.5: a patch is never stiffer than four subcontacts at its
    /// deepest indentation.
    double stiffness_weight = 1;
    struct Sub {
      int key;
      Vec3 shear_force;  ///< on b (unit: N)
    };
    /// Persistent subcontacts (double-buffered); subs[k] belongs to PairContact::points[k].
    std::vector<Sub> subs, next_subs;
  };

  std::vector<PairSprings> springs_;  ///< one per WorldCore::pairs entry
  std::vector<Vec3> forces_, torques_;
};

}  // namespace rigid::dynamics
