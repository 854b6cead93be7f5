#pragma once
// An hourly weather series: the site and, per interval, the solar radiation (and what goes with
// it) that skyband lights a scene with over a period. Read from weather files by io/epw_reader.h.
//
// Conventions:
// - Site: latitude_deg north positive, longitude_deg east positive (degrees, [−90, 90] and
//   [−180, 180]); time_zone_hours is the offset of the file's local STANDARD time from UTC in
//   hours, east positive (UTC−6 for Chicago, UTC+10 for Queensland); no daylight saving time is
//   ever applied. elevation_m is above mean sea level.
// - Time of a record: local standard time of that zone. `hour` h ∈ 1..24 labels the interval
//   (h − interval_hours, h] of the record's date — hour-ending, as in EnergyPlus, so hour 1 is
//   00:00–01:00 and hour 24 is 23:00–24:00. The sun of a record belongs at the middle of its
//   interval, mid_hour() = h − interval_hours/2 (11.5 for hour 12 of an hourly file).
// - Radiation: ghi/dni/dhi_Wh_m2 are energies per m² received over the interval: global and
//   diffuse on a horizontal surface, direct on a surface normal to the sun. Divided by
//   interval_hours they are the mean irradiances in W/m² (for hourly data the numbers are equal).
// - Illuminances (lux) are means over the interval; std::nullopt where the file marks them
//   missing (a luminous-efficacy model has to supply them). Dew point (°C) and ground albedo
//   (reflectance, 0..1) are likewise optional.
// - `year` is as written: typical-year files (TMY, TMYx) take each month from a different year,
//   so it may jump from one record to the next; the calendar position is month/day/hour.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace skyband {

struct WeatherLocation {
  std::string name;        // city or site, as written in the file
  std::string region;      // state / province / region (may be empty)
  std::string country;     // usually a 3-letter code
  std::string source;      // data source, e.g. "TMY3", "SRC-TMYx"
  std::string station_id;  // WMO station number, kept as text (leading zeros matter)
  double latitude_deg = 0;
  double longitude_deg = 0;
  double time_zone_hours = 0;  // local standard time − UTC (hours), east positive
  double elevation_m = 0;
};

struct WeatherRecord {
  int year = 0;
  int month = 1;  // 1..12
  int day = 1;    // 1..31
  int hour = 1;   // 1..24, hour-ending: covers (hour − interval_hours, hour]
  double interval_hours = 1;
  double ghi_Wh_m2 = 0;                           // global horizontal
  double dni_Wh_m2 = 0;                           // direct normal
  double dhi_Wh_m2 = 0;                           // diffuse horizontal
  std::optional<double> global_illuminance_lux;   // horizontal
  std::optional<double> direct_illuminance_lux;   // normal to the sun
  std::optional<double> diffuse_illuminance_lux;  // horizontal
  std::optional<double> dew_point_C;
  std::optional<double> albedo;  // ground reflectance, [0, 1]
  std::size_t line = 0;          // line of the record in its file (for messages); 0 if not read from one

  // Local standard time (hours after the record's midnight) at the middle of the interval.
  double mid_hour() const { return hour - 0.5 * interval_hours; }
};

struct WeatherSeries {
  std::filesystem::path file;  // where it was read from (messages)
  WeatherLocation location;
  std::vector<WeatherRecord> records;  // in file order, consecutive intervals
  // Suspicious but usable properties of the input, one line each, each naming the file. The
  // reader fills them; the caller decides whether to print them.
  std::vector<std::string> warnings;
};

// A calendar day without a year, for choosing a period of a (typical) year.
struct MonthDay {
  int month = 1;  // 1..12
  int day = 1;    // 1..days of the month, 29 allowed in February
};

// Parses "MM-DD" (one or two digits each, e.g. "12-01", "2-28"). February 29 is a valid day:
// it selects that day in leap-year files and nothing in the others. Anything else, including an
// impossible date ("02-30", "13-01", "04-31"), throws InputError naming `flag` and the text.
MonthDay parse_month_day(std::string_view text, std::string_view flag);

// Whether `date` lies in the inclusive period [from, to]; when `from` comes after `to` in the
// calendar the period wraps over the new year (12-01 to 02-28 is winter).
bool in_period(MonthDay date, MonthDay from, MonthDay to);

// The records of `series` whose date lies in [from, to] (see in_period), in file order, with the
// location, file and warnings of `series`. `from` and `to` must be possible dates (InputError
// otherwise). An empty selection is not an error here; the caller decides.
WeatherSeries select_period(const WeatherSeries& series, MonthDay from, MonthDay to);

// Days in `month` of `year` (Gregorian), and the most a month can have in any year (29 for
// February), for checking dates that carry no year.
bool is_leap_year(int year);
int month_length_days(int year, int month);
int max_month_length_days(int month);

}  // namespace skyband
