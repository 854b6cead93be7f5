#define BOOST_TEST_MODULE perez_efficacy
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>

#include "geometry/core/input_error.h"
#include "lighting/sky/perez_efficacy.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {
constexpr double kDeg = kPi / 180.0;
}

BOOST_AUTO_TEST_CASE(precipitable_water_from_dew_point) {
  // Perez90 eq. 3, closed forms: W = 1 cm at T_d = 0.075/0.07 °C; gendaylit.c's default dew point
  // 10.97353115 °C is the one that gives its former fixed W = 2 cm.
  BOOST_TEST(precipitable_water_cm(0.075 / 0.07) == 1.0, tt::tolerance(1e-15));
  BOOST_TEST(precipitable_water_cm(10.97353115) == 2.0, tt::tolerance(1e-9));
  BOOST_CHECK_THROW(precipitable_water_cm(std::nan("")), InputError);
}

BOOST_AUTO_TEST_CASE(ladybug_worked_example) {
  // ladybug-tools/ladybug tests/skymodel_test.py, estimate_illuminance_from_irradiance(altitude
  // 60°, GHI = 200 + 800 sin 60°, DNI 800, DHI 200, dew point 15 °C): global 99415.2739 lx,
  // direct normal 78879.2958 lx, diffuse 27609.2088 lx, zenith luminance 9056.0109 cd/m2.
  // That implementation uses Kasten–Young air mass (as here), I0 = 1360 W/m2 and
  // W = exp(0.08 T_d − 0.075) (0.08 where Perez90 eq. 3 has 0.07), so those inputs are passed
  // explicitly; ε = 4.48 falls in bin 6 for which its coefficients are those of the table here.
  // Its printed values have 9 significant digits: tolerance 1e-8.
  const double z = 30 * kDeg;
  const double ghi = 200 + 800 * std::sin(60 * kDeg);
  const PerezSkyCondition c = perez_sky_condition(200, 800, z, relative_air_mass_kasten_young(z), 1360);
  BOOST_TEST(c.bin == 5);
  const double w_ladybug = std::exp(0.08 * 15 - 0.075);
  const PerezIlluminance e = perez_illuminance(ghi, c, w_ladybug);
  BOOST_TEST(e.global_horizontal_lux == 99415.2739, tt::tolerance(1e-8));
  BOOST_TEST(e.direct_normal_lux == 78879.2958, tt::tolerance(1e-8));
  BOOST_TEST(e.diffuse_horizontal_lux == 27609.2088, tt::tolerance(1e-8));
  BOOST_TEST(e.zenith_luminance_cd_m2 == 9056.0109, tt::tolerance(1e-8));
  // With the paper's W (0.07) only the W terms change: Δη_g = b_6 ΔW, b_6 = 1.39 (Table 4).
  const PerezIlluminance p = perez_illuminance(ghi, c, precipitable_water_cm(15));
  BOOST_TEST((e.global_horizontal_lux - p.global_horizontal_lux) / ghi == 1.39 * (w_ladybug - precipitable_water_cm(15)),
             tt::tolerance(1e-10));
}

BOOST_AUTO_TEST_CASE(global_efficacy_plausible_for_typical_skies) {
  // Plausibility: measured efficacies of global daylight are about 100–130 lm/W for suns well
  // above the horizon (the range reviewed by P. J. Littlefair, "The luminous efficacy of
  // daylight: a review", Lighting Res. Technol. 17(4) 162–182, 1985). Every bin at a Δ it
  // usually takes (overcast ~0.25, clear ~0.12), W 1–3 cm, Z 20–70°: global within [95, 135];
  // diffuse within [95, 160] (the blue diffuse of clear skies is the most efficacious, ~150);
  // direct ≥ 0 and ≤ 115 lm/W. Observed ranges are printed.
  const double typical_delta[kPerezBinCount] = {0.25, 0.3, 0.3, 0.28, 0.25, 0.2, 0.15, 0.12};
  double gmin = 1e300, gmax = 0, dmin = 1e300, dmax = 0;
  for (int bin = 0; bin < kPerezBinCount; ++bin)
    for (double w : {1.0, 2.0, 3.0})
      for (double zdeg : {20.0, 45.0, 70.0}) {
        const PerezEfficacy e = perez_luminous_efficacy(bin, w, zdeg * kDeg, typical_delta[bin]);
        gmin = std::min(gmin, e.global_lm_W), gmax = std::max(gmax, e.global_lm_W);
        dmin = std::min(dmin, e.diffuse_lm_W), dmax = std::max(dmax, e.diffuse_lm_W);
        BOOST_TEST(e.direct_lm_W >= 0);
        BOOST_TEST(e.direct_lm_W <= 115);
        BOOST_TEST(e.zenith_luminance_per_dhi > 0);
      }
  BOOST_TEST_MESSAGE("global efficacy range " << gmin << " .. " << gmax << " lm/W; diffuse " << dmin << " .. " << dmax);
  BOOST_TEST(gmin >= 95);
  BOOST_TEST(gmax <= 135);
  BOOST_TEST(dmin >= 95);
  BOOST_TEST(dmax <= 160);
}

BOOST_AUTO_TEST_CASE(direct_efficacy_clamped_at_zero_for_low_sun) {
  // Eq. 8 at Z = 90° in bin 1, W = 2, Δ = 0.1: 57.20 − 4.55·2 − 2.98 exp(5.73·π/2 − 5) + 117.12·0.1
  // = −80.9 < 0, so the efficacy is 0 (Table 4 row 1).
  const double raw = 57.20 - 4.55 * 2 - 2.98 * std::exp(5.73 * 0.5 * kPi - 5) + 117.12 * 0.1;
  BOOST_TEST(raw < 0);
  BOOST_TEST(perez_luminous_efficacy(0, 2.0, 0.5 * kPi, 0.1).direct_lm_W == 0.0);
  // Bin 8, Z = 0, W = 2, Δ = 0.1: 101.18 + 1.58·2 − 1.10 e^−5 − 8.29·0.1 (Table 4 row 8).
  BOOST_TEST(perez_luminous_efficacy(7, 2.0, 0.0, 0.1).direct_lm_W == 101.18 + 3.16 - 1.10 * std::exp(-5.0) - 0.829,
             tt::tolerance(1e-13));
}

BOOST_AUTO_TEST_CASE(illuminance_uses_the_condition) {
  // Illuminance = irradiance × efficacy of the condition's bin, model zenith and clamped Δ;
  // a twilight hour (sun 4° below, DHI 5) uses Z = 90° and Δ ≥ 0.01; night is all zero.
  const PerezSkyCondition c = perez_sky_condition(5, 0, 94 * kDeg, 37.92, 1367);
  const PerezIlluminance t = perez_illuminance(5, c, 2.0);
  const PerezEfficacy e = perez_luminous_efficacy(0, 2.0, 0.5 * kPi, c.brightness);
  BOOST_TEST(t.diffuse_horizontal_lux == 5 * e.diffuse_lm_W, tt::tolerance(1e-15));
  BOOST_TEST(t.global_horizontal_lux == 5 * e.global_lm_W, tt::tolerance(1e-15));
  BOOST_TEST(t.direct_normal_lux == 0.0);
  BOOST_TEST(std::isfinite(t.zenith_luminance_cd_m2));
  const PerezSkyCondition night = perez_sky_condition(0, 0, 110 * kDeg, 1);
  const PerezIlluminance n = perez_illuminance(0, night, 2.0);
  BOOST_TEST(n.global_horizontal_lux == 0.0);
  BOOST_TEST(n.diffuse_horizontal_lux == 0.0);
  BOOST_TEST(n.direct_normal_lux == 0.0);
  BOOST_CHECK_THROW(perez_illuminance(-1, c, 2.0), InputError);
  BOOST_CHECK_THROW(perez_luminous_efficacy(8, 2.0, 0.3, 0.1), InputError);
  BOOST_CHECK_THROW(perez_luminous_efficacy(2, -1.0, 0.3, 0.1), InputError);
  BOOST_CHECK_THROW(perez_luminous_efficacy(2, 2.0, 0.3, 0.0), InputError);
}
