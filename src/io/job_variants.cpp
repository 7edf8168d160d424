#include "job_variants.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "rigid/contact/contact.hpp"
#include "rigid/core/error.hpp"
#include "toml_values.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;
using scenario::VariantDomain;
using scenario::VariantKey;
using scenario::VariantParameterInfo;
using scenario::VariantValue;

// Most variants a job may have: each multiplies the cube (the cell limit applies as well).
constexpr int kMaxVariants = 100000;

struct Reader {
  const std::string& path;
  const fs::path& base;
  std::size_t objects;

  const VariantParameterInfo& parameter(const std::string& name, const toml::node& at, const char* where) const {
    const VariantParameterInfo* info = scenario::find_variant_parameter(name);
    if (!info) {
      throw InputError(
          path, line_of(at),
          "unknown parameter '" + name + "' in " + where + " (parameters: " + scenario::variant_parameter_list() + ")");
    }
    if (info->key == VariantKey::scene && objects != 1) {
      throw InputError(path, line_of(at), "scene: alternative scenes need a job with exactly one [[object]]");
    }
    return *info;
  }

  // One value of a parameter, checked: a number in its admitted range, or a known text.
  VariantValue value(const VariantParameterInfo& info, const toml::node& n) const {
    VariantValue out;
    if (info.text) {
      const auto s = n.value<std::string>();
      if (!s || s->empty())
        throw InputError(path, line_of(n), std::string(info.name) + ": each value must be a non-empty string");
      out.text = *s;
      if (info.key == VariantKey::contact) {
        contact::ContactMethod method;
        if (!contact::parse_contact_method(*s, method)) {
          throw InputError(path, line_of(n), "contact must be \"rigid\" or \"penalty\", not \"" + *s + "\"");
        }
        out.method = method;
      }
      if (info.key == VariantKey::scene) {
        const fs::path file = (base / *s).lexically_normal();
        if (!fs::exists(file)) throw InputError(path, line_of(n), "scene: file not found: " + file.string());
        out.text = file.string();
      }
      return out;
    }
    const auto v = n.value<double>();
    if (!v)
      throw InputError(path, line_of(n), std::string(info.name) + ": values must be numbers (" + info.units + ")");
    if (const auto problem = scenario::variant_value_problem(info, *v)) {
      throw InputError(path, line_of(n), std::string(info.name) + " " + *problem);
    }
    out.number = *v;
    return out;
  }

  std::vector<VariantValue> list(const VariantParameterInfo& info, const toml::array& values,
                                 const toml::node& at) const {
    if (values.empty()) throw InputError(path, line_of(at), std::string(info.name) + ": the list of values is empty");
    std::vector<VariantValue> out;
    for (const toml::node& n : values) out.push_back(value(info, n));
    return out;
  }

  VariantDomain range(const VariantParameterInfo& info, const toml::array& bounds, bool log_spacing,
                      const toml::node& at) const {
    const std::string usage = std::string(info.name) + ": a range is [low, high]";
    if (bounds.size() != 2) throw InputError(path, line_of(at), usage + ", two numbers");
    VariantDomain d{info.key, value(info, *bounds.get(0)).number, value(info, *bounds.get(1)).number, log_spacing, {}};
    if (!(d.low < d.high)) {
      char buf[120];
      std::snprintf(buf, sizeof buf, ": the range [%g, %g] is empty (needs low < high)", d.low, d.high);
      throw InputError(path, line_of(at), info.name + std::string(buf));
    }
    if (log_spacing && !(d.low > 0))
      throw InputError(path, line_of(at), std::string(info.name) + ": a log-spaced range needs low > 0");
    return d;
  }

  // A [sweep] entry: [low, high]; { range = [low, high], spacing = "log" | "linear" };
  // { values = [...] }; for a text parameter also a plain list of strings.
  VariantDomain domain(const VariantParameterInfo& info, const toml::node& n) const {
    if (const auto* arr = n.as_array()) {
      if (info.text) return {info.key, 0, 0, false, list(info, *arr, n)};
      return range(info, *arr, false, n);
    }
    const auto* t = n.as_table();
    if (!t) {
      throw InputError(path, line_of(n),
                       std::string(info.name) +
                           ": give [low, high], { range = [low, high], spacing = \"log\" } "
                           "or { values = [...] }");
    }
    reject_unknown(*t, {"range", "spacing", "values"}, path, std::string("[sweep] ") + info.name);
    if (t->contains("values") == t->contains("range")) {
      throw InputError(path, line_of(n),
                       std::string(info.name) + ": give either range = [low, high] or values = [...]");
    }
    if (const auto* values = t->get("values")) {
      const auto* arr = values->as_array();
      if (!arr) throw InputError(path, line_of(*values), std::string(info.name) + ": values must be a list");
      return {info.key, 0, 0, false, list(info, *arr, *values)};
    }
    if (info.text) throw InputError(path, line_of(n), std::string(info.name) + " is text: give a list of values");
    const std::string spacing = optional_string(*t, "spacing", "linear", path);
    if (spacing != "linear" && spacing != "log") {
      throw InputError(path, line_of(n), std::string(info.name) + ": spacing must be \"linear\" or \"log\"");
    }
    const auto* bounds = t->get("range")->as_array();
    if (!bounds)
      throw InputError(path, line_of(*t->get("range")), std::string(info.name) + ": range must be [low, high]");
    return range(info, *bounds, spacing == "log", *t->get("range"));
  }

  int positive_integer(const toml::table& t, const char* key, int fallback, int most) const {
    const toml::node* n = t.get(key);
    if (!n) return fallback;
    const auto v = n->value<std::int64_t>();
    if (!v || *v < 1 || *v > most) {
      throw InputError(path, line_of(*n), std::string(key) + " must be an integer from 1 to " + std::to_string(most));
    }
    return int(*v);
  }

  scenario::VariantSpace sweep(const toml::table& t, std::uint64_t campaign_seed, std::vector<long>& lines) const {
    static const std::set<std::string> settings{"method", "count", "levels", "seed"};
    std::vector<VariantDomain> domains;
    std::set<VariantKey> seen;
    for (const auto& [key, node] : t) {
      const std::string name(key.str());
      if (settings.count(name)) continue;
      const VariantParameterInfo& info = parameter(name, node, "[sweep]");
      seen.insert(info.key);
      domains.push_back(domain(info, node));
    }
    if (domains.empty())
      throw InputError(path, line_of(t),
                       "[sweep] varies no parameter (parameters: " + scenario::variant_parameter_list() + ")");
    // in the catalogue's order: toml++ does not keep the file's, and the design depends on the order
    std::sort(domains.begin(), domains.end(),
              [](const VariantDomain& a, const VariantDomain& b) { return a.key < b.key; });
    const std::string method = optional_string(t, "method", "lhs", path);
    lines.push_back(line_of(t));
    if (method == "lhs") {
      if (t.contains("levels"))
        throw InputError(path, line_of(*t.get("levels")),
                         "levels belongs to method = \"grid\"; a Latin hypercube takes count");
      if (!t.contains("count"))
        throw InputError(path, line_of(t), "[sweep] method = \"lhs\" needs count = N (variants)");
      const int count = positive_integer(t, "count", 1, kMaxVariants);
      std::uint64_t seed = campaign_seed;
      if (const toml::node* s = t.get("seed")) {
        const auto v = s->value<std::int64_t>();
        if (!v || *v < 0) throw InputError(path, line_of(*s), "seed must be a non-negative integer");
        seed = std::uint64_t(*v);
      }
      return scenario::latin_hypercube(domains, count, seed);
    }
    if (method == "grid") {
      if (t.contains("count"))
        throw InputError(path, line_of(*t.get("count")), "count belongs to method = \"lhs\"; a grid takes levels");
      if (t.contains("seed"))
        throw InputError(path, line_of(*t.get("seed")), "a grid is not random: seed belongs to method = \"lhs\"");
      const int levels = positive_integer(t, "levels", 3, 1000);
      if (scenario::grid_size(domains, levels) > kMaxVariants) {
        throw InputError(path, line_of(t), "[sweep] grid has more than " + std::to_string(kMaxVariants) + " variants");
      }
      return scenario::grid_design(domains, levels);
    }
    throw InputError(path, line_of(*t.get("method")), "method must be \"lhs\" or \"grid\", not \"" + method + "\"");
  }

  scenario::VariantSpace tables(const toml::array& arr, std::vector<long>& lines) const {
    scenario::VariantSpace space;
    space.method = "list";
    if (arr.empty()) throw InputError(path, line_of(arr), "[[variant]] list is empty");
    if (arr.size() > std::size_t(kMaxVariants))
      throw InputError(path, line_of(arr), "more than " + std::to_string(kMaxVariants) + " variants");
    for (const toml::node& node : arr) {
      const auto* t = node.as_table();
      if (!t) throw InputError(path, line_of(node), "each [[variant]] must be a table");
      if (t->empty()) throw InputError(path, line_of(node), "[[variant]] sets no parameter");
      std::vector<std::pair<VariantKey, VariantValue>> row;
      for (const auto& [key, value] : *t) {
        const VariantParameterInfo& info = parameter(std::string(key.str()), value, "[[variant]]");
        row.emplace_back(info.key, this->value(info, value));
      }
      std::sort(row.begin(), row.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      std::vector<VariantKey> keys;
      std::vector<VariantValue> values;
      for (auto& [k, v] : row) {
        keys.push_back(k);
        values.push_back(std::move(v));
      }
      if (space.variants.empty()) {
        space.keys = keys;
      } else if (keys != space.keys) {
        throw InputError(path, line_of(node), "every [[variant]] must set the same parameters as the first");
      }
      space.variants.push_back(std::move(values));
      lines.push_back(line_of(node));
    }
    return space;
  }
};

}  // namespace

scenario::VariantSpace read_variants(const toml::table& root, const std::string& path, const fs::path& base,
                                     std::uint64_t campaign_seed, std::size_t objects, std::vector<long>& lines) {
  const Reader reader{path, base, objects};
  const toml::node* sweep = root.get("sweep");
  const toml::node* variant = root.get("variant");
  if (sweep && variant)
    throw InputError(path, line_of(*variant), "give the variants either as [sweep] or as [[variant]] tables, not both");
  if (sweep) {
    const auto* t = sweep->as_table();
    if (!t) throw InputError(path, line_of(*sweep), "sweep must be a table ([sweep])");
    return reader.sweep(*t, campaign_seed, lines);
  }
  if (variant) {
    const auto* arr = variant->as_array();
    if (!arr) throw InputError(path, line_of(*variant), "variant must be an array of tables ([[variant]])");
    return reader.tables(*arr, lines);
  }
  return {};
}

}  // namespace rigid::io
