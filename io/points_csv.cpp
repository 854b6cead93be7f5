#include "io/points_csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "geometry/input_error.h"
#include "io/atomic_file.h"

namespace skyband {
namespace {

struct Record {
  std::vector<std::string> cells;
  std::size_t line = 0;  // line where the record starts
};

// RFC 4180 records. Quoted fields may span lines; CR LF, LF and lone CR end records.
std::vector<Record> parse_records(const std::string& name, std::string_view text) {
  std::vector<Record> records;
  std::size_t i = 0, line = 1;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") i = 3;  // UTF-8 byte-order mark
  auto at_line_end = [&](std::size_t k) { return k < text.size() && (text[k] == '\n' || text[k] == '\r'); };
  auto skip_line_end = [&](std::size_t& k) {
    if (text[k] == '\r' && k + 1 < text.size() && text[k + 1] == '\n') ++k;
    ++k;
    ++line;
  };
  while (i < text.size()) {
    Record r;
    r.line = line;
    std::string cell;
    bool record_done = false;
    while (!record_done) {
      cell.clear();
      if (i < text.size() && text[i] == '"') {
        const std::size_t quote_line = line;
        ++i;
        for (;;) {
          if (i >= text.size())
            throw InputError(name + ":" + std::to_string(quote_line) + ": quoted field is never closed");
          if (text[i] == '"') {
            if (i + 1 < text.size() && text[i + 1] == '"') {
              cell += '"';
              i += 2;
              continue;
            }
            ++i;
            break;
          }
          if (text[i] == '\n' || (text[i] == '\r' && !(i + 1 < text.size() && text[i + 1] == '\n'))) ++line;
          cell += text[i++];
        }
        // After the closing quote only a separator or the end of the record may follow.
        if (i < text.size() && text[i] != ',' && !at_line_end(i))
          throw InputError(name + ":" + std::to_string(line) + ": unexpected text after the closing quote of field " +
                           std::to_string(r.cells.size() + 1) + ": '" + cell + "\"" + text[i] + "…'");
      } else {
        while (i < text.size() && text[i] != ',' && !at_line_end(i)) cell += text[i++];
      }
      r.cells.push_back(cell);
      if (i < text.size() && text[i] == ',') {
        ++i;
      } else {
        if (i < text.size()) skip_line_end(i);
        record_done = true;
      }
    }
    const bool blank = r.cells.size() == 1 && r.cells[0].find_first_not_of(" \t") == std::string::npos;
    if (!blank) records.push_back(std::move(r));
  }
  return records;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

double parse_number(const std::string& name, std::size_t line, const std::string& column, const std::string& cell) {
  const std::string t = trim(cell);
  std::string_view v = t;
  if (v.size() > 1 && v[0] == '+') v.remove_prefix(1);
  double x = 0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), x, std::chars_format::general);
  const std::string where = name + ":" + std::to_string(line) + ": column '" + column + "': ";
  if (v.empty()) throw InputError(where + "empty value");
  if (ec == std::errc::result_out_of_range) throw InputError(where + "value '" + cell + "' is out of the range of a double");
  if (ec != std::errc() || end != v.data() + v.size()) throw InputError(where + "value '" + cell + "' is not a number");
  if (!std::isfinite(x)) throw InputError(where + "non-finite value '" + cell + "'");
  return x;
}

bool needs_quotes(const std::string& s) {
  return s.find_first_of(",\"\r\n") != std::string::npos || (!s.empty() && (s.front() == ' ' || s.back() == ' '));
}

std::string csv_cell(const std::string& s) {
  if (!needs_quotes(s)) return s;
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + '"';
}

}  // namespace

PointsTable read_points_csv(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError("points file '" + name + "' does not exist");
  if (std::filesystem::is_directory(file, ec)) throw InputError("points file '" + name + "' is a directory");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot open points file '" + name + "'");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError("cannot read points file '" + name + "'");

  std::vector<Record> records = parse_records(name, text);
  if (records.empty()) throw InputError(name + ": no header row (the file is empty)");

  PointsTable table;
  table.file = file;
  table.header = records[0].cells;
  const std::size_t header_line = records[0].line;
  auto find_column = [&](const char* wanted) -> int {
    int found = -1;
    for (std::size_t c = 0; c < table.header.size(); ++c)
      if (trim(table.header[c]) == wanted) {
        if (found >= 0)
          throw InputError(name + ":" + std::to_string(header_line) + ": column '" + wanted + "' appears twice");
        found = static_cast<int>(c);
      }
    return found;
  };
  const int cx = find_column("x"), cy = find_column("y"), cz = find_column("z");
  const int cnx = find_column("nx"), cny = find_column("ny"), cnz = find_column("nz");
  for (const auto& [c, n] : {std::pair{cx, "x"}, std::pair{cy, "y"}, std::pair{cz, "z"}})
    if (c < 0)
      throw InputError(name + ":" + std::to_string(header_line) + ": required column '" + n +
                       "' is missing (columns x, y, z are required; nx, ny, nz optional)");
  const int normals = (cnx >= 0) + (cny >= 0) + (cnz >= 0);
  if (normals != 0 && normals != 3)
    throw InputError(name + ":" + std::to_string(header_line) +
                     ": normal columns must come together: found only some of nx, ny, nz");

  for (std::size_t r = 1; r < records.size(); ++r) {
    Record& rec = records[r];
    if (rec.cells.size() != table.header.size())
      throw InputError(name + ":" + std::to_string(rec.line) + ": row has " + std::to_string(rec.cells.size()) +
                       " cells, the header has " + std::to_string(table.header.size()) + " columns");
    auto value = [&](int c) {
      return parse_number(name, rec.line, trim(table.header[static_cast<std::size_t>(c)]), rec.cells[static_cast<std::size_t>(c)]);
    };
    QueryPoint q;
    q.position = Vec3(value(cx), value(cy), value(cz));
    q.normal = Vec3(0, 0, 1);
    if (normals == 3) {
      const Vec3 n(value(cnx), value(cny), value(cnz));
      const double length = n.norm();
      if (!(length > 0.0) || !std::isfinite(length))
        throw InputError(name + ":" + std::to_string(rec.line) + ": normal (" + rec.cells[static_cast<std::size_t>(cnx)] +
                         ", " + rec.cells[static_cast<std::size_t>(cny)] + ", " + rec.cells[static_cast<std::size_t>(cnz)] +
                         ") has zero or non-finite length");
      q.normal = n / length;
    }
    table.points.push_back(q);
    table.row_lines.push_back(rec.line);
    table.rows.push_back(std::move(rec.cells));
  }
  return table;
}

void write_points_csv(const std::filesystem::path& file, const PointsTable& table,
                      const std::vector<std::string>& extra_columns,
                      const std::vector<std::vector<double>>& extra_values) {
  if (extra_columns.size() != extra_values.size())
    throw std::invalid_argument("write_points_csv: " + std::to_string(extra_columns.size()) + " column names but " +
                                std::to_string(extra_values.size()) + " value columns");
  for (std::size_t c = 0; c < extra_values.size(); ++c)
    if (extra_values[c].size() != table.rows.size())
      throw std::invalid_argument("write_points_csv: column '" + extra_columns[c] + "' has " +
                                  std::to_string(extra_values[c].size()) + " values for " +
                                  std::to_string(table.rows.size()) + " rows");
  for (const auto& c : extra_columns)
    if (std::any_of(table.header.begin(), table.header.end(), [&](const std::string& h) { return trim(h) == trim(c); }))
      throw InputError("cannot write '" + file.string() + "': output column '" + c + "' already exists in the input '" +
                       table.file.string() + "'");

  write_atomically(file, [&](const std::filesystem::path& temp) {
    std::ofstream out(temp, std::ios::binary);
    if (!out) throw InputError("cannot write '" + file.string() + "'");
    std::string line;
    auto emit_row = [&](const std::vector<std::string>& cells, std::size_t row) {
      line.clear();
      for (std::size_t c = 0; c < cells.size(); ++c) {
        if (c) line += ',';
        line += csv_cell(cells[c]);
      }
      for (std::size_t c = 0; c < extra_values.size(); ++c) {
        if (!line.empty() || c) line += ',';
        if (row == static_cast<std::size_t>(-1)) {
          line += csv_cell(extra_columns[c]);
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
