#include "lighting/climate/moment_series.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include <date/date.h>
#include <date/tz.h>

#include "geometry/core/input_error.h"

namespace skyband {

namespace {

date::year_month_day parse_day(const std::string& text, std::string_view flag) {
  int y = 0;
  unsigned m = 0, d = 0;
  char a = 0, b = 0;
  std::size_t used = 0;
  if (std::sscanf(text.c_str(), "%d%c%u%c%u%zn", &y, &a, &m, &b, &d, &used) != 5 || a != '-' || b != '-' || used != text.size())
    throw InputError(std::string(flag) + " '" + text + "': expected a date YYYY-MM-DD");
  const date::year_month_day ymd{date::year{y}, date::month{m}, date::day{d}};
  if (!ymd.ok() || y < -2000 || y > 6000)
    throw InputError(std::string(flag) + " '" + text + "': not a date (years -2000 to 6000)");
  return ymd;
}

}  // namespace

std::pair<std::string, std::string> parse_date_range(std::string_view text, std::string_view flag) {
  const std::string s(text);
  const std::size_t colon = s.find(':');
  if (colon == std::string::npos) return {s, s};
  return {s.substr(0, colon), s.substr(colon + 1)};
}

std::vector<TimedMoment> moment_series(const MomentSeriesSpec& spec) {
  using namespace std::chrono;
  const date::year_month_day first = parse_day(spec.first_date, "--date"), last = parse_day(spec.last_date, "--date");
  const date::sys_days d0{first}, d1{last};
  if (d1 < d0) throw InputError("--date " + spec.first_date + ":" + spec.last_date + ": the last date is before the first");
  if (!(spec.step_minutes > 0 && spec.step_minutes <= 1440) || !std::isfinite(spec.step_minutes))
    throw InputError("--step " + std::to_string(spec.step_minutes) + ": must be in (0, 1440] minutes");
  if (spec.zone.empty() == !spec.utc_offset_hours)
    throw InputError(spec.zone.empty() ? "moments need a time zone: --zone NAME (e.g. Europe/Amsterdam) or --tz HOURS"
                                       : "give --zone or --tz, not both");
  const date::time_zone* zone = nullptr;
  if (!spec.zone.empty()) {
    try {
      zone = date::locate_zone(spec.zone);
    } catch (const std::exception&) {
      throw InputError("--zone '" + spec.zone + "': not a time zone of the tz database (e.g. Europe/Amsterdam, UTC)");
    }
  } else if (!(std::abs(*spec.utc_offset_hours) <= 18) || !std::isfinite(*spec.utc_offset_hours)) {
    throw InputError("--tz " + std::to_string(*spec.utc_offset_hours) + ": must be in [-18, 18] hours");
  }
  // The UTC instants of local midnight of the first date and after the last one.
  const auto utc_of_local_midnight = [&](date::sys_days day) -> sys_time<duration<double>> {
    if (zone) {
      const date::local_days local{day.time_since_epoch()};
      // (a midnight skipped by a daylight-saving change: the instant the day begins)
      return date::make_zoned(zone, local, date::choose::earliest).get_sys_time();
    }
    return sys_time<duration<double>>(day) - duration<double>(*spec.utc_offset_hours * 3600.0);
  };
  const auto t0 = utc_of_local_midnight(d0), t1 = utc_of_local_midnight(d1 + date::days{1});
  const double total_s = (t1 - t0).count(), step_s = spec.step_minutes * 60.0;
  const double count = std::ceil(total_s / step_s - 1e-9);
  if (count > 1e6) throw InputError("--date/--step: " + std::to_string(count) + " moments (at most 10^6)");
  std::vector<TimedMoment> out;
  out.reserve(static_cast<std::size_t>(count));
  for (std::size_t k = 0; k < static_cast<std::size_t>(count); ++k) {
    const double a = k * step_s, b = std::min(total_s, (k + 1) * step_s);
    const auto t = t0 + duration<double>(0.5 * (a + b));
    const auto whole = time_point_cast<seconds>(floor<seconds>(t));
    double offset_h = spec.utc_offset_hours.value_or(0);
    if (zone) offset_h = duration<double>(zone->get_info(whole).offset).count() / 3600.0;
    // Local civil time = UTC + offset.
    const auto local = t + duration<double>(offset_h * 3600.0);
    const auto day = floor<date::days>(local);
    const date::year_month_day ymd{day};
    const double sod = duration<double>(local - day).count();
    TimedMoment m;
    m.time.year = int(ymd.year());
    m.time.month = int(unsigned(ymd.month()));
    m.time.day = int(unsigned(ymd.day()));
    m.time.hour = int(sod / 3600);
    m.time.minute = int((sod - 3600.0 * m.time.hour) / 60);
    m.time.second = sod - 3600.0 * m.time.hour - 60.0 * m.time.minute;
    m.time.utc_offset_hours = offset_h;
    m.hours = (b - a) / 3600.0;
    out.push_back(m);
  }
  return out;
}

}  // namespace skyband
