#pragma once
// Closure check of a weather series: do its global, diffuse and direct radiation agree with its
// sun?
//
// Global horizontal radiation is the diffuse horizontal plus the direct beam on the horizontal:
//   GHI = DHI + DNI·cos z                                            (z: the sun's zenith)
// Measured and modelled files close this within a few per cent per month (instrument error,
// the sun taken at one instant of each interval). A file breaks it when a column holds another
// quantity (DNI written as a copy of GHI), columns are swapped, or the site in the header is not
// where the data were taken (a latitude of the wrong sign puts the sun on the wrong side of the
// sky), so every cos z — and with it every direct beam on a facade — is wrong.
//
// Per calendar month m the check sums, over the intervals whose sun is well above the horizon
// (z < max_zenith_deg: near the horizon cos z changes fast within an interval and the direct
// beam of an hour is ill-defined),
//   ratio(m) = Σ GHI / Σ (DHI + DNI·cos z)
// with cos z the one the caller lights the scene with (weather_hours.h: sun_dir.z at each
// interval's chosen instant). Months with fewer than min_hours such intervals, or without any
// radiation in them, are skipped. The worst month is the one whose ratio is furthest from 1.
//
// Measured with the sun at the middle of each hour-ending interval (the default), the worst
// months of real files lie within 3 % of closure: the shared Chicago (TMY3, 1.008), Heino (TMYx,
// 1.021, although its radiation comes 58 min early) and Cloncurry (TMYx, 1.011), and EPW and
// TMY3 files of Harare (IWEC, 0.998), Van Nuys (0.991), Houston (TMY2, 1.004), Denver (TMY,
// 0.981), Belfast (CIBSE, 0.997), Greensboro (TMY3, 0.996) and Honolulu (TMY3, 1.028). With the
// sun at the start or end of each interval instead they stay within 6 % (Honolulu 1.060 at the
// start). Broken files: an Athens IWEC file whose DNI column repeats its GHI 0.852 (May; high and
// low suns partly cancel within a month), Harare with its latitude's sign flipped 0.779 (June).
// The warning's tolerance, 10 %, lies between the two.
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>

#include "lighting/climate/weather_series.h"
#include "lighting/sky/cumulative_sky.h"

namespace skyband {

struct WeatherClosureOptions {
  // Intervals with a zenith at or above this (degrees) are left out.
  double max_zenith_deg = 85;
  // A month needs at least this many intervals with the sun above max_zenith_deg's altitude:
  // fewer (a polar month, a period cut short) give too few hours for a ratio.
  std::size_t min_hours = 24;
};

struct MonthClosure {
  std::size_t hours = 0;        // intervals used
  double ghi_Wh_m2 = 0;         // Σ GHI over them
  double components_Wh_m2 = 0;  // Σ (DHI + DNI·cos z) over them
  bool used = false;            // enough intervals and some radiation
  // Σ GHI / Σ (DHI + DNI·cos z); +∞ when only GHI has radiation, 0 when only the components do.
  double ratio = 1;
};

struct WeatherClosure {
  std::array<MonthClosure, 12> months{};  // index month − 1
  int worst_month = 0;                    // 1..12, 0 when no month is used
  double worst_ratio = 1;                 // months[worst_month − 1].ratio
  double max_zenith_deg = 85;             // the option used (for the message)
};

// `cos_zenith[i]` belongs to `records[i]` (std::invalid_argument if their lengths differ).
WeatherClosure weather_closure(std::span<const WeatherRecord> records, std::span<const double> cos_zenith,
                               const WeatherClosureOptions& options = {});

// The same with the sun of each interval from `hours` (weather_hours(series, …), one per record).
WeatherClosure weather_closure(const WeatherSeries& series, std::span<const WeatherHour> hours,
                               const WeatherClosureOptions& options = {});

// One line naming the file when the worst month's ratio is off 1 by more than `tolerance`
// (0.1: above 1.1 or below 0.9), e.g. "f.epw: global horizontal radiation does not equal diffuse
// + direct normal*cos(zenith): in June (month 6) GHI sums to 133.4 kWh/m2 against 171.3 for
// DHI + DNI*cos(zenith) (ratio 0.78, over 360 hours with the sun more than 5 degrees up; …);
// <the likely causes>"; std::nullopt otherwise.
std::optional<std::string> weather_closure_warning(const WeatherSeries& series, const WeatherClosure& closure,
                                                   double tolerance = 0.1);

}  // namespace skyband
