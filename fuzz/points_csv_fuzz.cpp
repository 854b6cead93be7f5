// Fuzz harness for read_points_csv and write_points_csv (io/points_csv.h): the input is a whole
// points file. A file that reads is also written back with one extra column, as `skyband svf`
// does, and read again: the round trip must give the same header, the same cells and bit-identical
// points, plus the extra column's values exactly (shortest round-trip form). A mismatch or an
// error on the re-read is a finding (aborts with the difference).
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "io/points_csv.h"

namespace {

bool same_bits(const skyband::Vec3& a, const skyband::Vec3& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

std::string shown(const std::string& s) {
  return "'" + s + "'";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using skyband::fuzz::finding;
  static const std::filesystem::path in_path = skyband::fuzz::temp_path("points", ".csv");
  static const std::filesystem::path out_path = skyband::fuzz::temp_path("points-out", ".csv");
  skyband::fuzz::write_input(in_path, data, size);

  skyband::PointsTable in;
  bool read = false;
  skyband::fuzz::expect_input_errors_only("read_points_csv", [&] {
    in = skyband::read_points_csv(in_path);
    read = true;
  });
  if (!read) return 0;

  const std::string extra = "skyband_fuzz_value";
  std::vector<double> values(in.rows.size());
  for (std::size_t r = 0; r < values.size(); ++r) values[r] = 0.1 * static_cast<double>(r) + 1e-300;
  bool written = false;
  skyband::fuzz::expect_input_errors_only("write_points_csv", [&] {  // InputError: the column exists
    skyband::write_points_csv(out_path, in, {extra}, {values});
    written = true;
  });
  if (!written) return 0;

  skyband::PointsTable back;
  try {
    back = skyband::read_points_csv(out_path);
  } catch (const std::exception& e) {
    finding(std::string("round trip: write_points_csv's output does not read back: ") + e.what());
  }
  if (back.header.size() != in.header.size() + 1 || back.header.back() != extra)
    finding("round trip: header has " + std::to_string(back.header.size()) + " columns, expected " +
            std::to_string(in.header.size() + 1) + " ending with " + shown(extra));
  for (std::size_t c = 0; c < in.header.size(); ++c)
    if (back.header[c] != in.header[c])
      finding("round trip: header cell " + std::to_string(c) + " " + shown(in.header[c]) + " became " + shown(back.header[c]));
  if (back.rows.size() != in.rows.size())
    finding("round trip: " + std::to_string(in.rows.size()) + " rows became " + std::to_string(back.rows.size()));
  for (std::size_t r = 0; r < in.rows.size(); ++r) {
    for (std::size_t c = 0; c < in.header.size(); ++c)
      if (back.rows[r][c] != in.rows[r][c])
        finding("round trip: row " + std::to_string(r) + " cell " + std::to_string(c) + " " + shown(in.rows[r][c]) + " became " +
                shown(back.rows[r][c]));
    double v = 0;
    const std::string& cell = back.rows[r].back();
    const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
    if (ec != std::errc() || end != cell.data() + cell.size() || std::memcmp(&v, &values[r], sizeof v) != 0)
      finding("round trip: extra value of row " + std::to_string(r) + " came back as " + shown(cell));
    if (!same_bits(back.points[r].position, in.points[r].position) || !same_bits(back.points[r].normal, in.points[r].normal))
      finding("round trip: point of row " + std::to_string(r) + " changed");
  }
  return 0;
}
