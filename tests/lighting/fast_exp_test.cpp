#define BOOST_TEST_MODULE fast_exp
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>

#include "lighting/brdf/beckmann.h"
#include "lighting/brdf/cook_torrance.h"
#include "lighting/integrals/fast_exp.h"

using namespace skyband;

// Against std::exp over the tabulated range, densely and at the table nodes and just below them:
// the Taylor remainder bound f⁵/120 with f < 1/64 is 2.7·10⁻¹¹ relative; 1e-10 allows rounding.
BOOST_AUTO_TEST_CASE(matches_std_exp) {
  double worst = 0;
  for (int i = 0; i < 640000; ++i) {  // [0, 64)
    const double x = i * 1e-4;
    worst = std::max(worst, std::abs(exp_neg(x) / std::exp(-x) - 1.0));
  }
  for (int k = 0; k < 64 * 64; ++k) {
    const double x = std::nextafter(k / 64.0 + 1.0 / 64.0, 0.0);
    worst = std::max(worst, std::abs(exp_neg(x) / std::exp(-x) - 1.0));
  }
  BOOST_TEST(worst <= 1e-10);
  BOOST_TEST_MESSAGE("max relative deviation " << worst);
}

// Outside the table std::exp itself: nothing is flushed to 0 (fast_exp.h says why).
BOOST_AUTO_TEST_CASE(out_of_range) {
  BOOST_TEST(exp_neg(64.5) == std::exp(-64.5));
  BOOST_TEST(exp_neg(700.0) == std::exp(-700.0));
  BOOST_TEST(exp_neg(1e300) == 0.0);
  BOOST_TEST(exp_neg(-1.0) == std::exp(1.0));
  BOOST_TEST(std::isnan(exp_neg(std::numeric_limits<double>::quiet_NaN())));
}

// The lobe factor of the sky march equals the library's to 1e-10 (same formula, other exp).
BOOST_AUTO_TEST_CASE(fast_lobe_factor_matches) {
  for (double m : {0.01, 0.1, 0.5})
    for (double ch : {0.3, 0.9, 0.999, 1.0}) {
      MicrofacetCosines c;
      c.n_dot_h = ch;
      c.n_dot_l = 0.7;
      c.n_dot_v = 0.6;
      c.v_dot_h = 0.8;
      const SpecularLobe lobe{m, 0.5, nullptr, false};
      const double a = lobe.factor(c), b = lobe.factor_fast(c);
      BOOST_TEST(std::abs(a - b) <= 1e-10 * std::abs(a) + 1e-300);
    }
}
