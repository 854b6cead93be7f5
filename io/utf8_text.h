#pragma once
// UTF-8 text as the readers see it: strict decoding of one sequence (RFC 3629 / Unicode 15
// table 3-7: no overlong forms, no surrogates U+D800–U+DFFF, nothing above U+10FFFF), and the
// printable form of a user's text for a one-line error message.
//
// Why the printable form: an InputError message is a C string (std::exception::what()), so a
// NUL inside a user's value cuts the message short, and a line break, carriage return or
// terminal escape inside it breaks the CLI's "one line per error" rule or rewrites the
// terminal. Every reader that quotes file text in a message passes it through printable_text,
// and the CLI prints the whole message through it once more.
#include <cstddef>
#include <string>
#include <string_view>

namespace skyband {

// The length (1–4 bytes) of the valid UTF-8 sequence that starts at text[i], storing its code
// point in *code_point; 0 if the bytes there are not a valid sequence (i < text.size()).
std::size_t utf8_sequence_length(std::string_view text, std::size_t i, char32_t* code_point);

// The byte offset of the first byte that does not begin a valid UTF-8 sequence, or npos.
std::size_t first_invalid_utf8(std::string_view text);

// `text` with every control character escaped: TAB, LF and CR as \t, \n, \r; other C0 controls,
// DEL and bytes that are not valid UTF-8 as \xNN; C1 controls (U+0080–U+009F) and the line and
// paragraph separators U+2028/U+2029 as \uNNNN. Valid printable UTF-8 is kept as it is, so
// "façade" stays "façade".
std::string printable_text(std::string_view text);

// True if printable_text(text) == text: valid UTF-8 without control characters.
bool is_printable_text(std::string_view text);

// "UTF-16" or "UTF-32" when `bytes` (after a UTF-8 byte-order mark, if any) begin as text in one of
// those encodings — a byte-order mark, or up to four code units (two of UTF-32) of printable ASCII
// or white space each beside zero bytes: what Windows tools write as "Unicode" — else "".
std::string_view wide_text_encoding(std::string_view bytes);

// The text readers' first check: throws InputError "<file>: UTF-16 text; <format> is read as
// UTF-8: convert it first, e.g. iconv -f UTF-16 -t UTF-8 ..." for such bytes, rather than
// reporting their zero bytes as a format error further on.
void refuse_wide_text(const std::string& file, std::string_view bytes, std::string_view format);

}  // namespace skyband
