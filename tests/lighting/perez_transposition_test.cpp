#define BOOST_TEST_MODULE perez_transposition
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "lighting/support/perez_transposition.h"
#include "shared_data.h"

namespace tt = boost::test_tools;
using skyband::test::perez1990_aoi_projection;
using skyband::test::perez1990_sky_diffuse;
using skyband::test::Perez1990Diffuse;

namespace {

// pvlib's plane-of-array test values (shared/data/reference/pvlib_transposition_reference.json,
// transcribed from pvlib-python tests/test_irradiance.py @ 6382338a, BSD-3-Clause).
nlohmann::json reference() {
  const std::filesystem::path p = std::filesystem::path(SKYBAND_SHARED_DATA) / "reference" / "pvlib_transposition_reference.json";
  std::ifstream in(p);
  BOOST_TEST_REQUIRE(in.good(), "cannot open " << p);
  return nlohmann::json::parse(in);
}

double num(const nlohmann::json& v) {
  return v.is_null() ? std::nan("") : v.get<double>();
}

}  // namespace

BOOST_AUTO_TEST_CASE(aoi_projection_cases, *skyband::test::needs_shared_data()) {
  // "aoi_cases_tilt_az_zen_az__aoi_proj": [tilt, surface az, zenith, sun az, aoi°, projection];
  // pvlib prints them to 7 decimals, truncated (−0.4924038 for −0.49240388): one unit of the
  // last printed digit.
  const auto j = reference();
  for (const auto& c : j["aoi_cases_tilt_az_zen_az__aoi_proj"]) {
    const double proj = perez1990_aoi_projection(c[0], c[1], c[2], c[3]);
    BOOST_TEST(std::abs(proj - num(c[5])) <= 1e-7);
    BOOST_TEST(std::abs(std::acos(std::clamp(proj, -1.0, 1.0)) * 180 / M_PI - num(c[4])) <= 1e-7);
  }
}

BOOST_AUTO_TEST_CASE(poa_components_exact, *skyband::test::needs_shared_data()) {
  // test_poa_components_diffuse_components_perez: tilt 40° facing south, apparent zenith and
  // azimuth, relative air mass, full DNI. pvlib compares with assert_frame_equal (rtol 1e-5);
  // the values are printed to 6–8 decimals, so 1e-7 relative (absolute 1e-6 at 0).
  const auto j = reference();
  const auto& in = j["inputs"];
  const auto& ex = j["cases_surface_tilt40_azimuth180"]["poa_components_perez_plus_sand_ground"];
  for (int i = 0; i < 4; ++i) {
    const Perez1990Diffuse d = perez1990_sky_diffuse(40, 180, in["dhi"][i], in["dni"][i], in["dni_extra"][i],
                                                     in["apparent_zenith"][i], in["azimuth"][i], num(in["relative_airmass"][i]));
    const auto close = [](double a, double b) { return std::abs(a - b) <= 1e-7 * std::abs(b) + 1e-6; };
    BOOST_TEST(close(d.sky_diffuse, num(ex["poa_sky_diffuse"][i])), "hour " << i << " sky " << d.sky_diffuse);
    BOOST_TEST(close(d.isotropic, num(ex["perez_isotropic"][i])), "hour " << i << " iso " << d.isotropic);
    BOOST_TEST(close(d.circumsolar, num(ex["perez_circumsolar"][i])), "hour " << i << " cs " << d.circumsolar);
    BOOST_TEST(close(d.horizon, num(ex["perez_horizon"][i])), "hour " << i << " hor " << d.horizon);
  }
  // test_perez_scalar: assert_allclose (rtol 1e-7) to 109.084332.
  const Perez1990Diffuse s =
      perez1990_sky_diffuse(40, 180, 118.45831879, 939.95469881, 1321.1655834833093, 10.56413562, 144.76567754, 1.01688136);
  BOOST_TEST(s.sky_diffuse == 109.084332, tt::tolerance(1e-7));
}

BOOST_AUTO_TEST_CASE(perez_test_with_nan_dni_two_decimals, *skyband::test::needs_shared_data()) {
  // test_perez / test_perez_components: hour 2 has DNI set to NaN in pvlib (skipped here), the
  // others are compared with check_less_precise=2 (two decimals): tolerance 0.005 absolute.
  const auto j = reference();
  const auto& in = j["inputs"];
  const auto& ex = j["cases_surface_tilt40_azimuth180"]["perez_allsitescomposite1990_with_dni_index2_set_to_NaN"];
  for (int i : {0, 1, 3}) {
    const Perez1990Diffuse d = perez1990_sky_diffuse(40, 180, in["dhi"][i], in["dni"][i], in["dni_extra"][i],
                                                     in["apparent_zenith"][i], in["azimuth"][i], num(in["relative_airmass"][i]));
    BOOST_TEST(std::abs(d.sky_diffuse - num(ex["sky_diffuse"][i])) < 0.005);
    BOOST_TEST(std::abs(d.isotropic - num(ex["isotropic"][i])) < 0.005);
    BOOST_TEST(std::abs(d.circumsolar - num(ex["circumsolar"][i])) < 0.005);
    BOOST_TEST(std::abs(d.horizon - num(ex["horizon"][i])) < 0.005);
  }
}

BOOST_AUTO_TEST_CASE(negative_horizon_case, *skyband::test::needs_shared_data()) {
  // test_perez_negative_horizon (Goodwin Creek, tilt 34° south): the horizon term is negative in
  // four of five hours and kept signed, so the sky diffuse falls below the isotropic part. pvlib
  // compares to 2 decimals. The totals are printed to 6 decimals and agree here to < 1e-6; the
  // printed components do not add up to the printed totals by up to 2.5e-5 (hour 3), so they are
  // checked to 5e-5 absolute.
  const auto j = reference();
  const auto& n = j["perez_negative_horizon_case"];
  int negative = 0;
  for (int i = 0; i < 5; ++i) {
    const Perez1990Diffuse d = perez1990_sky_diffuse(34, 180, n["dhi"][i], n["dni"][i], n["dni_extra"][i], n["solar_zenith"][i],
                                                     n["solar_azimuth"][i], n["airmass"][i]);
    BOOST_TEST(std::abs(d.sky_diffuse - num(n["expected_sky_diffuse"][i])) <= 1e-6);
    BOOST_TEST(std::abs(d.isotropic - num(n["expected_isotropic"][i])) <= 5e-5);
    BOOST_TEST(std::abs(d.circumsolar - num(n["expected_circumsolar"][i])) <= 5e-5);
    BOOST_TEST(std::abs(d.horizon - num(n["expected_horizon"][i])) <= 5e-5);
    BOOST_TEST(d.sky_diffuse == d.isotropic + d.circumsolar + d.horizon, tt::tolerance(1e-12));
    if (d.horizon < 0) ++negative;
  }
  BOOST_TEST(negative == 4);
}

BOOST_AUTO_TEST_CASE(horizontal_plane_is_dhi) {
  // Tilt 0: (1 − F1)·1 + F1·a/b with a = cos Z = b for Z ≤ 85°, horizon term 0: exactly DHI.
  for (double zen : {5.0, 40.0, 80.0}) {
    const Perez1990Diffuse d = perez1990_sky_diffuse(0, 180, 150, 600, 1367, zen, 200, 1.0 / std::cos(zen * M_PI / 180));
    BOOST_TEST(d.sky_diffuse == 150.0, tt::tolerance(1e-13));
  }
  // Night: NaN air mass or DHI = 0 → zeros.
  BOOST_TEST(perez1990_sky_diffuse(30, 180, 100, 0, 1367, 100, 0, std::nan("")).sky_diffuse == 0.0);
  BOOST_TEST(perez1990_sky_diffuse(30, 180, 0, 0, 1367, 100, 0, 38).sky_diffuse == 0.0);
}
