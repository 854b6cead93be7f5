#define BOOST_TEST_MODULE sky_radiance_grid
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "lighting/sky/sky_radiance_grid.h"
#include "lighting/spectrum/colour.h"
#include "lighting/support/analytic_sky.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {
// CIE standard overcast sky with a spectral tilt: L = (1 + 2 cos Z)/3 · (0.5 + i/40), a smooth
// function of p = (x, y)/(1 + z) (z = (1 − |p|²)/(1 + |p|²)), 0 at and below the horizon.
void overcast(const Vec3& d, Spectrum& out) {
  const double z = d.normalized().z();
  for (int i = 0; i < kSpectrumSamples; ++i) out[i] = z > 0 ? (1.0 + 2.0 * z) / 3.0 * (0.5 + i / 40.0) : 0.0;
}
Vec3 dir(double alt_deg, double az_deg) {
  const double a = alt_deg * kPi / 180, b = az_deg * kPi / 180;
  return Vec3(std::cos(a) * std::sin(b), std::cos(a) * std::cos(b), std::sin(a));
}
}  // namespace

// Bilinear interpolation on the stereographic grid: error ≤ (h²/8)(|∂²L/∂px²| + |∂²L/∂py²|),
// h = 2/400; for the overcast sky ∂²z/∂p² ≤ 4 in magnitude, so the error is ≤ 2.5·10⁻⁵·(2/3)·2·4
// ≈ 1.3·10⁻⁴ of L at 760 nm (factor 1.5): tolerance 2·10⁻⁴ absolute.
BOOST_AUTO_TEST_CASE(interpolates_a_smooth_sky) {
  const SkyRadianceGrid grid(overcast, 1);
  Spectrum g, e;
  for (double alt : {0.05, 1.0, 10.0, 33.3, 60.0, 89.0, 90.0})
    for (double az : {0.0, 17.0, 135.0, 222.2, 359.0}) {
      grid(dir(alt, az), g);
      overcast(dir(alt, az), e);
      for (int i : {0, 20, 40}) BOOST_TEST(std::abs(g[i] - e[i]) <= 2e-4, "alt " << alt << " az " << az << " i " << i);
    }
  // Any length of the direction vector (the projection uses ω/|ω|).
  Spectrum g2;
  grid(3.0 * dir(40, 70), g2);
  grid(dir(40, 70), g);
  BOOST_TEST(g2[10] == g[10], tt::tolerance(1e-12));
}

// At and below the horizon the grid gives 0, like the sky models; non-finite directions too.
BOOST_AUTO_TEST_CASE(zero_below_horizon) {
  const SkyRadianceGrid grid(overcast, 1);
  Spectrum g;
  for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0.3, 0.4, -0.2), Vec3(0, 0, -1), Vec3(0, 0, 0), Vec3(std::nan(""), 0, 1)}) {
    grid(d, g);
    for (int i = 0; i < kSpectrumSamples; ++i) BOOST_TEST(g[i] == 0.0);
  }
}

// Projection commutes with interpolation: the projected grid's channel k equals the dot product
// of weight k with the interpolated spectrum (to float storage, ~1e-7 relative).
BOOST_AUTO_TEST_CASE(projection_commutes_with_lookup) {
  const Vec3 sun = dir(35, 140);
  const SkyRadianceGrid grid([&](const Vec3& d, Spectrum& out) { test::clear_sky_radiance(sun, d, out); }, 0);
  const std::vector<Spectrum> w = {xyz_weights(0), xyz_weights(1), xyz_weights(2), Spectrum::constant(1.0)};
  const ProjectedSkyGrid p = grid.project(w);
  BOOST_TEST(p.channels() == 4);
  Spectrum l;
  double out[ProjectedSkyGrid::kMaxChannels];
  for (const Vec3& d : {dir(35, 140), dir(5, 10), dir(70, 300), dir(0.2, 200)}) {
    grid(d, l);
    p.lookup(d, out);
    const Xyz xyz = spectrum_to_xyz(l);
    BOOST_TEST(out[0] == xyz.X, tt::tolerance(1e-6));
    BOOST_TEST(out[1] == xyz.Y, tt::tolerance(1e-6));
    BOOST_TEST(out[2] == xyz.Z, tt::tolerance(1e-6));
    double sum = 0;
    for (int i = 0; i < kSpectrumSamples; ++i) sum += l[i];
    BOOST_TEST(out[3] == sum, tt::tolerance(1e-6));
    double out4[4];
    p.lookup_n<4>(d, out4);
    for (int k = 0; k < 4; ++k) BOOST_TEST(out4[k] == out[k]);
  }
  BOOST_CHECK_THROW(grid.project(std::vector<Spectrum>{}), std::invalid_argument);
  BOOST_CHECK_THROW(grid.project(std::vector<Spectrum>(13)), std::invalid_argument);
}

// add_scaled: by the linearity of bilinear interpolation, a look-up in a + k·b equals the look-up
// in a plus k times the look-up in b (up to the float storage of the sum, ~1e-7 relative).
BOOST_AUTO_TEST_CASE(add_scaled_sums_lookups) {
  const Vec3 sun1 = dir(35, 140), sun2 = dir(10, 250);
  const std::vector<Spectrum> w = {xyz_weights(1), Spectrum::constant(1.0)};
  const ProjectedSkyGrid a =
      SkyRadianceGrid([&](const Vec3& d, Spectrum& out) { test::clear_sky_radiance(sun1, d, out); }, 0).project(w);
  const ProjectedSkyGrid b =
      SkyRadianceGrid([&](const Vec3& d, Spectrum& out) { test::clear_sky_radiance(sun2, d, out); }, 0).project(w);
  ProjectedSkyGrid sum;  // empty: takes a's shape
  sum.add_scaled(a, 1.0);
  sum.add_scaled(b, 0.25);
  BOOST_TEST(sum.channels() == 2);
  double ra[2], rb[2], rs[2];
  for (const Vec3& d : {dir(35, 140), dir(5, 10), dir(70, 300), dir(12, 251)}) {
    a.lookup(d, ra);
    b.lookup(d, rb);
    sum.lookup(d, rs);
    for (int k = 0; k < 2; ++k) BOOST_TEST(rs[k] == ra[k] + 0.25 * rb[k], tt::tolerance(1e-6));
  }
  const ProjectedSkyGrid three = SkyRadianceGrid([&](const Vec3& d, Spectrum& out) { test::clear_sky_radiance(sun1, d, out); }, 0)
                                     .project(std::vector<Spectrum>{xyz_weights(0), xyz_weights(1), xyz_weights(2)});
  BOOST_CHECK_THROW(sum.add_scaled(three, 1.0), std::invalid_argument);
}
