#define BOOST_TEST_MODULE weather_closure
#include <boost/test/unit_test.hpp>

// The closure check GHI = DHI + DNI·cos z (lighting/climate/weather_closure.h) on synthetic years
// whose radiation is built from a closed form around a known sun, so that the expected ratios
// are known: exactly 1 for consistent data, far from 1 for DNI replaced by GHI and for a site
// whose latitude has the wrong sign.

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/core/vec3.h"
#include "lighting/climate/weather_closure.h"
#include "lighting/climate/weather_hours.h"
#include "lighting/climate/weather_series.h"
#include "lighting/support/spencer_sun.h"

using namespace skyband;
namespace tt = boost::test_tools;
using skyband::test::spencer_cos_zenith;

namespace {

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

struct Site {
  double latitude_deg, longitude_deg, time_zone_h;
};

// A site west of its zone meridian, as most of a time zone is (Denver-like).
constexpr Site kSite{40.0, -105.0, -7.0};
const double kCos85 = std::cos(85.0 * kPi / 180.0);

// A common year (2019) of hour-ending records at `site` whose radiation follows the Spencer sun
// (tests/lighting/support/spencer_sun.h) at the middle of each hour, c = cos z there:
//   DNI = 900·(1 − e^(−3c)),  DHI = 40 + 120·c,  GHI = DHI + DNI·c     (c > 0; all 0 otherwise)
// so that the records close exactly for that sun. `cos_zenith` receives each record's c.
WeatherSeries closed_year(const Site& site, std::vector<double>& cos_zenith) {
  WeatherSeries s;
  s.file = "synthetic.epw";
  s.location.latitude_deg = site.latitude_deg;
  s.location.longitude_deg = site.longitude_deg;
  s.location.time_zone_hours = site.time_zone_h;
  cos_zenith.clear();
  int n = 0;
  for (int month = 1; month <= 12; ++month)
    for (int day = 1; day <= month_length_days(2019, month); ++day) {
      ++n;
      for (int hour = 1; hour <= 24; ++hour) {
        WeatherRecord r;
        r.year = 2019, r.month = month, r.day = day, r.hour = hour;
        const double c = spencer_cos_zenith(site.latitude_deg, site.longitude_deg, site.time_zone_h, n, r.mid_hour());
        if (c > 0) {
          r.dni_Wh_m2 = 900 * (1 - std::exp(-3 * c));
          r.dhi_Wh_m2 = 40 + 120 * c;
          r.ghi_Wh_m2 = r.dhi_Wh_m2 + r.dni_Wh_m2 * c;
        }
        s.records.push_back(r);
        cos_zenith.push_back(c);
      }
    }
  return s;
}

// Σ GHI / Σ (DHI + DNI·c) over the records of `month` with c > cos 85°: the definition of the
// header, summed here directly as an independent check of the month bookkeeping.
double month_ratio(const WeatherSeries& s, const std::vector<double>& c, int month) {
  double ghi = 0, components = 0;
  for (std::size_t i = 0; i < s.records.size(); ++i)
    if (s.records[i].month == month && c[i] > kCos85) {
      ghi += s.records[i].ghi_Wh_m2;
      components += s.records[i].dhi_Wh_m2 + s.records[i].dni_Wh_m2 * c[i];
    }
  return ghi / components;
}

}  // namespace

BOOST_AUTO_TEST_CASE(consistent_radiation_closes_in_every_month) {
  std::vector<double> c;
  const WeatherSeries s = closed_year(kSite, c);
  const WeatherClosure w = weather_closure(s.records, c);
  for (int m = 1; m <= 12; ++m) {
    const MonthClosure& mc = w.months[std::size_t(m - 1)];
    BOOST_TEST_CONTEXT("month " << m) {
      BOOST_TEST(mc.used);  // at 40° N every month has > 200 hours with the sun above 5°
      BOOST_TEST(mc.hours > 200u);
      // GHI is DHI + DNI·c term by term: the sums differ by rounding alone (~300 terms of ~1e3,
      // 1e-12 relative leaves room for it).
      BOOST_TEST(mc.ratio == 1.0, tt::tolerance(1e-12));
    }
  }
  BOOST_TEST(w.worst_month >= 1);
  BOOST_TEST(!weather_closure_warning(s, w).has_value());
}

BOOST_AUTO_TEST_CASE(dni_holding_ghi_is_warned) {
  std::vector<double> c;
  WeatherSeries s = closed_year(kSite, c);
  for (WeatherRecord& r : s.records) r.dni_Wh_m2 = r.ghi_Wh_m2;
  const WeatherClosure w = weather_closure(s.records, c);
  BOOST_REQUIRE(w.worst_month >= 1);
  // The worst month is the one whose directly summed ratio is furthest from 1, with that ratio.
  // Here DHI + GHI·c exceeds GHI by c·(GHI − DNI), which the low winter sun (DNI well above
  // GHI) makes negative: the ratio rises from ≈1.05 in June to ≈1.5 in December.
  int furthest = 1;
  for (int m = 2; m <= 12; ++m)
    if (std::abs(month_ratio(s, c, m) - 1) > std::abs(month_ratio(s, c, furthest) - 1)) furthest = m;
  BOOST_TEST(w.worst_month == furthest);
  BOOST_TEST(w.worst_ratio == month_ratio(s, c, furthest), tt::tolerance(1e-12));
  BOOST_TEST(w.worst_ratio > 1.1);
  const auto text = weather_closure_warning(s, w);
  BOOST_REQUIRE(text.has_value());
  BOOST_TEST(contains(*text, "synthetic.epw: global horizontal radiation does not equal diffuse + direct normal"), *text);
  BOOST_TEST(text->find('\n') == std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_latitude_of_the_wrong_sign_is_warned) {
  // The data belong to 40° N; the sun is computed for 40° S: summer and winter swap.
  std::vector<double> c, flipped;
  const WeatherSeries s = closed_year(kSite, c);
  (void)closed_year({-kSite.latitude_deg, kSite.longitude_deg, kSite.time_zone_h}, flipped);
  const WeatherClosure w = weather_closure(s.records, flipped);
  BOOST_REQUIRE(w.worst_month >= 1);
  BOOST_TEST(w.worst_ratio == month_ratio(s, flipped, w.worst_month), tt::tolerance(1e-12));
  BOOST_TEST(std::abs(w.worst_ratio - 1) > 0.1);
  BOOST_TEST(weather_closure_warning(s, w).has_value());
}

BOOST_AUTO_TEST_CASE(the_sun_of_weather_hours_is_used) {
  // The same years through weather_hours (the NREL SPA, at each hour's middle). The SPA and
  // Spencer's series differ by ≤ 0.0006 rad in declination, ~35 s in the equation of time and
  // the SPA's refraction (≤ 0.2° above 5° of elevation): ≤ 0.004 in cos z, a few per cent of
  // the lowest hours' direct beam and ~1 % of a winter month's sums (measured: 0.991 in
  // February); 2 % bounds it and is still far inside the 10 % tolerance.
  std::vector<double> c;
  WeatherSeries s = closed_year(kSite, c);
  const WeatherClosure w = weather_closure(s, weather_hours(s, {}));
  BOOST_TEST_MESSAGE("SPA sun, consistent data: worst month " << w.worst_month << " ratio " << w.worst_ratio);
  BOOST_TEST(std::abs(w.worst_ratio - 1) < 0.02);
  BOOST_TEST(!weather_closure_warning(s, w).has_value());

  s.location.latitude_deg = -kSite.latitude_deg;  // the header's sign flipped
  const WeatherClosure f = weather_closure(s, weather_hours(s, {}));
  BOOST_TEST_MESSAGE("SPA sun, latitude flipped: worst month " << f.worst_month << " ratio " << f.worst_ratio);
  BOOST_TEST(std::abs(f.worst_ratio - 1) > 0.1);
  BOOST_TEST(weather_closure_warning(s, f).has_value());
}

BOOST_AUTO_TEST_CASE(low_sun_short_months_and_empty_components) {
  std::vector<double> c;
  WeatherSeries s = closed_year(kSite, c);
  // Inconsistent radiation with the sun below 5° of elevation is left out of the sums.
  for (std::size_t i = 0; i < s.records.size(); ++i)
    if (c[i] > 0 && c[i] <= kCos85) s.records[i].ghi_Wh_m2 += 500;
  const WeatherClosure low = weather_closure(s.records, c);
  for (const MonthClosure& m : low.months) BOOST_TEST(m.ratio == 1.0, tt::tolerance(1e-12));

  // A month with fewer than min_hours (24) hours of sun above 5° is not judged: the first 23 such
  // hours of June with GHI only.
  WeatherSeries short_june;
  std::vector<double> short_c;
  for (std::size_t i = 0; i < s.records.size() && short_c.size() < 23; ++i)
    if (s.records[i].month == 6 && c[i] > kCos85) {
      WeatherRecord r = s.records[i];
      r.dni_Wh_m2 = r.dhi_Wh_m2 = 0;
      short_june.records.push_back(r);
      short_c.push_back(c[i]);
    }
  const WeatherClosure few = weather_closure(short_june.records, short_c);
  BOOST_TEST(few.worst_month == 0);
  BOOST_TEST(!few.months[5].used);
  BOOST_TEST(few.months[5].hours == 23u);
  BOOST_TEST(!weather_closure_warning(short_june, few).has_value());

  // One more such hour: judged, and with DHI and DNI zero the ratio is infinite and warned.
  for (std::size_t i = 0; i < s.records.size(); ++i)
    if (s.records[i].month == 6 && c[i] > kCos85 && s.records[i].day == 30) {
      WeatherRecord r = s.records[i];
      r.dni_Wh_m2 = r.dhi_Wh_m2 = 0;
      short_june.records.push_back(r);
      short_c.push_back(c[i]);
      break;
    }
  const WeatherClosure enough = weather_closure(short_june.records, short_c);
  BOOST_TEST(enough.worst_month == 6);
  BOOST_TEST(std::isinf(enough.worst_ratio));
  const auto text = weather_closure_warning(short_june, enough);
  BOOST_REQUIRE(text.has_value());
  BOOST_TEST(contains(*text, "in June (month 6)"), *text);
  BOOST_TEST(contains(*text, "DHI and DNI are 0 there"), *text);
  BOOST_TEST(contains(*text, "over 24 hours"), *text);

  // A night-only series has nothing to judge.
  WeatherSeries night;
  std::vector<double> night_c;
  for (std::size_t i = 0; i < s.records.size(); ++i)
    if (c[i] <= 0) night.records.push_back(s.records[i]), night_c.push_back(c[i]);
  BOOST_TEST(weather_closure(night.records, night_c).worst_month == 0);

  BOOST_CHECK_THROW(weather_closure(s.records, std::vector<double>(3, 1.0)), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(warning_names_the_month_the_sums_and_the_causes) {
  WeatherSeries s;
  s.file = "site.epw";
  WeatherClosure w;
  w.worst_month = 12;
  MonthClosure& m = w.months[11];
  m.used = true;
  m.hours = 190;
  m.ghi_Wh_m2 = 38100;
  m.components_Wh_m2 = 24700;
  // The tolerance is 0.1 on either side of 1.
  for (const double r : {1.09, 0.91}) {
    w.worst_ratio = r;
    BOOST_TEST(!weather_closure_warning(s, w).has_value(), r);
  }
  w.worst_ratio = 38.1 / 24.7;
  const auto high = weather_closure_warning(s, w);
  BOOST_REQUIRE(high.has_value());
  BOOST_TEST(contains(*high, "site.epw: "), *high);
  BOOST_TEST(contains(*high, "in December (month 12) GHI sums to 38.1 kWh/m2 against 24.7"), *high);
  BOOST_TEST(contains(*high, "ratio 1.54, over 190 hours with the sun more than 5 degrees up"), *high);
  BOOST_TEST(contains(*high, "within 0.9-1.1"), *high);
  BOOST_TEST(contains(*high, "DNI is too small for this sun"), *high);
  BOOST_TEST(contains(*high, "latitude sign"), *high);
  BOOST_TEST(!weather_closure_warning(s, w, 0.6).has_value());  // a wider tolerance

  w.worst_ratio = 0.85;
  const auto low = weather_closure_warning(s, w);
  BOOST_REQUIRE(low.has_value());
  BOOST_TEST(contains(*low, "ratio 0.85"), *low);
  BOOST_TEST(contains(*low, "DNI or DHI is too large for this sun"), *low);

  w.worst_month = 0;  // nothing judged: nothing to say
  BOOST_TEST(!weather_closure_warning(s, w).has_value());
}
