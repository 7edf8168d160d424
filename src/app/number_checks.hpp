#pragma once
/// CLI11 validators for numeric options: a value that is empty, not a number, NaN, infinite or
/// out of range is a usage error (`rigid: error: --OPTION: ...`, exit 2). An option's automatic
/// choice is its absence, so 0 is no stand-in for "automatic".
#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>

namespace rigid::app {

/// The whole text as a double; nothing when it is empty, has trailing characters or overflows.
std::optional<double> whole_number(const std::string& text);

/// Any finite number.
CLI::Validator finite_number();
/// A finite number > 0.
CLI::Validator positive_number();
/// A finite number >= 0.
CLI::Validator non_negative_number();
/// A number that `problem` admits: the setting's own rule (for example
/// job::checkpoint_interval_problem), which returns "" or what is wrong.
CLI::Validator number_admitted_by(std::function<std::string(double)> problem);
/// A finite angle of at most kMaxAngleDeg in magnitude (unit: deg).
CLI::Validator angle_deg();

/// Larger rotations are typing errors, and lose every digit of the angle (unit: deg).
inline constexpr double kMaxAngleDeg = 1e6;

}  // namespace rigid::app
