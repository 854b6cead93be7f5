#define BOOST_TEST_MODULE weather_timing
#include <boost/test/unit_test.hpp>

#include <unistd.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "geometry/core/vec3.h"
#include "io/epw_reader.h"
#include "lighting/climate/weather_series.h"
#include "lighting/climate/weather_timing.h"
#include "lighting/support/spencer_sun.h"
#include "shared_data.h"

using namespace skyband;
namespace fs = std::filesystem;
namespace tt = boost::test_tools;
using skyband::test::spencer_cos_zenith;

namespace {

const fs::path kWeather = fs::path(SKYBAND_SHARED_DATA) / "weather";
const fs::path kChicago = kWeather / "USA_IL_Chicago-OHare.725300_TMY3.epw";
const fs::path kHeino = kWeather / "NLD_OV_Heino.062780_TMYx.2007-2021.epw";
const fs::path kCloncurry = kWeather / "AUS_QLD_Cloncurry.AP.943350_TMYx.epw";

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("skyband_weather_timing_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

struct Site {
  const char* name;
  double latitude_deg, longitude_deg, time_zone_h;
};

// A whole common year (2019) of clear-sky hourly records whose global radiation at label h on
// day n is ghi_Wh_m2(n, h), written as an EPW file (other fields as in a real TMYx record).
fs::path write_synthetic_epw(const TempDir& d, const std::string& name, const Site& site,
                             const std::function<double(int n, int h)>& ghi_Wh_m2) {
  const fs::path p = d.path / name;
  std::ofstream out(p, std::ios::binary);
  char line[512];
  std::snprintf(line, sizeof line, "LOCATION,%s,,XYZ,synthetic,0,%.4f,%.4f,%.2f,0\n", site.name, site.latitude_deg,
                site.longitude_deg, site.time_zone_h);
  out << line << "DESIGN CONDITIONS,0\nTYPICAL/EXTREME PERIODS,0\nGROUND TEMPERATURES,0\n"
      << "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\nCOMMENTS 1,clear-sky synthetic\nCOMMENTS 2,\n"
      << "DATA PERIODS,1,1,Data,Tuesday, 1/ 1,12/31\n";
  int n = 0;
  for (int month = 1; month <= 12; ++month)
    for (int day = 1; day <= month_length_days(2019, month); ++day) {
      ++n;
      for (int h = 1; h <= 24; ++h) {
        const double g = ghi_Wh_m2(n, h);
        std::snprintf(line, sizeof line,
                      "2019,%d,%d,%d,0,?9?9?9?9E0?9?9?9?9*9?9?9?9?9?9?9*9?9*9*9?9*9,20.0,10.0,50,101325,0,0,300,"
                      "%.3f,0,%.3f,0,0,0,0,180,2.0,0,0,777.7,77777,9,999999999,11,0.0850,0,88,0.200,0.0,0.0\n",
                      month, day, h, g, g);
        out << line;
      }
    }
  return p;
}

// Hour-ending radiation: the mean of 1000·max(cos z, 0) W/m² over the interval (t0, t0 + 1],
// by the midpoint rule on 60 one-minute steps.
double hourly_clear_sky_Wh_m2(const Site& s, int n, double t0_h) {
  double sum = 0;
  for (int k = 0; k < 60; ++k)
    sum += std::max(spencer_cos_zenith(s.latitude_deg, s.longitude_deg, s.time_zone_h, n, t0_h + (k + 0.5) / 60), 0.0);
  return 1000 * sum / 60;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Synthetic clear skies: radiation built from an independent sun model with known timing.

BOOST_AUTO_TEST_CASE(radiation_built_from_the_sun_is_centred_and_shifts_are_measured) {
  TempDir d;
  // Arizona-like (longitude 7° west of its zone meridian: solar noon ≈ 12:28 + equation of time)
  // and Sydney (southern hemisphere, east of its zone meridian).
  const Site sites[] = {{"Westland", 40.0, -112.0, -7.0}, {"Sydney", -33.87, 151.21, 10.0}};
  for (const Site& site : sites) {
    BOOST_TEST_CONTEXT(site.name) {
      // Each label h holds the energy of (h−1, h]: the EPW convention. Expected offset 0; the
      // 2-minute bound covers Spencer's equation-of-time error (≤ 35 s), refraction (absent here,
      // present in the SPA; symmetric about noon) and the partial hours at sunrise and sunset,
      // where an hour's mean and its mid-hour sample differ.
      const fs::path ok =
          write_synthetic_epw(d, "ok.epw", site, [&](int n, int h) { return hourly_clear_sky_Wh_m2(site, n, h - 1); });
      const WeatherSeries s = read_epw(ok);
      const WeatherTiming t = weather_timing(s);
      BOOST_TEST_MESSAGE(site.name << ": correct labels: offset " << t.offset_min << " min over " << t.days_used << " days");
      BOOST_TEST(std::abs(t.offset_min) < 2.0);
      BOOST_TEST(t.days_used == 365);  // every clear day has ≥ 2000 Wh/m² at these latitudes
      BOOST_TEST(t.days_total == 365);
      BOOST_TEST(!weather_timing_warning(s, t).has_value());

      // Labels one hour late (label h holds (h−2, h−1]): the radiation comes 60 min later than
      // the sun says. One hour early (label h holds (h, h+1]): 60 min earlier. Same 2-min bound.
      const WeatherSeries late = read_epw(
          write_synthetic_epw(d, "late.epw", site, [&](int n, int h) { return hourly_clear_sky_Wh_m2(site, n, h - 2); }));
      const WeatherTiming tl = weather_timing(late);
      BOOST_TEST_MESSAGE(site.name << ": labels 1 h late: offset " << tl.offset_min << " min");
      BOOST_TEST(tl.offset_min == 60.0, tt::tolerance(2.0 / 60.0));
      const auto wl = weather_timing_warning(late, tl);
      BOOST_REQUIRE(wl.has_value());
      BOOST_TEST(contains(*wl, "60 min later than the sun"), *wl);

      const WeatherSeries early =
          read_epw(write_synthetic_epw(d, "early.epw", site, [&](int n, int h) { return hourly_clear_sky_Wh_m2(site, n, h); }));
      const WeatherTiming te = weather_timing(early);
      BOOST_TEST_MESSAGE(site.name << ": labels 1 h early: offset " << te.offset_min << " min");
      BOOST_TEST(te.offset_min == -60.0, tt::tolerance(2.0 / 60.0));

      // Instantaneous values at the end of each hour (label h holds 1000·cos z(h)) read as hourly
      // means: each value belongs 30 min later than the mid-interval time it is placed at, so the
      // radiation appears 30 min early.
      const WeatherSeries instant = read_epw(write_synthetic_epw(d, "instant.epw", site, [&](int n, int h) {
        return 1000 * std::max(spencer_cos_zenith(site.latitude_deg, site.longitude_deg, site.time_zone_h, n, h), 0.0);
      }));
      const WeatherTiming ti = weather_timing(instant);
      BOOST_TEST_MESSAGE(site.name << ": instantaneous end-of-hour values: offset " << ti.offset_min << " min");
      BOOST_TEST(ti.offset_min == -30.0, tt::tolerance(2.0 / 30.0));
    }
  }
}

BOOST_AUTO_TEST_CASE(polar_night_and_partial_days_are_skipped) {
  TempDir d;
  // 80° N in a common year: no sun from late October to mid February; the radiation is built
  // from the sun, so those days have none and are skipped, the rest are centred.
  const Site arctic{"Arctic", 80.0, 15.0, 1.0};
  const fs::path p =
      write_synthetic_epw(d, "arctic.epw", arctic, [&](int n, int h) { return hourly_clear_sky_Wh_m2(arctic, n, h - 1); });
  const WeatherSeries s = read_epw(p);
  const WeatherTiming t = weather_timing(s);
  BOOST_TEST(t.days_total == 365);
  BOOST_TEST(t.days_used < 300);  // ≈ 110 days of polar night, by the declination
  BOOST_TEST(t.days_used > 200);
  BOOST_TEST(std::abs(t.offset_min) < 2.0);  // the same bound as the mid-latitude case

  // Only the dark days: nothing to measure, no warning.
  const WeatherSeries night = select_period(s, {12, 1}, {12, 31});
  const WeatherTiming tn = weather_timing(night);
  BOOST_TEST(tn.days_used == 0);
  BOOST_TEST(!weather_timing_warning(night, tn).has_value());

  // A day cut to 12 records is not a whole day and is not used.
  WeatherSeries half = select_period(s, {6, 1}, {6, 1});
  half.records.resize(12);
  BOOST_TEST(weather_timing(half).days_total == 0);
}

// ---------------------------------------------------------------------------------------------
// The shared real files. The README of shared/data/weather gives, measured on these files with
// the sun at the middle of each hour-ending interval: Chicago GHI-weighted mean hour 11.84 vs
// cos z-weighted 11.87 (centred); Heino 11.63 vs 12.59 (≈58 min early); Cloncurry 12.10 vs 12.63
// (≈32 min early).

BOOST_AUTO_TEST_CASE(shared_files_are_classified_as_the_readme_says, *skyband::test::needs_shared_data()) {
  struct Expected {
    fs::path file;
    double radiation_mean_hour, sun_mean_hour;  // README
    bool warned;
    const char* zone;
  };
  const Expected files[] = {
      {kChicago, 11.84, 11.87, false, "UTC-6"},
      {kHeino, 11.63, 12.59, true, "UTC+1"},
      {kCloncurry, 12.10, 12.63, true, "UTC+10"},
  };
  for (const auto& f : files) {
    BOOST_TEST_CONTEXT(f.file.filename().string()) {
      const WeatherSeries s = read_epw(f.file);
      const auto start = std::chrono::steady_clock::now();
      const WeatherTiming t = weather_timing(s);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      BOOST_TEST_MESSAGE(f.file.filename().string()
                         << ": offset " << t.offset_min << " min (radiation " << t.radiation_mean_hour << " h, sun "
                         << t.sun_mean_hour << " h, " << t.days_used << " of " << t.days_total << " days), " << ms << " ms");
      // The README's offset is the difference of its mean hours: −1.8, −57.6 and −31.8 min.
      // Measured here: Chicago −1.8 min (365 days), Heino −58.5 (325 days), Cloncurry −31.0 (365
      // days). ±5 min: the README's definition (annual means) differs slightly from the per-day
      // one here, and 5 min still separates a centred file (< 20 min) from a half-hour and a
      // full-hour error.
      const double readme_offset_min = 60 * (f.radiation_mean_hour - f.sun_mean_hour);
      BOOST_TEST(std::abs(t.offset_min - readme_offset_min) <= 5.0, t.offset_min << " vs " << readme_offset_min);
      const auto w = weather_timing_warning(s, t);
      BOOST_TEST(w.has_value() == f.warned);
      if (w) {
        BOOST_TEST(contains(*w, s.file.string() + ": radiation is "), *w);
        BOOST_TEST(contains(*w, "min earlier than the sun"), *w);
        BOOST_TEST(contains(*w, std::string("time zone (") + f.zone + ")"), *w);
        BOOST_TEST(contains(*w, "hour-ending vs hour-beginning"), *w);
        BOOST_TEST(w->find('\n') == std::string::npos);
      }
      // The whole year must take well under a second (measured ≈ 40 ms; 1 s leaves room for a
      // loaded machine).
      BOOST_TEST(ms < 1000.0);

      // With every day that has radiation (no daily threshold), the radiation's mean hour is the
      // README's GHI-weighted mean hour of the whole year, to its two decimals (±0.005 h).
      const WeatherTiming all = weather_timing(s, WeatherTimingOptions{0});
      BOOST_TEST(all.radiation_mean_hour == f.radiation_mean_hour, tt::tolerance(0.005 / f.radiation_mean_hour));
      // The sun's mean hour here weights each day's centroid by its GHI; the README weights all
      // hours by cos z. The equation of time moves the daily centroid by ±16 min over the year,
      // so the different seasonal weights may move the mean by a fraction of a minute: ±0.02 h.
      BOOST_TEST(all.sun_mean_hour == f.sun_mean_hour, tt::tolerance(0.02 / f.sun_mean_hour));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The warning text.

BOOST_AUTO_TEST_CASE(warning_says_how_much_in_which_direction_and_why) {
  WeatherSeries s;
  s.file = "site.epw";
  s.location.time_zone_hours = 5.5;
  WeatherTiming t;
  t.days_used = 200;
  t.radiation_mean_hour = 12.75;
  t.sun_mean_hour = 12.25;

  t.offset_min = 19.9;  // inside the default 20-min tolerance
  BOOST_TEST(!weather_timing_warning(s, t).has_value());
  t.offset_min = -19.9;
  BOOST_TEST(!weather_timing_warning(s, t).has_value());
  BOOST_TEST(weather_timing_warning(s, t, 10.0).has_value());  // a tighter tolerance

  t.offset_min = 30.0;
  const auto later = weather_timing_warning(s, t);
  BOOST_REQUIRE(later.has_value());
  BOOST_TEST(contains(*later, "site.epw: radiation is 30 min later than the sun"), *later);
  BOOST_TEST(contains(*later, "12.75 against 12.25"), *later);
  BOOST_TEST(contains(*later, "over 200 days"), *later);
  BOOST_TEST(contains(*later, "time zone (UTC+5.5)"), *later);
  BOOST_TEST(contains(*later, "instantaneous values at the start of each hour"), *later);
  BOOST_TEST(contains(*later, "middle of each hour-ending interval"), *later);

  t.offset_min = -58.0;
  const auto earlier = weather_timing_warning(s, t);
  BOOST_REQUIRE(earlier.has_value());
  BOOST_TEST(contains(*earlier, "58 min earlier than the sun"), *earlier);
  BOOST_TEST(contains(*earlier, "west of UTC+5.5"), *earlier);
  BOOST_TEST(contains(*earlier, "start of each hour instead of its end"), *earlier);

  // Near half an hour the likely cause is instantaneous readings, not the zone.
  t.offset_min = -31.0;
  const auto half = weather_timing_warning(s, t);
  BOOST_REQUIRE(half.has_value());
  BOOST_TEST(contains(*half, "31 min earlier than the sun"), *half);
  BOOST_TEST(contains(*half, "instantaneous values at the end of each hour"), *half);
  BOOST_TEST(contains(*half, "hour-ending vs hour-beginning"), *half);

  t.offset_min = 62.0;
  const auto hour_late = weather_timing_warning(s, t);
  BOOST_REQUIRE(hour_late.has_value());
  BOOST_TEST(contains(*hour_late, "62 min later than the sun"), *hour_late);
  BOOST_TEST(contains(*hour_late, "east of UTC+5.5 (e.g. daylight saving time)"), *hour_late);

  t.days_used = 0;  // nothing measured: nothing to say
  BOOST_TEST(!weather_timing_warning(s, t).has_value());
}
