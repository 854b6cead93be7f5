#define BOOST_TEST_MODULE exact_sky
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/exact_sky.h"
#include "geometry/support/lambert_oracle.h"
#include "geometry/support/scene_generators.h"

using namespace skyband;
using namespace skyband::oracle;

namespace {
Vec3 unit_normal(double tilt, double az) { return Vec3(std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt)); }
}

BOOST_AUTO_TEST_CASE(random_closed_boxes_against_the_union_oracle) {
  gen::RandomBoxParams params;
  params.count = 6;
  params.extent_m = 10;
  double worst_svf = 0, worst_exp = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const auto boxes = gen::random_boxes(params, seed);
    const TriangleSoup soup = gen::boxes_to_soup(boxes);
    const Scene scene(soup);
    ExactSky sky(scene, 1e-6);
    gen::Rng rng(seed * 77);
    for (int i = 0; i < 12; ++i) {
      QueryPoint q{Vec3(rng.uniform(-12, 12), rng.uniform(-12, 12), rng.uniform(0, 14)), unit_normal(rng.uniform(0, kPi), rng.uniform(0, 6.28))};
      if (i < 3) q.normal = Vec3(0, 0, 1);
      SkyFactors f;
      sky.compute(q, f);
      const auto ref = sky_union_oracle(q.position + 1e-6 * q.normal, q.normal, soup);
      worst_svf = std::max(worst_svf, std::abs(f.svf - ref.svf));
      worst_exp = std::max(worst_exp, std::abs(f.sky_exposure - ref.sky_exposure));
      BOOST_TEST(std::abs(f.svf - ref.svf) < 1e-9, "seed " << seed << " i " << i << " svf " << f.svf << " ref " << ref.svf);
      BOOST_TEST(std::abs(f.sky_exposure - ref.sky_exposure) < 1e-9, "seed " << seed << " i " << i << " exp " << f.sky_exposure << " ref " << ref.sky_exposure);
    }
  }
  BOOST_TEST_MESSAGE("worst svf " << worst_svf << " exposure " << worst_exp);
}

BOOST_AUTO_TEST_CASE(random_triangle_soup_against_the_union_oracle) {
  double worst_svf = 0, worst_exp = 0;
  int multi = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    gen::Rng rng(seed);
    TriangleSoup soup;
    for (int t = 0; t < 12; ++t) {
      const Vec3 c(rng.uniform(-8, 8), rng.uniform(-8, 8), rng.uniform(0, 8));
      for (int k = 0; k < 3; ++k) soup.vertices.push_back(c + Vec3(rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-3, 3)));
      const auto b = std::uint32_t(soup.vertices.size() - 3);
      soup.triangles.push_back({b, b + 1, b + 2});
    }
    const Scene scene(soup);
    ExactSky sky(scene, 1e-6);
    for (int i = 0; i < 10; ++i) {
      QueryPoint q{Vec3(rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(0, 5)), unit_normal(rng.uniform(0, kPi), rng.uniform(0, 6.28))};
      if (i < 3) q.normal = Vec3(0, 0, 1);
      SkyFactors f;
      sky.compute(q, f);
      if (sky.occluded().has_upper_intervals()) ++multi;
      const auto ref = sky_union_oracle(q.position + 1e-6 * q.normal, q.normal, soup);
      worst_svf = std::max(worst_svf, std::abs(f.svf - ref.svf));
      worst_exp = std::max(worst_exp, std::abs(f.sky_exposure - ref.sky_exposure));
      BOOST_TEST(std::abs(f.svf - ref.svf) < 1e-9, "seed " << seed << " i " << i << " svf " << f.svf << " ref " << ref.svf);
      BOOST_TEST(std::abs(f.sky_exposure - ref.sky_exposure) < 1e-9, "seed " << seed << " i " << i << " exp " << f.sky_exposure << " ref " << ref.sky_exposure);
    }
  }
  BOOST_TEST_MESSAGE("soup: worst svf " << worst_svf << " exposure " << worst_exp << ", points with gaps above an occluder " << multi);
}
