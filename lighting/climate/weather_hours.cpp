#include "lighting/climate/weather_hours.h"

#include <cmath>
#include <string>

#include "geometry/core/input_error.h"
#include "lighting/sky/perez_efficacy.h"
#include "lighting/sky/perez_sky.h"
#include "lighting/sun/sun_position.h"

namespace skyband {

namespace {

int day_of_year(int year, int month, int day) {
  int d = day;
  for (int m = 1; m < month; ++m) d += month_length_days(year, m);
  return d;
}

}  // namespace

std::vector<WeatherHour> weather_hours(const WeatherSeries& series, const WeatherHoursOptions& options,
                                       WeatherHoursReport* report) {
  if (options.albedo && !(*options.albedo >= 0 && *options.albedo <= 1))
    throw InputError("--albedo " + std::to_string(*options.albedo) + ": must be in [0, 1]");
  if (!(options.sun_fraction >= 0 && options.sun_fraction <= 1))
    throw InputError("--sun-at " + std::to_string(options.sun_fraction) + ": the sun's place in the interval must be in [0, 1]");
  WeatherHoursReport rep;
  std::vector<WeatherHour> out;
  out.reserve(series.records.size());
  SpaInput spa;
  spa.latitude_deg = series.location.latitude_deg;
  spa.longitude_deg = series.location.longitude_deg;
  spa.elevation_m = series.location.elevation_m;
  for (const WeatherRecord& r : series.records) {
    WeatherHour h;
    h.hours = r.interval_hours;
    // The sun at the chosen fraction of the interval (the middle by default), local standard
    // time of the file's zone; hour 24's end is the next day's 00:00 (24·60 minutes of the day).
    const double at = r.hour - (1.0 - options.sun_fraction) * r.interval_hours;
    const double minutes = std::round(at * 60.0 * 1e6) / 1e6;  // (exact for the usual half hours)
    spa.time = LocalDateTime{r.year, r.month, r.day, int(minutes / 60), 0, 0.0, series.location.time_zone_hours};
    spa.time.minute = int(minutes - 60.0 * spa.time.hour);
    spa.time.second = 60.0 * (minutes - 60.0 * spa.time.hour - spa.time.minute);
    const SpaResult sun = sun_position_spa(spa);
    const double alt = (90.0 - sun.zenith_deg) * kPi / 180.0, az = sun.azimuth_deg * kPi / 180.0;
    h.sun_dir = Vec3(std::sin(az) * std::cos(alt), std::cos(az) * std::cos(alt), std::sin(alt));
    h.day_of_year = day_of_year(r.year, r.month, r.day);
    // Wh/m² over the interval → mean W/m².
    h.ghi_W_m2 = r.ghi_Wh_m2 / r.interval_hours;
    h.dni_W_m2 = r.dni_Wh_m2 / r.interval_hours;
    h.dhi_W_m2 = r.dhi_Wh_m2 / r.interval_hours;
    if (r.global_illuminance_lux && r.direct_illuminance_lux && r.diffuse_illuminance_lux) {
      h.ghi_lx = *r.global_illuminance_lux;
      h.dni_lx = *r.direct_illuminance_lux;
      h.dhi_lx = *r.diffuse_illuminance_lux;
      ++rep.illuminance_from_file;
    } else {
      const double zenith = sun.zenith_deg * kPi / 180.0;
      const PerezSkyCondition c = perez_sky_condition(h.dhi_W_m2, h.dni_W_m2, zenith, h.day_of_year);
      const double w_cm = r.dew_point_C ? precipitable_water_cm(*r.dew_point_C) : kDefaultPrecipitableWater_cm;
      const PerezIlluminance e = perez_illuminance(h.ghi_W_m2, c, w_cm);
      h.ghi_lx = e.global_horizontal_lux;
      h.dni_lx = e.direct_normal_lux;
      h.dhi_lx = e.diffuse_horizontal_lux;
      ++rep.illuminance_modelled;
    }
    if (options.albedo) {
      h.albedo = *options.albedo;
    } else if (r.albedo) {
      h.albedo = *r.albedo;
      ++rep.albedo_from_file;
    } else {
      h.albedo = kDefaultAlbedo;
    }
    out.push_back(h);
  }
  if (report) *report = rep;
  return out;
}

}  // namespace skyband
