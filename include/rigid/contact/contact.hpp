#pragma once
/// Contact between two convex blocks: the common plane (shortest link, with the overlap step for
/// penetrating pairs; Nezami et al. 2006, physics.md §4), the subcontacts on it, and the force
/// law at each subcontact (physics.md §3). Pure functions: the caller owns all state.
#include <string_view>
#include <vector>

#include "rigid/contact/gjk.hpp"

namespace rigid::contact {

/// How contacts resist interpenetration.
enum class ContactMethod {
  /// The study's penalty springs (physics.md §3): F_n = K_N d^1.5 (1 + D dd/dt) per subcontact,
  /// incremental shear springs capped by Coulomb; explicit time step limited by the stiffness.
  penalty,
  /// Non-penetrating rigid contact (physics.md §12): Moreau-Jean time stepping, impulses solved
  /// at the velocity level with the Signorini condition, a Newton impact law and the Coulomb
  /// cone; the step follows the motion and the geometry, not a spring.
  rigid,
};

/// "penalty" or "rigid".
const char* contact_method_name(ContactMethod model);
/// Parses "penalty" or "rigid"; false for anything else.
bool parse_contact_method(std::string_view name, ContactMethod& model);

/// Contact law: the model, and the parameters of each (penalty values: the original study's,
/// physics.md §11).
struct ContactLaw {
  /// Which contact model (rigid by default: the rigid-block answer at the lower cost, docs/performance.md,
  /// "Rigid contact: what it changes"); the stiffness and damping below belong to the penalty model only.
  ContactMethod method = ContactMethod::rigid;
  /// Normal restitution e_n of the rigid model's Newton impact law (unit: 1): 0 = plastic impact,
  /// Housner's assumption, under which a rocking block keeps r = 1 - 1.5 sin^2 alpha of its
  /// angular velocity per impact (physics.md §2).
  double restitution = 0;
  /// K_N in F_n = K_N d^1.5 (1 + D dd/dt), d = indentation (unit: N/m^1.5; the study writes N/m).
  double normal_stiffness = 1e8;
  /// K_S: shear force grows by K_S per metre of tangential displacement (unit: N/m).
  double shear_stiffness = 1e8;
  /// Coulomb friction coefficient: |F_s| <= mu F_n (unit: 1).
  double friction = 0.6;
  /// Hysteretic damping factor D of the Lankarani-Nikravesh / Hunt-Crossley form above
  /// (unit: s/m). LN identify D = 3(1 - e^2)/(4 v_impact), so restitution falls with impact speed.
  double damping = 2.0;
};

/// The plane between two blocks.
struct CommonPlane {
  Vec3 normal{0, 0, 1};   ///< unit normal pointing from A to B
  double overlap = 0;     ///< > 0: depth of penetration along normal; < 0: gap (unit: m)
  Vec3 point_a{0, 0, 0};  ///< witness point on A (unit: m)
  Vec3 point_b{0, 0, 0};  ///< witness point on B (unit: m)
};

/// Finds the common plane of A and B. Separated blocks: the perpendicular bisector of the
/// shortest link. Penetrating blocks (overlap step): B is pulled apart virtually along the current
/// normal estimate (previous_normal, usually last step's) until they separate, the shortest link
/// of that configuration gives a better normal, and this repeats until the normal settles; the
/// fixed point is the direction of least overlap (minimum translational distance).
CommonPlane find_common_plane(const PlacedHull& a, const PlacedHull& b, const Vec3& previous_normal,
                              SupportHints& hints);

/// Which vertex a subcontact sits on: (side << 30) | vertex index; side 0 = vertex of A inside
/// B, side 1 = vertex of B inside A; kEdgeSubcontact = the closest-point (edge-edge) contact.
inline constexpr int kEdgeSubcontact = -1;
inline int subcontact_key(int side, int vertex) { return (side << 30) | vertex; }

/// A point of contact on the common plane.
struct SubcontactPoint {
  int key = kEdgeSubcontact;
  Vec3 point{0, 0, 0};  ///< contact point, half-way through the indentation (unit: m)
  double overlap = 0;   ///< indentation along the common-plane normal (unit: m)
};

/// Subcontacts of a penetrating pair: every vertex of one block inside the other (tested against
/// the other's face planes in its body frame), indentation measured to the other block's
/// supporting plane along the normal; when no vertex is inside (edge-edge crossing), one
/// subcontact at the middle of the shortest link. Appends to `out` (no allocation once `out` has
/// capacity).
void collect_subcontacts(const PlacedHull& a, const PlacedHull& b, const CommonPlane& plane,
                         std::vector<SubcontactPoint>& out);

/// Force on B at one subcontact (A receives the opposite).
/// overlap_rate: d(indentation)/dt, > 0 while approaching (unit: m/s).
/// tangential_step: relative tangential displacement of B against A over the last step (unit: m).
/// shear_force: the subcontact's accumulated shear force on B (world frame), carried across steps;
/// it is first projected onto the current tangent plane, then incremented, then capped by Coulomb.
/// Returns the total force on B; `slip` receives the frictional slip of this step (unit: m).
Vec3 subcontact_force(const ContactLaw& law, const Vec3& normal, double overlap, double overlap_rate,
                      const Vec3& tangential_step, Vec3& shear_force, double& slip);

}  // namespace rigid::contact
