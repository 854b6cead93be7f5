#define BOOST_TEST_MODULE fresnel_factors
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <stdexcept>

#include "lighting/brdf/fresnel.h"
#include "lighting/brdf/fresnel_factors.h"
#include "lighting/brdf/material.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {
// Largest |Σ_j U_j(cos θ) V_j(λ) − F_table(λ, cos θ)| over the table nodes and half-way points.
double max_deviation(const FresnelTable& t, const FresnelFactors& f) {
  double worst = 0;
  for (int n = 0; n <= 2 * (FresnelTable::kNodes - 1); ++n) {
    const double c = n / (2.0 * (FresnelTable::kNodes - 1));
    double u[FresnelFactors::kMaxRank];
    f.u(c, u);
    const Spectrum exact = t.eval(c);
    for (int i = 0; i < kSpectrumSamples; ++i) {
      double sum = 0;
      for (int j = 0; j < f.rank(); ++j) sum += u[j] * f.v(j)[i];
      worst = std::max(worst, std::abs(sum - exact[i]));
    }
  }
  return worst;
}
}  // namespace

// A real, wavelength-independent index gives the same F at every wavelength: exactly rank 1
// (the matrix is u·1ᵀ), reproduced to rounding. The value is the closed form fresnel_dielectric.
BOOST_AUTO_TEST_CASE(dielectric_is_rank_one) {
  const FresnelTable t = FresnelTable::dielectric(1.5);
  const FresnelFactors f(t);
  BOOST_TEST(f.rank() == 1);
  BOOST_TEST(max_deviation(t, f) <= 1e-12);
  double u[FresnelFactors::kMaxRank];
  f.u(1.0, u);
  BOOST_TEST(u[0] * f.v(0)[20] == fresnel_dielectric(1.0, 1.5), tt::tolerance(1e-12));  // 0.04
  const FresnelFactors one(FresnelTable::one());
  BOOST_TEST(one.rank() == 1);
  BOOST_TEST(max_deviation(FresnelTable::one(), one) <= 1e-12);
}

// Aluminium (spectral n, k): the separation meets its tolerance everywhere, including between
// nodes (linear interpolation of U commutes with the sum), and a tighter tolerance needs at least
// the same rank (Eckart–Young: the truncated SVD is the best rank-r approximation).
BOOST_AUTO_TEST_CASE(aluminium_within_tolerance) {
  const Material& al = find_material("aluminium-panel");
  const FresnelFactors f(al.fresnel);
  BOOST_TEST(f.rank() >= 2);
  BOOST_TEST(f.rank() <= FresnelFactors::kMaxRank);
  BOOST_TEST(f.max_abs_error() <= 5e-4);
  BOOST_TEST(max_deviation(al.fresnel, f) <= 5e-4 + 1e-12);
  const FresnelFactors loose(al.fresnel, 3e-2);
  BOOST_TEST(loose.rank() <= f.rank());
  BOOST_TEST(max_deviation(al.fresnel, loose) <= 3e-2);
  BOOST_TEST_MESSAGE("aluminium: rank " << f.rank() << ", max deviation " << f.max_abs_error());
}

// Impossible requests are errors, not silent truncation.
BOOST_AUTO_TEST_CASE(bad_tolerance) {
  const Material& al = find_material("aluminium-panel");
  BOOST_CHECK_THROW(FresnelFactors(al.fresnel, 0.0), std::invalid_argument);
  BOOST_CHECK_THROW(FresnelFactors(al.fresnel, 1e-9), std::invalid_argument);
}
