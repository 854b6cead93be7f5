#include "io/points_csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "geometry/core/input_error.h"
#include "io/atomic_file.h"
#include "io/csv_table.h"
#include "io/utf8_text.h"

namespace skyband {
namespace {

constexpr std::string_view kBom = "\xEF\xBB\xBF";  // U+FEFF in UTF-8

bool needs_quotes(const std::string& s, bool at_file_start) {
  // At byte 0 a cell that begins with U+FEFF would be read back as a byte-order mark and lose
  // it (csv_table.cpp strips one at byte 0): quoted, it starts with '"' and round-trips exactly.
  if (at_file_start && s.starts_with(kBom)) return true;
  return s.find_first_of(",\"\r\n") != std::string::npos || (!s.empty() && (s.front() == ' ' || s.back() == ' '));
}

std::string csv_cell(const std::string& s, bool at_file_start = false) {
  if (!needs_quotes(s, at_file_start)) return s;
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + '"';
}

}  // namespace

PointsTable read_points_csv(const std::filesystem::path& file) {
  const CsvTable csv = read_csv_table(file, "points file");
  const std::string name = file.string();
  const std::string header_at = name + ":" + std::to_string(csv.header_line);
  const int cx = csv.column("x"), cy = csv.column("y"), cz = csv.column("z");
  const int cnx = csv.column("nx"), cny = csv.column("ny"), cnz = csv.column("nz");
  for (const auto& [c, n] : {std::pair{cx, "x"}, std::pair{cy, "y"}, std::pair{cz, "z"}})
    if (c < 0)
      throw InputError(header_at + ": required column '" + n +
                       "' is missing (columns x, y, z are required; nx, ny, nz optional)");
  const int normals = (cnx >= 0) + (cny >= 0) + (cnz >= 0);
  if (normals != 0 && normals != 3)
    throw InputError(header_at + ": normal columns must come together: found only some of nx, ny, nz");

  PointsTable table;
  table.file = file;
  table.header = csv.header;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    QueryPoint q;
    q.position = Vec3(csv.number(r, cx), csv.number(r, cy), csv.number(r, cz));
    q.normal = Vec3(0, 0, 1);
    if (normals == 3) {
      const Vec3 n(csv.number(r, cnx), csv.number(r, cny), csv.number(r, cnz));
      const double length = n.norm();
      const auto& cells = csv.rows[r];
      if (!(length > 0.0) || !std::isfinite(length))
        throw InputError(csv.where(r) + ": normal (" + printable_text(cells[static_cast<std::size_t>(cnx)]) + ", " +
                         printable_text(cells[static_cast<std::size_t>(cny)]) + ", " +
                         printable_text(cells[static_cast<std::size_t>(cnz)]) + ") has zero or non-finite length");
      q.normal = n / length;
    }
    table.points.push_back(q);
  }
  table.row_lines = csv.row_lines;
  table.rows = csv.rows;
  return table;
}

void write_points_csv(const std::filesystem::path& file, const PointsTable& table, const std::vector<std::string>& extra_columns,
                      const std::vector<std::vector<double>>& extra_values) {
  if (extra_columns.size() != extra_values.size())
    throw std::invalid_argument("write_points_csv: " + std::to_string(extra_columns.size()) + " column names but " +
                                std::to_string(extra_values.size()) + " value columns");
  for (std::size_t c = 0; c < extra_values.size(); ++c)
    if (extra_values[c].size() != table.rows.size())
      throw std::invalid_argument("write_points_csv: column '" + extra_columns[c] + "' has " +
                                  std::to_string(extra_values[c].size()) + " values for " + std::to_string(table.rows.size()) +
                                  " rows");
  for (const auto& c : extra_columns)
    if (std::any_of(table.header.begin(), table.header.end(),
                    [&](const std::string& h) { return trim_csv_cell(h) == trim_csv_cell(c); }))
      throw InputError("cannot write '" + file.string() + "': output column '" + c + "' already exists in the input '" +
                       table.file.string() + "'");

  write_atomically(file, [&](const std::filesystem::path& temp) {
    std::ofstream out(temp, std::ios::binary);
    if (!out) throw InputError("cannot write '" + file.string() + "'");
    std::string line;
    auto emit_row = [&](const std::vector<std::string>& cells, std::size_t row) {
      line.clear();
      const bool header = row == static_cast<std::size_t>(-1);  // the header is written at byte 0
      for (std::size_t c = 0; c < cells.size(); ++c) {
        if (c) line += ',';
        line += csv_cell(cells[c], header && c == 0);
      }
      for (std::size_t c = 0; c < extra_values.size(); ++c) {
        if (!line.empty() || c) line += ',';
        if (header) {
          line += csv_cell(extra_columns[c], cells.empty() && c == 0);
        } else {
          char buffer[64];
          const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, extra_values[c][row]);
          line.append(buffer, end);
        }
      }
      line += '\n';
      out << line;
    };
    emit_row(table.header, static_cast<std::size_t>(-1));
    for (std::size_t r = 0; r < table.rows.size(); ++r) emit_row(table.rows[r], r);
    out.flush();
    if (!out) throw InputError("cannot write '" + file.string() + "' (disk full?)");
  });
}

}  // namespace skyband
