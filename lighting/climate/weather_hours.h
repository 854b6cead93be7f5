#pragma once
// A weather series (weather_series.h) made ready for lighting: per interval the sun at its middle
// or at a chosen fraction of it (NREL SPA, sun_position.h, in the file's local standard time), the mean irradiances, the
// illuminances (the file's where it has all three, else the Perez 1990 luminous efficacy model,
// perez_efficacy.h, with the precipitable water from the dew point) and the ground albedo (--albedo, else the file's where valid,
// else 0.2).
#include <optional>
#include <vector>

#include "lighting/climate/weather_series.h"
#include "lighting/sky/cumulative_sky.h"

namespace skyband {

inline constexpr double kDefaultAlbedo = 0.2;
// Precipitable water for the efficacy model where the file has no dew point: 2 cm, a typical
// mid-latitude value (the efficacies change by ~1 lm/W per cm).
inline constexpr double kDefaultPrecipitableWater_cm = 2.0;

struct WeatherHoursOptions {
  std::optional<double> albedo;  // overrides the file's albedo for every interval, [0, 1]
  // Where in its interval (h − Δ, h] a record's sun is placed: h − (1 − f)·Δ; 0.5 (the middle)
  // by default, 1 for files whose values are instantaneous at the hour's end, 0 at its start.
  double sun_fraction = 0.5;
};

struct WeatherHoursReport {
  std::size_t illuminance_from_file = 0;  // intervals whose illuminances came from the file
  std::size_t illuminance_modelled = 0;   // … from the Perez 1990 efficacy model
  std::size_t albedo_from_file = 0;       // intervals with the file's albedo
};

// Throws InputError naming the option for an albedo or a sun fraction outside [0, 1], and (via
// the SPA) for dates
// or a site outside its domain.
std::vector<WeatherHour> weather_hours(const WeatherSeries& series, const WeatherHoursOptions& options,
                                       WeatherHoursReport* report = nullptr);

}  // namespace skyband
