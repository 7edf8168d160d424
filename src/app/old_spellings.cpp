#include "old_spellings.hpp"

#include <algorithm>
#include <charconv>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "command_line.hpp"
#include "number_checks.hpp"

namespace rigid::app {

CLI::Option* add_old_spelling(CLI::App& cmd, CLI::Option& current, OldSpelling old) {
  const std::string now = current.get_name();
  const std::string note = old.name + " is now " + now + (old.unit.empty() ? "" : " (in " + old.unit + ")") +
                           "; the old spelling goes in the next release";
  CLI::Option* option = cmd.add_option(old.name, [&current, old, now, note](const CLI::results_t& values) {
    // the current option's callback has run by now (it was added first). Given with a value too,
    // it conflicts; given bare (an optional value left out, as in `--csv --out F`), it yields
    const bool bare = current.get_expected_min() == 0 && current.results() == CLI::results_t{current.get_default_str()};
    if (current.count() > 0 && !bare) {
      throw CLI::ValidationError(old.name, "is the old spelling of " + now + "; give only " + now);
    }
    current.clear();
    std::vector<std::string> converted;
    for (const std::string& v : values) converted.push_back(old.convert ? old.convert(v) : v);
    current.add_result(converted);
    current.run_callback();
    queue_note(note);
    return true;
  });
  option->group("");  // hidden
  option->expected(std::max(1, current.get_expected_min()), std::max(1, current.get_expected_max()));
  if (current.get_delimiter() != '\0') option->delimiter(current.get_delimiter());
  return option;
}

ValueConversion value_divided_by(double divisor) {
  return [divisor](const std::string& text) -> std::string {
    const std::optional<double> v = whole_number(text);
    if (!v) return text;
    char buf[32];
    const auto end = std::to_chars(buf, buf + sizeof buf, *v / divisor).ptr;
    return std::string(buf, end);
  };
}

}  // namespace rigid::app
