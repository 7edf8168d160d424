#pragma once
// Typed access to TOML values for every Rigid TOML file (scenes, states, jobs): a value of the
// wrong type is an error naming file:line, the key and the expected type, never a silent default
// (`fixed = "true"` must not read as false). Private to rigid_io.
#include <set>
#include <string>

#include <toml++/toml.h>

namespace rigid::io {

long line_of(const toml::node& n);

/// Parses TOML text; a syntax error becomes rigid::InputError(path, line, description).
toml::table parse_toml(const std::string& text, const std::string& path);

/// Throws rigid::InputError at the first key of t not in `allowed` ("unknown key 'K' in WHERE").
void reject_unknown(const toml::table& t, const std::set<std::string>& allowed, const std::string& path,
                    const std::string& where);

/// The value of `key` in t, or `fallback` when absent; rigid::InputError when of another type
/// (numbers: also when not finite; integers are accepted as numbers).
std::string optional_string(const toml::table& t, const char* key, const std::string& fallback,
                            const std::string& path);
bool optional_bool(const toml::table& t, const char* key, bool fallback, const std::string& path);
double optional_number(const toml::table& t, const char* key, double fallback, const std::string& path);

}  // namespace rigid::io
