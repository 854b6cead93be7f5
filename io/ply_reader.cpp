// Validating PLY reader (Turk, "The PLY Polygon File Format", 1994): ascii,
// binary_little_endian and binary_big_endian; vertex x, y, z (any scalar type), face list
// vertex_indices / vertex_index (any integer count and index type); every other element and
// property is read past and ignored. Header lines may end in CR LF.
//
// A count the header declares is never looped over or reserved before the data proves it: each
// element's entries are checked against the bytes left when the element starts (binary: the
// sizes of its scalars and list counts; ascii: one token and one separator per property), and
// an element without properties (it holds no data in either encoding, whatever its count) is
// skipped in O(1) and reported in a note.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "geometry/core/input_error.h"
#include "io/mesh_reader.h"
#include "io/utf8_text.h"

namespace skyband::mesh_io {
namespace {

enum class Scalar { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

bool scalar_from_name(std::string_view s, Scalar& out) {
  if (s == "char" || s == "int8")
    out = Scalar::kInt8;
  else if (s == "uchar" || s == "uint8")
    out = Scalar::kUint8;
  else if (s == "short" || s == "int16")
    out = Scalar::kInt16;
  else if (s == "ushort" || s == "uint16")
    out = Scalar::kUint16;
  else if (s == "int" || s == "int32")
    out = Scalar::kInt32;
  else if (s == "uint" || s == "uint32")
    out = Scalar::kUint32;
  else if (s == "float" || s == "float32")
    out = Scalar::kFloat32;
  else if (s == "double" || s == "float64")
    out = Scalar::kFloat64;
  else
    return false;
  return true;
}

std::size_t size_of(Scalar s) {
  switch (s) {
    case Scalar::kInt8:
    case Scalar::kUint8:
      return 1;
    case Scalar::kInt16:
    case Scalar::kUint16:
      return 2;
    case Scalar::kInt32:
    case Scalar::kUint32:
    case Scalar::kFloat32:
      return 4;
    case Scalar::kFloat64:
      return 8;
  }
  return 0;
}

bool is_integer(Scalar s) {
  return s != Scalar::kFloat32 && s != Scalar::kFloat64;
}

struct Property {
  std::string name;
  bool is_list = false;
  Scalar count_type = Scalar::kUint8;
  Scalar type = Scalar::kFloat32;
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::size_t header_line = 0;
  std::vector<Property> properties;
};

// Sequential reader of the body, ascii or binary; values come back as doubles (every PLY
// integer type and float fits a double exactly).
class BodyReader {
 public:
  BodyReader(const std::string& name, std::string_view body, std::size_t first_line, int format)
      : name_(name), body_(body), line_(first_line), format_(format) {}

  // `what` describes the value for messages, e.g. "vertex 12 property 'x'".
  double read(Scalar type, const std::string& what) {
    if (format_ == 0) return read_ascii(type, what);
    const std::size_t n = size_of(type);
    last_start_ = pos_;
    if (pos_ + n > body_.size())
      throw InputError(name_ + ": binary data ends at byte " + std::to_string(offset_ + pos_) + " while reading " + what);
    unsigned char b[8];
    std::memcpy(b, body_.data() + pos_, n);
    pos_ += n;
    const bool big = format_ == 2;
    if (big != (std::endian::native == std::endian::big))
      for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    switch (type) {
      case Scalar::kInt8: {
        std::int8_t v;
        std::memcpy(&v, b, 1);
        return v;
      }
      case Scalar::kUint8:
        return b[0];
      case Scalar::kInt16: {
        std::int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case Scalar::kUint16: {
        std::uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case Scalar::kInt32: {
        std::int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Scalar::kUint32: {
        std::uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Scalar::kFloat32: {
        float v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Scalar::kFloat64: {
        double v;
        std::memcpy(&v, b, 8);
        return v;
      }
    }
    return 0;
  }
  void set_offset(std::size_t header_bytes) { offset_ = header_bytes; }
  // Position for messages: "line N" (ascii) or "byte N" (binary).
  std::string where() const {
    return format_ == 0 ? name_ + ":" + std::to_string(token_line_) : name_ + ": byte " + std::to_string(offset_ + last_start_);
  }
  // Bytes of the body not read yet.
  std::size_t remaining() const { return body_.size() - pos_; }
  std::size_t trailing_tokens() {
    std::size_t n = 0;
    if (format_ != 0) return body_.size() - pos_;
    std::string_view t;
    while (next_token(t)) ++n;
    return n;
  }

 private:
  bool next_token(std::string_view& token) {
    auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; };
    while (pos_ < body_.size() && space(body_[pos_])) {
      // LF, CR LF and lone CR each end one line
      if (body_[pos_] == '\n' || (body_[pos_] == '\r' && (pos_ + 1 >= body_.size() || body_[pos_ + 1] != '\n'))) ++line_;
      ++pos_;
    }
    if (pos_ >= body_.size()) return false;
    const std::size_t start = pos_;
    while (pos_ < body_.size() && !space(body_[pos_])) ++pos_;
    token = body_.substr(start, pos_ - start);
    token_line_ = line_;
    return true;
  }
  double read_ascii(Scalar type, const std::string& what) {
    std::string_view token;
    if (!next_token(token)) throw InputError(name_ + ":" + std::to_string(line_) + ": file ends while reading " + what);
    if (is_integer(type)) return static_cast<double>(parse_integer(token, name_, token_line_, what.c_str()));
    return parse_coordinate(token, name_, token_line_, what.c_str());
  }

  const std::string& name_;
  std::string_view body_;
  std::size_t pos_ = 0, offset_ = 0, last_start_ = 0;
  std::size_t line_ = 1, token_line_ = 1;
  int format_;  // 0 ascii, 1 binary little endian, 2 binary big endian
};

}  // namespace

PolygonSoup parse_ply(const std::string& name, const std::string& bytes) {
  PolygonSoup soup;
  soup.polygon_start.push_back(0);
  if (bytes.empty()) return soup;  // empty mesh: reported by the caller

  // Header: text lines up to and including "end_header".
  std::vector<Element> elements;
  int format = -1;
  std::size_t pos = 0, line = 0;
  bool ended = false;
  std::vector<std::string_view> tokens;
  while (pos < bytes.size() && !ended) {
    const std::size_t eol = bytes.find('\n', pos);
    std::string_view text(bytes.data() + pos, (eol == std::string::npos ? bytes.size() : eol) - pos);
    pos = eol == std::string::npos ? bytes.size() : eol + 1;
    ++line;
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    reject_nul_bytes(name, text, "the PLY header", line);
    split_tokens(text, tokens);
    const std::string where = name + ":" + std::to_string(line) + ": ";
    if (line == 1) {
      if (tokens.size() != 1 || tokens[0] != "ply") throw InputError(where + "not a PLY file: the first line is not 'ply'");
      continue;
    }
    if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
    if (tokens[0] == "format") {
      if (tokens.size() < 3 || tokens[2] != "1.0")
        throw InputError(where + "unsupported PLY format line '" + printable_text(text) + "'");
      if (tokens[1] == "ascii")
        format = 0;
      else if (tokens[1] == "binary_little_endian")
        format = 1;
      else if (tokens[1] == "binary_big_endian")
        format = 2;
      else
        throw InputError(where + "unknown PLY format '" + printable_text(tokens[1]) + "'");
    } else if (tokens[0] == "element") {
      if (tokens.size() != 3) throw InputError(where + "malformed element line '" + printable_text(text) + "'");
      const long long count = parse_integer(tokens[2], name, line, "element count");
      if (count < 0 || count > 0xFFFFFFFFll)
        throw InputError(where + "element count " + std::to_string(count) + " is out of range");
      elements.push_back({printable_text(tokens[1]), static_cast<std::size_t>(count), line, {}});
    } else if (tokens[0] == "property") {
      if (elements.empty()) throw InputError(where + "property before any element");
      Property p;
      if (tokens.size() == 5 && tokens[1] == "list") {
        p.is_list = true;
        if (!scalar_from_name(tokens[2], p.count_type) || !is_integer(p.count_type))
          throw InputError(where + "list count type '" + printable_text(tokens[2]) + "' is not an integer type");
        if (!scalar_from_name(tokens[3], p.type))
          throw InputError(where + "unknown property type '" + printable_text(tokens[3]) + "'");
        p.name = printable_text(tokens[4]);
      } else if (tokens.size() == 3) {
        if (!scalar_from_name(tokens[1], p.type))
          throw InputError(where + "unknown property type '" + printable_text(tokens[1]) + "'");
        p.name = printable_text(tokens[2]);
      } else {
        throw InputError(where + "malformed property line '" + printable_text(text) + "'");
      }
      elements.back().properties.push_back(p);
    } else if (tokens[0] == "end_header") {
      ended = true;
    } else {
      throw InputError(where + "unknown PLY header keyword '" + printable_text(tokens[0]) + "'");
    }
  }
  if (!ended) throw InputError(name + ": PLY header has no 'end_header' line");
  if (format < 0) throw InputError(name + ": PLY header has no 'format' line");
  soup.format = format == 0 ? "PLY (ascii)" : format == 1 ? "PLY (binary little endian)" : "PLY (binary big endian)";

  if (format == 0) reject_nul_bytes(name, std::string_view(bytes).substr(pos), "the ascii PLY body", line + 1);
  BodyReader body(name, std::string_view(bytes).substr(pos), line + 1, format);
  body.set_offset(pos);
  bool have_vertices = false, have_faces = false, vertices_done = false;
  for (const Element& e : elements) {
    int ix = -1, iy = -1, iz = -1, ifaces = -1;
    for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
      const Property& p = e.properties[static_cast<std::size_t>(k)];
      if (e.name == "vertex" && !p.is_list) {
        if (p.name == "x") ix = k;
        if (p.name == "y") iy = k;
        if (p.name == "z") iz = k;
      }
      if (e.name == "face" && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) ifaces = k;
    }
    const bool vertex_element = e.name == "vertex";
    const bool face_element = e.name == "face";
    if (vertex_element) {
      if (ix < 0 || iy < 0 || iz < 0)
        throw InputError(name + ":" + std::to_string(e.header_line) + ": PLY vertex element lacks an x, y or z property");
      have_vertices = true;
    }
    if (face_element) {
      if (ifaces < 0)
        throw InputError(name + ":" + std::to_string(e.header_line) + ": PLY face element lacks a 'vertex_indices' list");
      if (!is_integer(e.properties[static_cast<std::size_t>(ifaces)].type))
        throw InputError(name + ":" + std::to_string(e.header_line) + ": PLY face indices are not of an integer type");
      have_faces = true;
      soup.faces_declared += e.count;
    }
    if (e.properties.empty()) {
      // No data in either encoding, whatever the count: skipped without looping over the count.
      if (e.count > 0) {
        soup.notes.push_back("element '" + e.name + "' (line " + std::to_string(e.header_line) + ") has no properties: its " +
                             std::to_string(e.count) + " entries hold no data and were skipped");
        if (soup.not_for_openmesh.empty())
          soup.not_for_openmesh = "OpenMesh 9 would loop over the " + std::to_string(e.count) + " entries of element '" + e.name +
                                  "', which has no properties";
      }
      continue;
    }
    // The smallest entry: binary, the bytes of its scalars and list counts (empty lists); ascii,
    // one token and one separator per property (the file's last token may lack its separator).
    std::size_t entry_bytes = 0;
    for (const Property& p : e.properties) entry_bytes += format == 0 ? 2 : size_of(p.is_list ? p.count_type : p.type);
    const std::size_t room = body.remaining() + (format == 0 ? 1 : 0);
    if (e.count > room / entry_bytes)
      throw InputError(name + ":" + std::to_string(e.header_line) + ": element '" + e.name + "' declares " +
                       std::to_string(e.count) + " entries of at least " + std::to_string(entry_bytes) +
                       " bytes each, but only " + std::to_string(body.remaining()) + " bytes of data are left");
    if (vertex_element) soup.vertices.reserve(soup.vertices.size() + e.count);
    for (std::size_t i = 0; i < e.count; ++i) {
      Vec3 p = Vec3::Zero();
      for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
        const Property& prop = e.properties[static_cast<std::size_t>(k)];
        const std::string what = e.name + " " + std::to_string(i) + " property '" + prop.name + "'";
        if (!prop.is_list) {
          const double v = body.read(prop.type, what);
          if (vertex_element && (k == ix || k == iy || k == iz)) {
            if (!std::isfinite(v)) throw InputError(body.where() + ": non-finite " + what + " (" + std::to_string(v) + ")");
            p[k == ix ? 0 : k == iy ? 1 : 2] = v;
          }
          continue;
        }
        const double count = body.read(prop.count_type, what + " count");
        if (count < 0) throw InputError(body.where() + ": negative list length " + std::to_string(count) + " in " + what);
        const auto n = static_cast<std::size_t>(count);
        if (face_element && k == ifaces && n < 3)
          throw InputError(body.where() + ": face " + std::to_string(i) + " has " + std::to_string(n) +
                           " vertices, at least 3 needed");
        for (std::size_t j = 0; j < n; ++j) {
          const double v = body.read(prop.type, what + " item " + std::to_string(j));
          if (face_element && k == ifaces) {
            if (v < 0 || v > 0xFFFFFFFEu || (vertices_done && v >= static_cast<double>(soup.vertices.size())))
              throw InputError(body.where() + ": face " + std::to_string(i) + " vertex index " +
                               std::to_string(static_cast<long long>(v)) + " is out of range [0, " +
                               std::to_string(soup.vertices.size()) + ")");
            soup.indices.push_back(static_cast<std::uint32_t>(v));
          }
        }
        if (face_element && k == ifaces) soup.polygon_start.push_back(static_cast<std::uint32_t>(soup.indices.size()));
      }
      if (vertex_element) add_vertex(soup, p);
    }
    if (vertex_element) vertices_done = true;
  }
  if (!have_faces && !have_vertices) throw InputError(name + ": PLY file has neither a vertex nor a face element");
  for (std::size_t f = 0; f < soup.polygon_count(); ++f)
    for (std::uint32_t k = soup.polygon_start[f]; k < soup.polygon_start[f + 1]; ++k)
      if (soup.indices[k] >= soup.vertices.size())
        throw InputError(name + ": face " + std::to_string(f) + " vertex index " + std::to_string(soup.indices[k]) +
                         " is out of range [0, " + std::to_string(soup.vertices.size()) + ")");
  if (const std::size_t rest = body.trailing_tokens())
    soup.notes.push_back("ignored " + std::to_string(rest) + (format == 0 ? " value(s)" : " byte(s)") +
                         " after the last declared element");
  return soup;
}

}  // namespace skyband::mesh_io
