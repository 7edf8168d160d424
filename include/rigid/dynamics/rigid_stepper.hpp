#pragma once
/// The rigid contact model's time step (physics.md §12): Moreau-Jean time stepping, with the
/// narrow phase of WorldCore (common plane, subcontacts and their persistent keys) giving the
/// rows of the velocity-level contact solver (contact_solver.hpp). Owns what only this model
/// keeps: each subcontact's normal impulse and each pair's friction impulse (the warm start of
/// the next step), and the solver's buffers, sized once so that a step never allocates.
#include <vector>

#include "rigid/dynamics/contact_solver.hpp"
#include "rigid/dynamics/world_core.hpp"

namespace rigid::dynamics {

class RigidStepper {
 public:
  explicit RigidStepper(const WorldCore& world);

  /// Advances `world` by dt (World::step), in the stages below.
  void step(WorldCore& world, double dt, const Vec3& ground_velocity_start, const Vec3& ground_velocity_end);
  /// Normal force of subcontact k of pair `pair` in the last step (unit: N): p_n / h.
  double subcontact_load(const WorldCore& world, std::size_t pair, std::size_t k) const;
  /// The pedestals were carried (World::carry_with_ground) and now move at `velocity`.
  void set_pedestal_velocity(const Vec3& velocity) { pedestal_velocity_ = velocity; }

 private:
  /// The impulses of one pair, kept across steps.
  struct PairImpulses {
    struct Sub {
      int key;
      double normal_impulse = 0;  ///< on b over the last step (unit: N s)
    };
    /// Persistent subcontacts (double-buffered); subs[k] belongs to PairContact::points[k].
    std::vector<Sub> subs, next_subs;
    /// The friction impulse of the pair's contact patch on b over the last step, along the plane
    /// (unit: N s) and twisting about the normal (unit: N m s).
    Vec3 friction_impulse{0, 0, 0};
    double twist_impulse = 0;
  };

  /// Stage 1: the free blocks' positions and orientations to the midpoint of the step, with the
  /// last velocities; the pedestals by half a step.
  void advance_to_midpoint(WorldCore& world, double dt);
  /// Stage 2: the narrow phase at the midpoint, into contact rows and friction patches (warm
  /// started from the last step's impulses of the same subcontacts).
  void gather_contacts(WorldCore& world, double dt, const Vec3& ground_velocity);
  /// Stage 2b: one friction patch per two bodies and face (compound bodies only).
  void merge_piece_patches(const WorldCore& world);
  /// Stage 3: the solver's bodies at their free velocities (gravity over the step). Returns the
  /// smallest bounding radius of a free block.
  double set_free_velocities(const WorldCore& world, double dt, const Vec3& ground_velocity);
  /// Stage 4: the impulses (warm start, velocity solve, split-impulse position correction); counts
  /// a solve that hits its sweep cap. Returns whether a position correction was computed.
  bool solve_impulses(WorldCore& world, double dt, double smallest_radius);
  /// Stage 5: Itasca local damping of the step's velocity change (when set).
  void apply_local_damping(const WorldCore& world);
  /// Stage 6: the impulses back to the pairs (next step's warm start), contact forces, slip and
  /// the pedestals' work.
  void store_impulses(WorldCore& world, double dt, const Vec3& ground_velocity);
  /// Stage 7: the second half of the step with the new velocities (and the position correction).
  void advance_from_midpoint(WorldCore& world, double dt, const Vec3& ground_velocity, const Vec3& ground_velocity_end,
                             bool corrected);

  std::vector<PairImpulses> impulses_;  ///< one per WorldCore::pairs entry
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
};

}  // namespace rigid::dynamics
