#define BOOST_TEST_MODULE sun_position
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "geometry/core/input_error.h"
#include "lighting/sun/sun_position.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {
// The worked example of Reda & Andreas, "Solar position algorithm for solar radiation
// applications", NREL/TP-560-34302 (rev. 2008), Appendix A.5 (Table A5.1 inputs, A5.2 outputs):
// 2003-10-17 12:30:30 local, tz −7 h, lat 39.742476°, lon −105.1786°, elevation 1830.14 m,
// pressure 820 mbar, temperature 11 °C, ΔT 67 s, atmospheric refraction 0.5667°.
SpaInput worked_example() {
  SpaInput in;
  in.latitude_deg = 39.742476;
  in.longitude_deg = -105.1786;
  in.elevation_m = 1830.14;
  in.time = LocalDateTime{2003, 10, 17, 12, 30, 30.0, -7.0};
  in.delta_t_s = 67.0;
  in.pressure_mbar = 820.0;
  in.temperature_C = 11.0;
  in.atmos_refraction_deg = 0.5667;
  return in;
}

bool mentions(const InputError& e, const std::string& a, const std::string& b) {
  const std::string m = e.what();
  return m.find(a) != std::string::npos && m.find(b) != std::string::npos;
}
}  // namespace

BOOST_AUTO_TEST_CASE(nrel_worked_example_zenith_azimuth) {
  const SpaResult r = sun_position_spa(worked_example());
  // Published to 5 decimals: half a unit of the last digit (5e-6°) plus double rounding → 1e-5°.
  BOOST_TEST(std::abs(r.zenith_deg - 50.11162) < 1e-5, "zenith " << r.zenith_deg);
  BOOST_TEST(std::abs(r.azimuth_deg - 194.34024) < 1e-5, "azimuth " << r.azimuth_deg);
}

BOOST_AUTO_TEST_CASE(nrel_worked_example_surface_incidence) {
  // Same example, surface slope 30°, azimuth rotation −10° (from south): incidence 25.18700°
  // (Table A5.2, 5 decimals → 1e-5).
  const SpaResult r = sun_position_spa(worked_example());
  BOOST_TEST(std::abs(surface_incidence_deg(r, 30.0, -10.0) - 25.18700) < 1e-5, surface_incidence_deg(r, 30.0, -10.0));
}

BOOST_AUTO_TEST_CASE(nrel_worked_example_intermediates) {
  // Intermediate values of Table A5.2; each tolerance is half a unit of the printed last digit
  // (plus a little for double rounding).
  const SpaResult r = sun_position_spa(worked_example());
  BOOST_TEST(std::abs(r.julian_day - 2452930.312847) < 1e-6);
  BOOST_TEST(std::abs(r.heliocentric_longitude_deg - 24.0182616917) < 1e-9);
  BOOST_TEST(std::abs(r.heliocentric_latitude_deg - (-0.0001011219)) < 1e-9);
  BOOST_TEST(std::abs(r.earth_radius_au - 0.9965422974) < 1e-9);
  BOOST_TEST(std::abs(r.nutation_longitude_deg - (-0.00399840)) < 1e-8);
  BOOST_TEST(std::abs(r.nutation_obliquity_deg - 0.00166657) < 1e-8);
  BOOST_TEST(std::abs(r.true_obliquity_deg - 23.440465) < 1e-6);
  BOOST_TEST(std::abs(r.apparent_longitude_deg - 204.0085519281) < 1e-9);
  BOOST_TEST(std::abs(r.right_ascension_deg - 202.22741) < 1e-5);
  BOOST_TEST(std::abs(r.declination_deg - (-9.31434)) < 1e-5);
  BOOST_TEST(std::abs(r.topocentric_right_ascension_deg - 202.22704) < 1e-5);
  BOOST_TEST(std::abs(r.topocentric_declination_deg - (-9.316179)) < 1e-6);
}

BOOST_AUTO_TEST_CASE(julian_day_of_j2000) {
  // J2000.0 = 2000-01-01 12:00 TT ≈ UT here: JD 2451545.0 by definition (Meeus ch. 7); a
  // proleptic Julian-calendar date 1000-01-01 00:00 UT is JD 2086302.5 (Meeus, Table 7.a era).
  BOOST_TEST(julian_day(LocalDateTime{2000, 1, 1, 12, 0, 0.0, 0.0}) == 2451545.0, tt::tolerance(1e-15));
  BOOST_TEST(julian_day(LocalDateTime{2000, 1, 1, 14, 0, 0.0, 2.0}) == 2451545.0, tt::tolerance(1e-15));
  // Meeus example 7.a: 1957-10-04.81 UT → JD 2436116.31.
  BOOST_TEST(std::abs(julian_day(LocalDateTime{1957, 10, 4, 19, 26, 24.0, 0.0}) - 2436116.31) < 1e-6);
}

BOOST_AUTO_TEST_CASE(equinox_noon_sun_on_equator_is_high) {
  // Independent geometric check: at the March 2026 equinox (2026-03-20 14:46 UT, USNO) the
  // declination is ~0, so at the equator at local apparent noon the zenith angle is ≈ 0. Apparent
  // noon is 12:00 − lon/15 h − EoT in UT, with the equation of time EoT ≈ −7.5 min on 20 March
  // (Meeus ch. 28); transit at 14:46 UT thus happens at lon ≈ −39.6°. The zenith must be below
  // 0.5° (1 min of time is 0.25° of hour angle; δ changes 0.4°/day; refraction ~0 at the zenith).
  SpaInput in;
  in.latitude_deg = 0;
  in.longitude_deg = -39.6;
  in.time = LocalDateTime{2026, 3, 20, 14, 46, 0.0, 0.0};
  const SpaResult r = sun_position_spa(in);
  BOOST_TEST(r.zenith_deg < 0.5, "zenith " << r.zenith_deg);
  BOOST_TEST(std::abs(r.declination_deg) < 0.02);
}

BOOST_AUTO_TEST_CASE(direction_convention) {
  // x east, y north, z up; azimuth clockwise from north.
  const Vec3 east = direction_from_altitude_azimuth_deg(0, 90);
  BOOST_TEST(east.x() == 1.0, tt::tolerance(1e-15));
  BOOST_TEST(std::abs(east.y()) < 1e-15);
  const Vec3 north30 = direction_from_altitude_azimuth_deg(30, 0);
  BOOST_TEST(north30.y() == std::cos(kPi / 6), tt::tolerance(1e-15));
  BOOST_TEST(north30.z() == 0.5, tt::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(iso8601_forms) {
  const LocalDateTime a = parse_iso8601("2026-06-21T12:00:00+02:00", "--time");
  BOOST_TEST(a.year == 2026);
  BOOST_TEST(a.month == 6);
  BOOST_TEST(a.day == 21);
  BOOST_TEST(a.hour == 12);
  BOOST_TEST(a.utc_offset_hours == 2.0);
  const LocalDateTime z = parse_iso8601("2026-06-21T10:00Z", "--time");
  BOOST_TEST(z.utc_offset_hours == 0.0);
  BOOST_TEST(julian_day(a) == julian_day(z), tt::tolerance(1e-15));
  const LocalDateTime n = parse_iso8601("2003-10-17T12:30:30.5-0700", "--time");
  BOOST_TEST(n.utc_offset_hours == -7.0);
  BOOST_TEST(n.second == 30.5, tt::tolerance(1e-15));
  const LocalDateTime tz = parse_iso8601("2003-10-17 12:30:30", "--time", -7.0);
  BOOST_TEST(tz.utc_offset_hours == -7.0);
  const LocalDateTime half = parse_iso8601("2026-01-01T00:00+05:30", "--time");
  BOOST_TEST(half.utc_offset_hours == 5.5, tt::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(iso8601_errors_name_flag_and_value) {
  for (const char* bad : {"noon", "2026-13-01T00:00Z", "2026-02-30T00:00Z", "2026-06-21T25:00Z", "2026-06-21T12:00:00+02:00junk",
                          "2026-06-21", "2026-06-21T12:00", "2026-06-21T12:60Z", ""}) {
    try {
      parse_iso8601(bad, "--time");
      BOOST_ERROR("accepted '" << bad << "'");
    } catch (const InputError& e) {
      BOOST_TEST(mentions(e, "--time", std::string("'") + bad + "'"), e.what());
    }
  }
  // Conflicting offsets.
  BOOST_CHECK_THROW(parse_iso8601("2026-06-21T12:00+02:00", "--time", 1.0), InputError);
  // Leap day accepted only in a leap year.
  BOOST_CHECK_NO_THROW(parse_iso8601("2024-02-29T00:00Z", "--time"));
  BOOST_CHECK_THROW(parse_iso8601("2100-02-29T00:00Z", "--time"), InputError);
}

BOOST_AUTO_TEST_CASE(spa_rejects_out_of_domain_inputs) {
  SpaInput in = worked_example();
  in.latitude_deg = 91;
  BOOST_CHECK_THROW(sun_position_spa(in), InputError);
  in = worked_example();
  in.longitude_deg = std::nan("");
  BOOST_CHECK_THROW(sun_position_spa(in), InputError);
  in = worked_example();
  in.time.year = 7000;
  BOOST_CHECK_THROW(sun_position_spa(in), InputError);
  in = worked_example();
  in.pressure_mbar = -1;
  BOOST_CHECK_THROW(sun_position_spa(in), InputError);
}
