#pragma once
/// Edge extension of a calibration's design (docs/validation-shaketable.md, "Designs that find the
/// optimum"): when the best value of a numeric parameter of the contact law sits at an edge of the
/// values tried, the next stage tries the values beside it, one parameter at a time through the
/// best parameter set, until every parameter is interior, at a physical limit, or the budget of
/// stages is spent. The lapse, which costs no simulation, is extended in the fit itself. Pure
/// functions: no simulation, no I/O.
#include <string>
#include <vector>

#include "rigid/calibration/outcome_model.hpp"
#include "rigid/dynamics/world_core.hpp"
#include "rigid/shaketable/physics.hpp"

namespace rigid::shaketable {

/// The numeric parameters of the contact law a design extends.
enum class LawParameter { normal_stiffness, damping, restitution, friction };
/// "K_N", "D", "e", "mu": the symbols of the docs and the progress lines.
const char* parameter_symbol(LawParameter p);
/// The parameters the physics' contact model uses: K_N, D and mu (penalty); e and mu (rigid).
std::vector<LawParameter> law_parameters(const Physics& p);
double parameter_value(const Physics& p, LawParameter q);

/// A closed range of values a parameter may physically take.
struct Range {
  double low = 0, high = 0;
};

/// Where extension stops: docs/physics.md §14 gives each reason.
struct PhysicalLimits {
  Range normal_stiffness{1e5, 1e13};  ///< per rock: stiffness_limits (unit: N/m^1.5)
  /// D >= 0; at 15 s/m a 0.1 m/s rocking impact is already fully plastic (Hunt & Crossley 1975)
  Range damping{0.0, 15.0};
  Range restitution{0.0, 1.0};  ///< energy is not created by an impact; 0 = plastic
  /// rock on rock or concrete: tan 22 deg (smooth saw-cut joints) to tan 50 deg (rough joints at
  /// low normal stress; Barton & Choubey 1977)
  Range friction{0.4, 1.2};
  /// 0: the model explains every outcome; 0.5: a quarter of the lab's outcomes would flip on a
  /// repeat, beyond which a test says more about the lab than about the rock
  Range lapse{0.0, 0.5};
  Range of(LawParameter q) const;
};

/// How deep, as a share of the base's half-width b (the centroid's horizontal distance to the
/// nearest edge of its support polygon, the lever arm it rocks about), the Hertzian sinkage
/// (m g / K_N)^(2/3) of the whole weight on the edge it pivots about may reach: at b, half the
/// base's width, the pivot sinks as deep as its lever arm is long, and the springs model a rock in
/// a pit rather than one rocking on its base.
inline constexpr double kMaxSinkageFraction = 1.0;
/// Below this static sinkage the penalty contact is as stiff as the rigid contact model, which the
/// design has anyway (unit: m).
inline constexpr double kRigidSinkage_m = 1e-6;

/// The stiffness range of a rock (its free block, resting on its base of half-width
/// `base_half_width_m`): bounded below by the sinkage limit, above by kRigidSinkage_m. (The penalty
/// model's automatic step is stable for any stiffness: it sets no bound.)
Range stiffness_limits(const std::vector<dynamics::BodyDef>& bodies, double base_half_width_m);

/// One parameter's place in the design.
enum class EdgeStatus { interior, at_edge_budget, at_physical_limit, not_identified, fixed };
/// "interior", "at edge (budget)", "at a physical limit", "not identified (another value within the 95 % region)",
/// "fixed (one value given)"
const char* status_text(EdgeStatus s);

struct ParameterReport {
  std::string name;           ///< "K_N", "D", "e", "mu", "lapse"
  double value = 0;           ///< the best's
  std::vector<double> tried;  ///< along the line through the best (the others held), ascending
  EdgeStatus status = EdgeStatus::interior;
};

/// The next stage of an extension, or its end (no physics).
struct ExtensionStage {
  int best_variant = 0;                     ///< in the fitted design
  std::vector<Physics> physics;             ///< the variants to simulate next (none: done)
  std::vector<std::string> moves;           ///< "K_N down to 2.5e5", one per variant
  std::vector<ParameterReport> parameters;  ///< the law's parameters as the design stands
};

/// From the design fitted so far (its grid, on one heading list, and the physics of its variants),
/// the best candidate's parameter set under `search`, and for each of its law's parameters the
/// values beside it along its line: the nearest value tried anywhere (`earlier`: e.g. stage 1)
/// on that side, else one step beyond the edge (K_N: the design's own ratio, else 2; the others:
/// the design's own step, else a default), clamped to `limits`. A parameter with another value on
/// the best's line within the 95 % likelihood-ratio region (calibration::kRegionLogLikelihoodDrop)
/// is not identified and not extended; one
/// given a single value (in all stages, with this contact model) is fixed by the user. With
/// `budget_left` false nothing is proposed and edges are marked "at edge (budget)".
ExtensionStage extension_stage(const calibration::OutcomeGrid& fitted, const std::vector<int>& observed,
                               const std::vector<Physics>& fitted_physics, const std::vector<Physics>& earlier,
                               const calibration::SearchSettings& search, const PhysicalLimits& limits,
                               bool budget_left);

/// The lapse grid extended until the best lapse is interior or at its limit: from the edge, the
/// grid's own outermost step, clamped to limits.lapse. No simulation, so no budget.
struct LapseExtension {
  calibration::SearchSettings search;
  ParameterReport report;
};
LapseExtension extend_lapses(const calibration::OutcomeGrid& fitted, const std::vector<int>& observed,
                             calibration::SearchSettings search, const Range& limits);

/// One line per stage for logs and the JSON: "stage 3 (extend K_N down to 2.5e5, D up to 6)".
std::string stage_purpose(int stage, const std::vector<std::string>& moves);

}  // namespace rigid::shaketable
