#define BOOST_TEST_MODULE sky_column_table
#include <boost/test/unit_test.hpp>

// The per-sky column tables (lighting/integrals/sky_column_table.h) against two independent computations:
// the definition of the cosine-weighted SVF under a uniform sky (E = π·L·SVF, with the exact
// horizon's closed-form SVF), and the two-dimensional Gauss–Legendre quadrature over the same fan
// (geometry/exact/sky_fan.h: integrate_fan_channels, which looks the sky grid up directly) under a
// physical sky with its aureole.

#include <array>
#include <cmath>
#include <vector>

#include "geometry/horizon/horizon_svf.h"
#include "geometry/mesh/triangle_soup.h"
#include "lighting/integrals/sky_column_table.h"
#include "lighting/sky/sky_model.h"
#include "lighting/sun/sun.h"

using namespace skyband;

namespace {

constexpr double kDeg = kPi / 180.0;

// A street block: two rows of boxes and a tower (column solids on no ground).
Scene block() {
  TriangleSoup soup;
  append_box(soup, Vec3(-20, -40, 0), Vec3(-6, 40, 18));
  append_box(soup, Vec3(6, -40, 0), Vec3(20, 40, 12));
  append_box(soup, Vec3(25, -8, 0), Vec3(45, 8, 60));
  return Scene(soup);
}

std::vector<QueryPoint> block_points() {
  return {{Vec3(0, -30, 0), Vec3(0, 0, 1)},      {Vec3(0, 0, 0), Vec3(0, 0, 1)},
          {Vec3(-5.9, -30, 1.5), Vec3(1, 0, 0)}, {Vec3(5.9, 10, 4.5), Vec3(-1, 0, 0)},
          {Vec3(16, -30, 12), Vec3(0, 0, 1)},    {Vec3(0, 20, 3), Vec3(0.3, -0.4, 0.866).normalized()},
          {Vec3(-80, -80, 0), Vec3(0, 0, 1)},    {Vec3(24.9, 0, 20), Vec3(-1, 0, 0)}};
}

ProjectedSkyGrid two_channels(const SkyRadianceGrid& g) {
  Spectrum w0 = Spectrum::constant(1.0), w1 = Spectrum::constant(0.0);
  w1[20] = 1.0;  // one wavelength alone: a second, differently shaped channel
  return g.project(std::array<Spectrum, 2>{w0, w1});
}

}  // namespace

BOOST_AUTO_TEST_CASE(uniform_sky_gives_pi_times_svf) {
  const Scene scene = block();
  HorizonSvf h(scene, scene.column_scene(), 1e-6);
  const SkyRadianceGrid grid([](const Vec3&, Spectrum& out) { out = Spectrum::constant(1.0); }, 1);
  const ProjectedSkyGrid projected = two_channels(grid);
  const SkyColumnTable table(projected, 1);
  std::vector<SkyFanTriangle> fan;
  for (const QueryPoint& q : block_points()) {
    SkyFactors f;
    BOOST_TEST_REQUIRE(h.compute(q, f));
    h.visible_fan(fan);
    double e[2];
    table.integrate_fan(fan, q.normal, e, 0.05);
    // Channel 0 is Σ_λ 1 = 41 per sr, channel 1 is 1 per sr. Tolerance 1e-5 relative: the tables'
    // bilinear interpolation in elevation (0.25° cells: ~Δe²/8·|S''| ≈ 2e-6) and the azimuth
    // quadrature of steep arcs (geometry/exact/sky_fan.h).
    BOOST_TEST(std::abs(e[0] - 41 * kPi * f.svf) < 1e-5 * 41 * kPi, "e0 " << e[0] << " svf " << f.svf);
    BOOST_TEST(std::abs(e[1] - kPi * f.svf) < 1e-5 * kPi);
  }
}

BOOST_AUTO_TEST_CASE(physical_sky_matches_the_direct_fan_quadrature) {
  const Scene scene = block();
  HorizonSvf h(scene, scene.column_scene(), 1e-6);
  for (double altitude : {8.0, 35.0, 70.0}) {
    const SkyModel sky(AtmosphereParams{}, direction_from_altitude_azimuth(altitude * kDeg, 200 * kDeg), SkyModelSpec{});
    const SkyRadianceGrid grid([&](const Vec3& d, Spectrum& out) { sky.radiance_into(d, out); }, 0);
    const ProjectedSkyGrid projected = two_channels(grid);
    const SkyColumnTable table(projected, 0);
    double open[2];
    {
      const Scene empty{TriangleSoup{}};
      HorizonSvf h0(empty, empty.column_scene(), 0.0);
      SkyFactors f;
      std::vector<SkyFanTriangle> fan;
      BOOST_TEST_REQUIRE(h0.compute(QueryPoint{Vec3(0, 0, 0), Vec3(0, 0, 1)}, f));
      h0.visible_fan(fan);
      table.integrate_fan(fan, Vec3(0, 0, 1), open, 0.05);
    }
    std::vector<SkyFanTriangle> fan;
    for (const QueryPoint& q : block_points()) {
      SkyFactors f;
      BOOST_TEST_REQUIRE(h.compute(q, f));
      h.visible_fan(fan);
      double a[2], b[2];
      table.integrate_fan(fan, q.normal, a, 0.05);
      integrate_fan_channels<2>(
          fan, q.normal, [&](const Vec3& d, double* c) { projected.lookup_unit_n<2>(d, c); }, b, 0.0125);
      // Relative to the open sky's horizontal irradiance: both read the same grid; what differs is
      // the tables' bilinear interpolation across the aureole (0.25° columns) and the quadratures
      // (measured ≤ 1e-5, worst with the sun at 8°).
      for (int k = 0; k < 2; ++k)
        BOOST_TEST(std::abs(a[k] - b[k]) < 2e-5 * open[k],
                   "altitude " << altitude << " channel " << k << ": " << a[k] << " vs " << b[k]);
    }
  }
}

BOOST_AUTO_TEST_CASE(needs_two_channels) {
  const SkyRadianceGrid grid([](const Vec3&, Spectrum& out) { out = Spectrum::constant(1.0); }, 1);
  const ProjectedSkyGrid one = grid.project(std::array<Spectrum, 1>{Spectrum::constant(1.0)});
  BOOST_CHECK_THROW(SkyColumnTable(one, 1), std::invalid_argument);
}
