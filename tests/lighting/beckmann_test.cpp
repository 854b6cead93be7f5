#define BOOST_TEST_MODULE beckmann
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "lighting/brdf/beckmann.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {
// ∫_hemisphere D_n(θ) cos θ dω = 2π ∫_0^{π/2} D_n(θ) cos θ sin θ dθ by composite 4-point
// Gauss–Legendre in θ (an independent quadrature: no change of variables shared with the code).
double projected_area(double m, int pieces) {
  static constexpr double xg[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static constexpr double wg[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  const double h = (kPi / 2) / pieces;
  double sum = 0;
  for (int p = 0; p < pieces; ++p) {
    const double mid = (p + 0.5) * h;
    for (int g = 0; g < 4; ++g) {
      const double t = mid + 0.5 * h * xg[g];
      sum += 0.5 * h * wg[g] * beckmann_d(std::cos(t), m) * std::cos(t) * std::sin(t);
    }
  }
  return 2 * kPi * sum;
}
}  // namespace

// Normalisation ∫ D_n cos θ_h dω = 1 (reference-notes §4.2). With 4000 GL pieces the step is
// 4·10⁻⁴ rad, ≤ 1/100 of the lobe width m/√2 even for m = 0.05: quadrature error ≪ 1e-9.
BOOST_AUTO_TEST_CASE(normalised) {
  for (double m : {0.05, 0.1, 0.3, 0.5}) {
    const double a = projected_area(m, 4000);
    BOOST_TEST(a == 1.0, tt::tolerance(1e-9));
  }
}

// Peak value D_n(0) = 1/(π m²) (closed form), and D_CT = π·D_n: D_n(θ)·π m² cos⁴θ = exp(−tan²θ/m²).
BOOST_AUTO_TEST_CASE(closed_form_values) {
  for (double m : {0.05, 0.3}) {
    BOOST_TEST(beckmann_d(1.0, m) == 1.0 / (kPi * m * m), tt::tolerance(1e-14));
    const double t = 0.2, c = std::cos(t);
    BOOST_TEST(beckmann_d(c, m) * kPi * m * m * std::pow(c, 4) == std::exp(-std::pow(std::tan(t) / m, 2)), tt::tolerance(1e-12));
  }
  BOOST_TEST(beckmann_d(0.0, 0.3) == 0.0);
  BOOST_TEST(beckmann_d(-0.5, 0.3) == 0.0);
}

// G by hand: at normal incidence and normal view (N = H = L = V) no masking, G = 1. For
// V at 80° from N in the plane of L = N: H bisects, N·H = cos 40°, V·H = cos 40°,
// 2(N·H)(N·V)/(V·H) = 2 cos 80° = 0.3473 < 1 (masking limits it).
BOOST_AUTO_TEST_CASE(geometric_attenuation) {
  BOOST_TEST(cook_torrance_g(1, 1, 1, 1) == 1.0);
  const double c40 = std::cos(40 * kPi / 180), c80 = std::cos(80 * kPi / 180);
  BOOST_TEST(cook_torrance_g(c40, c80, 1.0, c40) == 2 * c80, tt::tolerance(1e-14));
  // Symmetric in L and V.
  BOOST_TEST(cook_torrance_g(c40, 1.0, c80, c40) == cook_torrance_g(c40, c80, 1.0, c40));
  // Below the surface: 0.
  BOOST_TEST(cook_torrance_g(0.9, -0.1, 0.5, 0.7) == 0.0);
}
