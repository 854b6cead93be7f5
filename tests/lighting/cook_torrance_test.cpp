#define BOOST_TEST_MODULE cook_torrance
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "lighting/brdf/beckmann.h"
#include "lighting/brdf/cook_torrance.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {
double deg(double d) {
  return d * kPi / 180.0;
}

Vec3 spherical(double theta, double phi) {
  return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

// Brute-force albedo in light-direction space, ∫ f_s cos θ_l dω_l, composite midpoint in
// (μ = cos θ_l, φ) restricted to a window of half-width `win` around the mirror direction
// where the lobe lives (outside it f_s < e^{-(win/2m)^2}·… is negligible), plus a coarse
// whole-hemisphere pass. Independent of the half-vector substitution used by the library.
double albedo_light_space(double m, double theta_v, int n) {
  const Vec3 nrm(0, 0, 1), v = spherical(theta_v, 0);
  double sum = 0;
  // Integrate over θ_l ∈ [0, π/2], φ ∈ [−π, π] with sin θ dθ dφ, midpoint, n × 4n cells.
  const int nt = n, np = 4 * n;
  const double dt = (kPi / 2) / nt, dp = 2 * kPi / np;
  for (int i = 0; i < nt; ++i) {
    const double t = (i + 0.5) * dt;
    for (int j = 0; j < np; ++j) {
      const double p = -kPi + (j + 0.5) * dp;
      const Vec3 l = spherical(t, p);
      sum += cook_torrance_fs(nrm, l, v, m, 1.0) * l.z() * std::sin(t) * dt * dp;
    }
  }
  return sum;
}
}  // namespace

// White furnace (F = 1) against reference-notes §4.2's table [C] (3 decimals). The library's
// quadrature (600², midpoint in w and φ) is accurate to ~3e-4 (the jump at the horizon), plus
// ≤ 5e-4 rounding of the table: tolerance 1.5e-3. And always ≤ 1 (energy conservation).
BOOST_AUTO_TEST_CASE(white_furnace_table) {
  const double ms[] = {0.1, 0.2, 0.3, 0.5};
  const double tv[] = {0, 30, 60, 75};
  const double table[4][4] = {
      {1.000, 1.000, 0.999, 0.970}, {1.000, 0.999, 0.966, 0.928}, {0.996, 0.981, 0.925, 0.927}, {0.892, 0.875, 0.887, 0.934}};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const double a = cook_torrance_albedo(ms[i], deg(tv[j]));
      BOOST_TEST(std::abs(a - table[i][j]) <= 1.5e-3, "m = " << ms[i] << " θv = " << tv[j] << ": " << a);
      BOOST_TEST(a <= 1.0 + 3e-4, "albedo above 1 beyond quadrature error: " << a);
    }
}

// The quadrature converges: 600² vs 1200² nodes differ by less than the 3e-4 error claimed above.
BOOST_AUTO_TEST_CASE(albedo_quadrature_converges) {
  for (double m : {0.1, 0.5})
    for (double t : {0.0, 60.0}) {
      const double a = cook_torrance_albedo(m, deg(t), 600), b = cook_torrance_albedo(m, deg(t), 1200);
      BOOST_TEST(std::abs(a - b) <= 3e-4);
    }
}

// Independent cross-check in light-direction space (brute force, 400 × 1600 midpoint cells of
// 0.22°, against a reflected lobe ≈ √2·m rad ≈ 16° wide for m = 0.2): both quadratures carry
// O(1/n) errors from the horizon cut-off and the kinks of G, observed ≤ 1e-3; bound 2e-3.
BOOST_AUTO_TEST_CASE(albedo_light_space_cross_check) {
  for (double m : {0.2, 0.5})
    for (double t : {0.0, 45.0, 75.0}) {
      const double a = cook_torrance_albedo(m, deg(t)), b = albedo_light_space(m, deg(t), 400);
      BOOST_TEST(std::abs(a - b) <= 2e-3, "m = " << m << " θv = " << t << ": " << a << " vs " << b);
    }
}

// The seed's 1982 form R_s is exactly 4 f_s (reference-notes §4.2), so its "albedo" is ≈ 4.
BOOST_AUTO_TEST_CASE(paper_scale) {
  const Vec3 n(0, 0, 1), l = spherical(deg(30), 0.2), v = spherical(deg(35), kPi + 0.1);
  const double fs = cook_torrance_fs(n, l, v, 0.3, 0.7);
  BOOST_TEST(fs > 0.0);
  BOOST_TEST(cook_torrance_fs(n, l, v, 0.3, 0.7, true) == 4.0 * fs, tt::tolerance(1e-14));
  BOOST_TEST(cook_torrance_albedo(0.1, 0.0, 300, true) == 4.0 * cook_torrance_albedo(0.1, 0.0, 300), tt::tolerance(1e-14));
  // Directly from the paper's formula with D_CT = exp(−tan²α/m²)/(m² cos⁴α):
  MicrofacetCosines c;
  BOOST_REQUIRE(microfacet_cosines(n, l, v, c));
  const double ta = std::tan(std::acos(c.n_dot_h));
  const double d_ct = std::exp(-ta * ta / 0.09) / (0.09 * std::pow(c.n_dot_h, 4));
  const double g = cook_torrance_g(c.n_dot_h, c.n_dot_v, c.n_dot_l, c.v_dot_h);
  const double rs = 0.7 / kPi * d_ct * g / (c.n_dot_l * c.n_dot_v);
  BOOST_TEST(cook_torrance_fs(n, l, v, 0.3, 0.7, true) == rs, tt::tolerance(1e-12));
}

// Reciprocity f(l, v) = f(v, l) over a set of direction pairs and roughnesses (exact symmetry:
// H, D and G are symmetric in L and V; tolerance is rounding).
BOOST_AUTO_TEST_CASE(reciprocity) {
  const Vec3 n = Vec3(0.2, -0.3, 1).normalized();
  int checked = 0;
  for (double m : {0.05, 0.2, 0.5})
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) {
        const Vec3 l = spherical(deg(5 + 7 * i), 0.5 * i), v = spherical(deg(3 + 7 * j), 2.0 + 0.4 * j);
        const double a = cook_torrance_fs(n, l, v, m, 1.0), b = cook_torrance_fs(n, v, l, m, 1.0);
        BOOST_TEST(a == b, tt::tolerance(1e-12));
        if (a > 0) ++checked;
      }
  BOOST_TEST(checked > 100);  // the loop really exercises non-zero values
}

// Below-surface directions give zero, never NaN.
BOOST_AUTO_TEST_CASE(below_surface) {
  const Vec3 n(0, 0, 1);
  BOOST_TEST(cook_torrance_fs(n, Vec3(0, 0, -1), Vec3(0, 0, 1), 0.3, 1.0) == 0.0);
  BOOST_TEST(cook_torrance_fs(n, Vec3(1, 0, 0), Vec3(-1, 0, 0), 0.3, 1.0) == 0.0);
  BOOST_TEST(cook_torrance_fs(n, Vec3(0, 0, 1), Vec3(0, 0, 1), 0.001, 1.0) == 1.0 / (4 * kPi * 1e-6),
             tt::tolerance(1e-12));  // D_n(0)/4 at L = V = N
}
