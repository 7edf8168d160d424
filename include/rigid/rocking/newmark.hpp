#pragma once
/// Newmark (1965) rigid-plastic sliding: a rigid block on a horizontal base that moves with the
/// base while the base acceleration stays within the friction limit mu g, and slides against it,
/// resisted by mu m g, when it does not. The sliding oracle of the accuracy study (docs/accuracy.md),
/// beside Housner's rocking model. No I/O.
#include <vector>

namespace rigid::rocking {

/// Relative displacement of the block against the base (unit: m; > 0 toward +x) once the base is
/// quiet and the block has stopped. `base_acceleration` is sampled every `dt` (unit: m/s^2, s),
/// linear between samples and zero after the last; `friction` is mu. The block lags the base: a
/// base accelerating toward +x leaves it sliding toward -x. Integrated with a fixed step of 1e-5 s
/// (midpoint acceleration), each stop placed exactly within its step.
double newmark_displacement(const std::vector<double>& base_acceleration, double dt, double friction);

}  // namespace rigid::rocking
