/// STL reader and writers (ASCII and binary).
#include "rigid/io/stl.hpp"

#include "input_file.hpp"

#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

#include "rigid/core/error.hpp"

namespace rigid::io {
namespace {

using geometry::Triangle;
using geometry::TriangleSoup;

// binary layout: 80-byte header, uint32 facet count, then per facet 12 float32 + uint16
constexpr std::size_t kHeaderBytes = 84;
constexpr std::size_t kFacetBytes = 50;

[[noreturn]] void fail(const std::string& name, long line, const std::string& what) {
  throw InputError(name, line, what);
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

// bytes that never occur in ASCII STL text (but do in the binary count and floats)
bool is_control(char c) {
  const auto u = static_cast<unsigned char>(c);
  return (u < 0x20 && !is_space(c)) || u == 0x7f;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

// a token quoted in an error message: one line, printable, bounded
std::string quote(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string s = "'";
  for (std::size_t i = 0; i < token.size() && i < kMax; ++i) {
    const auto u = static_cast<unsigned char>(token[i]);
    s += (u >= 0x20 && u < 0x7f) ? token[i] : '?';
  }
  if (token.size() > kMax) s += "...";
  return s + "'";
}

struct Token {
  std::string_view text;  // empty at end of input
  long line = 0;
};

// Whitespace-separated tokens with line numbers; a lone CR (old Mac) also ends a line.
class Lexer {
 public:
  explicit Lexer(std::string_view s) : s_(s) {}

  // the next token; at the end an empty token on the line of the last one
  Token next() {
    skip_space();
    const std::size_t start = pos_;
    while (pos_ < s_.size() && !is_space(s_[pos_])) ++pos_;
    if (pos_ == start) return {{}, last_line_};
    last_line_ = line_;
    return {s_.substr(start, pos_ - start), line_};
  }

  Token peek() {
    const Lexer saved = *this;
    const Token t = next();
    *this = saved;
    return t;
  }

  /// line of the last token read (where an unexpected end of file is reported)
  long line() const { return last_line_; }

 private:
  void skip_space() {
    while (pos_ < s_.size() && is_space(s_[pos_])) {
      if (s_[pos_] == '\n' || (s_[pos_] == '\r' && (pos_ + 1 == s_.size() || s_[pos_ + 1] != '\n'))) {
        ++line_;
      }
      ++pos_;
    }
  }

  std::string_view s_;
  std::size_t pos_ = 0;
  long line_ = 1;
  long last_line_ = 1;
};

enum class NumberError { none, malformed, out_of_range };

NumberError parse_double(std::string_view token, double& value) {
  // from_chars rejects a leading '+', which some writers emit
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value, std::chars_format::general);
  if (ec == std::errc::result_out_of_range) return NumberError::out_of_range;
  if (ec != std::errc() || ptr != end) return NumberError::malformed;
  return NumberError::none;
}

class AsciiParser {
 public:
  AsciiParser(std::string_view s, const std::string& name) : lx_(s), name_(name) {}

  TriangleSoup parse() {
    TriangleSoup soup;
    Token t = lx_.next();
    if (!iequals(t.text, "solid")) fail(name_, t.line, "expected 'solid', found " + quote(t.text));
    for (;;) {
      // the solid's name: the rest of its line, unless the facets start on that line too
      while (true) {
        const Token n = lx_.peek();
        if (n.text.empty() || n.line != t.line || iequals(n.text, "facet") || iequals(n.text, "endsolid")) {
          break;
        }
        lx_.next();
      }
      for (;;) {
        const Token k = lx_.next();
        if (k.text.empty()) fail(name_, lx_.line(), "unexpected end of file: missing 'endsolid'");
        if (iequals(k.text, "endsolid")) break;
        if (!iequals(k.text, "facet")) {
          fail(name_, k.line, "expected 'facet' or 'endsolid', found " + quote(k.text));
        }
        soup.push_back(facet());
      }
      const long end_line = lx_.line();  // the 'endsolid' just read
      while (true) {
        const Token n = lx_.peek();
        if (n.text.empty() || n.line != end_line || iequals(n.text, "solid")) break;
        lx_.next();
      }
      t = lx_.next();
      if (t.text.empty()) break;
      if (!iequals(t.text, "solid")) {
        fail(name_, t.line, "expected 'solid' or end of file after 'endsolid', found " + quote(t.text));
      }
    }
    if (soup.empty()) fail(name_, 0, "no facets");
    return soup;
  }

 private:
  Token expect_token(const char* what) {
    const Token t = lx_.next();
    if (t.text.empty()) {
      fail(name_, lx_.line(), std::string("unexpected end of file: expected ") + what);
    }
    return t;
  }

  void expect(const char* keyword) {
    const Token t = expect_token((std::string("'") + keyword + "'").c_str());
    if (!iequals(t.text, keyword)) {
      fail(name_, t.line, std::string("expected '") + keyword + "', found " + quote(t.text));
    }
  }

  double number(bool vertex) {
    const Token t = expect_token(vertex ? "a vertex coordinate" : "a normal component");
    double x = 0;
    switch (parse_double(t.text, x)) {
      case NumberError::malformed:
        fail(name_, t.line,
             std::string("malformed number ") + quote(t.text) + (vertex ? " in vertex" : " in facet normal"));
      case NumberError::out_of_range:
        fail(name_, t.line, "number " + quote(t.text) + " is out of range");
      case NumberError::none:
        break;
    }
    // normals are recomputed, so a NaN normal (written by some exporters) is harmless
    if (vertex && !std::isfinite(x)) {
      fail(name_, t.line, "vertex coordinate " + quote(t.text) + " is NaN or infinite");
    }
    return x;
  }

  // after 'facet': [normal nx ny nz] outer loop vertex x y z (x3) endloop endfacet
  Triangle facet() {
    Token t = expect_token("'normal' or 'outer'");
    const bool has_normal = iequals(t.text, "normal");
    if (has_normal) {
      for (int i = 0; i < 3; ++i) number(false);
      t = expect_token("'outer'");
    }
    if (!iequals(t.text, "outer")) {
      fail(name_, t.line,
           std::string(has_normal ? "expected 'outer'" : "expected 'normal' or 'outer'") + ", found " + quote(t.text));
    }
    expect("loop");
    Triangle tri;
    Vec3* corner[3] = {&tri.a, &tri.b, &tri.c};
    for (int i = 0; i < 3; ++i) {
      const Token v = expect_token("'vertex'");
      if (iequals(v.text, "endloop")) {
        fail(name_, v.line, "facet has " + std::to_string(i) + " vertices; a facet needs 3");
      }
      if (!iequals(v.text, "vertex")) fail(name_, v.line, "expected 'vertex', found " + quote(v.text));
      for (int k = 0; k < 3; ++k) (*corner[i])[k] = number(true);
    }
    const Token e = expect_token("'endloop'");
    if (iequals(e.text, "vertex")) {
      fail(name_, e.line, "facet has more than 3 vertices; only triangles are supported");
    }
    if (!iequals(e.text, "endloop")) fail(name_, e.line, "expected 'endloop', found " + quote(e.text));
    expect("endfacet");
    return tri;
  }

  Lexer lx_;
  const std::string& name_;
};

std::uint32_t read_u32(const char* p) {
  std::uint32_t x = 0;
  for (int i = 3; i >= 0; --i) x = (x << 8) | static_cast<unsigned char>(p[i]);
  return x;
}

void write_u32(char* p, std::uint32_t x) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<char>((x >> (8 * i)) & 0xffu);
}

TriangleSoup parse_binary(std::string_view s, const std::string& name) {
  const std::uint32_t n = read_u32(s.data() + 80);
  if (n == 0) fail(name, 0, "binary STL with zero facets");
  TriangleSoup soup;
  soup.reserve(n);
  for (std::uint32_t f = 0; f < n; ++f) {
    // skip the 12-byte normal: it is recomputed from the vertices
    const char* p = s.data() + kHeaderBytes + kFacetBytes * f + 12;
    Triangle tri;
    Vec3* corner[3] = {&tri.a, &tri.b, &tri.c};
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) {
        const float x = std::bit_cast<float>(read_u32(p + 4 * (3 * i + k)));
        if (!std::isfinite(x)) {
          fail(name, 0, "facet " + std::to_string(f) + ": vertex coordinate is NaN or infinite");
        }
        (*corner[i])[k] = x;
      }
    }
    soup.push_back(tri);
  }
  return soup;
}

Vec3 unit_normal(const Triangle& t) {
  const Vec3 n = (t.b - t.a).cross(t.c - t.a);
  const double len = n.norm();
  return len > 0 && std::isfinite(len) ? Vec3(n / len) : Vec3::Zero();
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) fail(path, 0, std::string("cannot open for writing: ") + std::strerror(errno));
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) fail(path, 0, "write failed");
}

}  // namespace

geometry::TriangleSoup read_stl_from_memory(std::string_view bytes, const std::string& name) {
  if (bytes.empty()) fail(name, 0, "file is empty");
  bool text = true;
  for (char c : bytes) {
    if (is_control(c)) {
      text = false;
      break;
    }
  }
  std::string_view body = bytes;
  if (body.substr(0, 3) == "\xEF\xBB\xBF") body.remove_prefix(3);  // UTF-8 byte-order mark
  const Token first = Lexer(body).next();
  const bool starts_solid = iequals(first.text, "solid");

  // ASCII STL is pure text; a binary count (< 2^24 facets) always holds a zero byte
  if (text && starts_solid) return AsciiParser(body, name).parse();
  const std::size_t size = bytes.size();
  if (size >= kHeaderBytes) {
    const std::uint64_t n = read_u32(bytes.data() + 80);
    const std::uint64_t expected = kHeaderBytes + kFacetBytes * n;
    if (expected == size) return parse_binary(bytes, name);
    if (!text) {
      fail(name, 0,
           "binary STL is truncated or corrupt: " + std::to_string(size) + " bytes, but its header declares " +
               std::to_string(n) + " facets (84 + 50 * " + std::to_string(n) + " = " + std::to_string(expected) +
               " bytes)");
    }
  }
  if (text) {
    if (first.text.empty()) fail(name, 0, "file contains only whitespace");
    fail(name, first.line, "not an STL file: expected 'solid', found " + quote(first.text));
  }
  fail(name, 0,
       "not an STL file: " + std::to_string(size) +
           " bytes is too short for binary STL (84 bytes at least) and it is not text");
}

geometry::TriangleSoup read_stl(const std::string& path) {
  return read_stl_from_memory(read_input_file(path, kMaxBulkFileBytes), path);
}

void write_stl_binary(const std::string& path, const geometry::TriangleSoup& soup) {
  if (soup.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("write_stl_binary: more than 2^32 - 1 facets");
  }
  std::string bytes(kHeaderBytes + kFacetBytes * soup.size(), '\0');
  // never "solid...": readers that trust the prefix would take the file for ASCII
  const char header[] = "binary STL written by rigid";
  std::memcpy(bytes.data(), header, sizeof header - 1);
  write_u32(bytes.data() + 80, static_cast<std::uint32_t>(soup.size()));
  for (std::size_t f = 0; f < soup.size(); ++f) {
    const Triangle& t = soup[f];
    char* p = bytes.data() + kHeaderBytes + kFacetBytes * f;
    const Vec3 n = unit_normal(t);
    const Vec3* values[4] = {&n, &t.a, &t.b, &t.c};
    for (int i = 0; i < 4; ++i) {
      for (int k = 0; k < 3; ++k) {
        const double x = (*values[i])[k];
        const auto xf = static_cast<float>(x);
        if (!std::isfinite(x) || !std::isfinite(xf)) {
          throw std::invalid_argument("write_stl_binary: facet " + std::to_string(f) +
                                      ": coordinate is not finite in single precision");
        }
        write_u32(p + 4 * (3 * i + k), std::bit_cast<std::uint32_t>(xf));
      }
    }
    // attribute byte count stays zero
  }
  write_file(path, bytes);
}

void write_stl_ascii(const std::string& path, const geometry::TriangleSoup& soup, const std::string& solid_name) {
  std::string name;
  for (char c : solid_name) name += is_space(c) || is_control(c) ? '_' : c;
  std::string out = "solid " + name + "\n";
  auto append = [&out](double x) {
    char buf[32];
    // shortest representation that reads back to the same double
    const auto r = std::to_chars(buf, buf + sizeof buf, x);
    out.append(buf, r.ptr);
  };
  auto append3 = [&](const char* indent, const Vec3& v) {
    out += indent;
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append(v[k]);
    }
    out += '\n';
  };
  for (std::size_t f = 0; f < soup.size(); ++f) {
    const Triangle& t = soup[f];
    if (!t.a.allFinite() || !t.b.allFinite() || !t.c.allFinite()) {
      throw std::invalid_argument("write_stl_ascii: facet " + std::to_string(f) + ": coordinate is NaN or infinite");
    }
    append3("  facet normal", unit_normal(t));
    out += "    outer loop\n";
    append3("      vertex", t.a);
    append3("      vertex", t.b);
    append3("      vertex", t.c);
    out += "    endloop\n  endfacet\n";
  }
  out += "endsolid " + name + "\n";
  write_file(path, out);
}

}  // namespace rigid::io
