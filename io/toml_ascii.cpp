// TOML text as pure ASCII for toml++ 3.3.0 (toml_ascii.h). The lexer follows TOML 1.0.0's
// string and comment syntax (https://toml.io/en/v1.0.0#string); it needs no more of the grammar,
// since only where strings and comments are decides what happens to a non-ASCII character.
#include "io/toml_ascii.h"

#include <cstdio>
#include <vector>

#include "geometry/core/input_error.h"
#include "io/utf8_text.h"

namespace skyband {
namespace {

std::string escape_code_point(char32_t c) {
  char buf[16];
  std::snprintf(buf, sizeof buf, c <= 0xFFFF ? "\\u%04X" : "\\U%08X", static_cast<unsigned>(c));
  return buf;
}

bool is_forbidden_control(unsigned char c) {
  return (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7F;
}

}  // namespace

AsciiToml::AsciiToml(std::string_view in, const std::string& name) {
  enum class State { kOutside, kComment, kBasic, kMlBasic, kLiteral, kMlLiteral } state = State::kOutside;
  std::size_t i = in.starts_with("\xEF\xBB\xBF") ? 3 : 0;  // TOML allows a byte-order mark
  std::uint32_t line = 1, col = 1;                         // of in[i], in the original text
  std::uint32_t out_col = 1;                               // of the next character of text_
  text_.reserve(in.size());
  expansions_.emplace_back();
  const auto where = [&](std::uint32_t column) {
    return name + ":" + std::to_string(line) + ":" + std::to_string(column) + ": ";
  };
  const auto at = [&](std::size_t k) { return i + k < in.size() ? in[i + k] : '\0'; };
  const auto run_of = [&](char q) {
    std::size_t n = 0;
    while (at(n) == q) ++n;
    return n;
  };
  // Emits `s` for `chars` characters (`bytes` bytes) of the input.
  const auto emit = [&](std::string_view s, std::size_t bytes, std::uint32_t chars) {
    if (s.size() != chars) expansions_.back().push_back({out_col, static_cast<std::uint32_t>(s.size())});
    text_ += s;
    out_col += static_cast<std::uint32_t>(s.size());
    i += bytes;
    col += chars;
  };
  const auto copy = [&](std::size_t n) { emit(in.substr(i, n), n, static_cast<std::uint32_t>(n)); };  // ASCII as is
  const auto end_line = [&] {                                                                         // after copying a '\n'
    ++line;
    col = 1;
    out_col = 1;
    expansions_.emplace_back();
  };
  const auto check_control = [&](unsigned char c, std::uint32_t column) {
    if (is_forbidden_control(c)) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "%04X", static_cast<unsigned>(c));
      throw InputError(where(column) + "control character U+" + buf +
                       ": TOML allows none but tab (inside a basic string write it as \\u" + buf + ")");
    }
  };

  // Bracket nesting outside strings ('[' array, '{' inline table) and whether only blanks precede
  // on the current top-level line: a '[' there opens a table header, elsewhere an array.
  std::vector<char> nest;
  bool line_start = true;
  // Two shapes toml++ 3.3.0 never checks before an assertion (TOML_ASSERT_ASSUME, undefined
  // behaviour where NDEBUG makes it an assumption): a table header whose key starts with neither
  // a key character nor a quote (`[}`, `[ #`), and '}' where an array expects a value (`[}`,
  // `[1, }`). Both are errors in TOML; here they get one before toml++ sees them. `from` is the
  // offset after the '[' (or ',') in question.
  const auto check_after_bracket = [&](std::size_t from, bool header) {
    std::uint32_t l = line, k = col + static_cast<std::uint32_t>(from);
    std::size_t j = i + from;
    while (j < in.size()) {
      const char d = in[j];
      if (d == ' ' || d == '\t') {
        ++j, ++k;
      } else if (!header && (d == '\n' || d == '\r')) {
        if (d == '\n') ++l, k = 0;
        ++j, ++k;
      } else if (!header && d == '#') {
        while (j < in.size() && in[j] != '\n') ++j;
      } else {
        break;
      }
    }
    if (j >= in.size()) return;  // end of text: toml++'s own error
    const char d = in[j];
    const auto shown = [&] {
      return d >= 0x20 && d < 0x7F ? std::string("'") + d + "'" : std::string("a control or non-ASCII character");
    };
    const bool key_start = (d >= 'A' && d <= 'Z') || (d >= 'a' && d <= 'z') || (d >= '0' && d <= '9') || d == '_' || d == '-' ||
                           d == '"' || d == '\'' || d == ']';
    const std::string at_d = name + ":" + std::to_string(l) + ":" + std::to_string(k) + ": ";
    if (header && !key_start) throw InputError(at_d + "a table header holds a key (bare, or quoted), saw " + shown());
    if (!header && d == '}') throw InputError(at_d + "expected a value or ']' in the array, saw '}'");
  };

  while (i < in.size()) {
    char32_t c = 0;
    const std::size_t n = utf8_sequence_length(in, i, &c);
    if (n == 0) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "0x%02X", static_cast<unsigned>(static_cast<unsigned char>(in[i])));
      throw InputError(where(col) + "the text is not valid UTF-8 (byte " + buf + ")");
    }
    if (c < 0x80) check_control(static_cast<unsigned char>(c), col);
    const bool ascii = c < 0x80;
    switch (state) {
      case State::kOutside:
        if (!ascii) {
          const std::string ch(in.substr(i, n));
          throw InputError(where(col) + "character '" + printable_text(ch) + "' (U+" + escape_code_point(c).substr(2) +
                           ") outside a string or comment: TOML keys and values other than strings are ASCII; quote a "
                           "key that holds it (\"" +
                           printable_text(ch) + "\" = ...)");
        }
        if (c == '[') {
          const bool header = nest.empty() && line_start;
          if (!header) nest.push_back('[');
          check_after_bracket(header && at(1) == '[' ? 2 : 1, header);
        } else if (c == ',' && !nest.empty() && nest.back() == '[') {
          check_after_bracket(1, false);
        } else if (c == '{') {
          nest.push_back('{');
        } else if ((c == ']' || c == '}') && !nest.empty() && nest.back() == (c == ']' ? '[' : '{')) {
          nest.pop_back();
        }
        if (c != ' ' && c != '\t' && c != '\r' && c != '\n') line_start = false;
        if (c == '\n' && nest.empty()) line_start = true;
        if (c == '#') {
          state = State::kComment;
          copy(1);
        } else if (c == '"') {
          state = run_of('"') >= 3 ? State::kMlBasic : State::kBasic;
          copy(state == State::kMlBasic ? 3 : 1);
        } else if (c == '\'') {
          state = run_of('\'') >= 3 ? State::kMlLiteral : State::kLiteral;
          if (state == State::kMlLiteral)
            emit("\"\"\"", 3, 3);
          else
            emit("\"", 1, 1);
        } else {
          copy(1);
          if (c == '\n') end_line();
        }
        break;

      case State::kComment:
        if (!ascii) {
          emit("?", n, 1);  // a comment has no value; one character for one keeps the columns
        } else {
          copy(1);
          if (c == '\n') {
            end_line();
            state = State::kOutside;
            if (nest.empty()) line_start = true;
          }
        }
        break;

      case State::kBasic:
      case State::kMlBasic:
        if (c == '\\') {
          // An escape: the backslash and the next character are copied together, so that \" and
          // \\ stay inside the string and a line-ending backslash stays one.
          if (i + 1 >= in.size()) {
            copy(1);
            break;
          }
          const auto next = static_cast<unsigned char>(in[i + 1]);
          if (next >= 0x80) throw InputError(where(col) + "'\\' followed by a non-ASCII character is not a TOML escape sequence");
          check_control(next, col + 1);
          copy(2);
          if (next == '\n') end_line();
        } else if (c == '"') {
          const std::size_t quotes = state == State::kBasic ? 1 : run_of('"');
          copy(quotes);
          if (state == State::kBasic || quotes >= 3) state = State::kOutside;  // toml++ checks 3–5
        } else if (!ascii) {
          emit(escape_code_point(c), n, 1);
        } else {
          copy(1);
          if (c == '\n') {
            end_line();
            if (state == State::kBasic) state = State::kOutside;  // unterminated: toml++'s error
          }
        }
        break;

      case State::kLiteral:
      case State::kMlLiteral:
        if (c == '\'') {
          if (state == State::kLiteral) {
            emit("\"", 1, 1);
            state = State::kOutside;
            break;
          }
          const std::size_t quotes = run_of('\'');
          if (quotes < 3) {
            copy(quotes);  // a quote or two inside: as they are in a basic string
            break;
          }
          if (quotes > 5)
            throw InputError(where(col) + std::to_string(quotes) +
                             " quotes (') in a row in a multi-line literal string: at most 5 (two of them in the string)");
          // ''' closes; one or two quotes before it belong to the string.
          emit(std::string(quotes - 3, '\'') + "\"\"\"", quotes, static_cast<std::uint32_t>(quotes));
          state = State::kOutside;
        } else if (c == '\\') {
          emit("\\\\", 1, 1);
        } else if (c == '"') {
          emit("\\\"", 1, 1);
        } else if (!ascii) {
          emit(escape_code_point(c), n, 1);
        } else {
          copy(1);
          if (c == '\n') {
            end_line();
            if (state == State::kLiteral) state = State::kOutside;  // unterminated: toml++'s error
          }
        }
        break;
    }
  }
}

std::uint32_t AsciiToml::original_column(std::uint32_t line, std::uint32_t column) const {
  if (line == 0 || line > expansions_.size()) return column;
  std::uint32_t shift = 0;
  for (const Expansion& e : expansions_[line - 1]) {
    if (column < e.column) break;
    if (column < e.column + e.width) return e.column - shift;  // inside an escape: its character
    shift += e.width - 1;
  }
  return column - shift;
}

}  // namespace skyband
