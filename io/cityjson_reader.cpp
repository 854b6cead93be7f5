#include "io/cityjson_reader.h"

#include <simdjson.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string_view>
#include <tuple>
#include <unordered_map>

#include "geometry/core/input_error.h"
#include "geometry/mesh/polygon_with_holes_triangulation.h"
#include "io/crs_codes.h"
#include "io/utf8_text.h"

namespace skyband {
namespace {

namespace od = simdjson::ondemand;
namespace dom = simdjson::dom;
using Elem = dom::element;
constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
constexpr int kMaxDepth = 1024;  // JSON nesting accepted (simdjson's DOM default)

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// A JSON value quoted in a message: compact, at most ~60 characters, control characters escaped.
// simdjson writes numbers in the shortest form that round-trips (1.5, 2.0, 1e+20).
std::string value_text(const Elem& v) {
  std::string text = simdjson::to_string(v);
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return printable_text(text);
}

// JSON text without the whitespace outside strings.
std::string minified(std::string_view raw) {
  std::string out;
  bool in_string = false, escaped = false;
  for (const char c : raw) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      continue;
    } else if (c == '"') {
      in_string = true;
    }
    out += c;
  }
  return out;
}

// RFC 6901 JSON Pointer token escaping ("~" → "~0", "/" → "~1").
std::string pointer_token(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

// Where we are: file name, line (CityJSONSeq; 0 = not a line-based file), and a JSON pointer.
struct Where {
  std::string file;
  std::size_t line = 0;
  std::string prefix() const { return line ? file + ":" + std::to_string(line) + ": " : file + ": "; }
};

[[noreturn]] void fail(const Where& where, const std::string& pointer, const std::string& message) {
  throw InputError(where.prefix() + printable_text(pointer) + (pointer.empty() ? "" : ": ") + message);
}

// Notes aggregated by reason: "<count> × <reason> (first: <where>)".
class Notes {
 public:
  void add(const std::string& reason, const std::string& example) {
    auto [it, inserted] = counts_.try_emplace(reason, Entry{0, example, order_.size()});
    if (inserted) order_.push_back(reason);
    ++it->second.count;
  }
  void emit(std::vector<std::string>& out) const {
    for (const std::string& reason : order_) {
      const Entry& e = counts_.at(reason);
      out.push_back(std::to_string(e.count) + " x " + reason +
                    (e.example.empty() ? "" : " (first: " + printable_text(e.example) + ")"));
    }
  }

 private:
  struct Entry {
    std::size_t count;
    std::string example;
    std::size_t order;
  };
  std::map<std::string, Entry> counts_;
  std::vector<std::string> order_;
};

// ---- JSON text (simdjson) ------------------------------------------------------------------
//
// A chunk of JSON text (a whole file or one CityJSONSeq line) lies in a simdjson padded buffer:
// SIMDJSON_PADDING readable bytes follow text.end(), so any part of it can be handed to simdjson
// as it is (a member's or a CityObject's text is parsed on its own without a copy).

std::size_t padded_capacity(std::string_view text, std::string_view part) {
  return static_cast<std::size_t>(text.data() + text.size() + simdjson::SIMDJSON_PADDING - part.data());
}

std::string_view trimmed(const char* begin, const char* end) {
  while (end > begin && (end[-1] == ' ' || end[-1] == '\t' || end[-1] == '\n' || end[-1] == '\r')) --end;
  return {begin, static_cast<std::size_t>(end - begin)};
}

// Integers beyond 64 bits (which simdjson's DOM refuses) written as decimals ("…0" → "…0.0"),
// so that they parse as the nearest double, as a JSON number without a 64-bit integer form is.
std::string widen_big_integers(std::string_view text) {
  std::string out;
  out.reserve(text.size() + 16);
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      out += c;
      ++i;
      continue;
    }
    if (c == '"') in_string = true;
    if (c != '-' && !(c >= '0' && c <= '9')) {
      out += c;
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < text.size() && (std::isdigit(static_cast<unsigned char>(text[j])) || text[j] == '.' || text[j] == 'e' ||
                               text[j] == 'E' || text[j] == '+' || text[j] == '-'))
      ++j;
    const std::string_view token = text.substr(i, j - i);
    out += token;
    if (token.find_first_of(".eE") == std::string_view::npos) {
      std::int64_t s;
      std::uint64_t u;
      const bool fits = token[0] == '-' ? std::from_chars(token.data(), token.data() + token.size(), s).ec == std::errc()
                                        : std::from_chars(token.data(), token.data() + token.size(), u).ec == std::errc();
      if (!fits) out += ".0";
    }
    i = j;
  }
  return out;
}

// Parses `part` (inside a padded text) into `parser`'s DOM.
simdjson::error_code parse_dom(dom::parser& parser, std::string_view part, Elem& out) {
  simdjson::error_code e = parser.parse(part.data(), part.size(), false).get(out);
  if (e == simdjson::NUMBER_ERROR) {  // validated text: an integer beyond 64 bits
    const std::string widened = widen_big_integers(part);
    e = parser.parse(widened).get(out);
  }
  return e;
}

// True if `token` is a JSON number as the grammar writes it (RFC 8259 §6).
bool json_number_syntax(std::string_view t) {
  std::size_t i = 0;
  if (i < t.size() && t[i] == '-') ++i;
  if (i >= t.size() || !std::isdigit(static_cast<unsigned char>(t[i]))) return false;
  if (t[i] == '0')
    ++i;
  else
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i;
  if (i < t.size() && t[i] == '.') {
    ++i;
    if (i >= t.size() || !std::isdigit(static_cast<unsigned char>(t[i]))) return false;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i;
  }
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    ++i;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    if (i >= t.size() || !std::isdigit(static_cast<unsigned char>(t[i]))) return false;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i;
  }
  return i == t.size();
}

// The JSON text of a value: an array or object whole, a scalar's token.
std::string_view raw_value(od::value v) {
  od::json_type t;
  if (v.type().get(t) == simdjson::SUCCESS) {
    std::string_view raw;
    if (t == od::json_type::array) {
      od::array a;
      if (v.get_array().get(a) == simdjson::SUCCESS && a.raw_json().get(raw) == simdjson::SUCCESS) return raw;
    } else if (t == od::json_type::object) {
      od::object o;
      if (v.get_object().get(o) == simdjson::SUCCESS && o.raw_json().get(raw) == simdjson::SUCCESS) return raw;
    }
  }
  const std::string_view token = v.raw_json_token();
  return trimmed(token.data(), token.data() + token.size());
}

// A validated value's text (inside a padded text) quoted in a message, as value_text would;
// with an integer beyond 64 bits (which the DOM does not take) or beyond 4 KB, as written.
std::string raw_value_text(std::string_view raw) {
  if (raw.size() <= 4096) {
    dom::parser parser;
    Elem e;
    if (parser.parse(raw.data(), raw.size(), false).get(e) == simdjson::SUCCESS) return value_text(e);
  }
  std::string s = minified(raw.substr(0, 4096));
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return printable_text(s);
}

bool ends_token(char c) {
  return std::string_view("[]{},: \t\r\n").find(c) != std::string_view::npos;
}

// The token at `at` in `text`, quoted for a message: a structural character, or up to the next one.
std::string token_text(std::string_view text, const char* at) {
  const char* end = text.data() + text.size();
  if (!at || at >= end) return "end of input";
  if (std::string_view("[]{},:").find(*at) != std::string_view::npos) return "'" + std::string(1, *at) + "'";
  const char* p = at;
  while (p < end && p - at < 40 && !ends_token(*p)) ++p;
  if (p == at) ++p;
  return "'" + printable_text(std::string_view(at, static_cast<std::size_t>(p - at))) + "'";
}

// The first syntax error of a JSON text by the grammar of RFC 8259, for the errors whose place
// simdjson cannot tell (a quote missing somewhere leaves a string open at the end): where and
// what. Only ever run on text already known to be malformed.
class SyntaxLocator {
 public:
  explicit SyntaxLocator(std::string_view text) : t_(text) {}
  std::pair<const char*, std::string> find() {
    try {
      value(0);
      space();
      if (i_ < t_.size()) return {t_.data() + i_, "unexpected " + token_text(t_, t_.data() + i_) + " after the JSON value"};
    } catch (const Found& f) {
      return {t_.data() + f.at, f.what};
    }
    return {nullptr, "a string is not closed"};
  }

 private:
  struct Found {
    std::size_t at;
    std::string what;
  };
  [[noreturn]] void error(std::size_t at, const std::string& what) { throw Found{at, what}; }
  [[noreturn]] void unexpected() {
    error(i_, i_ < t_.size() ? "unexpected " + token_text(t_, t_.data() + i_) : std::string("unexpected end of input"));
  }
  void space() {
    while (i_ < t_.size() && (t_[i_] == ' ' || t_[i_] == '\t' || t_[i_] == '\n' || t_[i_] == '\r')) ++i_;
  }
  bool digit() const { return i_ < t_.size() && t_[i_] >= '0' && t_[i_] <= '9'; }
  void expect(char c) {
    space();
    if (i_ >= t_.size() || t_[i_] != c) unexpected();
    ++i_;
  }
  void string() {
    const std::size_t open = i_++;
    while (true) {
      if (i_ >= t_.size()) error(open, "a string opened here is not closed");
      const char c = t_[i_];
      if (c == '"') {
        ++i_;
        return;
      }
      if (static_cast<unsigned char>(c) < 0x20) error(i_, "unescaped control character in a string");
      if (c == '\\') {
        if (i_ + 1 >= t_.size()) error(open, "a string opened here is not closed");
        const char e = t_[i_ + 1];
        if (e == 'u') {
          for (std::size_t k = 2; k < 6; ++k)
            if (i_ + k >= t_.size() || !std::isxdigit(static_cast<unsigned char>(t_[i_ + k])))
              error(i_, "invalid escape in a string");
          i_ += 6;
          continue;
        }
        if (std::string_view("\"\\/bfnrt").find(e) == std::string_view::npos) error(i_, "invalid escape in a string");
        i_ += 2;
        continue;
      }
      ++i_;
    }
  }
  void value(int depth) {
    space();
    if (depth > kMaxDepth) error(i_, "nested deeper than " + std::to_string(kMaxDepth) + " levels");
    if (i_ >= t_.size()) unexpected();
    const char c = t_[i_];
    if (c == '{') {
      ++i_;
      space();
      if (i_ < t_.size() && t_[i_] == '}') {
        ++i_;
        return;
      }
      while (true) {
        space();
        if (i_ >= t_.size() || t_[i_] != '"') unexpected();
        string();
        expect(':');
        value(depth + 1);
        space();
        if (i_ < t_.size() && t_[i_] == ',') {
          ++i_;
          continue;
        }
        expect('}');
        return;
      }
    }
    if (c == '[') {
      ++i_;
      space();
      if (i_ < t_.size() && t_[i_] == ']') {
        ++i_;
        return;
      }
      while (true) {
        value(depth + 1);
        space();
        if (i_ < t_.size() && t_[i_] == ',') {
          ++i_;
          continue;
        }
        expect(']');
        return;
      }
    }
    if (c == '"') return string();
    for (const std::string_view literal : {"true", "false", "null"})
      if (t_.substr(i_, literal.size()) == literal) {
        i_ += literal.size();
        if (i_ < t_.size() && !ends_token(t_[i_])) break;
        return;
      }
    if (c == '-' || (c >= '0' && c <= '9')) {
      const std::size_t start = i_;
      while (i_ < t_.size() && !ends_token(t_[i_])) ++i_;
      if (!json_number_syntax(t_.substr(start, i_ - start))) error(start, "invalid number " + token_text(t_, t_.data() + start));
      return;
    }
    error(i_, "invalid literal " + token_text(t_, t_.data() + i_));
  }

  std::string_view t_;
  std::size_t i_ = 0;
};

// ---- Pass 1: the whole chunk checked as JSON, its members located ---------------------------

// The "vertices" array as read, before the transform is known (members come in any order): per
// coordinate its bits (an int64, or a double) and its kind, per vertex whether it is an array of
// exactly 3 numbers. 25 bytes per vertex; converted in place to coordinates by read_vertices.
struct RawVertices {
  enum Kind : std::uint8_t { kInteger = 0, kDecimal = 1, kBigInteger = 2, kNotNumber = 3 };
  static constexpr std::uint8_t kNotTriple = 0x40;
  std::vector<Vec3> values;
  std::vector<std::uint8_t> kinds;  // bits 2k, 2k + 1: the kind of coordinate k; kNotTriple
};

struct ObjectText {
  std::string id;         // unescaped
  std::string_view text;  // the CityObject's JSON value
};

// One CityJSON value (a file, a CityJSONSeq line), checked as JSON: its root members' texts
// (the last of equal names, as a JSON object keeps it), "vertices" read, "CityObjects" split.
struct Chunk {
  std::string_view text;  // the whole chunk, in a padded buffer
  bool root_is_object = false;
  std::map<std::string, std::string_view, std::less<>> members;
  bool vertices_is_array = false;
  RawVertices vertices;
  bool city_objects_is_object = false;
  std::vector<ObjectText> objects;  // in the file's order

  std::optional<std::string_view> member(std::string_view name) const {
    const auto it = members.find(name);
    if (it == members.end()) return std::nullopt;
    return it->second;
  }
};

// Walks an on-demand document, checking every value as JSON (numbers included: an overflowing
// number is an error); throws InputError "not JSON (…)" with the line and column.
class JsonChecker {
 public:
  JsonChecker(std::string_view text, const Where& where, od::document& doc) : text_(text), where_(where), doc_(doc) {}

  // The document's root: its members located (a root object) or just checked.
  void root(Chunk& chunk) {
    od::json_type t;
    check(doc_.type().get(t));
    if (t == od::json_type::object) {
      od::object root;
      if (doc_.get_object().get(root)) fail_root();
      chunk.root_is_object = true;
      for (auto f : root) {
        od::field field;
        check(std::move(f).get(field));
        std::string_view key;
        check(field.unescaped_key().get(key));
        const std::string name(key);
        od::value v = field.value();
        const char* begin = v.raw_json_token().data();
        od::json_type vt;
        check(v.type().get(vt));
        if (name == "vertices") {
          chunk.vertices = {};
          chunk.vertices_is_array = vt == od::json_type::array;
          if (chunk.vertices_is_array)
            vertices(v, chunk.vertices);
          else
            value(v, 1);
        } else if (name == "CityObjects") {
          chunk.objects.clear();
          chunk.city_objects_is_object = vt == od::json_type::object;
          if (chunk.city_objects_is_object)
            city_objects(v, chunk.objects);
          else
            value(v, 1);
        } else {
          value(v, 1);
        }
        chunk.members[name] = trimmed(begin, location());
      }
    } else if (t == od::json_type::array) {
      od::value v;
      if (doc_.get_value().get(v)) fail_root();
      value(v, 0);
    } else {
      scalar_document(t);
    }
    end();
  }

  // A document that must hold one value and nothing after it.
  void whole() {
    od::json_type t;
    check(doc_.type().get(t));
    if (t == od::json_type::array || t == od::json_type::object) {
      od::value v;
      if (doc_.get_value().get(v)) fail_root();
      value(v, 0);
    } else {
      scalar_document(t);
    }
    end();
  }

  // "not JSON (why at line L, column C)": the first syntax error of the text by the grammar when
  // that comes before what simdjson found (simdjson's stage 1 finds some errors, such as a string
  // left open by a missing quote, only further on), else simdjson's error.
  [[noreturn]] static void report(std::string_view text, const Where& where, const char* at, std::string why) {
    const auto [first, what] = SyntaxLocator(text).find();
    if (first && (!at || first <= at)) {
      at = first;
      why = what;
    }
    throw InputError(where.prefix() + "not JSON (" + why + position(text, where, at) + ")");
  }

  [[noreturn]] void fail(simdjson::error_code e, const char* at = nullptr) {
    if (!at) {
      const char* here = nullptr;
      if (doc_.current_location().get(here) == simdjson::SUCCESS) at = here;
    }
    report(text_, where_, at, reason(e, at));
  }

  // Stage-1 errors (simdjson's iterate): invalid UTF-8, unescaped control characters, an
  // unclosed string, no value at all.
  [[noreturn]] static void fail_scan(std::string_view text, const Where& where, simdjson::error_code e) {
    const char* at = nullptr;
    std::string why;
    switch (e) {
      case simdjson::UTF8_ERROR: {
        why = "invalid UTF-8";
        const std::size_t i = first_invalid_utf8(text);
        if (i != std::string_view::npos) at = text.data() + i;
        break;
      }
      case simdjson::UNESCAPED_CHARS: {
        why = "unescaped control character in a string";
        bool in_string = false, escaped = false;
        for (std::size_t i = 0; i < text.size() && !at; ++i) {
          const char c = text[i];
          if (!in_string) {
            in_string = c == '"';
          } else if (escaped) {
            escaped = false;
          } else if (c == '\\') {
            escaped = true;
          } else if (c == '"') {
            in_string = false;
          } else if (static_cast<unsigned char>(c) < 0x20) {
            at = text.data() + i;
          }
        }
        break;
      }
      case simdjson::UNCLOSED_STRING:
        why = "a string is not closed";
        break;
      case simdjson::EMPTY:
        why = "no JSON value";
        break;
      case simdjson::CAPACITY:
        why = "larger than the JSON parser's 4 GB";
        break;
      default:
        why = simdjson::error_message(e);
    }
    report(text, where, at, why);
  }

 private:
  void check(simdjson::error_code e) {
    if (e) fail(e);
  }

  const char* location() {
    const char* at = nullptr;
    if (doc_.current_location().get(at) != simdjson::SUCCESS) at = text_.data() + text_.size();
    return at;
  }

  // The root array or object refused as a whole (simdjson checks that the text's last bracket
  // closes it): either content follows the value or the value is not closed.
  [[noreturn]] void fail_root() {
    int depth = 0;
    bool in_string = false, escaped = false;
    for (std::size_t i = 0; i < text_.size(); ++i) {
      const char c = text_[i];
      if (in_string) {
        if (escaped)
          escaped = false;
        else if (c == '\\')
          escaped = true;
        else if (c == '"')
          in_string = false;
      } else if (c == '"') {
        in_string = true;
      } else if (c == '[' || c == '{') {
        ++depth;
      } else if ((c == ']' || c == '}') && --depth <= 0) {
        const std::size_t next = text_.find_first_not_of(" \t\r\n", i + 1);
        const char* at = next == std::string_view::npos ? nullptr : text_.data() + next;
        if (depth == 0 && at) report(text_, where_, at, "unexpected " + token_at(at) + " after the JSON value");
        break;
      }
    }
    const char* end = text_.data() + text_.size();
    report(text_, where_, end, "unexpected end of input: an array or object is not closed");
  }

  void end() {
    const char* at = nullptr;
    if (doc_.current_location().get(at) == simdjson::SUCCESS)
      report(text_, where_, at, "unexpected " + token_at(at) + " after the JSON value");
  }

  void scalar_document(od::json_type t) {
    std::string_view token;
    const char* at = doc_.raw_json_token().get(token) == simdjson::SUCCESS ? token.data() : nullptr;
    simdjson::error_code e = simdjson::SUCCESS;
    switch (t) {
      case od::json_type::number: {
        double d;
        e = doc_.get_double().get(d);
        break;
      }
      case od::json_type::string: {
        std::string_view s;
        e = doc_.get_string().get(s);
        break;
      }
      case od::json_type::boolean: {
        bool b;
        e = doc_.get_bool().get(b);
        break;
      }
      default: {
        bool null = false;
        e = doc_.is_null().get(null);
        if (!e && !null) e = simdjson::N_ATOM_ERROR;
      }
    }
    if (e == simdjson::TRAILING_CONTENT) report(text_, where_, nullptr, "unexpected content after the JSON value");
    if (e) fail(e, at);
  }

  // Any value, checked down to its last number.
  void value(od::value v, int depth) {
    if (depth > kMaxDepth) fail(simdjson::DEPTH_ERROR, v.raw_json_token().data());
    od::json_type t;
    check(v.type().get(t));
    switch (t) {
      case od::json_type::array: {
        od::array a;
        check(v.get_array().get(a));
        for (auto element : a) {
          od::value x;
          check(std::move(element).get(x));
          value(x, depth + 1);
        }
        return;
      }
      case od::json_type::object: {
        od::object o;
        check(v.get_object().get(o));
        for (auto f : o) {
          od::field field;
          check(std::move(f).get(field));
          std::string_view key;
          check(field.unescaped_key().get(key));
          value(field.value(), depth + 1);
        }
        return;
      }
      case od::json_type::number: {
        double d;
        const simdjson::error_code e = v.get_double().get(d);
        if (e) fail(e, v.raw_json_token().data());
        return;
      }
      case od::json_type::string: {
        std::string_view s;
        const simdjson::error_code e = v.get_string().get(s);
        if (e) fail(e, v.raw_json_token().data());
        return;
      }
      case od::json_type::boolean: {
        bool b;
        const simdjson::error_code e = v.get_bool().get(b);
        if (e) fail(e, v.raw_json_token().data());
        return;
      }
      case od::json_type::null: {
        bool null = false;
        const simdjson::error_code e = v.is_null().get(null);
        if (e || !null) fail(e ? e : simdjson::N_ATOM_ERROR, v.raw_json_token().data());
        return;
      }
    }
  }

  // One coordinate: its bits and kind (RawVertices).
  std::uint8_t coordinate(od::value c, std::uint64_t& bits) {
    od::json_type t;
    check(c.type().get(t));
    if (t != od::json_type::number) {
      value(c, 3);
      return RawVertices::kNotNumber;
    }
    std::int64_t i;
    if (c.get_int64().get(i) == simdjson::SUCCESS) {
      bits = std::bit_cast<std::uint64_t>(i);
      return RawVertices::kInteger;
    }
    double d;
    const std::string_view token = c.raw_json_token();
    const simdjson::error_code e = c.get_double().get(d);  // also integers beyond int64
    if (e) fail(e, token.data());
    bits = std::bit_cast<std::uint64_t>(d);
    return trimmed(token.data(), token.data() + token.size()).find_first_of(".eE") == std::string_view::npos
               ? RawVertices::kBigInteger
               : RawVertices::kDecimal;
  }

  void vertices(od::value v, RawVertices& out) {
    od::array a;
    check(v.get_array().get(a));
    std::size_t n = 0;
    if (a.count_elements().get(n) == simdjson::SUCCESS) {
      out.values.reserve(n);
      out.kinds.reserve(n);
    }
    for (auto element : a) {
      od::value p;
      check(std::move(element).get(p));
      std::uint8_t kind = 0;
      std::array<std::uint64_t, 3> bits{};
      od::json_type t;
      check(p.type().get(t));
      if (t == od::json_type::array) {
        od::array coordinates;
        check(p.get_array().get(coordinates));
        std::size_t k = 0;
        for (auto c : coordinates) {
          od::value x;
          check(std::move(c).get(x));
          if (k < 3)
            kind |= static_cast<std::uint8_t>(coordinate(x, bits[k]) << (2 * k));
          else
            value(x, 3);
          ++k;
        }
        if (k != 3) kind |= RawVertices::kNotTriple;
      } else {
        value(p, 2);
        kind = RawVertices::kNotTriple;
      }
      Vec3 x;
      std::memcpy(x.data(), bits.data(), sizeof bits);
      out.values.push_back(x);
      out.kinds.push_back(kind);
    }
  }

  // "CityObjects": each object's text, checked by simdjson's DOM parser (faster than walking it
  // here; the objects are parsed again one at a time when read).
  void city_objects(od::value v, std::vector<ObjectText>& out) {
    od::object objects;
    check(v.get_object().get(objects));
    dom::parser parser;
    for (auto f : objects) {
      od::field field;
      check(std::move(f).get(field));
      std::string_view key;
      check(field.unescaped_key().get(key));
      od::value o = field.value();
      const char* begin = o.raw_json_token().data();
      od::json_type t;
      check(o.type().get(t));
      std::string_view text;
      if (t == od::json_type::object) {
        od::object object;
        check(o.get_object().get(object));
        check(object.raw_json().get(text));
        Elem e;
        if (parse_dom(parser, text, e) != simdjson::SUCCESS) locate(text);
      } else {
        value(o, 2);
        text = trimmed(begin, location());
      }
      out.push_back({std::string(key), text});
    }
  }

  // The first JSON error inside `part` (which the DOM parser refused), with its position.
  [[noreturn]] void locate(std::string_view part) {
    od::parser parser;
    od::document doc;
    const simdjson::error_code e = parser.iterate(part.data(), part.size(), padded_capacity(text_, part)).get(doc);
    if (e) fail(e, part.data());
    JsonChecker inner(text_, where_, doc);
    inner.whole();
    // Both parsers disagree: report the DOM parser's reason at the value's start.
    dom::parser p;
    Elem ignored;
    fail(parse_dom(p, part, ignored), part.data());
  }

  std::string position(const char* at) const { return position(text_, where_, at); }

  static std::string position(std::string_view text, const Where& where, const char* at) {
    if (!at || at < text.data() || at > text.data() + text.size()) return "";
    const std::size_t offset = static_cast<std::size_t>(at - text.data());
    const std::string_view before = text.substr(0, offset);
    const std::size_t nl = before.rfind('\n');
    const std::size_t column = nl == std::string_view::npos ? offset + 1 : offset - nl;
    if (where.line) return " at column " + std::to_string(column);
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
    return " at line " + std::to_string(line) + ", column " + std::to_string(column);
  }

  // The token at `at`, quoted: a structural character, or up to the next one.
  std::string token_at(const char* at) const { return token_text(text_, at); }

  std::string reason(simdjson::error_code e, const char* at) const {
    const std::string token = token_at(at);
    switch (e) {
      case simdjson::NUMBER_ERROR: {
        std::string_view t;
        if (at) {
          const char* end = text_.data() + text_.size();
          const char* p = at;
          while (p < end && p - at < 400 && !ends_token(*p)) ++p;
          t = std::string_view(at, static_cast<std::size_t>(p - at));
        }
        if (json_number_syntax(t)) return "number overflow: " + printable_text(t) + " is beyond the range of a double";
        return "invalid number " + token;
      }
      case simdjson::T_ATOM_ERROR:
      case simdjson::F_ATOM_ERROR:
      case simdjson::N_ATOM_ERROR:
        return "invalid literal " + token;
      case simdjson::INCORRECT_TYPE:
        return at && *at != '"' && *at != '-' && !std::isdigit(static_cast<unsigned char>(*at)) ? "invalid literal " + token
                                                                                                : "unexpected " + token;
      case simdjson::STRING_ERROR:
        return "invalid escape in a string";
      case simdjson::TRAILING_CONTENT:
        return "unexpected content after the JSON value";
      case simdjson::DEPTH_ERROR:
        return "nested deeper than " + std::to_string(kMaxDepth) + " levels";
      case simdjson::TAPE_ERROR:
      case simdjson::INCOMPLETE_ARRAY_OR_OBJECT:
      case simdjson::UNEXPECTED_ERROR:
        return "unexpected " + token;
      default:
        return std::string(simdjson::error_message(e)) + " (near " + token + ")";
    }
  }

  std::string_view text_;
  const Where& where_;
  od::document& doc_;
};

// Pass 1 over a chunk: checks all of it as JSON (syntax errors come before any other), locates
// its members and reads its vertices. The on-demand parser's index of the text (4 bytes per
// structural character) is freed on return.
Chunk scan_chunk(std::string_view text, const Where& where) {
  Chunk chunk;
  chunk.text = text;
  od::parser parser;
  od::document doc;
  const simdjson::error_code e = parser.iterate(text.data(), text.size(), text.size() + simdjson::SIMDJSON_PADDING).get(doc);
  if (e) JsonChecker::fail_scan(text, where, e);
  JsonChecker(text, where, doc).root(chunk);
  return chunk;
}

// A validated part of a chunk in `parser`'s DOM (the element lives until its next parse).
Elem dom_of(dom::parser& parser, const Chunk& chunk, std::string_view part, const Where& where, const std::string& pointer) {
  Elem e;
  const simdjson::error_code code = parse_dom(parser, part, e);
  if (code) fail(where, pointer, std::string("not JSON (") + simdjson::error_message(code) + ")");
  return e;
}

// ---- DOM access: the types and members a CityJSON reader asks about ----------------------------

bool is_unsigned(const Elem& e) {
  std::int64_t i;
  return e.is_uint64() || (e.get_int64().get(i) == simdjson::SUCCESS && i >= 0);
}
std::uint64_t unsigned_value(const Elem& e) {  // after is_unsigned
  std::uint64_t u;
  if (e.get_uint64().get(u) == simdjson::SUCCESS) return u;
  return static_cast<std::uint64_t>(e.get_int64().value_unsafe());
}
double number(const Elem& e) {  // after is_number()
  double d = 0;
  if (e.get_double().get(d) != simdjson::SUCCESS) d = 0;
  return d;
}
std::string string_of(const Elem& e) {  // after is_string()
  std::string_view s;
  if (e.get_string().get(s) != simdjson::SUCCESS) s = {};
  return std::string(s);
}
bool is_string_equal(const Elem& e, std::string_view s) {
  std::string_view v;
  return e.get_string().get(v) == simdjson::SUCCESS && v == s;
}
// A member of an object (the last of equal names, as a JSON object keeps it); none if `e` is
// not an object.
std::optional<Elem> member(const Elem& e, std::string_view name) {
  dom::object o;
  if (e.get_object().get(o) != simdjson::SUCCESS) return std::nullopt;
  std::optional<Elem> found;
  for (const dom::key_value_pair kv : o)
    if (kv.key == name) found = kv.value;
  return found;
}
// The elements of an array (empty if `e` is not one).
std::vector<Elem> elements(const Elem& e) {
  std::vector<Elem> out;
  dom::array a;
  if (e.get_array().get(a) != simdjson::SUCCESS) return out;
  for (const Elem x : a) out.push_back(x);
  return out;
}
std::size_t array_size(const Elem& e) {
  dom::array a;
  if (e.get_array().get(a) != simdjson::SUCCESS) return 0;
  const std::size_t n = a.size();
  if (n < 0xFFFFFF) return n;  // the tape saturates its count there
  std::size_t count = 0;
  for ([[maybe_unused]] const Elem x : a) ++count;
  return count;
}

// A JSON pointer spelled out only when a message or a note needs it (building it for every
// vertex index would cost an allocation each): a base pointer and the array indices below it.
struct Path {
  const std::string* base;
  std::array<std::size_t, 8> index{};
  std::size_t depth = 0;
  Path child(std::size_t i) const {
    Path p = *this;
    if (p.depth < p.index.size()) p.index[p.depth++] = i;
    return p;
  }
  std::string str() const {
    std::string s = *base;
    for (std::size_t k = 0; k < depth; ++k) {
      s += '/';
      s += std::to_string(index[k]);
    }
    return s;
  }
};

// ---- LoD -----------------------------------------------------------------------------------

struct Lod {
  std::string text;              // as written ("2.2", or the number's shortest form in 1.0)
  std::vector<long long> parts;  // numeric components: "2.2" → {2, 2}, "1" → {1}
};

// Numeric comparison component by component, missing components are 0 ("1" == "1.0").
int compare(const Lod& a, const Lod& b) {
  const std::size_t n = std::max(a.parts.size(), b.parts.size());
  for (std::size_t i = 0; i < n; ++i) {
    const long long x = i < a.parts.size() ? a.parts[i] : 0, y = i < b.parts.size() ? b.parts[i] : 0;
    if (x != y) return x < y ? -1 : 1;
  }
  return 0;
}

std::optional<Lod> parse_lod_text(const std::string& text) {
  Lod lod{text, {}};
  std::size_t i = 0;
  while (true) {
    long long v = 0;
    const auto [end, ec] = std::from_chars(text.data() + i, text.data() + text.size(), v);
    if (ec != std::errc() || v < 0) return std::nullopt;
    lod.parts.push_back(v);
    i = static_cast<std::size_t>(end - text.data());
    if (i == text.size()) return lod;
    if (text[i] != '.' || i + 1 == text.size()) return std::nullopt;
    ++i;
  }
}

Lod parse_lod(const Elem& v, const Where& where, const std::string& pointer) {
  std::string text;
  if (v.is_string())
    text = string_of(v);
  else if (v.is_number())
    text = simdjson::to_string(v);  // shortest round-trip form: 1.2 → "1.2", 2.0 → "2.0", 2 → "2"
  if (auto lod = parse_lod_text(text)) return *lod;
  fail(where, pointer + "/lod", "LoD " + value_text(v) + " is not a LoD such as \"2.2\" or 1");
}

// ---- Vertices ------------------------------------------------------------------------------

// A number for a message: 6 significant digits (1e+15, 0.125, 1e-320).
std::string number_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

struct Transform {
  bool present = false;
  std::array<double, 3> scale{1, 1, 1}, translate{0, 0, 0};
};

Transform read_transform(const Chunk& chunk, dom::parser& parser, const Where& where, const std::string& version, Notes& notes) {
  Transform t;
  const auto text = chunk.member("transform");
  if (!text) {
    if (version != "1.0")
      notes.add("no \"transform\" although CityJSON " + version + " requires one: vertices read as real coordinates",
                "/transform");
    return t;
  }
  const Elem transform = dom_of(parser, chunk, *text, where, "/transform");
  if (!transform.is_object()) fail(where, "/transform", "transform " + value_text(transform) + " is not an object");
  for (const char* name : {"scale", "translate"}) {
    const auto m = member(transform, name);
    const std::string pointer = std::string("/transform/") + name;
    if (!m) fail(where, pointer, "missing");
    if (!m->is_array() || array_size(*m) != 3) fail(where, pointer, value_text(*m) + " is not an array of 3 numbers");
    const std::vector<Elem> values = elements(*m);
    for (std::size_t k = 0; k < 3; ++k) {
      const Elem& v = values[k];
      if (!v.is_number() || !std::isfinite(number(v)))
        fail(where, pointer + "/" + std::to_string(k), value_text(v) + " is not a finite number");
      (name[0] == 's' ? t.scale : t.translate)[k] = number(v);
      if (name[0] != 's') continue;
      if (number(v) == 0) fail(where, pointer + "/" + std::to_string(k), "scale 0 collapses every vertex");
      // Below 1e-12 m (a picometre) the integer vertices span less than a millimetre, and a
      // subnormal scale loses the integers' digits in the product: no model is drawn at that scale.
      if (std::abs(number(v)) < 1e-12)
        fail(where, pointer + "/" + std::to_string(k),
             "scale " + value_text(v) + " is below 1e-12 m: the vertices would collapse");
    }
  }
  // A translation whose spacing of doubles is coarser than the scale rounds every coordinate to
  // that spacing: the file's integers carry digits the sums cannot hold.
  for (std::size_t k = 0; k < 3; ++k) {
    const double t_abs = std::abs(t.translate[k]);
    const double spacing = std::nextafter(t_abs, std::numeric_limits<double>::infinity()) - t_abs;
    if (spacing > std::abs(t.scale[k]))
      notes.add("transform translate " + number_text(t.translate[k]) + " holds coordinates only to " + number_text(spacing) +
                    " m, coarser than the scale " + number_text(t.scale[k]) + ": vertices are rounded to that step",
                "/transform/translate/" + std::to_string(k));
  }
  t.present = true;
  return t;
}

// x = i · scale + translate as CityJSON defines it: one correctly rounded product and one
// correctly rounded sum (no contraction into a fused multiply-add, which would round once).
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("fp-contract=off")))
#endif
double
apply_transform(long long i, double scale, double translate) {
#if defined(__clang__)
#pragma clang fp contract(off)
#endif
  const double product = static_cast<double>(i) * scale;
  return product + translate;
}

// The text of vertex v (k < 0) or of its coordinate k, quoted for a message.
std::string vertex_text(const Chunk& chunk, std::string_view vertices, std::size_t v, int k) {
  od::parser parser;
  od::document doc;
  od::array array;
  if (parser.iterate(vertices.data(), vertices.size(), padded_capacity(chunk.text, vertices)).get(doc) ||
      doc.get_array().get(array))
    return "?";
  std::size_t i = 0;
  for (auto element : array) {
    od::value p;
    if (std::move(element).get(p)) return "?";
    if (i++ != v) continue;
    if (k < 0) return raw_value_text(raw_value(p));
    od::array coordinates;
    if (p.get_array().get(coordinates)) return "?";
    int j = 0;
    for (auto c : coordinates) {
      od::value x;
      if (std::move(c).get(x)) return "?";
      if (j++ == k) return raw_value_text(raw_value(x));
    }
    return "?";
  }
  return "?";
}

// All of a chunk's vertices (a CityJSON file, or one CityJSONFeature), validated.
std::vector<Vec3> read_vertices(Chunk& chunk, const Transform& t, const Where& where) {
  const auto text = chunk.member("vertices");
  if (!text) fail(where, "/vertices", "missing");
  if (!chunk.vertices_is_array) fail(where, "/vertices", raw_value_text(*text) + " is not an array");
  RawVertices& raw = chunk.vertices;
  constexpr long long kExactInDouble = 1LL << 53;  // |i| ≤ 2⁵³ converts to double exactly
  for (std::size_t v = 0; v < raw.values.size(); ++v) {
    const std::uint8_t kinds = raw.kinds[v];
    // The pointers are spelled out only for a message (an allocation per coordinate otherwise).
    const auto pointer = [&] { return "/vertices/" + std::to_string(v); };
    if (kinds & RawVertices::kNotTriple)
      fail(where, pointer(), "vertex " + vertex_text(chunk, *text, v, -1) + " is not an array of 3 numbers");
    std::array<std::uint64_t, 3> bits;
    std::memcpy(bits.data(), raw.values[v].data(), sizeof bits);
    for (int k = 0; k < 3; ++k) {
      const auto kind = static_cast<RawVertices::Kind>((kinds >> (2 * k)) & 3);
      const auto cpointer = [&] { return pointer() + "/" + std::to_string(k); };
      const auto text_of = [&] {
        return kind == RawVertices::kInteger ? std::to_string(std::bit_cast<std::int64_t>(bits[k]))
                                             : vertex_text(chunk, *text, v, k);
      };
      double x;
      if (t.present) {
        if (kind == RawVertices::kBigInteger) fail(where, cpointer(), "integer coordinate " + text_of() + " exceeds 2^53");
        if (kind != RawVertices::kInteger)
          fail(where, cpointer(), "coordinate " + text_of() + " is not an integer (the transform requires integer vertices)");
        const long long i = std::bit_cast<std::int64_t>(bits[k]);
        if (i > kExactInDouble || i < -kExactInDouble)
          fail(where, cpointer(), "integer coordinate " + text_of() + " exceeds 2^53");
        x = apply_transform(i, t.scale[k], t.translate[k]);
      } else {
        if (kind == RawVertices::kNotNumber) fail(where, cpointer(), "coordinate " + text_of() + " is not a number");
        x = kind == RawVertices::kInteger ? static_cast<double>(std::bit_cast<std::int64_t>(bits[k]))
                                          : std::bit_cast<double>(bits[k]);
      }
      if (!std::isfinite(x)) fail(where, cpointer(), "coordinate " + text_of() + " is not finite after the transform");
      raw.values[v][k] = x;
    }
  }
  raw.kinds = {};
  return std::move(raw.values);
}

// ---- Geometry templates --------------------------------------------------------------------

struct Templates {
  bool present = false;
  std::vector<Elem> geometries;  // "templates", in the templates parser's DOM
  std::vector<Vec3> vertices;    // "vertices-templates", real coordinates
};

Templates read_templates(const Chunk& chunk, dom::parser& parser, const Where& where) {
  Templates t;
  const auto text = chunk.member("geometry-templates");
  if (!text) return t;
  const Elem gt = dom_of(parser, chunk, *text, where, "/geometry-templates");
  if (!gt.is_object()) fail(where, "/geometry-templates", value_text(gt) + " is not an object");
  const auto g = member(gt, "templates");
  const auto v = member(gt, "vertices-templates");
  if (!g || !g->is_array()) fail(where, "/geometry-templates/templates", "missing or not an array");
  if (!v || !v->is_array()) fail(where, "/geometry-templates/vertices-templates", "missing or not an array");
  t.present = true;
  t.geometries = elements(*g);
  std::size_t i = 0;
  for (const Elem& p : elements(*v)) {
    const std::string pointer = "/geometry-templates/vertices-templates/" + std::to_string(i++);
    if (!p.is_array() || array_size(p) != 3) fail(where, pointer, value_text(p) + " is not an array of 3 numbers");
    const std::vector<Elem> c = elements(p);
    Vec3 x;
    for (std::size_t k = 0; k < 3; ++k) {
      if (!c[k].is_number() || !std::isfinite(number(c[k])))
        fail(where, pointer + "/" + std::to_string(k), value_text(c[k]) + " is not a finite number");
      x[static_cast<int>(k)] = number(c[k]);
    }
    t.vertices.push_back(x);
  }
  return t;
}

// ---- The reader ----------------------------------------------------------------------------

struct Counts {
  std::size_t objects = 0, objects_with_geometry = 0, skipped_objects = 0, surfaces = 0, surfaces_with_holes = 0;
  std::map<std::string, std::size_t> lods_used;
};

class ModelBuilder {
 public:
  ModelBuilder(const std::string& file, const CityModelReadOptions& options, TriangleSoup& soup, Counts& counts, Notes& notes)
      : options_(options), soup_(soup), counts_(counts), notes_(notes) {
    if (options.lod) {
      auto lod = parse_lod_text(*options.lod);
      if (!lod) throw InputError(file + ": requested LoD '" + printable_text(*options.lod) + "' is not a LoD such as \"2.2\"");
      requested_ = *lod;
    }
  }

  // Reads one chunk: the CityObjects of a CityJSON file or of one CityJSONFeature, with the
  // chunk's own vertices. The objects are taken in the order of their ids (as a JSON object
  // library that keeps members sorted gives them), each parsed on its own into a small DOM.
  void read_chunk(const Chunk& chunk, const std::vector<Vec3>& vertices, const Templates& templates, const Where& where) {
    where_ = &where;
    vertices_ = &vertices;
    templates_ = &templates;
    remap_.assign(vertices.size(), kUnused);

    const auto text = chunk.member("CityObjects");
    if (!text) fail(where, "/CityObjects", "missing");
    if (!chunk.city_objects_is_object) fail(where, "/CityObjects", raw_value_text(*text) + " is not an object");

    // The objects by id; of equal ids the last one (a JSON object keeps one member per name).
    std::vector<const ObjectText*> objects;
    objects.reserve(chunk.objects.size());
    for (const ObjectText& o : chunk.objects) objects.push_back(&o);
    std::stable_sort(objects.begin(), objects.end(), [](const ObjectText* a, const ObjectText* b) { return a->id < b->id; });
    std::vector<const ObjectText*> unique;
    unique.reserve(objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i)
      if (i + 1 == objects.size() || objects[i + 1]->id != objects[i]->id) unique.push_back(objects[i]);
    objects = std::move(unique);

    // Pass 1: each object's chosen LoD (none: nothing to read).
    std::vector<std::optional<Lod>> chosen(objects.size());
    for (std::size_t n = 0; n < objects.size(); ++n) {
      const std::string pointer = "/CityObjects/" + pointer_token(objects[n]->id);
      const Elem object = dom_of(parser_, chunk, objects[n]->text, where, pointer);
      if (!object.is_object()) fail(where, pointer, value_text(object) + " is not an object");
      chosen[n] = choose_lod(object, pointer);
    }
    const auto chosen_of = [&](std::string_view id) -> const std::optional<Lod>* {
      const auto it =
          std::lower_bound(objects.begin(), objects.end(), id, [](const ObjectText* o, std::string_view i) { return o->id < i; });
      if (it == objects.end() || (*it)->id != id) return nullptr;
      return &chosen[static_cast<std::size_t>(it - objects.begin())];
    };
    // Pass 2: read, skipping parents superseded by children read at a higher LoD.
    for (std::size_t n = 0; n < objects.size(); ++n) {
      ++counts_.objects;
      const std::string& id = objects[n]->id;
      const std::string pointer = "/CityObjects/" + pointer_token(id);
      const Elem object = dom_of(parser_, chunk, objects[n]->text, where, pointer);
      const auto type = member(object, "type");
      if (!type || !type->is_string()) fail(where, pointer + "/type", "missing or not a string");
      const auto geometry = member(object, "geometry");
      if (!geometry || (geometry->is_array() && array_size(*geometry) == 0)) continue;  // no geometry: fine
      if (!geometry->is_array()) fail(where, pointer + "/geometry", value_text(*geometry) + " is not an array");
      const std::optional<Lod>& lod = chosen[n];
      if (!lod) {
        ++counts_.skipped_objects;
        notes_.add("objects skipped: no geometry of the requested LoD " + requested_->text, pointer);
        continue;
      }
      if (!options_.lod && !options_.keep_lower_lod_parents) {
        if (const auto children = member(object, "children"); children && children->is_array()) {
          std::optional<Lod> best_child;
          for (const Elem& c : elements(*children)) {
            std::string_view child;
            if (c.get_string().get(child) != simdjson::SUCCESS) continue;
            const std::optional<Lod>* ch = chosen_of(child);
            if (ch && *ch && (!best_child || compare(**ch, *best_child) > 0)) best_child = **ch;
          }
          if (best_child && compare(*lod, *best_child) < 0) {
            ++counts_.skipped_objects;
            notes_.add("parent objects skipped: their highest LoD is below their children's (LoD " + lod->text + " parent, LoD " +
                           best_child->text + " children)",
                       pointer);
            continue;
          }
        }
      }
      material_fallback_ = string_of(*type);
      object_name_ = &id;
      object_index_ = kUnused;
      const std::size_t surfaces_before = counts_.surfaces;
      std::size_t g = 0;
      for (const Elem& geom : elements(*geometry)) {
        const std::string gpointer = pointer + "/geometry/" + std::to_string(g++);
        const auto [glod, is_instance] = geometry_lod(geom, gpointer);
        if (compare(glod, *lod) != 0) continue;
        if (is_instance)
          read_instance(geom, gpointer);
        else
          read_geometry(geom, gpointer, nullptr);
      }
      if (counts_.surfaces > surfaces_before) {
        ++counts_.objects_with_geometry;
        ++counts_.lods_used[lod->text];
      } else {
        ++counts_.skipped_objects;
        notes_.add("objects skipped: nothing with area at their LoD", pointer);
      }
    }
  }

 private:
  // The LoD of a geometry (a GeometryInstance takes its template's), and whether it is an instance.
  std::pair<Lod, bool> geometry_lod(const Elem& geom, const std::string& pointer) {
    if (!geom.is_object()) fail(*where_, pointer, value_text(geom) + " is not an object");
    const auto type = member(geom, "type");
    if (!type || !type->is_string()) fail(*where_, pointer + "/type", "missing or not a string");
    if (is_string_equal(*type, "GeometryInstance")) {
      const auto [tmpl, k] = template_of(geom, pointer);
      const auto lod = member(tmpl, "lod");
      const std::string tpointer = "/geometry-templates/templates/" + std::to_string(k);
      if (!lod) fail(*where_, tpointer + "/lod", "missing");
      return {parse_lod(*lod, *where_, tpointer), true};
    }
    const auto lod = member(geom, "lod");
    if (!lod) fail(*where_, pointer + "/lod", "missing");
    return {parse_lod(*lod, *where_, pointer), false};
  }

  std::pair<Elem, std::size_t> template_of(const Elem& geom, const std::string& pointer) {
    const auto t = member(geom, "template");
    if (!t || !is_unsigned(*t)) fail(*where_, pointer + "/template", "missing or not a non-negative integer");
    if (!templates_->present)
      fail(*where_, pointer + "/template", "template " + value_text(*t) + " but the file has no \"geometry-templates\"");
    const std::uint64_t k = unsigned_value(*t);
    if (k >= templates_->geometries.size())
      fail(*where_, pointer + "/template",
           "template " + value_text(*t) + " out of range (" + std::to_string(templates_->geometries.size()) + " templates)");
    return {templates_->geometries[k], static_cast<std::size_t>(k)};
  }

  std::optional<Lod> choose_lod(const Elem& object, const std::string& pointer) {
    const auto geometry = member(object, "geometry");
    if (!geometry || !geometry->is_array()) return std::nullopt;
    std::optional<Lod> best;
    std::size_t g = 0;
    for (const Elem& geom : elements(*geometry)) {
      const Lod lod = geometry_lod(geom, pointer + "/geometry/" + std::to_string(g++)).first;
      if (requested_) {
        if (compare(lod, *requested_) == 0) return lod;
      } else if (!best || compare(lod, *best) > 0) {
        best = lod;
      }
    }
    return best;
  }

  std::uint32_t material(const std::string& name) {
    const auto [it, inserted] = material_index_.try_emplace(name, static_cast<std::uint32_t>(soup_.material_names.size()));
    if (inserted) soup_.material_names.push_back(name);
    return it->second;
  }

  // A chunk vertex index (JSON) → soup index; validates the index.
  template <class Pointer>
  std::uint32_t chunk_vertex(const Elem& index, const Pointer& pointer_of) {
    const auto pointer = [&] { return std::string(pointer_of()); };
    if (!is_unsigned(index)) fail(*where_, pointer(), "vertex index " + value_text(index) + " is not a non-negative integer");
    const std::uint64_t i = unsigned_value(index);
    if (i >= vertices_->size())
      fail(*where_, pointer(),
           "vertex index " + value_text(index) + " out of range (" + std::to_string(vertices_->size()) + " vertices)");
    std::uint32_t& m = remap_[i];
    if (m == kUnused) {
      m = static_cast<std::uint32_t>(soup_.vertices.size());
      soup_.vertices.push_back((*vertices_)[i]);
    }
    return m;
  }

  struct Instance {
    std::array<double, 16> matrix;  // row-major
    Vec3 reference;
    std::vector<std::uint32_t> remap;  // template vertex → soup index for this instance
  };

  template <class Pointer>
  std::uint32_t template_vertex(const Elem& index, const Pointer& pointer_of, Instance& inst) {
    const auto pointer = [&] { return std::string(pointer_of()); };
    if (!is_unsigned(index))
      fail(*where_, pointer(), "template vertex index " + value_text(index) + " is not a non-negative integer");
    const std::uint64_t i = unsigned_value(index);
    if (i >= templates_->vertices.size())
      fail(*where_, pointer(),
           "template vertex index " + value_text(index) + " out of range (" + std::to_string(templates_->vertices.size()) +
               " template vertices)");
    std::uint32_t& m = inst.remap[i];
    if (m == kUnused) {
      const Vec3& v = templates_->vertices[i];
      const auto& M = inst.matrix;
      double h[4];
      for (int r = 0; r < 4; ++r) h[r] = M[4 * r] * v.x() + M[4 * r + 1] * v.y() + M[4 * r + 2] * v.z() + M[4 * r + 3];
      if (!(std::isfinite(h[3]) && h[3] != 0)) fail(*where_, pointer(), "the transformation matrix maps the vertex to infinity");
      const Vec3 p = (h[3] == 1 ? Vec3(h[0], h[1], h[2]) : Vec3(h[0] / h[3], h[1] / h[3], h[2] / h[3])) + inst.reference;
      m = static_cast<std::uint32_t>(soup_.vertices.size());
      soup_.vertices.push_back(p);
    }
    return m;
  }

  void read_instance(const Elem& geom, const std::string& pointer) {
    const auto [tmpl, k] = template_of(geom, pointer);
    const std::string tpointer = "/geometry-templates/templates/" + std::to_string(k);
    const auto b = member(geom, "boundaries");
    if (!b || !b->is_array() || array_size(*b) != 1)
      fail(*where_, pointer + "/boundaries", "a GeometryInstance needs boundaries [reference vertex index]");
    Instance inst;
    const std::uint32_t ref = chunk_vertex(elements(*b)[0], [&] { return pointer + "/boundaries/0"; });
    inst.reference = soup_.vertices[ref];
    const auto m = member(geom, "transformationMatrix");
    if (!m || !m->is_array() || array_size(*m) != 16)
      fail(*where_, pointer + "/transformationMatrix", "missing or not an array of 16 numbers");
    const std::vector<Elem> values = elements(*m);
    for (std::size_t j = 0; j < 16; ++j) {
      if (!values[j].is_number() || !std::isfinite(number(values[j])))
        fail(*where_, pointer + "/transformationMatrix/" + std::to_string(j), value_text(values[j]) + " is not a finite number");
      inst.matrix[j] = number(values[j]);
    }
    inst.remap.assign(templates_->vertices.size(), kUnused);
    if (const auto t = member(tmpl, "type"); t && is_string_equal(*t, "GeometryInstance"))
      fail(*where_, tpointer + "/type", "a template cannot itself be a GeometryInstance");
    read_geometry(tmpl, tpointer, &inst);
    ++instances_;
  }

  // Surface depth (array levels above a surface) of each geometry type with area.
  static int surface_depth(const std::string& type) {
    if (type == "MultiSurface" || type == "CompositeSurface") return 1;
    if (type == "Solid") return 2;
    if (type == "MultiSolid" || type == "CompositeSolid") return 3;
    return 0;
  }

  void read_geometry(const Elem& geom, const std::string& pointer, Instance* inst) {
    const auto type_value = member(geom, "type");
    if (!type_value || !type_value->is_string()) fail(*where_, pointer + "/type", "missing or not a string");
    const std::string type = string_of(*type_value);
    const int depth = surface_depth(type);
    if (depth == 0) {
      if (type == "MultiPoint" || type == "MultiLineString")
        notes_.add(type + " geometries skipped (no area)", pointer);
      else
        fail(*where_, pointer + "/type", "unknown geometry type " + value_text(*type_value));
      return;
    }
    const auto b = member(geom, "boundaries");
    if (!b) fail(*where_, pointer + "/boundaries", "missing");
    // Semantics: surfaces[] and values nested one level less deep than boundaries' rings.
    std::vector<Elem> sem_surfaces;
    bool has_semantics = false;
    std::optional<Elem> values;
    std::string sem_pointer = pointer + "/semantics";
    if (const auto s = member(geom, "semantics"); s && !s->is_null()) {
      if (!s->is_object()) fail(*where_, sem_pointer, value_text(*s) + " is not an object");
      const auto surf = member(*s, "surfaces");
      const auto val = member(*s, "values");
      if (!surf || !surf->is_array()) fail(*where_, sem_pointer + "/surfaces", "missing or not an array");
      sem_surfaces = elements(*surf);
      has_semantics = true;
      if (val && !val->is_null()) values = *val;
    }
    const std::string bpointer = pointer + "/boundaries", vpointer = sem_pointer + "/values";
    walk(*b, depth, values ? &*values : nullptr, Path{&bpointer}, Path{&vpointer}, has_semantics ? &sem_surfaces : nullptr, inst);
  }

  void walk(const Elem& node, int depth, const Elem* values, const Path& pointer, const Path& vpointer,
            const std::vector<Elem>* sem_surfaces, Instance* inst) {
    if (!node.is_array())
      fail(*where_, pointer.str(), value_text(node) + " is not an array (boundaries nested to the wrong depth)");
    if (values && !values->is_array())
      fail(*where_, vpointer.str(), value_text(*values) + " is not an array (semantic values nested to the wrong depth)");
    const dom::array children = node.get_array().value_unsafe();
    dom::array child_values;
    if (values) {
      child_values = values->get_array().value_unsafe();
      const std::size_t nv = array_size(*values), nb = array_size(node);
      if (nv != nb)
        fail(*where_, vpointer.str(), std::to_string(nv) + " semantic values for " + std::to_string(nb) + " boundaries");
    }
    auto value_it = values ? child_values.begin() : dom::array::iterator();
    std::size_t i = 0;
    for (const Elem child : children) {
      std::optional<Elem> value;
      if (values) {
        value = *value_it;
        ++value_it;
        if (value->is_null()) value.reset();
      }
      const Path p = pointer.child(i), vp = vpointer.child(i);
      ++i;
      if (depth > 1) {
        walk(child, depth - 1, value ? &*value : nullptr, p, vp, sem_surfaces, inst);
        continue;
      }
      std::string name = material_fallback_;
      if (value) {
        if (!is_unsigned(*value) || unsigned_value(*value) >= sem_surfaces->size())
          fail(*where_, vp.str(),
               "semantic value " + value_text(*value) + " is not an index into the " + std::to_string(sem_surfaces->size()) +
                   " semantic surfaces");
        const Elem& s = (*sem_surfaces)[unsigned_value(*value)];
        const auto t = member(s, "type");
        if (!s.is_object() || !t || !t->is_string())
          fail(*where_, vp.str(), "semantic surface " + value_text(s) + " has no \"type\" string");
        name = string_of(*t);
      }
      read_surface(child, p, name, inst);
    }
  }

  void read_surface(const Elem& surface, const Path& pointer, const std::string& name, Instance* inst) {
    if (!surface.is_array())
      fail(*where_, pointer.str(), value_text(surface) + " is not an array of rings (boundaries nested to the wrong depth)");
    rings_.clear();
    std::size_t r = 0;
    const dom::array rings = surface.get_array().value_unsafe();
    for (const Elem ring : rings) {
      const Path rp = pointer.child(r);
      if (!ring.is_array())
        fail(*where_, rp.str(), value_text(ring) + " is not an array of vertex indices (boundaries nested to the wrong depth)");
      const dom::array indices = ring.get_array().value_unsafe();
      std::vector<std::uint32_t> out;
      out.reserve(indices.size());
      std::size_t k = 0;
      for (const Elem index : indices) {
        const Path ip = rp.child(k++);
        if (index.is_array()) fail(*where_, ip.str(), value_text(index) + " is not a vertex index (boundaries nested too deep)");
        const auto ip_str = [&] { return ip.str(); };
        const std::uint32_t s = inst ? template_vertex(index, ip_str, *inst) : chunk_vertex(index, ip_str);
        if (!out.empty() && out.back() == s) {
          notes_.add("repeated consecutive vertices removed", ip.str());
          continue;
        }
        out.push_back(s);
      }
      if (out.size() > 1 && out.front() == out.back()) {
        out.pop_back();
        notes_.add("rings closed by repeating their first vertex: repeat removed", rp.str());
      }
      distinct_.assign(out.begin(), out.end());
      std::sort(distinct_.begin(), distinct_.end());
      if (std::unique(distinct_.begin(), distinct_.end()) - distinct_.begin() < 3) {
        if (r == 0) {
          notes_.add("surfaces skipped: outer ring with fewer than 3 distinct vertices", rp.str());
          return;
        }
        notes_.add("inner rings (holes) skipped: fewer than 3 distinct vertices", rp.str());
        ++r;
        continue;
      }
      rings_.push_back(std::move(out));
      ++r;
    }
    if (rings_.empty()) {
      notes_.add("surfaces skipped: no rings", pointer.str());
      return;
    }
    const PolygonWithHolesTriangulation t = triangulate_polygon_with_holes(soup_.vertices, rings_);
    if (t.holes_dropped) notes_.add("surfaces with crossing rings: holes not cut out (surface filled)", pointer.str());
    if (t.method == PolygonTriangulationMethod::kFanZeroArea) notes_.add("zero-area surfaces (fan-triangulated)", pointer.str());
    if (t.method == PolygonTriangulationMethod::kFanSelfIntersecting)
      notes_.add("self-crossing surfaces (fan-triangulated)", pointer.str());
    const std::uint32_t m = material(name);
    if (object_index_ == kUnused && !t.triangles.empty()) {
      object_index_ = static_cast<std::uint32_t>(soup_.object_names.size());
      soup_.object_names.push_back(object_name_ ? *object_name_ : std::string());
    }
    for (const auto& tri : t.triangles) {
      soup_.triangles.push_back(tri);
      soup_.triangle_material.push_back(m);
      soup_.triangle_object.push_back(object_index_);
    }
    ++counts_.surfaces;
    if (rings_.size() > 1 && !t.holes_dropped) ++counts_.surfaces_with_holes;
  }

 public:
  std::size_t instances_ = 0;

 private:
  const CityModelReadOptions& options_;
  std::optional<Lod> requested_;
  TriangleSoup& soup_;
  Counts& counts_;
  Notes& notes_;
  dom::parser parser_;  // one CityObject at a time
  const Where* where_ = nullptr;
  const std::vector<Vec3>* vertices_ = nullptr;
  const Templates* templates_ = nullptr;
  std::vector<std::uint32_t> remap_;
  std::unordered_map<std::string, std::uint32_t> material_index_;
  std::string material_fallback_;
  const std::string* object_name_ = nullptr;  // the CityObject being read
  std::uint32_t object_index_ = kUnused;      // its index in soup_.object_names, once it has a triangle
  std::vector<std::vector<std::uint32_t>> rings_;
  std::vector<std::uint32_t> distinct_;
};

// "type" and "version" of a CityJSON root (or the CityJSONSeq header): returns "1.0"/"1.1"/"2.0".
std::string check_header(const Chunk& chunk, dom::parser& parser, const Where& where, bool sequence) {
  if (!chunk.root_is_object) fail(where, "", "the JSON value is not an object (not CityJSON)");
  const auto type_text = chunk.member("type");
  if (!type_text) fail(where, "/type", "missing is not \"CityJSON\"");
  {
    const Elem type = dom_of(parser, chunk, *type_text, where, "/type");
    if (!is_string_equal(type, "CityJSON")) fail(where, "/type", value_text(type) + " is not \"CityJSON\"");
  }
  const auto version_text = chunk.member("version");
  if (!version_text) fail(where, "/version", "missing or not a string");
  const Elem version = dom_of(parser, chunk, *version_text, where, "/version");
  if (!version.is_string()) fail(where, "/version", "missing or not a string");
  const std::string v = string_of(version);
  for (const char* supported : {"1.0", "1.1", "2.0"}) {
    const std::string s = supported;
    if (v == s || (v.size() > s.size() && v.compare(0, s.size() + 1, s + ".") == 0)) {
      if (sequence && s == "1.0")
        fail(where, "/version", "CityJSONSeq needs CityJSON 1.1 or 2.0, the header says " + value_text(version));
      return s;
    }
  }
  fail(where, "/version", "unsupported CityJSON version " + value_text(version) + " (supported: 1.0, 1.1, 2.0)");
}

// metadata.referenceSystem: kept verbatim; geographic / geocentric CRSs refused.
std::string check_crs(const Chunk& chunk, dom::parser& parser, const Where& where, std::vector<std::string>& notes) {
  std::optional<Elem> rs;
  if (const auto text = chunk.member("metadata")) {
    const Elem metadata = dom_of(parser, chunk, *text, where, "/metadata");
    rs = member(metadata, "referenceSystem");
  }
  if (!rs || (rs->is_string() && string_of(*rs).empty())) {
    notes.push_back("no referenceSystem: coordinates taken as metres in an unknown projected CRS");
    return "";
  }
  if (!rs->is_string()) fail(where, "/metadata/referenceSystem", value_text(*rs) + " is not a string");
  const std::string crs = string_of(*rs);
  const std::string l = lower(crs);
  const auto& geographic = geographic_epsg_codes();
  std::string refused;
  if (l.find("crs84") != std::string::npos || l.find("crs:84") != std::string::npos) refused = "OGC CRS84";
  for (const int code : crs_epsg_codes(crs))
    if (std::find(geographic.begin(), geographic.end(), code) != geographic.end()) refused = "EPSG:" + std::to_string(code);
  if (!refused.empty())
    fail(where, "/metadata/referenceSystem",
         value_text(*rs) + " is a geographic or geocentric CRS (" + refused +
             "): degrees are not metres; reproject to a projected CRS first (e.g. cjio crs_reproject)");
  if (crs_epsg_codes(crs).empty())
    notes.push_back("referenceSystem " + printable_text(crs) + " names no EPSG code: taken as metres");
  return crs;
}

// A padded copy of one line (CityJSONSeq).
simdjson::padded_string padded(std::string_view line) {
  return simdjson::padded_string(line.data(), line.size());
}

struct Reader {
  std::filesystem::path path;
  const CityModelReadOptions& options;
  TriangleSoup soup;
  CityModelReport report;
  Counts counts;
  Notes notes;
  std::size_t instances = 0;

  void read_single(Chunk& chunk) {
    Where where{path.string(), 0};
    dom::parser parser;  // the small root members, one after another
    const std::string version = check_header(chunk, parser, where, false);
    report.format = "CityJSON " + version;
    report.crs = check_crs(chunk, parser, where, report.notes);
    const Transform transform = read_transform(chunk, parser, where, version, notes);
    const std::vector<Vec3> vertices = read_vertices(chunk, transform, where);
    dom::parser templates_parser;
    const Templates templates = read_templates(chunk, templates_parser, where);
    ModelBuilder builder(where.file, options, soup, counts, notes);
    builder.read_chunk(chunk, vertices, templates, where);
    instances = builder.instances_;
  }

  // CityJSONSeq: `next_line(line)` gives the lines one at a time (false at the end).
  template <class NextLine>
  void read_sequence(NextLine&& next_line) {
    Where where{path.string(), 0};
    std::string line;
    std::size_t line_number = 0;
    bool have_header = false;
    std::string version;
    Transform transform;
    dom::parser header_parser, templates_parser;  // templates_parser keeps the header's templates
    Templates templates;
    std::optional<ModelBuilder> builder;
    while (next_line(line)) {
      ++line_number;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.find_first_not_of(" \t") == std::string::npos) continue;
      where.line = line_number;
      const simdjson::padded_string text = padded(line);
      Chunk chunk = scan_chunk(std::string_view(text.data(), text.size()), where);
      if (!have_header) {
        version = check_header(chunk, header_parser, where, true);
        report.format = "CityJSONSeq " + version;
        report.crs = check_crs(chunk, header_parser, where, report.notes);
        transform = read_transform(chunk, header_parser, where, version, notes);
        templates = read_templates(chunk, templates_parser, where);
        builder.emplace(where.file, options, soup, counts, notes);
        // The header's own CityObjects/vertices are normally empty; read them if not.
        if (chunk.city_objects_is_object && !chunk.objects.empty()) {
          const std::vector<Vec3> vertices = read_vertices(chunk, transform, where);
          builder->read_chunk(chunk, vertices, templates, where);
        }
        have_header = true;
        continue;
      }
      if (!chunk.root_is_object) fail(where, "", "the line is not a JSON object (not a CityJSONFeature)");
      const auto type_text = chunk.member("type");
      if (!type_text) fail(where, "/type", "missing is not \"CityJSONFeature\"");
      {
        const Elem type = dom_of(header_parser, chunk, *type_text, where, "/type");
        if (!is_string_equal(type, "CityJSONFeature")) fail(where, "/type", value_text(type) + " is not \"CityJSONFeature\"");
      }
      ++report.features;
      const std::vector<Vec3> vertices = read_vertices(chunk, transform, where);
      builder->read_chunk(chunk, vertices, templates, where);
    }
    if (!have_header) throw InputError(path.string() + ": empty file (no CityJSON header line)");
    instances = builder->instances_;
  }
};

// The file's bytes in a padded buffer (SIMDJSON_PADDING zero bytes after them).
simdjson::padded_string read_padded(const std::filesystem::path& file, std::ifstream& in) {
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size < 0 || !in) {  // not seekable: read it as a stream
    in.clear();
    in.seekg(0, std::ios::beg);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw InputError(file.string() + ": read error");
    return simdjson::padded_string(text);
  }
  simdjson::padded_string text(static_cast<std::size_t>(size));
  if (size > 0 && !text.data()) throw InputError(file.string() + ": cannot allocate " + std::to_string(size) + " bytes");
  std::memset(text.data() + size, 0, simdjson::SIMDJSON_PADDING);
  in.read(text.data(), size);
  if (in.gcount() != size) throw InputError(file.string() + ": read error");
  return text;
}

}  // namespace

const std::vector<int>& geographic_epsg_codes() {
  static const std::vector<int> codes{4326, 4979, 4258, 4937, 4289, 4269, 4617, 4283, 7844, 4612, 6668,
                                      6697, 4490, 4167, 4171, 4230, 4277, 4978, 4936, 9518, 9705};
  return codes;
}

bool is_cityjson_path(const std::filesystem::path& file) {
  const std::string ext = lower(file.extension().string());
  return ext == ".json" || ext == ".jsonl";
}

std::string CityModelReport::summary() const {
  std::ostringstream os;
  os << file << ": " << format << (crs.empty() ? ", no CRS" : ", CRS " + crs) << "\n";
  if (features) os << "  " << features << " features\n";
  os << "  " << objects << " objects, " << objects_with_geometry << " read, " << skipped_objects << " skipped; " << surfaces
     << " surfaces (" << surfaces_with_holes << " with holes) -> " << triangles << " triangles, " << vertices << " vertices\n";
  os << "  LoDs:";
  for (const auto& [lod, n] : lods_used) os << " " << lod << " (" << n << " objects)";
  os << "\n";
  for (const std::string& n : notes) os << "  note: " << n << "\n";
  return os.str();
}

namespace {
TriangleSoup read_cityjson_unguarded(const std::filesystem::path& file, const CityModelReadOptions& options,
                                     CityModelReport* report) {
  Reader reader{file, options, {}, {}, {}, {}, 0};
  reader.report.file = file.string();
  const std::string ext = lower(file.extension().string());
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open");
  if (ext == ".jsonl") {
    bool first = true;
    reader.read_sequence([&](std::string& line) {
      if (std::getline(in, line)) {
        if (first) refuse_wide_text(file.string(), line, "CityJSONSeq");
        first = false;
        return true;
      }
      if (in.bad()) throw InputError(file.string() + ": read error");
      return false;
    });
  } else {
    const simdjson::padded_string buffer = read_padded(file, in);
    const std::string_view text(buffer.data(), buffer.size());
    refuse_wide_text(file.string(), text, "CityJSON");
    std::optional<Chunk> chunk;
    try {
      chunk = scan_chunk(text, Where{file.string(), 0});
    } catch (const InputError&) {
      // A CityJSONSeq saved as .json: the first line alone is a CityJSON header, more follow.
      const std::size_t eol = text.find('\n');
      const bool more = eol != std::string_view::npos && text.find_first_not_of(" \t\r\n", eol) != std::string_view::npos;
      bool header = false;
      if (more) {
        try {
          const simdjson::padded_string first = padded(text.substr(0, eol));
          const Chunk c = scan_chunk(std::string_view(first.data(), first.size()), Where{file.string(), 1});
          dom::parser parser;
          Elem type;
          if (const auto t = c.member("type"); c.root_is_object && t && parse_dom(parser, *t, type) == simdjson::SUCCESS)
            header = is_string_equal(type, "CityJSON");
        } catch (const InputError&) {
        }
      }
      if (!header) throw;
    }
    if (chunk) {
      reader.read_single(*chunk);
    } else {
      reader.report.notes.push_back("CityJSONSeq content (one JSON object per line) in a " + ext + " file");
      std::size_t pos = 0;
      reader.read_sequence([&](std::string& line) {
        if (pos >= text.size()) return false;
        std::size_t eol = text.find('\n', pos);
        if (eol == std::string_view::npos) eol = text.size();
        line.assign(text.substr(pos, eol - pos));
        pos = eol + 1;
        return true;
      });
    }
  }
  CityModelReport& r = reader.report;
  r.objects = reader.counts.objects;
  r.objects_with_geometry = reader.counts.objects_with_geometry;
  r.skipped_objects = reader.counts.skipped_objects;
  r.surfaces = reader.counts.surfaces;
  r.surfaces_with_holes = reader.counts.surfaces_with_holes;
  r.triangles = reader.soup.triangles.size();
  r.vertices = reader.soup.vertices.size();
  r.lods_used = reader.counts.lods_used;
  if (reader.instances) r.notes.push_back(std::to_string(reader.instances) + " geometry instances (templates) placed");
  reader.notes.emit(r.notes);
  if (r.triangles == 0)
    throw InputError(file.string() + ": no triangles (" + std::to_string(r.objects) + " objects, " +
                     std::to_string(r.skipped_objects) + " skipped" +
                     (options.lod ? ", requested LoD " + printable_text(*options.lod) : std::string()) + ")");
  if (report) *report = std::move(r);
  return std::move(reader.soup);
}

}  // namespace

TriangleSoup read_cityjson(const std::filesystem::path& file, const CityModelReadOptions& options, CityModelReport* report) {
  try {
    return read_cityjson_unguarded(file, options, report);
  } catch (const simdjson::simdjson_error& e) {
    // Every value is checked before use; this is a safety net so that no simdjson exception
    // escapes as anything but an input error.
    throw InputError(file.string() + ": malformed CityJSON (" + printable_text(e.what()) + ")");
  }
}

}  // namespace skyband
