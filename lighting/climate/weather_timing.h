#pragma once
// Timing sanity check of a weather series: is its radiation centred on its sun?
//
// A weather file's time stamps are only as good as its header's time zone and its hour
// convention. When either is wrong (data in UTC under a local time zone, hour-beginning values
// written as hour-ending, daylight saving time) every sun position computed for a record is off
// by the same amount, and the direct beam lands on the wrong facades. The file shows it: over a
// day the radiation must rise and fall with the sun.
//
// For each whole day d (records with intervals covering 24 h) the check compares two centroids
// in local standard time, using the mid-interval times t_h = h − interval/2 (weather_series.h):
//   radiation:  c_rad(d) = Σ_h GHI_h·t_h / Σ_h GHI_h
//   sun:        c_sun(d) = Σ_h max(cos z(t_h), 0)·t_h / Σ_h max(cos z(t_h), 0)
// with z the topocentric zenith from the NREL SPA (lighting/sun/sun_position.h) at t_h in the file's
// time zone. Clouds scale the radiation of a whole hour but cannot move its centre by much on
// average, so over many days the difference measures the clock error. Days with too little
// radiation (daily GHI below min_daily_ghi_Wh_m2: dark winter days, polar night) or no sun are
// skipped; the others are averaged weighting each day by its GHI:
//   offset = Σ_d GHI(d)·(c_rad(d) − c_sun(d)) / Σ_d GHI(d)     (in minutes)
// Negative: the radiation comes earlier than the sun.
//
// A correct hour-ending file gives |offset| of a few minutes (the remaining asymmetry of cloud
// cover between mornings and afternoons); labels one hour late or early give ≈ +60 or −60 min,
// and instantaneous values at the end of each hour read as hourly means ≈ −30 min.
#include <optional>
#include <string>

#include "lighting/climate/weather_series.h"

namespace skyband {

struct WeatherTimingOptions {
  // Days with less global radiation are skipped: their centroid is dominated by a few cloudy
  // hours. 500 Wh/m²·day is an overcast winter day at mid-latitudes.
  double min_daily_ghi_Wh_m2 = 500;
};

struct WeatherTiming {
  double offset_min = 0;           // radiation − sun (minutes), GHI-weighted mean over the days used
  double radiation_mean_hour = 0;  // Σ_d GHI(d)·c_rad(d) / Σ_d GHI(d) = the GHI-weighted mean hour
  double sun_mean_hour = 0;        // Σ_d GHI(d)·c_sun(d) / Σ_d GHI(d)
  int days_used = 0;               // days that passed the filters
  int days_total = 0;              // whole days in the series
};

// Throws InputError if a record's date is outside the SPA's domain (years −2000…6000). A series
// without a usable day gives days_used = 0 and offset 0.
WeatherTiming weather_timing(const WeatherSeries& series, const WeatherTimingOptions& options = {});

// One line naming the file when |offset| > tolerance_min and at least one day was used, e.g.
// "f.epw: radiation is 58 min earlier than the sun (…): the file's time zone (UTC+1) or its hour
// convention (hour-ending vs hour-beginning) may not match its data; <likely cause for that
// direction and size: zone or hour labels near an hour, instantaneous readings near half an
// hour>. Sun positions are computed at the middle of each hour-ending interval in UTC+1.";
// std::nullopt otherwise.
std::optional<std::string> weather_timing_warning(const WeatherSeries& series, const WeatherTiming& timing,
                                                  double tolerance_min = 20);

}  // namespace skyband
