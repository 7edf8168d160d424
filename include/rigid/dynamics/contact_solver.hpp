#pragma once
/// Velocity-level solver of the rigid contact model (physics.md §12): projected Gauss-Seidel over
/// contact patches. A patch is the contact of two convex blocks on their common plane: one
/// Signorini row per contact point (normal impulse >= 0, relative normal velocity at or above a
/// target, complementary) and one friction row for the whole patch (sliding along the plane and
/// twisting about its normal, inside the Coulomb limit mu N of the patch's total normal impulse N).
/// Each patch is solved as one block (its normal rows and friction together, exactly); the
/// patches are swept in a fixed order with a tolerance and an iteration cap, single-threaded: the same inputs give
/// the same impulses bit for bit. No allocation.
///
/// Why friction per patch, not per point: a rigid block on four corners leaves the split of
/// friction among them statically indeterminate, and per-point Coulomb discs solved by Gauss-Seidel
/// drift into self-equilibrated tangential components (the corners pulling against each other)
/// that use up friction capacity: a block slid at 0.956 mu g that way. The total Coulomb limit of a
/// planar patch is mu N, with the limit surface for combined sliding and twisting approximated by
/// an ellipsoid (Howe & Cutkosky 1996), the usual choice of patch-friction solvers; it is also
/// independent of how finely the faces are meshed.
#include <vector>

#include <Eigen/Core>

#include "rigid/core/types.hpp"

namespace rigid::dynamics {

/// Velocities of one body as the solver sees them (world frame). A body with inverse mass 0 and
/// a zero inverse inertia (a pedestal) is moved by nothing.
struct SolverBody {
  Vec3 velocity{0, 0, 0};               ///< unit: m/s
  Vec3 angular_velocity{0, 0, 0};       ///< unit: rad/s
  double inverse_mass = 0;              ///< unit: 1/kg
  Mat3 inverse_inertia = Mat3::Zero();  ///< world frame (unit: 1/(kg m^2))
};

/// One contact point between bodies a and b; impulses act on b, their opposite on a.
struct ContactRow {
  int a = 0, b = 0;
  Vec3 ra{0, 0, 0}, rb{0, 0, 0};  ///< contact point relative to each centroid (unit: m)
  Vec3 normal{0, 0, 1};           ///< unit, from a to b
  /// The relative normal velocity must end at or above this (unit: m/s): 0 for a closed contact
  /// with a plastic impact, -gap/h for a contact still open by `gap` (it may close, not cross),
  /// e |u_n^-| after an impact with restitution e.
  double target_normal_velocity = 0;
  /// Normal velocity the position correction (split impulse) asks for (unit: m/s; >= 0).
  double correction_velocity = 0;
  double normal_impulse = 0;      ///< p_n (unit: N s); in: warm start, out: solution
  double correction_impulse = 0;  ///< split impulse (unit: N s), moves positions only
  // filled by prepare()
  double normal_mass = 0;             ///< 1 / (J_n M^-1 J_n^T)
  Vec3 ra_n{0, 0, 0}, rb_n{0, 0, 0};  ///< ra x n, rb x n
  /// I_a^-1 (ra x n), I_b^-1 (rb x n): the angular velocity a unit normal impulse gives each body
  Vec3 turn_a{0, 0, 0}, turn_b{0, 0, 0};
};

/// The friction of one contact patch: rows [first_row, first_row + row_count) of the same pair.
struct FrictionPatch {
  int a = 0, b = 0;
  int first_row = 0, row_count = 0;
  Vec3 ra{0, 0, 0}, rb{0, 0, 0};  ///< patch centre relative to each centroid (unit: m)
  Vec3 normal{0, 0, 1};
  Vec3 tangent1{1, 0, 0}, tangent2{0, 1, 0};
  double friction = 0;  ///< Coulomb coefficient mu (unit: 1)
  /// Lever arm of the twisting friction (unit: m): the mean distance of the points from the
  /// centre, so that twisting is resisted up to mu N radius, as by friction at the points.
  double radius = 0;
  /// Impulse along tangent1, tangent2 (unit: N s) and the twisting impulse about the normal
  /// (unit: N m s); in: warm start, out: solution.
  Eigen::Vector3d impulse{0, 0, 0};
  Eigen::Matrix3d mass = Eigen::Matrix3d::Zero();  ///< filled by prepare(): (J M^-1 J^T)^-1
};

struct SolverSettings {
  /// Sweeps stop once a sweep changed no body's velocity by more than velocity_tolerance and no
  /// angular velocity by more than angular_tolerance. The motion, not the impulses: where rows are
  /// redundant (four corners of a face) the impulses can still shift among them without moving
  /// anything, and need not settle for the motion to be right.
  double velocity_tolerance = 1e-9;  ///< unit: m/s (the world sets it from g and the step)
  double angular_tolerance = 1e-9;   ///< unit: rad/s
  int max_iterations = 200;
};

struct SolverResult {
  int iterations = 0;  ///< sweeps of the velocity solve
  bool converged = false;
};

/// Velocity of b relative to a at the point with lever arms ra, rb from their centroids.
Vec3 relative_velocity(const SolverBody& a, const SolverBody& b, const Vec3& ra, const Vec3& rb);

/// Sets the patch's tangents: an orthonormal pair completing its normal, a fixed function of it.
void set_tangents(FrictionPatch& patch);

/// Effective masses of the rows and patches (normals, tangents and lever arms set).
void prepare(const std::vector<SolverBody>& bodies, std::vector<ContactRow>& rows, std::vector<FrictionPatch>& patches);

/// Applies the warm-start impulses of the rows and patches to the bodies' velocities.
void warm_start(std::vector<SolverBody>& bodies, const std::vector<ContactRow>& rows,
                const std::vector<FrictionPatch>& patches);

/// Which impulses a patch solve finds: the velocity step's (normal rows to their targets, with the
/// patch's friction) or the split-impulse position correction's (normal rows to their
/// correction velocities, no friction).
enum class PatchProblem { velocity, correction };

/// Solves one patch exactly with every other impulse held: its closed normal rows (Signorini)
/// and its friction together, by active-set pivoting on the normal rows alternating with the
/// friction state (sticking, or sliding with friction mu N along the radial projection of the
/// impulse that would stop the patch: the Gauss-Seidel friction row's fixed point). A patch of
/// more than 12 closed rows keeps the corners of their convex hull on the plane. Applies the
/// impulse changes to a and b. Returns false for more than 12 corners, a singular friction block
/// or pivoting that does not settle (changing nothing), or a point between the corners left
/// sinking (the corners' impulses kept); the caller then falls back to a Gauss-Seidel visit.
/// `velocity_tolerance` (unit: m/s): how far a row may stay below its target.
bool solve_patch_exactly(SolverBody& a, SolverBody& b, ContactRow* rows, FrictionPatch& patch, PatchProblem problem,
                         double velocity_tolerance);

/// Solves for the impulses (starting from the current ones, already applied to the bodies by
/// warm_start) and leaves the bodies at their end-of-step velocities: block Gauss-Seidel over the
/// patches, each solved exactly (solve_patch_exactly) or, failing that, by one projected
/// Gauss-Seidel visit of its rows. A lone patch (a block on a pedestal) is solved in one sweep;
/// patches that share a free block are visited point by point (physics.md §12: why, and what was
/// tried).
/// `scratch` holds a copy of the bodies between sweeps (no allocation once it has their size).
SolverResult solve_velocities(std::vector<SolverBody>& bodies, std::vector<ContactRow>& rows,
                              std::vector<FrictionPatch>& patches, const SolverSettings& settings,
                              std::vector<SolverBody>& scratch);

/// Split-impulse position correction: normal-only impulses that bring each penetrating row to its
/// correction_velocity, applied to `pseudo` velocities (zeroed first) that move positions only,
/// so no kinetic energy is added.
SolverResult solve_correction(const std::vector<SolverBody>& bodies, std::vector<SolverBody>& pseudo,
                              std::vector<ContactRow>& rows, const std::vector<FrictionPatch>& patches,
                              const SolverSettings& settings, std::vector<SolverBody>& scratch);

}  // namespace rigid::dynamics
