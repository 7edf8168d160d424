#include "number_checks.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <optional>
#include <string>

namespace rigid::app {
namespace {

// A validator that parses the whole text as a double and applies `ok` to it; `wanted` names the
// accepted values in the message. No description in --help, where it would stand between the
// type and the default (`FLOAT:a number >= 0=5`): the option's own text says what it takes.
CLI::Validator number_where(std::function<bool(double)> ok, const std::string& wanted) {
  return CLI::Validator(
      [ok, wanted](std::string& text) -> std::string {
        const std::optional<double> v = whole_number(text);
        if (v && std::isfinite(*v) && ok(*v)) return {};
        return "'" + text + "' is not " + wanted;
      },
      "");
}

}  // namespace

std::optional<double> whole_number(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE) return std::nullopt;
  return v;
}

CLI::Validator finite_number() {
  return number_where([](double) { return true; }, "a finite number");
}

CLI::Validator positive_number() {
  return number_where([](double v) { return v > 0; },
                      "a positive number (leave the option out for the automatic value)");
}

CLI::Validator non_negative_number() {
  return number_where([](double v) { return v >= 0; }, "a number >= 0");
}

CLI::Validator number_admitted_by(std::function<std::string(double)> problem) {
  return CLI::Validator(
      [problem](std::string& text) -> std::string {
        const std::optional<double> v = whole_number(text);
        if (!v) return "'" + text + "' is not a number";
        const std::string why = problem(*v);
        return why.empty() ? why : "'" + text + "' " + why;
      },
      "");
}

CLI::Validator angle_deg() {
  return number_where([](double v) { return std::abs(v) <= kMaxAngleDeg; }, "an angle of at most 1e6 deg");
}

}  // namespace rigid::app
