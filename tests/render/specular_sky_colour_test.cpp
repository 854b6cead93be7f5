#define BOOST_TEST_MODULE specular_sky_colour
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "lighting/brdf/material.h"
#include "lighting/integrals/specular_sky.h"
#include "lighting/sky/sky_radiance_grid.h"
#include "lighting/spectrum/colour.h"
#include "lighting/support/analytic_sky.h"
#include "lighting/support/hand_cache.h"
#include "render/specular_sky_colour.h"

namespace tt = boost::test_tools;
using namespace skyband;
using skyband::test::single_point_cache;
using skyband::test::view_at;

namespace {
double deg(double d) {
  return d * kPi / 180.0;
}
std::vector<std::pair<double, double>> some_occlusion(int band, double delta) {
  if (band % 7 == 3) return {};
  return {{0.0, 1.1}, {1.3 + 0.2 * std::sin(3.0 * delta), 2.5}, {2.7, kPi}};
}
}  // namespace

// The XYZ march against the spectral march on the same gridded sky, converted with the CIE
// weights afterwards (an independent path: 41 radiances × the full Fresnel table per node). The
// nodes are the same; what differs is (1) the Fresnel separation, ≤ 5·10⁻⁴ absolute in F, i.e.
// ≤ 6·10⁻⁴ relative for F ≥ 0.9 (aluminium) and 0 for dielectrics (rank 1, exact), and (2) the
// truncation measure G (luminance vs channel mean). With ε = 10⁻⁹ truncation vanishes and only
// (1) remains: tolerance 10⁻³. At the default ε both are within their 1% truncation target of
// the full integral, so they agree within 2%.
BOOST_AUTO_TEST_CASE(colour_march_matches_spectral_march) {
  const Vec3 sun = Vec3(0.4, -0.5, 0.6).normalized();
  const SkyRadianceGrid grid([&](const Vec3& d, Spectrum& out) { test::clear_sky_radiance(sun, d, out); }, 0);
  for (const char* name : {"window-glass", "ceramic-tile", "aluminium-panel", "painted-wall"}) {
    const Material& m = find_material(name);
    const ColourSpecularSky colour(grid, &m.fresnel);
    for (const Vec3& n : {Vec3(0, 0, 1), Vec3(0.8, 0.6, 0), Vec3(-0.3, 0.4, 0.8)})
      for (bool occluded : {false, true}) {
        const VisibilityCache vc = occluded ? single_point_cache(n, 64, some_occlusion) : single_point_cache(n, 64);
        const PointVisibilityView v = vc.view(0);
        for (auto [tv, pv] : {std::pair{10.0, 0.3}, std::pair{50.0, 2.0}, std::pair{75.0, 4.0}}) {
          const Vec3 view = view_at(n, deg(tv), pv);
          for (double eps : {1e-9, 1e-3}) {
            SpecularSkyOptions opt;
            opt.epsilon = eps;
            const Xyz c = colour.radiance_xyz(v, view, m.specular_lobe(), opt);
            const Xyz s = spectrum_to_xyz(specular_sky_radiance(v, view, m.specular_lobe(), grid, opt));
            const double tol = eps < 1e-6 ? 1e-3 : 2e-2;
            const double floor = 1e-6;  // lobes wholly below the horizon reflect ~0
            BOOST_TEST(std::abs(c.Y - s.Y) <= tol * std::max(s.Y, floor), name << " n " << n.transpose() << " occl " << occluded
                                                                               << " θv " << tv << " ε " << eps << ": " << c.Y
                                                                               << " vs " << s.Y);
            BOOST_TEST(std::abs(c.Z - s.Z) <= tol * std::max(s.Z, floor));
          }
        }
      }
  }
}

// A lobe built for another Fresnel table is a programming error, not a silent mismatch.
BOOST_AUTO_TEST_CASE(fresnel_table_must_match) {
  const SkyRadianceGrid grid([](const Vec3&, Spectrum& out) { out = Spectrum::constant(1.0); }, 1);
  const ColourSpecularSky colour(grid, &find_material("ceramic-tile").fresnel);
  const VisibilityCache vc = single_point_cache(Vec3(0, 0, 1), 16);
  BOOST_CHECK_THROW(colour.radiance_xyz(vc.view(0), Vec3(0, 0.3, 1), find_material("window-glass").specular_lobe()),
                    std::logic_error);
}

// White furnace in XYZ: uniform sky L(λ) = 1, F = 1 → XYZ = albedo·(Σ W_c), the albedo from the
// independent half-vector quadrature cook_torrance_albedo (accurate to 3·10⁻⁴), within the
// march's 1% target.
BOOST_AUTO_TEST_CASE(white_furnace_in_xyz) {
  const SkyRadianceGrid grid([](const Vec3& d, Spectrum& out) { out = Spectrum::constant(d.z() > 0 ? 1.0 : 0.0); }, 1);
  const ColourSpecularSky colour(grid, nullptr);
  const VisibilityCache vc = single_point_cache(Vec3(0, 0, 1), 64);
  const Xyz unit = spectrum_to_xyz(Spectrum::constant(1.0));
  for (double m : {0.1, 0.3})
    for (double tv : {0.0, 45.0, 70.0}) {
      const SpecularLobe lobe{m, 1.0, nullptr, false};
      const Xyz r = colour.radiance_xyz(vc.view(0), view_at(Vec3(0, 0, 1), deg(tv), 0.7), lobe);
      const double albedo = cook_torrance_albedo(m, deg(tv));
      BOOST_TEST(r.Y == albedo * unit.Y, tt::tolerance(1e-2));
      BOOST_TEST(r.X == albedo * unit.X, tt::tolerance(1e-2));
    }
}

// Runtime dispatch (specular_sky_colour.h): the AVX2 + FMA build of the march, when this
// processor runs it, against the portable build of the same source. Same nodes and stop
// decisions; FMA rounds once where the portable build rounds twice, so sums differ by a few
// ulps per operation, ~10⁻¹³ relative after ~10³ evaluations: tolerance 10⁻⁹ (a stop decision
// flipped by a last-bit tie would move the result by up to ε = 10⁻³ of the total, and would
// fail it). Every material rank (glass 1, aluminium 4), open and occluded, several views.
// Where the processor lacks AVX2 the two are the same function and must agree exactly.
BOOST_AUTO_TEST_CASE(avx2_build_matches_portable_build) {
  BOOST_TEST_MESSAGE("AVX2 + FMA march in use: " << ColourSpecularSky::uses_avx2());
  const Vec3 sun = Vec3(0.4, -0.5, 0.6).normalized();
  const SkyRadianceGrid grid([&](const Vec3& d, Spectrum& out) { test::clear_sky_radiance(sun, d, out); }, 0);
  for (const char* name : {"window-glass", "ceramic-tile", "aluminium-panel"}) {
    const Material& m = find_material(name);
    const ColourSpecularSky colour(grid, &m.fresnel);
    for (const Vec3& n : {Vec3(0, 0, 1), Vec3(0.8, 0.6, 0), Vec3(-0.3, 0.4, 0.8)})
      for (bool occluded : {false, true}) {
        const VisibilityCache vc = occluded ? single_point_cache(n, 64, some_occlusion) : single_point_cache(n, 64);
        for (auto [tv, pv] : {std::pair{10.0, 0.3}, std::pair{50.0, 2.0}, std::pair{80.0, 4.0}}) {
          const Vec3 view = view_at(n, deg(tv), pv);
          SpecularSkyStats sd, sp;
          const Xyz d = colour.radiance_xyz(vc.view(0), view, m.specular_lobe(), {}, &sd);
          const Xyz p = colour.radiance_xyz_portable(vc.view(0), view, m.specular_lobe(), {}, &sp);
          BOOST_TEST(sd.radiance_evals == sp.radiance_evals);
          for (auto [a, b] : {std::pair{d.X, p.X}, std::pair{d.Y, p.Y}, std::pair{d.Z, p.Z}}) {
            BOOST_TEST(std::abs(a - b) <= 1e-9 * std::max(std::abs(b), 1e-12), name << " θv " << tv << ": " << a << " vs " << b);
            if (!ColourSpecularSky::uses_avx2()) BOOST_TEST(a == b);
          }
        }
      }
  }
}
