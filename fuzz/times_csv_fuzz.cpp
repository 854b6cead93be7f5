// Fuzz harness for the times file of `skyband irradiance --times`: the input is a whole times
// file. The CLI's reader (read_moments in cli/cmd_irradiance.cpp) is not a library function,
// so this harness repeats its steps over the library calls it makes: read_csv_table, the column
// look-ups, CsvTable::number for sun_altitude / sun_azimuth / hours with the same range checks,
// and parse_iso8601 + sun_position_spa for a `time` column (at a fixed site: 52° N, 4.4° E, no
// --tz). Keep it in step with read_moments — better, move read_moments into io/ and call it here.
// Beyond "InputError or success", every moment that is accepted must have a finite unit sun
// direction and a finite total of hours (an accepted file that sums to ∞ is a finding).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "fuzz/fuzz_support.h"
#include "io/csv_table.h"
#include "lighting/sun/sun_position.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

// The unit direction towards the sun (sun_position.h's convention: azimuth clockwise from north).
skyband::Vec3 sun_direction(double altitude_deg, double azimuth_deg) {
  const double alt = altitude_deg * kPi / 180, az = azimuth_deg * kPi / 180;
  return {std::sin(az) * std::cos(alt), std::cos(az) * std::cos(alt), std::sin(alt)};
}

void read_times(const std::filesystem::path& path) {
  using skyband::InputError;
  const skyband::CsvTable csv = skyband::read_csv_table(path, "times file");
  const std::string header_at = path.string() + ":" + std::to_string(csv.header_line);
  const int ct = csv.column("time"), calt = csv.column("sun_altitude"), caz = csv.column("sun_azimuth"), ch = csv.column("hours");
  const bool by_time = ct >= 0, by_angle = calt >= 0 || caz >= 0;
  if (by_time == by_angle)
    throw InputError(header_at + ": give either a 'time' column or 'sun_altitude' and 'sun_azimuth' columns");
  if (by_angle && (calt < 0 || caz < 0)) throw InputError(header_at + ": 'sun_altitude' and 'sun_azimuth' come together");
  double total_hours = 0;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    skyband::Vec3 dir;
    if (by_time) {
      skyband::SpaInput in;
      in.latitude_deg = 52.0;
      in.longitude_deg = 4.4;
      in.time =
          skyband::parse_iso8601(skyband::trim_csv_cell(csv.rows[r][static_cast<std::size_t>(ct)]), csv.where(r), std::nullopt);
      const skyband::SpaResult s = skyband::sun_position_spa(in);
      dir = sun_direction(90.0 - s.zenith_deg, s.azimuth_deg);
    } else {
      const double alt = csv.number(r, calt), az = csv.number(r, caz);
      if (alt < -90 || alt > 90) throw InputError(csv.where(r) + ": sun_altitude must be in [-90, 90] degrees");
      dir = sun_direction(alt, az);
    }
    if (!dir.allFinite() || std::abs(dir.norm() - 1) > 1e-9)
      skyband::fuzz::finding(csv.where(r) + ": accepted moment has sun direction (" + std::to_string(dir.x()) + ", " +
                             std::to_string(dir.y()) + ", " + std::to_string(dir.z()) + ")");
    if (ch >= 0) {
      const double hours = csv.number(r, ch);
      if (hours < 0) throw InputError(csv.where(r) + ": hours must be >= 0");
      total_hours += hours;
    }
  }
  if (csv.rows.empty()) throw InputError(path.string() + ": no moments (the file has a header only)");
  if (!std::isfinite(total_hours))
    skyband::fuzz::finding(path.string() + ": accepted times file whose hours sum to " + std::to_string(total_hours));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path = skyband::fuzz::temp_path("times", ".csv");
  skyband::fuzz::write_input(path, data, size);
  skyband::fuzz::expect_input_errors_only("times file", [&] { read_times(path); });
  return 0;
}
