#include "lighting/climate/weather_closure.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "geometry/core/vec3.h"

namespace skyband {
namespace {

constexpr const char* kMonthNames[12] = {"January", "February", "March",     "April",   "May",      "June",
                                         "July",    "August",   "September", "October", "November", "December"};

// How far a ratio is from closure: |ratio − 1| (+∞ for an infinite ratio).
double deviation(double ratio) {
  return std::abs(ratio - 1.0);
}

}  // namespace

WeatherClosure weather_closure(std::span<const WeatherRecord> records, std::span<const double> cos_zenith,
                               const WeatherClosureOptions& options) {
  if (records.size() != cos_zenith.size())
    throw std::invalid_argument("weather_closure: " + std::to_string(records.size()) + " records but " +
                                std::to_string(cos_zenith.size()) + " zenith cosines");
  WeatherClosure out;
  out.max_zenith_deg = options.max_zenith_deg;
  const double min_cos = std::cos(options.max_zenith_deg * (kPi / 180.0));
  for (std::size_t i = 0; i < records.size(); ++i) {
    const WeatherRecord& r = records[i];
    const double c = cos_zenith[i];
    if (!(c > min_cos) || r.month < 1 || r.month > 12) continue;
    MonthClosure& m = out.months[static_cast<std::size_t>(r.month - 1)];
    ++m.hours;
    m.ghi_Wh_m2 += r.ghi_Wh_m2;
    m.components_Wh_m2 += r.dhi_Wh_m2 + r.dni_Wh_m2 * c;
  }
  double worst = -1;
  for (std::size_t k = 0; k < out.months.size(); ++k) {
    MonthClosure& m = out.months[k];
    m.used = m.hours >= options.min_hours && (m.ghi_Wh_m2 > 0 || m.components_Wh_m2 > 0);
    if (!m.used) continue;
    m.ratio = m.components_Wh_m2 > 0 ? m.ghi_Wh_m2 / m.components_Wh_m2 : std::numeric_limits<double>::infinity();
    if (deviation(m.ratio) > worst) {
      worst = deviation(m.ratio);
      out.worst_month = static_cast<int>(k) + 1;
      out.worst_ratio = m.ratio;
    }
  }
  return out;
}

WeatherClosure weather_closure(const WeatherSeries& series, std::span<const WeatherHour> hours,
                               const WeatherClosureOptions& options) {
  std::vector<double> cos_zenith(hours.size());
  for (std::size_t i = 0; i < hours.size(); ++i) cos_zenith[i] = hours[i].sun_dir.z();  // unit vector, z up
  return weather_closure(series.records, cos_zenith, options);
}

std::optional<std::string> weather_closure_warning(const WeatherSeries& series, const WeatherClosure& closure, double tolerance) {
  if (closure.worst_month < 1 || !(deviation(closure.worst_ratio) > tolerance)) return std::nullopt;
  const MonthClosure& m = closure.months[static_cast<std::size_t>(closure.worst_month - 1)];
  char ratio[64];
  if (std::isfinite(closure.worst_ratio))
    std::snprintf(ratio, sizeof ratio, "ratio %.2f", closure.worst_ratio);
  else
    std::snprintf(ratio, sizeof ratio, "DHI and DNI are 0 there");
  char numbers[320];
  std::snprintf(numbers, sizeof numbers,
                "in %s (month %d) GHI sums to %.1f kWh/m2 against %.1f for DHI + DNI*cos(zenith) (%s, over %zu hours "
                "with the sun more than %g degrees up; consistent files stay within %g-%g)",
                kMonthNames[closure.worst_month - 1], closure.worst_month, m.ghi_Wh_m2 / 1000.0, m.components_Wh_m2 / 1000.0,
                ratio, m.hours, 90.0 - closure.max_zenith_deg, 1.0 - tolerance, 1.0 + tolerance);
  // GHI above the components: the direct beam is too weak for this sun (DNI too small, or the sun
  // placed lower than where the data were taken); below: too strong (DNI holding GHI where the
  // sun is high, DHI too large, the sun placed higher). A wrong site moves the sun either way.
  const char* beam = closure.worst_ratio > 1 ? "DNI is too small for this sun" : "DNI or DHI is too large for this sun";
  return series.file.string() + ": global horizontal radiation does not equal diffuse + direct normal*cos(zenith): " + numbers +
         "; " + beam +
         ": a column may hold another quantity (DNI written as GHI, columns swapped) or the header's site (latitude "
         "sign, longitude, time zone) may not be where the data were taken. The direct sun on every face depends on both.";
}

}  // namespace skyband
