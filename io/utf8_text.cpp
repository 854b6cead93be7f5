// Strict UTF-8 decoding and printable escapes (utf8_text.h).
#include "io/utf8_text.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "geometry/core/input_error.h"

namespace skyband {
namespace {

bool is_escaped_code_point(char32_t c) {
  return c < 0x20 || c == 0x7F || (c >= 0x80 && c <= 0x9F) || c == 0x2028 || c == 0x2029;
}

}  // namespace

std::size_t utf8_sequence_length(std::string_view text, std::size_t i, char32_t* code_point) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) {
    *code_point = b0;
    return 1;
  }
  // Unicode table 3-7 "Well-Formed UTF-8 Byte Sequences": the allowed range of the second byte
  // depends on the first (this excludes overlong forms, surrogates and code points > U+10FFFF).
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;
  char32_t c = 0;
  if (b0 >= 0xC2 && b0 <= 0xDF)
    n = 2, c = b0 & 0x1Fu;
  else if (b0 == 0xE0)
    n = 3, lo = 0xA0, c = b0 & 0x0Fu;
  else if (b0 >= 0xE1 && b0 <= 0xEC)
    n = 3, c = b0 & 0x0Fu;
  else if (b0 == 0xED)
    n = 3, hi = 0x9F, c = b0 & 0x0Fu;
  else if (b0 >= 0xEE && b0 <= 0xEF)
    n = 3, c = b0 & 0x0Fu;
  else if (b0 == 0xF0)
    n = 4, lo = 0x90, c = b0 & 0x07u;
  else if (b0 >= 0xF1 && b0 <= 0xF3)
    n = 4, c = b0 & 0x07u;
  else if (b0 == 0xF4)
    n = 4, hi = 0x8F, c = b0 & 0x07u;
  else
    return 0;
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    const unsigned char b = byte(i + k);
    if (b < (k == 1 ? lo : 0x80) || b > (k == 1 ? hi : 0xBF)) return 0;
    c = (c << 6) | (b & 0x3Fu);
  }
  *code_point = c;
  return n;
}

std::size_t first_invalid_utf8(std::string_view text) {
  char32_t c;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_sequence_length(text, i, &c);
    if (n == 0) return i;
    i += n;
  }
  return std::string_view::npos;
}

std::string printable_text(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  char buf[16];
  char32_t c;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_sequence_length(text, i, &c);
    if (n == 0) {
      std::snprintf(buf, sizeof buf, "\\x%02X", static_cast<unsigned>(static_cast<unsigned char>(text[i])));
      out += buf;
      ++i;
      continue;
    }
    if (!is_escaped_code_point(c)) {
      out.append(text.substr(i, n));
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else {
      std::snprintf(buf, sizeof buf, c < 0x80 ? "\\x%02X" : "\\u%04X", static_cast<unsigned>(c));
      out += buf;
    }
    i += n;
  }
  return out;
}

bool is_printable_text(std::string_view text) {
  char32_t c;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_sequence_length(text, i, &c);
    if (n == 0 || is_escaped_code_point(c)) return false;
    i += n;
  }
  return true;
}

std::string_view wide_text_encoding(std::string_view b) {
  if (b.substr(0, 3) == "\xEF\xBB\xBF") b.remove_prefix(3);  // what follows a UTF-8 byte-order mark
  const auto at = [&](std::size_t i) { return i < b.size() ? static_cast<unsigned char>(b[i]) : 0x100u; };
  if ((at(0) == 0xFF && at(1) == 0xFE && at(2) == 0 && at(3) == 0) ||
      (at(0) == 0 && at(1) == 0 && at(2) == 0xFE && at(3) == 0xFF))
    return "UTF-32";
  if ((at(0) == 0xFF && at(1) == 0xFE) || (at(0) == 0xFE && at(1) == 0xFF)) return "UTF-16";
  // Without a byte-order mark: the first code units (up to 4 of UTF-16, 2 of UTF-32, as many as
  // the text holds) are printable ASCII or white space, each beside the zero bytes of its unit.
  const auto ascii = [](unsigned c) { return c == 0x09 || c == 0x0A || c == 0x0D || (c >= 0x20 && c < 0x7F); };
  const auto units = [&](std::size_t width, bool big_endian) {
    const std::size_t n = std::min<std::size_t>(b.size() / width, width == 2 ? 4 : 2);
    if (n == 0) return false;
    for (std::size_t u = 0; u < n; ++u)
      for (std::size_t k = 0; k < width; ++k) {
        const bool low = big_endian ? k == width - 1 : k == 0;
        const unsigned c = at(u * width + k);
        if (low ? !ascii(c) : c != 0) return false;
      }
    return true;
  };
  if (units(4, false) || units(4, true)) return "UTF-32";
  if (units(2, false) || units(2, true)) return "UTF-16";
  return "";
}

void refuse_wide_text(const std::string& file, std::string_view bytes, std::string_view format) {
  const std::string_view encoding = wide_text_encoding(bytes);
  if (encoding.empty()) return;
  const std::filesystem::path p(file);
  throw InputError(file + ": " + std::string(encoding) + " text; " + std::string(format) +
                   " is read as UTF-8: convert it first, e.g. iconv -f " + std::string(encoding) + " -t UTF-8 " +
                   p.filename().string() + " > " + p.stem().string() + "-utf8" + p.extension().string());
}

}  // namespace skyband
