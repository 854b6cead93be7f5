#define BOOST_TEST_MODULE moment_series
#include <boost/test/unit_test.hpp>

// Generated moments (lighting/climate/moment_series.h): counts and weights from the calendar, daylight
// saving changes from the IANA tz database (EU rule: last Sunday of March 01:00 UTC, last Sunday
// of October 01:00 UTC; Directive 2000/84/EC), fixed offsets, and every bad input named.

#include <cmath>
#include <numeric>
#include <string>

#include "geometry/core/input_error.h"
#include "lighting/climate/moment_series.h"

using namespace skyband;

namespace {

MomentSeriesSpec day(const std::string& first, const std::string& last, double step, const std::string& zone) {
  MomentSeriesSpec s;
  s.first_date = first;
  s.last_date = last;
  s.step_minutes = step;
  s.zone = zone;
  return s;
}

double total_hours(const std::vector<TimedMoment>& m) {
  return std::accumulate(m.begin(), m.end(), 0.0, [](double a, const TimedMoment& t) { return a + t.hours; });
}

void throws_naming(const MomentSeriesSpec& s, const std::string& part) {
  try {
    moment_series(s);
    BOOST_ERROR("no error for " << part);
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find(part) != std::string::npos, e.what());
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(one_day_in_steps_at_their_middles) {
  const auto m = moment_series(day("2026-06-21", "2026-06-21", 10, "Europe/Amsterdam"));
  BOOST_TEST(m.size() == 144u);  // 24 h / 10 min
  BOOST_TEST(total_hours(m) == 24.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(m.front().time.hour == 0);
  BOOST_TEST(m.front().time.minute == 5);              // the middle of 00:00–00:10
  BOOST_TEST(m.front().time.utc_offset_hours == 2.0);  // CEST
  BOOST_TEST(m.back().time.hour == 23);
  BOOST_TEST(m.back().time.minute == 55);
}

BOOST_AUTO_TEST_CASE(daylight_saving_days_have_23_and_25_hours) {
  // 2026-03-29 and 2026-10-25 are the last Sundays of March and October.
  const auto spring = moment_series(day("2026-03-29", "2026-03-29", 60, "Europe/Amsterdam"));
  BOOST_TEST(spring.size() == 23u);
  BOOST_TEST(total_hours(spring) == 23.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(spring.front().time.utc_offset_hours == 1.0);
  BOOST_TEST(spring.back().time.utc_offset_hours == 2.0);
  BOOST_TEST(spring[1].time.hour == 1);  // 01:30 CET
  BOOST_TEST(spring[2].time.hour == 3);  // 03:30 CEST: 02:00–03:00 does not exist that night
  const auto autumn = moment_series(day("2026-10-25", "2026-10-25", 60, "Europe/Amsterdam"));
  BOOST_TEST(autumn.size() == 25u);
  BOOST_TEST(total_hours(autumn) == 25.0, boost::test_tools::tolerance(1e-12));
  // A week spanning the change: 7·24 − 1 hours.
  const auto week = moment_series(day("2026-03-26", "2026-04-01", 30, "Europe/Amsterdam"));
  BOOST_TEST(total_hours(week) == 7 * 24.0 - 1, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(fixed_offsets_and_a_step_that_does_not_divide_the_day) {
  MomentSeriesSpec s = day("2024-02-28", "2024-03-01", 7, "");
  s.utc_offset_hours = -6;
  const auto m = moment_series(s);
  // 2024 is a leap year: 3 days = 4320 min = 617 steps of 7 min and one of 1 min.
  BOOST_TEST(m.size() == 618u);
  BOOST_TEST(total_hours(m) == 72.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(m.back().hours == 1.0 / 60, boost::test_tools::tolerance(1e-9));
  for (const TimedMoment& t : m) BOOST_TEST(t.time.utc_offset_hours == -6.0);
}

BOOST_AUTO_TEST_CASE(bad_input_is_named) {
  throws_naming(day("2026-02-30", "2026-02-30", 10, "UTC"), "2026-02-30");
  throws_naming(day("2026-3-1x", "2026-3-1x", 10, "UTC"), "YYYY-MM-DD");
  throws_naming(day("2026-03-02", "2026-03-01", 10, "UTC"), "before the first");
  throws_naming(day("2026-03-01", "2026-03-01", 0, "UTC"), "--step");
  throws_naming(day("2026-03-01", "2026-03-01", 1441, "UTC"), "--step");
  throws_naming(day("2026-03-01", "2026-03-01", 10, "Europe/Atlantis"), "Europe/Atlantis");
  throws_naming(day("2026-03-01", "2026-03-01", 10, ""), "--zone");
  MomentSeriesSpec both = day("2026-03-01", "2026-03-01", 10, "UTC");
  both.utc_offset_hours = 1;
  throws_naming(both, "not both");
  throws_naming(day("2000-01-01", "2030-01-01", 1, "UTC"), "at most");
  const auto r = parse_date_range("2026-01-01:2026-01-31", "--date");
  BOOST_TEST(r.first == "2026-01-01");
  BOOST_TEST(r.second == "2026-01-31");
  BOOST_TEST(parse_date_range("2026-05-05", "--date").second == "2026-05-05");
}
