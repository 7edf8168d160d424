#pragma once
/// A tiny JSON object writer for the CLI's one-line outputs (no dependency needed for flat
/// objects of numbers, booleans and strings).
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

namespace rigid::app {

class JsonObject {
 public:
  JsonObject& add(const std::string& key, double v) {
    char buf[32];
    if (std::isfinite(v)) {
      std::snprintf(buf, sizeof buf, "%.10g", v);
    } else {
      std::snprintf(buf, sizeof buf, "null");
    }
    return raw(key, buf);
  }
  JsonObject& add(const std::string& key, long v) { return raw(key, std::to_string(v)); }
  JsonObject& add(const std::string& key, bool v) { return raw(key, v ? "true" : "false"); }
  JsonObject& add(const std::string& key, const std::optional<double>& v) {
    return v ? add(key, *v) : raw(key, "null");
  }
  JsonObject& add(const std::string& key, const std::string& v) { return raw(key, quote(v)); }
  JsonObject& add(const std::string& key, const char* v) { return add(key, std::string(v)); }
  /// Inserts an already formatted JSON value (array or object).
  JsonObject& raw(const std::string& key, const std::string& json) {
    text_ += (text_.empty() ? "{" : ", ") + quote(key) + ": " + json;
    return *this;
  }
  std::string str() const { return text_.empty() ? "{}" : text_ + "}"; }

  static std::string quote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\') {
        out += '\\';
        out += c;
      } else if (static_cast<unsigned char>(c) < 0x20) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04x", c);
        out += buf;
      } else {
        out += c;
      }
    }
    return out + "\"";
  }

 private:
  std::string text_;
};

}  // namespace rigid::app
