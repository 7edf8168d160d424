#include "ply_check.hpp"

#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "rigid/core/error.hpp"

namespace rigid::io {
namespace {

enum class Format { ascii, little_endian, big_endian };

struct Property {
  std::string name;
  int size = 0;          // bytes of the value (binary), of each item for a list
  bool integer = false;  // the value (or each item) is an integer type
  bool is_signed = false;
  bool list = false;
  int count_size = 0;  // list: bytes of the item count
  bool count_signed = false;
  bool count_integer = false;
  std::string type, count_type;  // the header's words, for the canonical header
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  long line = 0;
  std::vector<Property> properties;
  int corners = -1;            // face: index of the vertex_indices list among the properties
  int axis[3] = {-1, -1, -1};  // vertex: indices of x, y, z among the properties
};

// PLY's scalar types: bytes, integer?, signed?; size 0 for an unknown name
struct ScalarType {
  int size = 0;
  bool integer = false;
  bool is_signed = false;
};

ScalarType scalar_type(const std::string& name) {
  static const std::pair<const char*, ScalarType> types[] = {
      {"char", {1, true, true}},    {"int8", {1, true, true}},     {"uchar", {1, true, false}},
      {"uint8", {1, true, false}},  {"short", {2, true, true}},    {"int16", {2, true, true}},
      {"ushort", {2, true, false}}, {"uint16", {2, true, false}},  {"int", {4, true, true}},
      {"int32", {4, true, true}},   {"uint", {4, true, false}},    {"uint32", {4, true, false}},
      {"float", {4, false, true}},  {"float32", {4, false, true}}, {"double", {8, false, true}},
      {"float64", {8, false, true}}};
  for (const auto& [type_name, type] : types) {
    if (name == type_name) return type;
  }
  return {};
}

std::vector<std::string> split_words(std::string_view line) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) words.emplace_back(line.substr(start, i - start));
  }
  return words;
}

// The header, read line by line up to end_header; `body` is the offset of the first body byte.
struct Header {
  Format format = Format::ascii;
  std::vector<Element> elements;
  std::size_t body = 0;
  long body_line = 0;  // line number of the first body line (ASCII)
};

// a header longer than this is no PLY header (real ones are a few hundred bytes)
constexpr std::size_t kMaxHeaderBytes = 1 << 20;
// more properties per element than any scanner writes; bounds the per-record work
constexpr std::size_t kMaxProperties = 256;

Header read_header(std::string_view bytes, const std::string& name) {
  Header h;
  std::size_t pos = 0;
  long line_no = 0;
  bool has_format = false;
  while (true) {
    const std::size_t eol = bytes.find('\n', pos);
    if (eol == std::string_view::npos || eol > kMaxHeaderBytes) {
      throw InputError(name, 0, "no end_header line: the PLY header never ends (truncated or not a PLY file)");
    }
    const std::string_view line = bytes.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    const std::vector<std::string> w = split_words(line);
    if (line_no == 1) {
      if (w.size() != 1 || w[0] != "ply") throw InputError(name, 1, "not a PLY file (the first line is not 'ply')");
      continue;
    }
    if (line.find('\0') != std::string_view::npos) throw InputError(name, line_no, "a NUL byte in the PLY header");
    // a carriage return may end a line (CRLF) but not split one: the importer reads "float\ry"
    // as one word where this check reads two, and the two then disagree on the body's layout
    if (const std::size_t cr = line.find('\r'); cr != std::string_view::npos && cr + 1 != line.size())
      throw InputError(name, line_no, "a carriage return inside a PLY header line");
    // exporters write no empty header lines, and the importer reads them otherwise than this
    // check (a fuzzer's find: blank lines between properties, on which the importer crashed)
    if (w.empty()) throw InputError(name, line_no, "an empty line in the PLY header");
    if (w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") {
      if (!has_format) throw InputError(name, line_no, "the PLY header has no format line");
      // the importer skips blanks and line ends before a binary body, this check does not: a body
      // that starts with one would be laid out differently by the two (a fuzzer's find, on which
      // the importer aborted)
      if (h.format != Format::ascii && pos < bytes.size() &&
          (bytes[pos] == ' ' || bytes[pos] == '\t' || bytes[pos] == '\r' || bytes[pos] == '\n'))
        throw InputError(name, line_no + 1,
                         "the binary body begins with a blank or line-end byte, which the importer would skip and "
                         "this check would not: re-export the mesh");
      h.body = pos;
      h.body_line = line_no + 1;
      return h;
    }
    if (w[0] == "format") {
      // one format line, before the elements: a second one would be read by this check and the
      // first by the importer, which would then parse the body in another encoding
      if (has_format) throw InputError(name, line_no, "a second format line in the PLY header");
      if (!h.elements.empty()) throw InputError(name, line_no, "the format line must come before the elements");
      if (w.size() != 3 || w[2] != "1.0") throw InputError(name, line_no, "format line must be 'format TYPE 1.0'");
      if (w[1] == "ascii")
        h.format = Format::ascii;
      else if (w[1] == "binary_little_endian")
        h.format = Format::little_endian;
      else if (w[1] == "binary_big_endian")
        h.format = Format::big_endian;
      else
        throw InputError(name, line_no, "unknown PLY format '" + w[1] + "'");
      has_format = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) throw InputError(name, line_no, "element line must be 'element NAME COUNT'");
      Element e;
      e.name = w[1];
      e.line = line_no;
      const auto [end, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (ec != std::errc() || end != w[2].data() + w[2].size() ||
          e.count > std::numeric_limits<std::uint32_t>::max()) {
        throw InputError(name, line_no, "element '" + e.name + "': count '" + w[2] + "' is not a number below 2^32");
      }
      for (const auto& other : h.elements) {
        if (other.name == e.name) throw InputError(name, line_no, "element '" + e.name + "' declared twice");
      }
      if (e.name == "tristrips")
        throw InputError(name, line_no, "triangle strips are not read: save the mesh with faces");
      h.elements.push_back(e);
    } else if (w[0] == "property") {
      if (h.elements.empty()) throw InputError(name, line_no, "property before any element");
      Element& e = h.elements.back();
      if (e.properties.size() >= kMaxProperties)
        throw InputError(name, line_no, "more than 256 properties in one element");
      Property p;
      if (w.size() == 5 && w[1] == "list") {
        const ScalarType count = scalar_type(w[2]), item = scalar_type(w[3]);
        if (count.size == 0 || item.size == 0) throw InputError(name, line_no, "unknown type in a list property");
        if (!count.integer) throw InputError(name, line_no, "a list's length must have an integer type");
        p.list = true;
        p.count_size = count.size;
        p.count_signed = count.is_signed;
        p.count_integer = count.integer;
        p.size = item.size;
        p.integer = item.integer;
        p.is_signed = item.is_signed;
        p.name = w[4];
        p.count_type = w[2];
        p.type = w[3];
      } else if (w.size() == 3) {
        const ScalarType t = scalar_type(w[1]);
        if (t.size == 0) throw InputError(name, line_no, "unknown property type '" + w[1] + "'");
        p.size = t.size;
        p.integer = t.integer;
        p.is_signed = t.is_signed;
        p.name = w[2];
        p.type = w[1];
      } else {
        throw InputError(name, line_no, "property line must be 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
      }
      for (const auto& other : e.properties) {
        if (other.name == p.name) throw InputError(name, line_no, "property '" + p.name + "' declared twice");
      }
      e.properties.push_back(p);
    } else {
      throw InputError(name, line_no, "unknown PLY header line '" + w[0] + "'");
    }
  }
}

// The structure Rigid needs: vertices with scalar x, y, z; faces with an integer corner list.
void check_elements(Header& h, const std::string& name, std::uint64_t& vertices) {
  bool has_vertex = false, has_face = false;
  for (Element& e : h.elements) {
    if (e.name == "vertex") {
      has_vertex = true;
      vertices = e.count;
      for (int a = 0; a < 3; ++a) {
        const std::string axis(1, "xyz"[a]);
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
          if (e.properties[k].name == axis && !e.properties[k].list) e.axis[a] = int(k);
        }
        if (e.axis[a] < 0) throw InputError(name, e.line, "element 'vertex' has no scalar property '" + axis + "'");
      }
    } else if (e.name == "face") {
      has_face = true;
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
        if (!p.list || !p.integer || !p.count_integer) {
          throw InputError(name, e.line, "face property '" + p.name + "' must be a list of integers");
        }
        e.corners = int(k);
      }
      if (e.corners < 0) throw InputError(name, e.line, "element 'face' has no vertex_indices list");
    }
  }
  if (!has_vertex) throw InputError(name, 0, "the PLY header declares no 'vertex' element");
  if (!has_face) throw InputError(name, 0, "the PLY header declares no 'face' element (a point cloud is no surface)");
}

// Fewest body bytes the header's counts need: a binary record holds every scalar and list count
// (faces at least three corners); an ASCII record a digit and a separator per value.
void check_counts_fit(const Header& h, std::size_t body_bytes, const std::string& name) {
  long double needed = 0;
  for (const Element& e : h.elements) {
    long double record = 0;
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      const int least_items = int(k) == e.corners ? 3 : 0;
      if (h.format == Format::ascii)
        record += 2.0L * (1 + (p.list ? least_items : 0));
      else
        record += p.list ? p.count_size + least_items * p.size : p.size;
    }
    needed += record * static_cast<long double>(e.count);
    if (needed > static_cast<long double>(body_bytes) + 1) {
      char what[256];
      std::snprintf(what, sizeof what,
                    "the header declares %llu %s records, more than the file's %zu bytes after the header can hold "
                    "(truncated, or a wrong count)",
                    static_cast<unsigned long long>(e.count), e.name.c_str(), body_bytes);
      throw InputError(name, e.line, what);
    }
  }
}

// ---- binary body ------------------------------------------------------------------------------

struct BinaryReader {
  std::string_view bytes;
  std::size_t pos = 0;
  bool big_endian = false;

  bool has(std::size_t n) const { return n <= bytes.size() - pos; }
  // the integer or real at pos as a double (every integer of up to 32 bits is exact)
  double value(int size, bool integer, bool is_signed) {
    unsigned char b[8];
    std::memcpy(b, bytes.data() + pos, size);
    pos += size;
    if (big_endian) {
      for (int i = 0; i < size / 2; ++i) std::swap(b[i], b[size - 1 - i]);
    }
    if (!integer) {
      if (size == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      }
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    std::uint64_t u = 0;
    for (int i = size - 1; i >= 0; --i) u = (u << 8) | b[i];
    if (is_signed && (u >> (8 * size - 1)) != 0) return double(std::int64_t(u) - (std::int64_t(1) << (8 * size)));
    return double(u);
  }
};

std::string record_name(const Element& e, std::uint64_t r) { return e.name + " " + std::to_string(r); }

void check_corner_count(double n, const Element& e, std::uint64_t r, const std::string& name, long line) {
  if (n < 3) {
    throw InputError(name, line,
                     record_name(e, r) + " has " + std::to_string(static_cast<long long>(n)) +
                         " corners: points and lines are no surface");
  }
}

void check_corner(double index, std::uint64_t vertices, const Element& e, std::uint64_t r, const std::string& name,
                  long line) {
  if (!(index >= 0 && index < double(vertices))) {
    char what[160];
    std::snprintf(what, sizeof what, "%s: corner index %.0f is not one of the %llu vertices", record_name(e, r).c_str(),
                  index, static_cast<unsigned long long>(vertices));
    throw InputError(name, line, what);
  }
}

void check_binary_body(const Header& h, std::string_view bytes, std::uint64_t vertices, const std::string& name,
                       std::string& canonical) {
  BinaryReader in{bytes, h.body, h.format == Format::big_endian};
  for (const Element& e : h.elements) {
    // records of no property take no bytes: nothing to read, however many are declared
    if (e.properties.empty()) continue;
    const bool vertex = e.name == "vertex";
    for (std::uint64_t r = 0; r < e.count; ++r) {
      std::string_view xyz[3];
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        const auto truncated = [&] {
          return InputError(name, 0, "the file ends inside " + record_name(e, r) + " (truncated)");
        };
        if (!p.list) {
          if (!in.has(p.size)) throw truncated();
          for (int a = 0; a < 3; ++a) {
            if (vertex && e.axis[a] == int(k)) xyz[a] = bytes.substr(in.pos, std::size_t(p.size));
          }
          in.pos += p.size;
          continue;
        }
        const std::size_t list_start = in.pos;
        if (!in.has(p.count_size)) throw truncated();
        const double n = in.value(p.count_size, p.count_integer, p.count_signed);
        if (int(k) == e.corners) check_corner_count(n, e, r, name, 0);
        if (n < 0) throw InputError(name, 0, record_name(e, r) + ": negative list length");
        if (!in.has(std::size_t(n) * p.size)) throw truncated();
        if (int(k) != e.corners) {
          in.pos += std::size_t(n) * p.size;
          continue;
        }
        for (std::size_t c = 0; c < std::size_t(n); ++c)
          check_corner(in.value(p.size, true, p.is_signed), vertices, e, r, name, 0);
        canonical.append(bytes.substr(list_start, in.pos - list_start));
      }
      if (vertex) {
        for (const std::string_view& v : xyz) canonical.append(v);
      }
    }
  }
}

// ---- ASCII body -------------------------------------------------------------------------------

// Numbers separated by blanks, one record per line (the layout assimp's ASCII reader expects).
struct AsciiReader {
  std::string_view bytes;
  std::size_t pos = 0;
  long line = 0;

  // moves to the next non-blank line; false at the end of the file
  bool next_line() {
    while (pos < bytes.size()) {
      const char c = bytes[pos];
      if (c == ' ' || c == '\t' || c == '\r') {
        ++pos;
      } else if (c == '\n') {
        ++pos;
        ++line;
      } else {
        return true;
      }
    }
    return false;
  }
  // the next word on this line; empty at the line's end
  std::string_view word() {
    while (pos < bytes.size() && (bytes[pos] == ' ' || bytes[pos] == '\t' || bytes[pos] == '\r')) ++pos;
    const std::size_t start = pos;
    while (pos < bytes.size() && bytes[pos] != ' ' && bytes[pos] != '\t' && bytes[pos] != '\r' && bytes[pos] != '\n')
      ++pos;
    return bytes.substr(start, pos - start);
  }
};

double ascii_number(std::string_view word, bool integer, const Element& e, std::uint64_t r, const std::string& name,
                    long line) {
  double v = 0;
  const char* end = word.data() + word.size();
  if (integer) {
    long long i = 0;
    const auto [stop, ec] = std::from_chars(word.data(), end, i);
    if (ec == std::errc() && stop == end) return double(i);
  } else {
    const auto [stop, ec] = std::from_chars(word.data(), end, v);
    if (ec == std::errc() && stop == end) return v;
    // 1e999 reads as a number too large for a double: say so as for inf
    if (ec == std::errc::result_out_of_range && stop == end)
      throw InputError(name, line,
                       record_name(e, r) + ": '" + std::string(word.substr(0, 32)) +
                           "' is not a finite number (beyond the range of a double)");
  }
  if (word.empty()) throw InputError(name, line, record_name(e, r) + ": the line ends before the record does");
  throw InputError(name, line,
                   record_name(e, r) + ": '" + std::string(word.substr(0, 32)) + "' is not " +
                       (integer ? "an integer" : "a number"));
}

void check_ascii_body(const Header& h, std::string_view bytes, std::uint64_t vertices, const std::string& name,
                      std::string& canonical) {
  AsciiReader in{bytes, h.body, h.body_line};
  for (const Element& e : h.elements) {
    const bool vertex = e.name == "vertex";
    for (std::uint64_t r = 0; r < e.count; ++r) {
      if (!in.next_line())
        throw InputError(name, in.line, "the file ends before " + record_name(e, r) + " (truncated)");
      const long line = in.line;
      std::string_view xyz[3];
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (!p.list) {
          const std::string_view word = in.word();
          ascii_number(word, p.integer, e, r, name, line);
          for (int a = 0; a < 3; ++a) {
            if (vertex && e.axis[a] == int(k)) xyz[a] = word;
          }
          continue;
        }
        const std::string_view count_word = in.word();
        const double n = ascii_number(count_word, true, e, r, name, line);
        if (int(k) == e.corners) canonical.append(count_word);
        if (int(k) == e.corners) check_corner_count(n, e, r, name, line);
        if (n < 0) throw InputError(name, line, record_name(e, r) + ": negative list length");
        // each item needs at least two bytes: more than the rest of the file holds is a wrong count
        if (n > double(bytes.size() - in.pos)) {
          throw InputError(
              name, line,
              record_name(e, r) + ": the list is longer than the rest of the file (truncated, or a wrong count)");
        }
        for (std::size_t c = 0; c < std::size_t(n); ++c) {
          const std::string_view word = in.word();
          const double v = ascii_number(word, p.integer, e, r, name, line);
          if (int(k) != e.corners) continue;
          check_corner(v, vertices, e, r, name, line);
          canonical.append(" ").append(word);
        }
        if (int(k) == e.corners) canonical.append("\n");
      }
      if (!in.word().empty())
        throw InputError(name, line, record_name(e, r) + ": more values than the header declares");
      if (vertex) canonical.append(xyz[0]).append(" ").append(xyz[1]).append(" ").append(xyz[2]).append("\n");
    }
  }
}

// The header of the canonical file: the format, the vertices' x, y, z and the faces' corner list
// with the types the file gave them, nothing else.
std::string canonical_header(const Header& h) {
  static const char* formats[] = {"ascii", "binary_little_endian", "binary_big_endian"};
  std::string out = std::string("ply\nformat ") + formats[int(h.format)] + " 1.0\n";
  for (const Element& e : h.elements) {
    if (e.name == "vertex") {
      out += "element vertex " + std::to_string(e.count) + "\n";
      for (int a = 0; a < 3; ++a)
        out += "property " + e.properties[std::size_t(e.axis[a])].type + " " + "xyz"[a] + "\n";
    } else if (e.name == "face") {
      const Property& p = e.properties[std::size_t(e.corners)];
      out += "element face " + std::to_string(e.count) + "\nproperty list " + p.count_type + " " + p.type +
             " vertex_indices\n";
    }
  }
  return out + "end_header\n";
}

}  // namespace

std::string check_ply(std::string_view bytes, const std::string& name) {
  Header h = read_header(bytes, name);
  std::uint64_t vertices = 0;
  check_elements(h, name, vertices);
  check_counts_fit(h, bytes.size() - h.body, name);
  // the body in the file's element order, each record cut to what the canonical header declares
  std::string body;
  if (h.format == Format::ascii)
    check_ascii_body(h, bytes, vertices, name, body);
  else
    check_binary_body(h, bytes, vertices, name, body);
  return canonical_header(h) + body;
}

}  // namespace rigid::io
