#include "lighting/climate/weather_series.h"

#include <charconv>

#include "geometry/core/input_error.h"

namespace skyband {

bool is_leap_year(int year) {
  return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

int max_month_length_days(int month) {
  static constexpr int kDays[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month >= 1 && month <= 12 ? kDays[month - 1] : 0;
}

int month_length_days(int year, int month) {
  return month == 2 && !is_leap_year(year) ? 28 : max_month_length_days(month);
}

MonthDay parse_month_day(std::string_view text, std::string_view flag) {
  const auto fail = [&](const std::string& why) {
    return InputError(std::string(flag) + " '" + std::string(text) + "': " + why + " (expected MM-DD, e.g. 12-01)");
  };
  const auto number = [&](std::string_view part, const char* what) {
    int value = 0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
    if (part.empty() || part.size() > 2 || ec != std::errc() || end != part.data() + part.size() || part[0] == '-')
      throw fail(std::string("cannot read the ") + what);
    return value;
  };
  const auto dash = text.find('-');
  if (dash == std::string_view::npos) throw fail("no '-' between month and day");
  const MonthDay date{number(text.substr(0, dash), "month"), number(text.substr(dash + 1), "day")};
  if (date.month < 1 || date.month > 12) throw fail("month must be 1..12");
  if (date.day < 1 || date.day > max_month_length_days(date.month))
    throw fail("month " + std::to_string(date.month) + " has no day " + std::to_string(date.day));
  return date;
}

bool in_period(MonthDay date, MonthDay from, MonthDay to) {
  const auto key = [](MonthDay d) { return d.month * 100 + d.day; };
  const int k = key(date), a = key(from), b = key(to);
  return a <= b ? (a <= k && k <= b) : (k >= a || k <= b);
}

WeatherSeries select_period(const WeatherSeries& series, MonthDay from, MonthDay to) {
  for (const auto& [d, what] : {std::pair{from, "start"}, std::pair{to, "end"}})
    if (d.month < 1 || d.month > 12 || d.day < 1 || d.day > max_month_length_days(d.month))
      throw InputError("period " + std::string(what) + " " + std::to_string(d.month) + "-" + std::to_string(d.day) +
                       " is not a date (month 1..12, day within the month)");
  WeatherSeries out;
  out.file = series.file;
  out.location = series.location;
  out.warnings = series.warnings;
  for (const auto& r : series.records)
    if (in_period({r.month, r.day}, from, to)) out.records.push_back(r);
  return out;
}

}  // namespace skyband
