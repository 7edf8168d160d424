#pragma once
/// Rocking parameters of a scene with one free block (physics.md §2): the slenderness alpha and
/// frequency parameter p that normalise its fragility (the probit of the plots is in
/// ln(PGA / (g tan alpha)) and ln((PGV/PGA) p / alpha)). Rigid statics of the block as it rests.
#include <cmath>
#include <optional>
#include <vector>

#include "rigid/scenario/scene.hpp"

namespace rigid::analysis {

struct RockingParameters {
  double alpha = 0;    ///< smallest tipping angle over the edges of the support polygon (unit: rad)
  double radius = 0;   ///< R: distance from the centroid to that edge (unit: m)
  double p = 0;        ///< sqrt(m g R / I_edge), I_edge the inertia about that edge (unit: rad/s)
  double azimuth = 0;  ///< horizontal direction from the centroid to the edge (unit: rad, from +x)
  /// The support polygon: counter-clockwise (x, y) corners relative to the centroid (unit: m).
  std::vector<Eigen::Vector2d> support_polygon;
  /// alpha for a ground acceleration along each of kRockingAzimuths directions, k * 2 pi / n from
  /// +x towards +y (the field convention: x north, y east seen from above with z up): the block
  /// leans against the inertial force, towards -azimuth, and tips when the resultant of gravity
  /// and that force leaves the polygon, at a / g = tan(alpha_k) = s / h, s the distance from the
  /// centroid's projection to the polygon's boundary along -azimuth and h the centroid's height
  /// above that boundary point (unit: rad). Its minimum over all directions is `alpha`.
  std::vector<double> alpha_by_azimuth;
};

/// The quasi-static toppling acceleration of the block along its weakest direction, tan(alpha)
/// (unit: g): below it a block at rest on a rigid base cannot start to rock (physics.md §2).
inline double static_toppling_g(const RockingParameters& r) { return std::tan(r.alpha); }

/// Directions of RockingParameters::alpha_by_azimuth: every 22.5 degrees, a superset of the
/// tilt test's eight (analysis::tilt_survey).
inline constexpr int kRockingAzimuths = 16;

/// The rocking parameters of the scene's single free block, resting on fixed blocks: its support
/// polygon is the horizontal convex hull of its vertices within `contact_tolerance` of a fixed
/// block and of the fixed blocks' vertices that close to it (a block on a narrower pedestal top);
/// for each polygon edge the block tips when its centroid passes over the edge, at
/// tan(alpha_e) = d / h (d the horizontal distance from the centroid to the edge, h the centroid's
/// height above it). Empty when the scene has not exactly one free block, or the block is not
/// resting (fewer than three support points, or the centroid outside the polygon).
std::optional<RockingParameters> rocking_parameters(const scenario::Scene& scene, double contact_tolerance = 1e-3);

}  // namespace rigid::analysis
