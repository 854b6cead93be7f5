#define BOOST_TEST_MODULE perez_sky
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "geometry/core/input_error.h"
#include "lighting/sky/perez_sky.h"
#include "lighting/sun/sun_position.h"
#include "lighting/support/perez_transposition.h"
#include "shared_data.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {

constexpr double kDeg = kPi / 180.0;

// --- Independent brute-force integration over the sky hemisphere ------------------------------
// Adaptive Gauss–Kronrod 7/15 (QUADPACK qk15 nodes and weights), nested: zenith angle θ outside,
// azimuth φ inside — a different parametrisation from the library's sun-centred one and a
// different (adaptive) rule. Break points: θ at the sun's zenith angle, φ at the sun's and the
// antisolar azimuth (the two cone points of exp(dγ)) and wherever the caller needs one.
constexpr double kXgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                            0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                            0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                            0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                            0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                            0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                            0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

template <class F>
double gk15(const F& f, double a, double b, double& err) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double rk = fc * kWgk[7], rg = fc * kWg[3];
  for (int j = 0; j < 7; ++j) {
    const double x = h * kXgk[j];
    const double s = f(c - x) + f(c + x);
    rk += kWgk[j] * s;
    if (j % 2 == 1) rg += kWg[j / 2] * s;
  }
  err = std::abs((rk - rg) * h);
  return rk * h;
}

template <class F>
double adaptive(const F& f, double a, double b, double tol, int depth = 0) {
  double err;
  const double r = gk15(f, a, b, err);
  if (err <= tol || depth >= 30) return r;
  const double m = 0.5 * (a + b);
  return adaptive(f, a, m, 0.5 * tol, depth + 1) + adaptive(f, m, b, 0.5 * tol, depth + 1);
}

template <class F>
double adaptive_pieces(const F& f, std::vector<double> breaks, double tol) {
  std::sort(breaks.begin(), breaks.end());
  const double span = breaks.back() - breaks.front();
  double s = 0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i)
    if (breaks[i + 1] > breaks[i]) s += adaptive(f, breaks[i], breaks[i + 1], tol * (breaks[i + 1] - breaks[i]) / span);
  return s;
}

Vec3 dir_zen_az(double zenith_rad, double azimuth_rad) {
  return Vec3(std::sin(azimuth_rad) * std::sin(zenith_rad), std::cos(azimuth_rad) * std::sin(zenith_rad), std::cos(zenith_rad));
}

// ∫_{z>0} L(w) max(0, n·w) dω by the nested adaptive rule; `tol` absolute.
double plane_integral_brute(const PerezSky& sky, const Vec3& n, double tol) {
  const Vec3& s = sky.sun_dir;
  const double zs = std::atan2(std::hypot(s.x(), s.y()), s.z());
  const double phis = std::atan2(s.x(), s.y());
  const double tilt = std::acos(std::clamp(n.z(), -1.0, 1.0));
  const double phin = std::atan2(n.x(), n.y());
  const auto row = [&](double th) {
    const double ct = std::cos(th), st = std::sin(th);
    const auto f = [&](double ph) {
      const Vec3 w(std::sin(ph) * st, std::cos(ph) * st, ct);
      return sky.radiance(w) * std::max(0.0, n.dot(w));
    };
    std::vector<double> br = {phis, phis + kPi, phis + 2 * kPi};
    // where the plane's own horizon crosses this row: cos(φ − φn) = −cot(tilt) cot(θ)
    if (std::sin(tilt) > 1e-12 && st > 1e-12) {
      const double c = -std::cos(tilt) * ct / (std::sin(tilt) * st);
      if (std::abs(c) < 1) {
        for (double ph : {phin + std::acos(c), phin - std::acos(c)}) {
          double p = ph;
          while (p < phis) p += 2 * kPi;
          while (p >= phis + 2 * kPi) p -= 2 * kPi;
          br.push_back(p);
        }
      }
    }
    return adaptive_pieces(f, br, 0.05 * tol) * st;
  };
  std::vector<double> br = {0.0, 0.5 * kPi};
  if (zs < 0.5 * kPi) br.push_back(zs);
  return adaptive_pieces(row, br, tol);
}

double horizontal_integral_brute(const PerezSky& sky, double tol) {
  return plane_integral_brute(sky, Vec3(0, 0, 1), tol);
}

// DNI that puts ε at `eps` for DHI and zenith Z (Perez90 eq. 1 solved for DNI).
double dni_for_clearness(double eps, double dhi, double zenith_rad) {
  const double kz3 = kPerezKappa * zenith_rad * zenith_rad * zenith_rad;
  return dhi * (eps * (1 + kz3) - kz3 - 1);
}

Vec3 sun_from_zenith_azimuth_deg(double zenith_deg, double azimuth_deg) {
  return direction_from_altitude_azimuth_deg(90.0 - zenith_deg, azimuth_deg);
}

struct TestSky {
  const char* what;
  double dhi, eps, zenith_deg, azimuth_deg;
  int day;
};

// One sky per bin at mid-bin clearness with an ordinary DHI, plus the hard cases named in them.
// (DHI and ε are chosen, DNI follows; Δ from Kasten–Young air mass and Spencer I0.)
const std::vector<TestSky>& test_skies() {
  static const std::vector<TestSky> skies = {
      {"bin 1 overcast", 180, 1.03, 40, 160, 80},
      {"bin 2", 160, 1.15, 35, 200, 120},
      {"bin 3", 150, 1.35, 55, 120, 150},
      {"bin 4", 140, 1.7, 25, 180, 172},
      {"bin 5", 120, 2.3, 65, 250, 200},
      {"bin 6", 100, 3.5, 45, 140, 230},
      {"bin 7", 80, 5.3, 30, 190, 260},
      {"bin 8", 70, 8.0, 50, 210, 290},
      {"bin 8, very clear, strong circumsolar peak", 45, 11.0, 20, 180, 172},
      {"bin 6, sun 2 deg above the horizon", 40, 3.2, 88, 100, 100},
      {"bin 3, sun 0.3 deg above the horizon", 25, 1.4, 89.7, 280, 300},
      {"bin 1, sun 3 deg below the horizon, DHI > 0", 8, 1.0, 93, 300, 10},
      {"bin 2, sun 3 deg below the horizon, DHI > 0", 8, 1.1, 93, 60, 190},
  };
  return skies;
}

PerezSky make_test_sky(const TestSky& t, int nodes = 24) {
  const double z = t.zenith_deg * kDeg;
  const double dni = dni_for_clearness(t.eps, t.dhi, std::min(z, 0.5 * kPi));
  const PerezSkyCondition c = perez_sky_condition(t.dhi, std::max(0.0, dni), z, t.day);
  return make_perez_sky(c, sun_from_zenith_azimuth_deg(t.zenith_deg, t.azimuth_deg), t.dhi, nodes);
}

}  // namespace

// ------------------------------------------------------------------------------------------------

BOOST_AUTO_TEST_CASE(air_mass_and_extraterrestrial_irradiance_match_pvlib) {
  // pvlib tests/test_atmosphere.py, kastenyoung1989 at zenith 0, 80, 89.9°: 1.000, 5.586, 36.467
  // (atol 0.001 there).
  BOOST_TEST(relative_air_mass_kasten_young(0.0) == 1.000, tt::tolerance(0.001));
  BOOST_TEST(relative_air_mass_kasten_young(80 * kDeg) == 5.586, tt::tolerance(0.001 / 5.586));
  BOOST_TEST(relative_air_mass_kasten_young(89.9 * kDeg) == 36.467, tt::tolerance(0.001 / 36.467));
  // At 90° the formula gives 1/(0.50572 · 6.07995^−1.6364) = 37.92 (closed form); beyond, the
  // zenith is clamped, so m(100°) equals it.
  BOOST_TEST(relative_air_mass_kasten_young(0.5 * kPi) == 37.92, tt::tolerance(0.01 / 37.92));
  BOOST_TEST(relative_air_mass_kasten_young(100 * kDeg) == relative_air_mass_kasten_young(0.5 * kPi));
  // pvlib's transposition fixture (shared/data/reference): relative air mass 7.58831596, 1.01688136,
  // 3.27930443 at apparent zenith 82.85457044, 10.56413562, 72.41687122°, from kastenyoung1989.
  BOOST_TEST(relative_air_mass_kasten_young(82.85457044 * kDeg) == 7.58831596, tt::tolerance(1e-8));
  BOOST_TEST(relative_air_mass_kasten_young(10.56413562 * kDeg) == 1.01688136, tt::tolerance(1e-8));
  BOOST_TEST(relative_air_mass_kasten_young(72.41687122 * kDeg) == 3.27930443, tt::tolerance(1e-8));
  // The same fixture's dni_extra, pvlib get_extra_radiation(2014-06-24 = day 175), Spencer method,
  // solar constant 1366.1: 1321.1655834833093 W/m2; pvlib's test value for 2016-10-26 (day 300):
  // 1383.636203. Both to their printed digits.
  BOOST_TEST(extraterrestrial_normal_irradiance_W_m2(175, 1366.1) == 1321.1655834833093, tt::tolerance(1e-13));
  BOOST_TEST(extraterrestrial_normal_irradiance_W_m2(300, 1366.1) == 1383.636203, tt::tolerance(1e-9));
  BOOST_CHECK_THROW(extraterrestrial_normal_irradiance_W_m2(0), InputError);
  BOOST_CHECK_THROW(extraterrestrial_normal_irradiance_W_m2(367), InputError);
  BOOST_CHECK_THROW(relative_air_mass_kasten_young(std::nan("")), InputError);
}

BOOST_AUTO_TEST_CASE(clearness_and_brightness_closed_forms) {
  // Perez90 eq. 1: DNI = 0 gives ε = 1 for any zenith; Z = 0 gives ε = 1 + DNI/DHI.
  for (double z : {0.0, 0.3, 1.2, 0.5 * kPi}) BOOST_TEST(perez_sky_clearness(120, 0, z) == 1.0, tt::tolerance(1e-15));
  BOOST_TEST(perez_sky_clearness(100, 450, 0.0) == 5.5, tt::tolerance(1e-15));
  BOOST_TEST(std::isinf(perez_sky_clearness(0, 300, 0.5)));
  // Perez90 eq. 2: Δ = DHI m / I0 = 100·2/1000.
  BOOST_TEST(perez_sky_brightness(100, 2, 1000) == 0.2, tt::tolerance(1e-15));
  // The condition: model zenith clamped to 90°, Δ clamped to [0.01, 0.6] (gendaylit).
  const PerezSkyCondition dim = perez_sky_condition(3, 0, 30 * kDeg, 1.0, 1367);
  BOOST_TEST(dim.brightness_unclamped == 3.0 / 1367, tt::tolerance(1e-15));
  BOOST_TEST(dim.brightness == kPerezMinBrightness);
  const PerezSkyCondition bright = perez_sky_condition(500, 0, 80 * kDeg, 5.6, 1367);
  BOOST_TEST(bright.brightness == kPerezMaxBrightness);
  const PerezSkyCondition twilight = perez_sky_condition(10, 0, 95 * kDeg, 38, 1367);
  BOOST_TEST(twilight.model_zenith_rad == 0.5 * kPi);
  BOOST_TEST(twilight.sun_zenith_rad == 95 * kDeg);
  BOOST_TEST(twilight.bin == 0);
  // Bad user parameters.
  BOOST_CHECK_THROW(perez_sky_condition(-1, 0, 0.5, 1, 1367), InputError);
  BOOST_CHECK_THROW(perez_sky_condition(10, std::nan(""), 0.5, 1, 1367), InputError);
  BOOST_CHECK_THROW(perez_sky_condition(10, 0, 3.5, 1, 1367), InputError);
  BOOST_CHECK_THROW(perez_sky_condition(10, 0, 0.5, 0, 1367), InputError);
  BOOST_CHECK_THROW(perez_sky_condition(10, 0, 0.5, 1, -1), InputError);
}

BOOST_AUTO_TEST_CASE(clearness_bin_edges) {
  // Perez93 Table 1 bin edges; each edge belongs to the bin above it.
  BOOST_TEST(perez_clearness_bin(0.5) == 0);
  BOOST_TEST(perez_clearness_bin(1.0) == 0);
  BOOST_TEST(perez_clearness_bin(std::numeric_limits<double>::infinity()) == 7);
  BOOST_TEST(perez_clearness_bin(100.0) == 7);
  BOOST_CHECK_THROW(perez_clearness_bin(std::nan("")), InputError);
  const double inf = std::numeric_limits<double>::infinity();
  for (int i = 1; i < kPerezBinCount; ++i) {
    const double e = kPerezClearnessLowerEdges[i];
    BOOST_TEST(perez_clearness_bin(e) == i);
    BOOST_TEST(perez_clearness_bin(std::nextafter(e, -inf)) == i - 1);
    BOOST_TEST(perez_clearness_bin(std::nextafter(e, inf)) == i);
    BOOST_TEST(perez_clearness_bin(e - 1e-9) == i - 1);
    BOOST_TEST(perez_clearness_bin(e + 1e-9) == i);
    // Through the condition, sun at the zenith: ε = 1 + DNI/DHI exactly up to rounding.
    for (double de : {-1e-9, 1e-9}) {
      const double dni = 100.0 * (e + de - 1.0);
      const PerezSkyCondition c = perez_sky_condition(100, dni, 0.0, 1.0, 1367);
      BOOST_TEST(c.bin == (de < 0 ? i - 1 : i));
    }
  }
}

BOOST_AUTO_TEST_CASE(coefficients_follow_the_table_and_the_clamps) {
  // Δ = 0, Z = 0: each linear coefficient is its x1 (Perez93 Table 1, first column); bin 8 row:
  // a1 = −1.0500, b1 = −0.3250, c1 = 31.0625, d1 = −7.2312, e1 = 1.5000.
  const PerezSkyCoefficients k8 = perez_sky_coefficients_raw(7, 0.0, 0.0);
  BOOST_TEST(k8.a == -1.0500);
  BOOST_TEST(k8.b == -0.3250);
  BOOST_TEST(k8.c == 31.0625);
  BOOST_TEST(k8.d == -7.2312);
  BOOST_TEST(k8.e == 1.5000);
  // x = x1 + x2 Z + Δ(x3 + x4 Z) is linear in Δ at fixed Z and in Z at fixed Δ: the midpoint
  // values are the means (bins 2..8, all five coefficients).
  for (int bin = 1; bin < kPerezBinCount; ++bin) {
    const auto p = perez_sky_coefficients_raw(bin, 0.1, 0.4), q = perez_sky_coefficients_raw(bin, 0.5, 0.4);
    const auto m = perez_sky_coefficients_raw(bin, 0.3, 0.4);
    BOOST_TEST(m.c == 0.5 * (p.c + q.c), tt::tolerance(1e-13));
    BOOST_TEST(m.e == 0.5 * (p.e + q.e), tt::tolerance(1e-12));
  }
  // Bin 1, eqs. 7–8 at Δ = 0: c = exp(0^c3) − c4 = 1 − 1 = 0, d = −exp(0) + d3 = −1 + 0.9738.
  const PerezSkyCoefficients k1 = perez_sky_coefficients_raw(0, 0.0, 0.7);
  BOOST_TEST(k1.c == 0.0, tt::tolerance(1e-15));
  BOOST_TEST(k1.d == -1.0 + 0.9738, tt::tolerance(1e-14));
  // Bin 1 at Δ = 0.2, Z = 0: c = exp((0.2·2.8)^1.2375) − 1, d = −exp(0.2·1.8734) + 0.9738 + 0.2·0.2809.
  const PerezSkyCoefficients k1b = perez_sky_coefficients_raw(0, 0.2, 0.0);
  BOOST_TEST(k1b.c == std::exp(std::pow(0.56, 1.2375)) - 1.0, tt::tolerance(1e-14));
  BOOST_TEST(k1b.d == -std::exp(0.2 * 1.8734) + 0.9738 + 0.2 * 0.2809, tt::tolerance(1e-14));
  // gendaylit's floor Δ ≥ 0.2 in bins 2–5 (not in 1, 6–8).
  PerezSkyCondition c;
  c.brightness = 0.05;
  c.model_zenith_rad = 0.6;
  for (int bin = 0; bin < kPerezBinCount; ++bin) {
    c.bin = bin;
    const double used = (bin >= 1 && bin <= 4) ? 0.2 : 0.05;
    const auto k = perez_sky_coefficients(c), r = perez_sky_coefficients_raw(bin, used, 0.6);
    BOOST_TEST(k.a == r.a);
    BOOST_TEST(k.c == r.c);
    BOOST_TEST(k.b == std::min(r.b, 0.0));
  }
  // b ≤ 0: bin 7 at Δ = 0.6, Z = 0 has b = −0.3 + 0.6·0.7023 = 0.1214 > 0 in the table.
  BOOST_TEST(perez_sky_coefficients_raw(6, 0.6, 0.0).b == -0.3 + 0.6 * 0.7023, tt::tolerance(1e-14));
  c.bin = 6;
  c.brightness = 0.6;
  c.model_zenith_rad = 0.0;
  BOOST_TEST(perez_sky_coefficients(c).b == 0.0);
  BOOST_CHECK_THROW(perez_sky_coefficients_raw(8, 0.1, 0.1), InputError);
}

BOOST_AUTO_TEST_CASE(normalisation_matches_brute_force_integration) {
  // For every test sky the library's quadrature scale k makes ∫ k·l cos θ dω = DHI; the adaptive
  // zenith-frame integration (tolerance 1e-12·DHI) must agree to 1e-9 relative. Observed
  // differences are printed (≤ 4e-10, the largest for the sun 0.3° above the horizon).
  for (const TestSky& t : test_skies()) {
    const PerezSky sky = make_test_sky(t);
    BOOST_TEST_REQUIRE(sky.scale > 0);
    const double brute = horizontal_integral_brute(sky, 1e-12 * t.dhi);
    BOOST_TEST_MESSAGE(t.what << ": bin " << sky.condition.bin + 1 << " Delta " << sky.condition.brightness
                              << "  brute/DHI - 1 = " << brute / t.dhi - 1);
    BOOST_TEST(brute == t.dhi, tt::tolerance(1e-9));
  }
}

BOOST_AUTO_TEST_CASE(quadrature_converges_and_timing) {
  // The integral with the default 24 nodes against 48 and 96: |I24 − I96| ≤ 1e-9 I96 and
  // |I48 − I96| ≤ 1e-12 I96 (geometric convergence of every piece; see perez_sky.h). Also
  // a sweep over all bins × Δ × Z, where Δ spans the clamped range: 24 nodes within 1e-8.
  for (const TestSky& t : test_skies()) {
    const PerezSky sky = make_test_sky(t);
    const double i24 = perez_horizontal_integral(sky.coefficients, sky.sun_dir, 24);
    const double i48 = perez_horizontal_integral(sky.coefficients, sky.sun_dir, 48);
    const double i96 = perez_horizontal_integral(sky.coefficients, sky.sun_dir, 96);
    BOOST_TEST(i24 == i96, tt::tolerance(1e-9));
    BOOST_TEST(i48 == i96, tt::tolerance(1e-12));
  }
  double worst = 0;
  for (int bin = 0; bin < kPerezBinCount; ++bin)
    for (double D : {0.01, 0.08, 0.2, 0.4, 0.6})
      for (double zdeg : {0.0, 20.0, 50.0, 75.0, 86.0, 89.5, 92.0}) {
        PerezSkyCondition c;
        c.bin = bin;
        c.brightness = D;
        c.model_zenith_rad = std::min(zdeg, 90.0) * kDeg;
        const PerezSkyCoefficients k = perez_sky_coefficients(c);
        const Vec3 sun = sun_from_zenith_azimuth_deg(zdeg, 37.0);
        const double i24 = perez_horizontal_integral(k, sun, 24), i96 = perez_horizontal_integral(k, sun, 96);
        if (i96 > 0) worst = std::max(worst, std::abs(i24 / i96 - 1));
      }
  BOOST_TEST_MESSAGE("worst |I24/I96 - 1| over bins x Delta x Z: " << worst);
  BOOST_TEST(worst <= 1e-8);

  // Timing of one normalisation (coefficients + integral), best of 5 runs over the test skies;
  // reported, not asserted (shared machine).
  std::vector<PerezSkyCondition> conds;
  std::vector<Vec3> suns;
  for (const TestSky& t : test_skies()) {
    const PerezSky s = make_test_sky(t);
    conds.push_back(s.condition);
    suns.push_back(s.sun_dir);
  }
  double best = 1e300, sink = 0;
  for (int rep = 0; rep < 5; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < 20; ++r)
      for (std::size_t i = 0; i < conds.size(); ++i) sink += make_perez_sky(conds[i], suns[i], 100.0).scale;
    best = std::min(
        best, std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / (20.0 * conds.size()));
  }
  BOOST_TEST_MESSAGE("make_perez_sky: " << best << " us per call (mean over the test skies, best of 5)");
  BOOST_TEST(sink > 0);
}

BOOST_AUTO_TEST_CASE(clamped_corners_stay_finite_and_normalised) {
  // Skies where the clamps act (b ≥ 0 in the table, negative gradation or indicatrix): finite,
  // non-negative, and normalised — brute force to 1e-7 (the integrand has kinks where a factor
  // is clamped at 0, which the adaptive rule resolves only slowly; tolerance from its own error).
  struct Corner {
    int bin;
    double delta, zenith_deg;
  };
  for (const Corner& cc :
       {Corner{6, 0.6, 0.0}, Corner{3, 0.6, 0.0}, Corner{5, 0.6, 89.0}, Corner{7, 0.6, 85.0}, Corner{5, 0.01, 30.0}}) {
    PerezSkyCondition c;
    c.dhi_W_m2 = 100;
    c.bin = cc.bin;
    c.brightness = cc.delta;
    c.sun_zenith_rad = c.model_zenith_rad = cc.zenith_deg * kDeg;
    const PerezSky sky = make_perez_sky(c, sun_from_zenith_azimuth_deg(cc.zenith_deg, 123.0), 100.0);
    BOOST_TEST_REQUIRE(std::isfinite(sky.scale));
    BOOST_TEST_REQUIRE(sky.scale > 0);
    BOOST_TEST(sky.coefficients.b <= 0);
    const double brute = horizontal_integral_brute(sky, 1e-9 * 100);
    BOOST_TEST_MESSAGE("corner bin " << cc.bin + 1 << " Delta " << cc.delta << " Z " << cc.zenith_deg
                                     << ": brute/DHI - 1 = " << brute / 100 - 1);
    BOOST_TEST(brute == 100.0, tt::tolerance(1e-7));
  }
}

BOOST_AUTO_TEST_CASE(no_nan_or_inf_anywhere) {
  // Skies of every bin over Δ below, inside and above the clamp range and suns from the zenith to
  // 10° below the horizon, evaluated on directions including θ → 90° (cos θ down to the smallest
  // subnormal), the sun and the antisolar point: radiance finite and ≥ 0, scale finite.
  std::vector<Vec3> dirs;
  for (double ct : {1.0, 0.7, 0.2, 1e-3, 1e-8, 1e-15, 1e-300, std::numeric_limits<double>::denorm_min(), 0.0, -1e-12, -0.5})
    for (double az = 0; az < 360; az += 22.5) {
      const double st = std::sqrt(std::max(0.0, 1 - ct * ct));
      dirs.emplace_back(std::sin(az * kDeg) * st, std::cos(az * kDeg) * st, ct);
    }
  int skies = 0;
  const double mid_eps[kPerezBinCount] = {1.03, 1.15, 1.35, 1.7, 2.3, 3.5, 5.3, 9.0};
  for (int bin = 0; bin < kPerezBinCount; ++bin)
    for (double D : {0.001, 0.01, 0.1, 0.3, 0.6, 2.0})  // Δ before the clamp to [0.01, 0.6]
      for (double zdeg : {0.0, 30.0, 80.0, 89.9, 90.0, 93.0, 100.0}) {
        const double z = zdeg * kDeg, m = relative_air_mass_kasten_young(z), i0 = 1367;
        const double dhi = D * i0 / m;
        const double dni = dni_for_clearness(mid_eps[bin], dhi, std::min(z, 0.5 * kPi));
        const PerezSkyCondition c = perez_sky_condition(dhi, dni, z, m, i0);
        BOOST_TEST_REQUIRE(c.bin == bin);
        const Vec3 sun = sun_from_zenith_azimuth_deg(zdeg, 200.0);
        const PerezSky sky = make_perez_sky(c, sun, dhi);
        BOOST_TEST_REQUIRE(std::isfinite(sky.scale));
        BOOST_TEST_REQUIRE(sky.scale > 0);
        std::vector<Vec3> all = dirs;
        all.push_back(sun);
        all.push_back(-sun);
        for (const Vec3& d : all) {
          const double L = sky.radiance(d);
          if (!std::isfinite(L) || L < 0) BOOST_ERROR("bad radiance " << L << " bin " << bin + 1 << " D " << D << " Z " << zdeg);
        }
        ++skies;
      }
  BOOST_TEST(skies == 8 * 6 * 7);
  // DHI = 0: no sky at all.
  const PerezSkyCondition night = perez_sky_condition(0, 0, 100 * kDeg, 1);
  const PerezSky dark = make_perez_sky(night, sun_from_zenith_azimuth_deg(100, 0), 0.0);
  BOOST_TEST(dark.scale == 0.0);
  BOOST_TEST(dark.radiance(Vec3(0, 0, 1)) == 0.0);
  BOOST_CHECK_THROW(make_perez_sky(night, Vec3(0, 0, 2), 0.0), InputError);
  BOOST_CHECK_THROW(make_perez_sky(night, Vec3(0, 0, 1), -1.0), InputError);
}

BOOST_AUTO_TEST_CASE(symmetric_about_the_suns_vertical_plane) {
  // l depends on θ and γ only, and γ is the same for azimuths φs ± δ: mirror directions have
  // equal radiance (to rounding of the direction vectors, 1e-12).
  for (const TestSky& t : test_skies()) {
    const PerezSky sky = make_test_sky(t);
    const double phis = t.azimuth_deg * kDeg;
    for (double th : {5.0, 30.0, 60.0, 85.0, 89.99})
      for (double dphi : {1.0, 10.0, 45.0, 90.0, 135.0, 179.0}) {
        const double a = sky.radiance(dir_zen_az(th * kDeg, phis + dphi * kDeg));
        const double b = sky.radiance(dir_zen_az(th * kDeg, phis - dphi * kDeg));
        BOOST_TEST(a == b, tt::tolerance(1e-12));
      }
  }
}

BOOST_AUTO_TEST_CASE(overcast_limit_resembles_cie_overcast_gradation) {
  // Bin 1 with small Δ: the azimuthal mean of L decreases monotonically from the zenith to the
  // horizon, as in the CIE standard overcast sky (1 + 2 cos θ)/3 (Moon & Spencer; zenith/horizon
  // 3), though less steeply (observed 1.56, asserted in [1.3, 3.5]); and the circumsolar
  // term is weak: at θ = 45° the azimuthal max/min ratio is < 1.1.
  const PerezSkyCondition c = perez_sky_condition(100, 0, 50 * kDeg, 1.55, 1367);  // Δ = 0.113, ε = 1
  BOOST_TEST(c.bin == 0);
  const PerezSky sky = make_perez_sky(c, sun_from_zenith_azimuth_deg(50, 180), 100.0);
  const auto mean_at = [&](double th) {
    double s = 0;
    for (int i = 0; i < 360; ++i) s += sky.radiance(dir_zen_az(th * kDeg, (i + 0.5) * kDeg));
    return s / 360;
  };
  double prev = mean_at(0.0);
  const double zenith = prev;
  for (double th = 5; th < 90; th += 5) {
    const double m = mean_at(th);
    BOOST_TEST(m < prev);
    prev = m;
  }
  const double horizon = mean_at(89.9);
  BOOST_TEST_MESSAGE("bin 1 overcast: zenith/horizon = " << zenith / horizon << " (CIE overcast: 3)");
  BOOST_TEST(zenith / horizon > 1.3);
  BOOST_TEST(zenith / horizon < 3.5);
  double lo = 1e300, hi = 0;
  for (int i = 0; i < 360; ++i) {
    const double L = sky.radiance(dir_zen_az(45 * kDeg, i * kDeg));
    lo = std::min(lo, L);
    hi = std::max(hi, L);
  }
  BOOST_TEST(hi / lo < 1.1);
}

BOOST_AUTO_TEST_CASE(clear_sky_is_brightest_near_the_sun) {
  // Bin 8 (the very clear test sky): the brightest of a 1°-grid of sky directions lies within 5°
  // of the sun, and the radiance 3° from the sun exceeds that of every grid direction at least 60°
  // from it (the bright clear-sky horizon included) more than 3-fold (observed value printed).
  const TestSky& t = test_skies()[8];
  const PerezSky sky = make_test_sky(t);
  double best = 0, far_max = 0;
  Vec3 best_dir(0, 0, 1);
  for (int i = 0; i < 90; ++i)
    for (int j = 0; j < 360; ++j) {
      const Vec3 d = dir_zen_az((i + 0.5) * kDeg, j * kDeg);
      const double L = sky.radiance(d);
      if (L > best) best = L, best_dir = d;
      if (std::acos(std::clamp(d.dot(sky.sun_dir), -1.0, 1.0)) >= 60 * kDeg) far_max = std::max(far_max, L);
    }
  BOOST_TEST(std::acos(std::clamp(best_dir.dot(sky.sun_dir), -1.0, 1.0)) < 5 * kDeg);
  const double near = sky.radiance(dir_zen_az(t.zenith_deg * kDeg + 3 * kDeg, t.azimuth_deg * kDeg));
  BOOST_TEST_MESSAGE("bin 8: L(3 deg from sun) / max L(>= 60 deg from sun) = " << near / far_max);
  BOOST_TEST(near > 3 * far_max);
  // The overcast sky of the previous test has no such peak: there the same ratio is < 1.5.
  const PerezSkyCondition c = perez_sky_condition(100, 0, 50 * kDeg, 1.55, 1367);
  const PerezSky overcast = make_perez_sky(c, sun_from_zenith_azimuth_deg(50, 180), 100.0);
  const double o_near = overcast.radiance(dir_zen_az(53 * kDeg, kPi));
  const double o_far = overcast.radiance(dir_zen_az(50 * kDeg, 0.0));  // 80° from the sun
  BOOST_TEST(o_near < 1.5 * o_far);
}

// ------------------------------------------------------------------------------------------------
// The integrated Perez 1993 sky on unobstructed tilted planes against the Perez 1990 transposition
// (tests/lighting/support/perez_transposition.h). Two different models fitted to different data
// for different purposes: the 1990 model puts its circumsolar fraction F1 of DHI at the sun's
// position and adds a horizon band, the 1993 distribution spreads the circumsolar brightening
// over tens of degrees and brightens the whole horizon region. Differences are reported relative
// to the 1990 sky diffuse and relative to the plane's total irradiance (beam + sky diffuse +
// ground with albedo 0.2); the asserted bounds are the observed worst cases rounded up.

namespace {

Vec3 plane_normal(double tilt_deg, double azimuth_deg) {
  return Vec3(std::sin(tilt_deg * kDeg) * std::sin(azimuth_deg * kDeg), std::sin(tilt_deg * kDeg) * std::cos(azimuth_deg * kDeg),
              std::cos(tilt_deg * kDeg));
}

nlohmann::json load_pvlib_reference() {
  const std::filesystem::path p = std::filesystem::path(SKYBAND_SHARED_DATA) / "reference" / "pvlib_transposition_reference.json";
  std::ifstream in(p);
  BOOST_TEST_REQUIRE(in.good(), "cannot open " << p);
  return nlohmann::json::parse(in);
}

struct PlaneCompare {
  double ours, theirs, total;  // W/m2: our sky diffuse, Perez 1990 sky diffuse, plane total
  double rel_diffuse() const { return ours / theirs - 1; }
  double rel_total() const { return (ours - theirs) / total; }
};

PlaneCompare compare_on_plane(double dhi, double dni, double dni_extra, double zen_deg, double az_deg, double air_mass,
                              double tilt, double plane_az) {
  const PerezSkyCondition c = perez_sky_condition(dhi, dni, zen_deg * kDeg, air_mass, dni_extra);
  const PerezSky sky = make_perez_sky(c, sun_from_zenith_azimuth_deg(zen_deg, az_deg), dhi);
  const double ours = plane_integral_brute(sky, plane_normal(tilt, plane_az), 1e-9 * dhi);
  const double theirs = test::perez1990_sky_diffuse(tilt, plane_az, dhi, dni, dni_extra, zen_deg, az_deg, air_mass).sky_diffuse;
  const double beam = dni * std::max(0.0, test::perez1990_aoi_projection(tilt, plane_az, zen_deg, az_deg));
  const double ghi = dhi + dni * std::max(0.0, std::cos(zen_deg * kDeg));
  const double ground = 0.2 * ghi * 0.5 * (1 - std::cos(tilt * kDeg));
  return {ours, theirs, beam + theirs + ground};
}

}  // namespace

BOOST_AUTO_TEST_CASE(plane_integral_of_a_uniform_sky) {
  // Oracle for the plane integration used below: a uniform sky (all coefficients 0, l ≡ 1) of
  // DHI 100 gives a plane tilted β the view-factor value 100 (1 + cos β)/2 (closed form).
  PerezSky sky;
  sky.sun_dir = sun_from_zenith_azimuth_deg(40, 150);
  sky.scale = 100.0 / kPi;
  for (double tilt : {0.0, 30.0, 60.0, 90.0, 120.0})
    for (double az : {0.0, 100.0, 180.0}) {
      const double got = plane_integral_brute(sky, plane_normal(tilt, az), 1e-11);
      BOOST_TEST(got == 100 * 0.5 * (1 + std::cos(tilt * kDeg)), tt::tolerance(1e-10));
    }
}

BOOST_AUTO_TEST_CASE(tilted_planes_against_perez1990_pvlib_inputs, *skyband::test::needs_shared_data()) {
  const nlohmann::json j = load_pvlib_reference();
  const auto& in = j["inputs"];
  // pvlib fixture, hours 1–3 (hour 0 is night), tilt 40° facing south; and the Goodwin Creek
  // negative-horizon case, tilt 34° facing south (its Perez 1990 values are pvlib's published
  // ones, checked in perez_transposition_test).
  double worst_d = 0, worst_t = 0;
  const auto check = [&](const char* what, int i, const PlaneCompare& r) {
    BOOST_TEST_MESSAGE(what << " " << i << ": ours " << r.ours << " Perez1990 " << r.theirs << "  rel(diffuse) "
                            << r.rel_diffuse() << "  rel(total) " << r.rel_total());
    worst_d = std::max(worst_d, std::abs(r.rel_diffuse()));
    worst_t = std::max(worst_t, std::abs(r.rel_total()));
    BOOST_TEST(std::abs(r.rel_diffuse()) < 0.13);  // observed worst 0.112 (Goodwin Creek hour 0)
    BOOST_TEST(std::abs(r.rel_total()) < 0.08);    // observed worst 0.073 (same hour)
  };
  for (int i = 1; i <= 3; ++i)
    check("pvlib hour", i,
          compare_on_plane(in["dhi"][i], in["dni"][i], in["dni_extra"][i], in["apparent_zenith"][i], in["azimuth"][i],
                           in["relative_airmass"][i], 40, 180));
  const auto& n = j["perez_negative_horizon_case"];
  for (int i = 0; i < 5; ++i)
    check("Goodwin Creek", i,
          compare_on_plane(n["dhi"][i], n["dni"][i], n["dni_extra"][i], n["solar_zenith"][i], n["solar_azimuth"][i],
                           n["airmass"][i], 34, 180));
  BOOST_TEST_MESSAGE("pvlib inputs: worst |rel(diffuse)| " << worst_d << ", worst |rel(total)| " << worst_t);
}

BOOST_AUTO_TEST_CASE(tilted_planes_against_perez1990_orientations) {
  // Skies: the pvlib fixture's midday hour (clear, sun 10.6° from the zenith), a hazy afternoon,
  // an overcast hour, and the fixture's low evening sun; planes tilted 0/30/60/90° facing
  // N/E/S/W. Tilt 0 equals DHI in both models by construction (ours to the brute-force
  // tolerance, 1e-8).
  struct Hour {
    double dhi, dni, zen, az;
  };
  const Hour hours[] = {{118.45831879, 939.95469881, 10.56413562, 144.76567754},
                        {200, 350, 45, 230},
                        {250, 0, 55, 160},
                        {62.03376265, 646.22886049, 72.41687122, 287.04104128}};
  const double dni_extra = extraterrestrial_normal_irradiance_W_m2(175, 1366.1);
  // Bounds per tilt on |ours − Perez1990| / plane total and on |ours/Perez1990 − 1| (observed
  // worst over the four skies and four azimuths, rounded up; per-orientation worst printed).
  const double bound_total[4] = {1e-8, 0.05, 0.09, 0.13};
  const double bound_diffuse[4] = {1e-8, 0.12, 0.15, 0.47};
  double worst_total[4][4] = {}, worst_diffuse[4][4] = {};
  const char* facing[4] = {"N", "E", "S", "W"};
  for (const Hour& h : hours) {
    const double m = relative_air_mass_kasten_young(h.zen * kDeg);
    for (int ti = 0; ti < 4; ++ti)
      for (int ai = 0; ai < 4; ++ai) {
        const double tilt = 30.0 * ti, paz = 90.0 * ai;
        const PlaneCompare r = compare_on_plane(h.dhi, h.dni, dni_extra, h.zen, h.az, m, tilt, paz);
        if (ti == 0) {
          BOOST_TEST(r.ours == h.dhi, tt::tolerance(1e-8));
          BOOST_TEST(r.theirs == h.dhi, tt::tolerance(1e-12));
        }
        worst_total[ti][ai] = std::max(worst_total[ti][ai], std::abs(r.rel_total()));
        worst_diffuse[ti][ai] = std::max(worst_diffuse[ti][ai], std::abs(r.rel_diffuse()));
        BOOST_TEST_MESSAGE("sky (DHI " << h.dhi << ", DNI " << h.dni << ", Z " << h.zen << ") tilt " << tilt << " az " << paz
                                       << ": ours " << r.ours << " Perez1990 " << r.theirs << "  rel(diffuse) " << r.rel_diffuse()
                                       << "  rel(total) " << r.rel_total());
        BOOST_TEST(std::abs(r.rel_total()) <= bound_total[ti]);
        BOOST_TEST(std::abs(r.rel_diffuse()) <= bound_diffuse[ti]);
      }
  }
  for (int ti = 0; ti < 4; ++ti)
    for (int ai = 0; ai < 4; ++ai)
      BOOST_TEST_MESSAGE("tilt " << 30 * ti << " facing " << facing[ai] << ": worst |rel(total)| " << worst_total[ti][ai]
                                 << ", worst |rel(diffuse)| " << worst_diffuse[ti][ai]);
}
