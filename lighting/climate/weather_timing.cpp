#include "lighting/climate/weather_timing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "geometry/core/vec3.h"
#include "lighting/sun/sun_position.h"

namespace skyband {
namespace {

std::string utc_offset_text(double hours) {
  char b[32];
  std::snprintf(b, sizeof b, "UTC%+g", hours);
  return b;
}

// Local standard time `hour_of_day` (hours after midnight, [0, 24)) of the record's date.
LocalDateTime local_time(const WeatherRecord& r, double hour_of_day, double time_zone_hours) {
  LocalDateTime t;
  t.year = r.year;
  t.month = r.month;
  t.day = r.day;
  const double minutes = std::max(0.0, hour_of_day) * 60.0;
  t.hour = static_cast<int>(minutes / 60.0);
  t.minute = static_cast<int>(minutes - 60.0 * t.hour);
  t.second = (minutes - 60.0 * t.hour - t.minute) * 60.0;
  t.utc_offset_hours = time_zone_hours;
  return t;
}

}  // namespace

WeatherTiming weather_timing(const WeatherSeries& series, const WeatherTimingOptions& options) {
  WeatherTiming out;
  const auto& recs = series.records;
  const auto& loc = series.location;
  SpaInput spa;
  spa.latitude_deg = loc.latitude_deg;
  spa.longitude_deg = loc.longitude_deg;
  spa.elevation_m = loc.elevation_m;

  double weight = 0, offset_sum = 0, radiation_sum = 0, sun_sum = 0;
  for (std::size_t begin = 0; begin < recs.size();) {
    std::size_t end = begin;
    double hours = 0, ghi = 0, ghi_t = 0;
    while (end < recs.size() && recs[end].year == recs[begin].year && recs[end].month == recs[begin].month &&
           recs[end].day == recs[begin].day) {
      hours += recs[end].interval_hours;
      ghi += recs[end].ghi_Wh_m2;
      ghi_t += recs[end].ghi_Wh_m2 * recs[end].mid_hour();
      ++end;
    }
    const std::size_t day_begin = begin;
    begin = end;
    if (std::abs(hours - 24.0) > 1e-6) continue;  // a partial day would bias both centroids
    ++out.days_total;
    if (!(ghi >= options.min_daily_ghi_Wh_m2) || ghi <= 0) continue;  // also skips the sun computation

    double sun = 0, sun_t = 0;
    for (std::size_t i = day_begin; i < end; ++i) {
      const double t = recs[i].mid_hour();
      spa.time = local_time(recs[i], t, loc.time_zone_hours);
      const double cos_z = std::cos(sun_position_spa(spa).zenith_deg * (kPi / 180.0));
      const double s = std::max(cos_z, 0.0);
      sun += s;
      sun_t += s * t;
    }
    if (!(sun > 0)) continue;
    const double c_rad = ghi_t / ghi, c_sun = sun_t / sun;
    weight += ghi;
    offset_sum += ghi * (c_rad - c_sun);
    radiation_sum += ghi * c_rad;
    sun_sum += ghi * c_sun;
    ++out.days_used;
  }
  if (out.days_used > 0) {
    out.offset_min = 60.0 * offset_sum / weight;
    out.radiation_mean_hour = radiation_sum / weight;
    out.sun_mean_hour = sun_sum / weight;
  }
  return out;
}

std::optional<std::string> weather_timing_warning(const WeatherSeries& series, const WeatherTiming& timing,
                                                  double tolerance_min) {
  if (timing.days_used == 0 || !(std::abs(timing.offset_min) > tolerance_min)) return std::nullopt;
  const bool earlier = timing.offset_min < 0;
  const std::string zone = utc_offset_text(series.location.time_zone_hours);
  char numbers[256];
  std::snprintf(numbers, sizeof numbers,
                "%.0f min %s than the sun (GHI-weighted mean hour %.2f against %.2f for the sun, over %d days)",
                std::abs(timing.offset_min), earlier ? "earlier" : "later", timing.radiation_mean_hour, timing.sun_mean_hour,
                timing.days_used);
  // Radiation earlier than the sun: each value happened later than the time it is placed at —
  // the data's clock is behind the header's zone (data in a zone further west, e.g. UTC), each
  // value is labelled by the start of its hour, or (half an hour) each value is an
  // instantaneous reading at the end of its hour or a mean centred on it. Later: the reverse (a
  // zone further east, daylight saving time, labels one hour late, readings at the start).
  const bool half_hour = std::abs(timing.offset_min) < 45;
  std::string looks;
  if (half_hour)
    looks = earlier ? "about half an hour suggests instantaneous values at the end of each hour, or means centred on "
                      "the hour, stored as hour-ending means (--sun-at end places the sun at each hour's end)"
                    : "about half an hour suggests instantaneous values at the start of each hour stored as "
                      "hour-ending means (--sun-at start places the sun at each hour's start)";
  else
    looks = earlier ? "the data look as if they were in a time zone west of " + zone +
                          " or labelled by the start of each hour instead of its end"
                    : "the data look as if they were in a time zone east of " + zone +
                          " (e.g. daylight saving time) or labelled one hour late";
  return series.file.string() + ": radiation is " + numbers + ": the file's time zone (" + zone +
         ") or its hour convention (hour-ending vs hour-beginning) may not match its data; " + looks +
         ". Sun positions are computed at the middle of each hour-ending interval in " + zone + ".";
}

}  // namespace skyband
