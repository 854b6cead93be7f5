#define BOOST_TEST_MODULE exact_sign
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

#include "geometry/exact_sign.h"

using namespace skyband;

// The filtered predicates against their exact fallbacks (CGAL exact rational arithmetic): on
// random input (decided by the filter) and on constructed near-degenerate input (coplanar up to
// one ulp, where the filter must hand over), the signs are identical.

BOOST_AUTO_TEST_CASE(orientation_filter_agrees_with_exact) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  int decided_zero = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    Vec3 d(u(rng), u(rng), u(rng));
    if (i % 2 == 1) {
      // A point on the plane of a, b, c up to rounding: d = a + s(b − a) + t(c − a), then nudged
      // by 0, ±1 ulp in one coordinate.
      const double s = u(rng) / 50, t = u(rng) / 50;
      d = a + s * (b - a) + t * (c - a);
      const int k = i % 3;
      if (i % 5 == 1) d[k] = std::nextafter(d[k], 1e300);
      if (i % 5 == 3) d[k] = std::nextafter(d[k], -1e300);
    }
    const int fast = exact_orientation(a, b, c, d);
    const int slow = exact_orientation_slow(a, b, c, d);
    BOOST_TEST(fast == slow);
    decided_zero += slow == 0;
  }
  // Exactly coplanar integer points (z = x + 2y): the determinant is exactly 0.
  for (int i = 0; i < 100; ++i) {
    auto pt = [&](int x, int y) { return Vec3(x, y, x + 2.0 * y); };
    BOOST_TEST(exact_orientation(pt(i, 1), pt(3, -i), pt(-2 * i, 5), pt(7, 7 + i)) == 0);
  }
  BOOST_TEST_MESSAGE("exactly coplanar random cases: " << decided_zero);
}

// Sign convention: det[a − d, b − d, c − d]; for the unit tetrahedron a = x, b = y, c = z, d = 0
// it is det(I) = +1, and swapping two points flips it.
BOOST_AUTO_TEST_CASE(orientation_sign_convention) {
  const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  BOOST_TEST(exact_orientation(x, y, z, o) == 1);
  BOOST_TEST(exact_orientation(y, x, z, o) == -1);
  BOOST_TEST(exact_orientation_slow(x, y, z, o) == 1);
  BOOST_TEST(exact_orientation(x, y, 2.0 * x - y, o) == 0);
}

BOOST_AUTO_TEST_CASE(dot_sign_filter_agrees_with_exact) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const Vec3 m(u(rng), u(rng), u(rng));
    Vec3 d(1e3 * u(rng), 1e3 * u(rng), 1e3 * u(rng));
    if (i % 2 == 1) {
      // d nearly perpendicular to m: remove its m component, then nudge by an ulp.
      d = d - (m.dot(d) / m.squaredNorm()) * m;
      if (i % 3 == 1) d[i % 3] = std::nextafter(d[i % 3], 1e300);
    }
    double value = 0;
    const int s = exact_dot_sign(m, d, value);
    BOOST_TEST(s == exact_dot_sign_slow(m, d));
    // The float value carried for interpolation has the exact sign.
    BOOST_TEST((value > 0) - (value < 0) == s);
  }
}
