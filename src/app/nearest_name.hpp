#pragma once
/// "Did you mean": the known name nearest to a misspelt one, for usage errors (command_line.hpp).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rigid::app {

/// Edits (insertions, deletions, substitutions, swaps of two adjacent characters) that turn a into b.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate `typed` most likely misspells: the nearest by edit_distance when it is at most a third
/// of `typed`'s length (at least 1), else the one candidate `typed` begins; empty when there is none.
std::string nearest_name(std::string_view typed, const std::vector<std::string>& candidates);

}  // namespace rigid::app
