#define BOOST_TEST_MODULE sky_table
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "geometry/core/vec3.h"
#include "lighting/atmosphere/atmosphere.h"
#include "lighting/atmosphere/phase_functions.h"
#include "lighting/atmosphere/sky_table.h"
#include "lighting/sun/sun.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {
double deg(double d) {
  return d * kPi / 180.0;
}
int index_of_nm(double nm) {
  return static_cast<int>(std::lround((nm - kLambdaMinNm) / kLambdaStepNm));
}

// Worst relative error of the table against direct integration over `n` random sky directions
// (uniform on the upper hemisphere, fixed seed), at 400, 550 and 700 nm. The error is relative
// to max(direct, floor_fraction × the brightest sampled direct radiance at that wavelength);
// floor_fraction = 0 gives the plain relative error.
double worst_table_error(const Atmosphere& atm, const SkyTable& table, ScatteringOrders orders, int n, unsigned seed,
                         double floor_fraction) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<Spectrum> direct, interp;
  Spectrum brightest;
  for (int k = 0; k < n; ++k) {
    const double z = U(rng), phi = 2.0 * kPi * U(rng), s = std::sqrt(1.0 - z * z);
    const Vec3 v(s * std::cos(phi), s * std::sin(phi), z);
    direct.push_back(atm.sky_radiance(v, table.sun_direction(), orders));
    interp.push_back(table.radiance(v));
    for (int i = 0; i < kSpectrumSamples; ++i) brightest[i] = std::max(brightest[i], direct.back()[i]);
  }
  double worst = 0;
  for (int k = 0; k < n; ++k)
    for (double nm : {400.0, 550.0, 700.0}) {
      const int i = index_of_nm(nm);
      const double ref = std::max(direct[k][i], floor_fraction * brightest[i]);
      worst = std::max(worst, std::abs(interp[k][i] - direct[k][i]) / ref);
    }
  return worst;
}
}  // namespace

// Interpolation error of the table against Atmosphere::sky_radiance (the direct integral) over
// 400 random directions per case, sun altitudes 4°, 17°, 60° (the paper's figures), single and
// multiple scattering. Bound 0.5% relative (the sky table's accuracy target), everywhere including the
// aureole: the phase functions are applied exactly at look-up, so no directions near the sun
// need to be excluded. Measured worst (printed): 0.31% (4°, single, near the horizon), ≤ 0.08%
// otherwise.
// Twilight (sun −2°): single scattering is exactly zero where the whole view ray lies in the
// Earth's shadow, so a relative bound is meaningless there; the error is taken relative to
// max(L, 1% of the brightest sampled L). Measured: 5.0% single, 0.47% multiple. The single-
// scattering table is NOT within 0.5% in twilight: the Earth's shadow edge on the view rays is a
// kink in direction that cells of ~2–4° smooth over (known limitation, sky_table.h); the bounds
// below (10% single, 1% multiple, where the smooth multiple term dominates) guard against
// regressions, they are not accuracy claims.
BOOST_AUTO_TEST_CASE(interpolation_error_below_half_percent) {
  const Atmosphere atm(AtmosphereParams{});
  for (double alt : {-2.0, 4.0, 17.0, 60.0}) {
    for (auto orders : {ScatteringOrders::Single, ScatteringOrders::Multiple}) {
      const SkyTable table(atm, direction_from_altitude_azimuth(deg(alt), deg(200)), orders);
      const double floor_fraction = alt < 0.0 ? 0.01 : 0.0;
      const double worst = worst_table_error(atm, table, orders, 400, 11u + static_cast<unsigned>(alt + 2.0), floor_fraction);
      BOOST_TEST_MESSAGE("sun " << alt << "°, " << (orders == ScatteringOrders::Single ? "single" : "multiple")
                                << ": worst table error " << worst << (alt < 0.0 ? " (floor 1% of max)" : " (relative)"));
      const double bound = alt >= 0.0 ? 0.005 : (orders == ScatteringOrders::Single ? 0.10 : 0.01);
      BOOST_TEST(worst < bound);
    }
  }
}

// The table keeps the symmetry about the sun's vertical plane and clamps below the horizon.
BOOST_AUTO_TEST_CASE(table_symmetry_and_horizon_clamp) {
  const Atmosphere atm(AtmosphereParams{});
  const double sun_az = deg(75);
  const SkyTable table(atm, direction_from_altitude_azimuth(deg(8), sun_az), ScatteringOrders::Single);
  for (double alt : {0.5, 10.0, 45.0})
    for (double d : {3.0, 60.0, 150.0}) {
      const Spectrum a = table.radiance(direction_from_altitude_azimuth(deg(alt), sun_az + deg(d)));
      const Spectrum b = table.radiance(direction_from_altitude_azimuth(deg(alt), sun_az - deg(d)));
      BOOST_TEST(a[20] == b[20], tt::tolerance(1e-9));
    }
  const Spectrum below = table.radiance(direction_from_altitude_azimuth(deg(-30), deg(10)));
  const Spectrum horizon = table.radiance(direction_from_altitude_azimuth(0.0, deg(10)));
  BOOST_TEST(below[20] == horizon[20], tt::tolerance(1e-12));
}

// Independent check of the single-scattering integral: a pure Rayleigh atmosphere (no aerosol,
// no ozone) with the sun at the zenith is, away from the horizon, a plane-parallel slab of
// optical depth τ whose singly scattered sky radiance has a closed form:
//   L(μ) = E0 p_R(μ)/μ · ∫_0^τ e^{−t} e^{−(τ−t)/μ} dt = E0 p_R(μ) (e^{−τ} − e^{−τ/μ}) / (1 − μ)
// (μ = cos of the view zenith angle = cos of the scattering angle). Compared over view zenith
// cosines μ ∈ [0.2, 1] as the flux E = 2π ∫ L μ dμ: there the spherical air mass differs from
// sec z by < 0.3% (4.98 vs 5.0 at μ = 0.2), so tolerance 0.5%. Nearer the horizon the plane-
// parallel slab is infinitely long while the shell's horizontal air mass is ~35: the full-
// hemisphere fluxes differ by 0.25% / 0.8% / 1.5% at 400 / 550 / 700 nm (measured; larger for
// thinner τ because the slab's horizon radiance saturates at e^{−τ} while the shell's is
// 1 − e^{−35τ}).
BOOST_AUTO_TEST_CASE(rayleigh_zenith_sun_matches_plane_parallel_closed_form) {
  AtmosphereParams p;
  p.aod550 = 0.0;
  p.ozone_du = 0.0;
  const Atmosphere atm(p);
  const Spectrum e0 = Atmosphere::extraterrestrial_irradiance();
  const Spectrum tau = atm.rayleigh_optical_depth();
  const int n = 400;  // midpoint rule in μ on [0.2, 1]; both sides use the same nodes
  Spectrum e_model;
  std::vector<double> mus;
  for (int k = 0; k < n; ++k) {
    const double mu = 0.2 + 0.8 * (k + 0.5) / n;
    const Vec3 v(std::sqrt(1.0 - mu * mu), 0.0, mu);
    e_model += atm.sky_radiance(v, Vec3(0, 0, 1), ScatteringOrders::Single) * (2.0 * kPi * mu * 0.8 / n);
    mus.push_back(mu);
  }
  for (double nm : {400.0, 550.0, 700.0}) {
    const int i = index_of_nm(nm);
    const double t = tau[i];
    double e = 0;
    for (double mu : mus)
      e += 2.0 * kPi * mu * 0.8 / n * e0[i] * rayleigh_phase(mu) * (std::exp(-t) - std::exp(-t / mu)) / (1.0 - mu);
    BOOST_TEST_MESSAGE(nm << " nm: model " << e_model[i] << ", plane-parallel " << e << " (" << 100.0 * (e_model[i] / e - 1.0)
                          << "%)");
    BOOST_TEST(e_model[i] == e, tt::tolerance(0.005));
  }
}

// SkyTable::horizontal_irradiance (Gauss–Legendre over the table) against a fine midpoint rule
// over the direct integral, sun at the zenith (radiance independent of azimuth, so E = 2π∫L μ dμ;
// 2000 nodes in μ, error < 1e-4). Tolerance 0.3%: the table's interpolation error (< 0.05% here)
// plus the 32-node quadrature of the steep horizon brightening.
BOOST_AUTO_TEST_CASE(horizontal_irradiance_quadrature) {
  const Atmosphere atm(AtmosphereParams{});
  const SkyTable table(atm, Vec3(0, 0, 1), ScatteringOrders::Multiple);
  const Spectrum e_table = table.horizontal_irradiance();
  const int n = 2000;
  Spectrum e;
  for (int k = 0; k < n; ++k) {
    const double mu = (k + 0.5) / n;
    e += atm.sky_radiance(Vec3(std::sqrt(1.0 - mu * mu), 0.0, mu), Vec3(0, 0, 1), ScatteringOrders::Multiple) *
         (2.0 * kPi * mu / n);
  }
  for (double nm : {400.0, 550.0, 700.0}) {
    const int i = index_of_nm(nm);
    BOOST_TEST_MESSAGE(nm << " nm: table quadrature " << e_table[i] << ", midpoint " << e[i]);
    BOOST_TEST(e_table[i] == e[i], tt::tolerance(0.003));
  }
}

// Multiple scattering only adds light: the multiple-scattering sky is brighter than the single
// one in every direction and wavelength, and by more at short wavelengths (larger τ_R) for a
// low sun. Its ground-albedo term grows with the albedo.
BOOST_AUTO_TEST_CASE(multiple_scattering_adds_light) {
  const Atmosphere atm(AtmosphereParams{});
  const Vec3 sun = direction_from_altitude_azimuth(deg(17), deg(250));
  const Vec3 zenith(0, 0, 1);
  const Spectrum s = atm.sky_radiance(zenith, sun, ScatteringOrders::Single);
  const Spectrum m = atm.sky_radiance(zenith, sun, ScatteringOrders::Multiple);
  for (int i = 0; i < kSpectrumSamples; ++i) BOOST_TEST(m[i] > s[i]);
  AtmosphereParams bright;
  bright.ground_albedo = 0.8;
  const Spectrum mb = Atmosphere(bright).sky_radiance(zenith, sun, ScatteringOrders::Multiple);
  BOOST_TEST(mb[20] > m[20]);
}
