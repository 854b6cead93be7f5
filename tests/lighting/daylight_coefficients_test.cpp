#define BOOST_TEST_MODULE daylight_coefficients
#include <boost/test/unit_test.hpp>

// Daylight coefficients (lighting/integrals/daylight_coefficients.h) against closed forms: under a uniform
// sky of radiance 1 the coefficients sum to π·SVF (Lambert), the SVF being the exact region's
// (geometry/visibility/visible_sky.h, checked against an exact oracle elsewhere); under a sky linear in the
// direction's height, L = ω_z, an open horizontal face receives ∫ ω_z cos θ dω = 2π/3. The grid's
// hat functions are integrated to second order at their kinks: the bounds are the measured
// accuracy with margin.

#include <cmath>
#include <numeric>
#include <vector>

#include "geometry/mesh/scene.h"
#include "geometry/visibility/sky_visibility.h"
#include "lighting/integrals/daylight_coefficients.h"

using namespace skyband;

namespace {

void add_quad(TriangleSoup& s, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const auto base = std::uint32_t(s.vertices.size());
  s.vertices.insert(s.vertices.end(), {a, b, c, d});
  s.triangles.push_back({base, base + 1, base + 2});
  s.triangles.push_back({base, base + 2, base + 3});
}

double dot_sky(const std::vector<float>& dc, double (*sky)(const Vec3&)) {
  const auto& nodes = daylight_nodes();
  double e = 0;
  for (std::size_t j = 0; j < nodes.size(); ++j)
    e += dc[j] * std::max(0.0, nodes[j].a * sky(nodes[j].da) + nodes[j].b * sky(nodes[j].db));
  return e;
}

double uniform(const Vec3& d) {
  return d.z() > 0 ? 1.0 : 0.0;
}
double height(const Vec3& d) {
  return std::max(0.0, d.z());
}

}  // namespace

BOOST_AUTO_TEST_CASE(open_faces_under_closed_form_skies) {
  const Scene empty{TriangleSoup{}};
  SkyVisibility sv(empty, VisibilityOptions{}, SkyFactorsMethod::exact);
  std::vector<float> dc(kDaylightCoefficientNodes);
  daylight_coefficients(sv.compute({Vec3(0, 0, 0), Vec3(0, 0, 1)}), VisibilityOptions{}, dc);
  BOOST_TEST(dot_sky(dc, uniform) == kPi, boost::test_tools::tolerance(2e-3));
  BOOST_TEST(dot_sky(dc, height) == 2 * kPi / 3, boost::test_tools::tolerance(5e-3));
  // A wall: half the hemisphere, cosine-weighted: π/2.
  daylight_coefficients(sv.compute({Vec3(0, 0, 0), Vec3(1, 0, 0)}), VisibilityOptions{}, dc);
  BOOST_TEST(dot_sky(dc, uniform) == kPi / 2, boost::test_tools::tolerance(2e-3));
}

BOOST_AUTO_TEST_CASE(occluded_points_give_pi_times_their_svf) {
  TriangleSoup soup;
  add_quad(soup, Vec3(-30, 8, 0), Vec3(30, 8, 0), Vec3(30, 8, 20), Vec3(-30, 8, 20));
  add_quad(soup, Vec3(6, -30, 0), Vec3(6, 30, 0), Vec3(6, 30, 9), Vec3(6, -30, 9));
  add_quad(soup, Vec3(-3, -2, 6), Vec3(3, -2, 6), Vec3(3, 2, 6.5), Vec3(-3, 2, 6.5));  // a canopy
  const Scene scene(soup);
  SkyVisibility sv(scene, VisibilityOptions{}, SkyFactorsMethod::exact);
  std::vector<float> dc(kDaylightCoefficientNodes);
  const QueryPoint pts[] = {{Vec3(0, 0, 1), Vec3(0, 0, 1)},
                            {Vec3(2, 3, 4), Vec3(0, 1, 0)},
                            {Vec3(-5, -4, 2), Vec3(0.3, 0.5, 0.81).normalized()},
                            {Vec3(5.9, 0, 3), Vec3(-1, 0, 0)}};
  for (const QueryPoint& q : pts) {
    const VisibleSky& sky = sv.compute(q);
    daylight_coefficients(sky, VisibilityOptions{}, dc);
    // Absolute, in SVF units: the lines' δ discretisation (64 lines, doubled at most twice towards
    // the tolerance 5e-4) and the hats' quadrature.
    BOOST_TEST(std::abs(dot_sky(dc, uniform) / kPi - sky.factors.svf) < 1e-3,
               dot_sky(dc, uniform) / kPi << " vs " << sky.factors.svf);
  }
}
