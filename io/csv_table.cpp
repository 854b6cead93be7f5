// RFC 4180 reading shared by the points and times files (csv_table.h).
#include "io/csv_table.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>

#include "geometry/core/input_error.h"
#include "io/utf8_text.h"

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
          if (i >= text.size()) throw InputError(name + ":" + std::to_string(quote_line) + ": quoted field is never closed");
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
                           std::to_string(r.cells.size() + 1) + ": '" + printable_text(cell + "\"" + text[i]) + "…'");
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
  // The cell and the column name are the user's text: printable (a NUL would cut the message).
  const std::string where = name + ":" + std::to_string(line) + ": column '" + printable_text(column) + "': ";
  if (v.empty()) throw InputError(where + "empty value");
  if (ec == std::errc::result_out_of_range)
    throw InputError(where + "value '" + printable_text(cell) + "' is out of the range of a double");
  if (ec != std::errc() || end != v.data() + v.size())
    throw InputError(where + "value '" + printable_text(cell) + "' is not a number");
  if (!std::isfinite(x)) throw InputError(where + "non-finite value '" + printable_text(cell) + "'");
  return x;
}

}  // namespace

std::string trim_csv_cell(const std::string& s) {
  return trim(s);
}

CsvTable read_csv_table(const std::filesystem::path& file, const std::string& what) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError(what + " '" + name + "' does not exist");
  if (std::filesystem::is_directory(file, ec)) throw InputError(what + " '" + name + "' is a directory");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot open " + what + " '" + name + "'");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError("cannot read " + what + " '" + name + "'");
  refuse_wide_text(name, text, "CSV");

  std::vector<Record> records = parse_records(name, text);
  if (records.empty()) throw InputError(name + ": no header row (the file is empty)");
  // Spreadsheets in many locales save "CSV" with ';' (and decimal commas), or tabs: one cell here.
  if (records[0].cells.size() == 1)
    for (const char separator : {';', '\t'})
      if (records[0].cells[0].find(separator) != std::string::npos)
        throw InputError(name + ":" + std::to_string(records[0].line) + ": the header '" + printable_text(records[0].cells[0]) +
                         "' is one column: the file separates its values with " + (separator == ';' ? "';'" : "tabs") +
                         "; skyband reads comma-separated values (RFC 4180): save it with ',' between values and '.' as the "
                         "decimal point");
  CsvTable t;
  t.file = file;
  t.header = records[0].cells;
  t.header_line = records[0].line;
  for (std::size_t r = 1; r < records.size(); ++r) {
    Record& rec = records[r];
    if (rec.cells.size() != t.header.size())
      throw InputError(name + ":" + std::to_string(rec.line) + ": row has " + std::to_string(rec.cells.size()) +
                       " cells, the header has " + std::to_string(t.header.size()) + " columns");
    t.row_lines.push_back(rec.line);
    t.rows.push_back(std::move(rec.cells));
  }
  return t;
}

int CsvTable::column(const std::string& name) const {
  int found = -1;
  for (std::size_t c = 0; c < header.size(); ++c)
    if (trim(header[c]) == name) {
      if (found >= 0)
        throw InputError(file.string() + ":" + std::to_string(header_line) + ": column '" + name + "' appears twice");
      found = static_cast<int>(c);
    }
  return found;
}

double CsvTable::number(std::size_t r, int c) const {
  const auto cu = static_cast<std::size_t>(c);
  return parse_number(file.string(), row_lines[r], trim(header[cu]), rows[r][cu]);
}

std::string CsvTable::text(std::size_t r, int c) const {
  const auto cu = static_cast<std::size_t>(c);
  std::string t = trim(rows[r][cu]);
  if (!is_printable_text(t))
    throw InputError(where(r) + ": column '" + printable_text(trim(header[cu])) + "': value '" + printable_text(t) +
                     "' holds a control character or is not UTF-8");
  return t;
}

std::string CsvTable::where(std::size_t r) const {
  return file.string() + ":" + std::to_string(row_lines[r]);
}

}  // namespace skyband
