#include "toml_values.hpp"

#include <cmath>

#include "rigid/core/error.hpp"

namespace rigid::io {

long line_of(const toml::node& n) { return static_cast<long>(n.source().begin.line); }

toml::table parse_toml(const std::string& text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(path, static_cast<long>(e.source().begin.line), std::string(e.description()));
  }
}

void reject_unknown(const toml::table& t, const std::set<std::string>& allowed, const std::string& path,
                    const std::string& where) {
  for (const auto& [key, node] : t) {
    if (!allowed.count(std::string(key.str()))) {
      throw InputError(path, line_of(node), "unknown key '" + std::string(key.str()) + "' in " + where);
    }
  }
}

namespace {

[[noreturn]] void wrong_type(const toml::node& n, const char* key, const char* expected, const std::string& path) {
  throw InputError(path, line_of(n), std::string(key) + " must be " + expected);
}

}  // namespace

std::string optional_string(const toml::table& t, const char* key, const std::string& fallback,
                            const std::string& path) {
  const toml::node* n = t.get(key);
  if (!n) return fallback;
  if (const auto v = n->value_exact<std::string>()) return *v;
  wrong_type(*n, key, "a string (in quotes)", path);
}

bool optional_bool(const toml::table& t, const char* key, bool fallback, const std::string& path) {
  const toml::node* n = t.get(key);
  if (!n) return fallback;
  if (const auto v = n->value_exact<bool>()) return *v;
  wrong_type(*n, key, "true or false (a boolean, no quotes)", path);
}

double optional_number(const toml::table& t, const char* key, double fallback, const std::string& path) {
  const toml::node* n = t.get(key);
  if (!n) return fallback;
  if (!n->is_number()) wrong_type(*n, key, "a number", path);
  const double v = *n->value<double>();
  if (!std::isfinite(v)) wrong_type(*n, key, "a finite number", path);
  return v;
}

}  // namespace rigid::io
