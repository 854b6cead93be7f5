#pragma once
// NREL TMY3 CSV weather files → WeatherSeries (lighting/climate/weather_series.h), and the weather-file
// entry point that picks EPW or TMY3 by content.
//
// Format: Wilcox and Marion, "Users Manual for TMY3 Data Sets", NREL/TP-581-43156 (2008), §3.
// Line 1: site — USAF station number, name, state, time zone (hours from UTC, E+), latitude
// (N+), longitude (E+), elevation (m). Line 2: the column names. Then one record per hour:
// "Date (MM/DD/YYYY)", "Time (HH:MM)" — the end of the 60-minute interval in local standard time,
// 01:00 … 24:00 — and the data. Columns used, found by name (their order is the manual's, but
// files cut down by other tools keep the names): "GHI (W/m^2)", "DNI (W/m^2)", "DHI (W/m^2)"
// (the energy received over the hour ending at the time, Wh/m²: the hourly mean in W/m²),
// "GH illum (lx)", "DN illum (lx)", "DH illum (lx)", "Dew-point (C)", "Alb (unitless)" and its
// flag "Alb source".
// Fields are comma-separated, RFC 4180 style on every line: a field in double quotes may hold
// commas (a site name such as "GREENSBORO, PIEDMONT TRIAD INT") and "" for a quote; spaces around
// a field are trimmed; a quote never closed on its line, or text after a closing quote, is an
// InputError naming the line and the field.
// Missing values are -9900 (the manual's code), and anything ≤ -9900:
//   radiation missing or < 0 or > 1400 Wh/m²  → InputError (no default is sensible)
//   illuminance missing → std::nullopt; < 0 or > 150000 lux → InputError
//   dew point missing → std::nullopt; outside (−70, 70) °C → InputError
//   albedo missing → std::nullopt; source flag '?' (no known source: TMY3 files write 0.00
//   flagged '?' where they have no albedo), 0 (no ground reflects nothing: files write 0 where the
//   albedo is unknown) or outside [0, 1] → std::nullopt, counted in one warning for the file
// Records must be consecutive hours (February 29 allowed, the year may change between records:
// typical years take each month from another year; 12/31 24:00 wraps to 01/01 01:00).
// Every InputError is one line naming file:line, the column and the value.
// Warnings (WeatherSeries::warnings): records not covering whole calendar years, albedos
// treated as missing (one line: how many for each reason, the first line), no solar radiation
// at all.
#include <filesystem>

#include "lighting/climate/weather_series.h"

namespace skyband {

WeatherSeries read_tmy3_csv(const std::filesystem::path& file);

// EPW (io/epw_reader.h) or TMY3 CSV by content: a file whose first line starts with "LOCATION"
// is EPW; one whose second line starts with "Date (MM/DD/YYYY)" is TMY3; anything else is an
// InputError naming both formats.
WeatherSeries read_weather_file(const std::filesystem::path& file);

}  // namespace skyband
