#pragma once
// EnergyPlus weather files (EPW) → WeatherSeries (lighting/climate/weather_series.h).
//
// Format: EnergyPlus "Auxiliary Programs", Weather Converter Program, "EnergyPlus Weather File
// (EPW) Data Dictionary" (NREL/EnergyPlus, doc/auxiliary-programs/src/weather-converter-program/
// energyplus-weather-file-epw-data-dictionary.tex). Eight header lines — LOCATION first, DATA
// PERIODS eighth — then one record per hour of 35 comma-separated fields (32 in files of older
// converters, which end after the present weather codes: no albedo or precipitation; a warning;
// empty fields after the 35th, a trailing comma, are dropped with a warning, a value there is an
// InputError: it may mean a field inserted or shifted). Fields used here
// (1-based): 1–4 year, month, day, hour (hour h covers (h−1, h] local standard time); 5 minute;
// 8 dew point; 14–16 global horizontal, direct normal and diffuse horizontal radiation (Wh/m²
// over the hour); 17–19 the matching illuminances (lux); 33 albedo. LOCATION fields, counted
// after the keyword: 1 city, 2 state/province/region, 3 country, 4 source, 5 WMO number,
// 6 latitude (N+), 7 longitude (E+), 8 time zone (hours from UTC, E+), 9 elevation (m); fields
// after the ninth (some writers add a climate zone) are ignored with a warning.
//
// Accepted: LF, CR LF or lone CR line ends, a UTF-8 byte-order mark, empty lines after the last
// record, 8760 or 8784 (leap year) hourly records or any other run of consecutive hours (a
// partial year is reported in the warnings), years that change from record to record (typical
// years combine months of different years), the year wrapping from 12-31 hour 24 to 01-01 hour 1.
//
// Missing and invalid values, per field (the data dictionary counts a value ≥ its \missing code
// as missing):
//   global/direct/diffuse radiation  missing ≥ 9999     → InputError (irradiance is required;
//                                                          no default is sensible)
//                                    < 0 or > 1400 Wh/m² → InputError
//   illuminances                     missing ≥ 999900   → std::nullopt
//                                    < 0 or > 150000 lux → InputError
//   dew point                        missing ≥ 99.9     → std::nullopt
//                                    outside (−70, 70) °C (the dictionary's range) → InputError
//   albedo                           missing ≥ 999      → std::nullopt
//                                    0 (no ground reflects nothing: IWEC and other files write
//                                    0 where it is unknown) → std::nullopt and a warning
//                                    outside [0, 1]     → std::nullopt and a warning
//   latitude ±90°, longitude ±180°, time zone −12..+14 h (the dictionary says ±12; real zones
//   reach UTC+14), elevation [−1000, 9999.9) m; month 1..12, day within the month (February 29
//   allowed), hour 1..24, minute 0..60; records in consecutive hours → InputError otherwise.
// Every InputError is one line naming file:line, the field by number and name, and the value,
// e.g. "chicago.epw:1203: field 15 (direct normal radiation) = '-3': negative; …".
//
// Warnings (returned in WeatherSeries::warnings, each naming the file; only what the file alone
// shows — consistency with the sun's position is checked in lighting/climate/weather_timing.h):
// diffuse above global by more than 5 % in many daylight records, February 29 in a year that is
// not a leap year, records not covering whole calendar years (not starting 01-01 hour 1 or not
// ending 12-31 hour 24), invalid albedo values, no solar radiation at all.
#include <filesystem>

#include "lighting/climate/weather_series.h"

namespace skyband {

// Throws InputError (see above) for a file that cannot be opened or read as EPW.
WeatherSeries read_epw(const std::filesystem::path& file);

}  // namespace skyband
