#pragma once
/// Old spellings of options, accepted for one release after a rename: each use prints one note
/// `rigid: note: OLD is now NEW (in UNIT); the old spelling goes in the next release` on stderr
/// and gives the current option the same value, so old and new spellings give the same results.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace rigid::app {

/// One value of an old spelling (each item of a list) to the current option's text.
using ValueConversion = std::function<std::string(const std::string&)>;

struct OldSpelling {
  std::string name;         ///< as typed, e.g. "--flatten-mm"
  std::string unit;         ///< the current option's unit when the rename changed it (e.g. "m"), else empty
  ValueConversion convert;  ///< old value to current value (e.g. value_divided_by(1000)); empty: unchanged
};

/// Accepts `old.name` on `cmd` as the old spelling of `current` (an option of `cmd`): hidden from
/// --help and from "did you mean"; it takes as many values as `current` (at least one), sets
/// `current` from them through `old.convert` (so `current`'s checks apply) and queues the note
/// (command_line.hpp). Giving both spellings is a usage error, unless `current` takes an optional
/// value and was given bare: then the old spelling's value is its value.
CLI::Option* add_old_spelling(CLI::App& cmd, CLI::Option& current, OldSpelling old);

/// A unit change by a power of ten or any other divisor (mm to m: value_divided_by(1000)): the
/// quotient, correctly rounded as the division is, in the shortest text that reads back exactly.
/// A value that is not a number passes unchanged, for `current`'s own check to refuse.
ValueConversion value_divided_by(double divisor);

}  // namespace rigid::app
