#pragma once
// A CSV table as skyband reads it (points, moments): RFC 4180 — comma separated, fields may be
// quoted with "…" and then contain commas, quotes written "" and line breaks; CR LF, LF or lone
// CR line ends; one UTF-8 byte-order mark at byte 0 and blank lines are ignored (U+FEFF anywhere
// else, a second one included, is part of a cell). The first record is the
// header; every row must have as many cells as the header. Errors are InputErrors naming the
// file and line (and the column and value, for numbers).
#include <filesystem>
#include <string>
#include <vector>

namespace skyband {

struct CsvTable {
  std::filesystem::path file;
  std::vector<std::string> header;  // cells as written
  std::size_t header_line = 0;
  std::vector<std::vector<std::string>> rows;  // raw cell text
  std::vector<std::size_t> row_lines;          // line where each row starts

  // Index of the column whose trimmed name is `name`, −1 if there is none; InputError if it
  // appears twice.
  int column(const std::string& name) const;
  // The number in row r, column c (std::from_chars, correctly rounded): InputError naming
  // file:line, the column and the text for an empty, non-numeric or non-finite cell.
  double number(std::size_t r, int c) const;
  // The text in row r, column c, trimmed: InputError naming file:line, the column and the text
  // (escaped) if it holds a control character or is not UTF-8 — text that goes on into a parser
  // whose messages quote it (a NUL would cut them short, a line break split them).
  std::string text(std::size_t r, int c) const;
  // "file:line" of row r, for messages.
  std::string where(std::size_t r) const;
};

// `what` names the file's role in messages ("points file", "times file").
CsvTable read_csv_table(const std::filesystem::path& file, const std::string& what);

// Spaces and tabs trimmed from both ends.
std::string trim_csv_cell(const std::string& s);

}  // namespace skyband
