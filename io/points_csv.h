#pragma once
// Calculation points as CSV — the input and output of `skyband svf`.
//
// Input: a header row, then one row per point (RFC 4180: comma separated, fields may be quoted
// with "…" and then contain commas, quotes written "" and line breaks; CR LF or LF line ends; a
// UTF-8 byte-order mark at byte 0 and blank lines are ignored; U+FEFF anywhere else is data).
// Columns `x`, `y`, `z` (metres, world frame) are required; `nx`, `ny`, `nz` (the surface
// normal, any length, normalised on read) are optional together and default to (0, 0, 1).
// Column names are matched after trimming spaces. Every other column passes through unchanged.
// Coordinates are parsed exactly (std::from_chars, correctly rounded) and never shifted.
// Errors (InputError naming file, line, column and value): missing x/y/z column, only some of
// nx/ny/nz, a repeated coordinate column, a row with fewer or more cells than the header, a
// non-number or non-finite value, a zero normal, an unterminated quote. A header without rows
// is a valid table of 0 points.
//
// Output: the input header and rows in input order (cells re-quoted only where CSV needs it),
// plus extra numeric columns printed in the shortest form that round-trips (std::to_chars),
// written atomically (io/atomic_file.h). Reading the output back gives the same header and
// cells: in particular a first header cell that itself begins with U+FEFF (after the file's own
// byte-order mark, or after leading blank lines) is written quoted, since the reader strips one
// byte-order mark at byte 0 and only there.
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/bands/band_visibility.h"

namespace skyband {

struct PointsTable {
  std::filesystem::path file;
  std::vector<std::string> header;             // all input columns, in order
  std::vector<std::vector<std::string>> rows;  // raw cell text, passed through unchanged
  std::vector<std::size_t> row_lines;          // line number of each row in the input (messages)
  std::vector<QueryPoint> points;              // one per row
};

PointsTable read_points_csv(const std::filesystem::path& file);

// extra_values is [column][row]; each column must have one value per row (std::invalid_argument
// otherwise — a programming error, not a user error). Extra column names must not repeat an
// input column (InputError).
void write_points_csv(const std::filesystem::path& file, const PointsTable& table, const std::vector<std::string>& extra_columns,
                      const std::vector<std::vector<double>>& extra_values);

}  // namespace skyband
