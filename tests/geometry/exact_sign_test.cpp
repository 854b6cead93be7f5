#define BOOST_TEST_MODULE exact_sign
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

#include "geometry/core/exact_sign.h"

using namespace skyband;

// The filtered predicates against their exact fallbacks (CGAL exact rational arithmetic): on
// random input (decided by the filter) and on constructed near-degenerate input (coplanar up to
// one ulp, where the filter must hand over), the signs are identical.

BOOST_AUTO_TEST_CASE(orientation_filter_agrees_with_exact) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  int decided_zero = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    Vec3 d{u(rng), u(rng), u(rng)};
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
    const Vec3 m{u(rng), u(rng), u(rng)};
    Vec3 d{1e3 * u(rng), 1e3 * u(rng), 1e3 * u(rng)};
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

BOOST_AUTO_TEST_CASE(orient2d_filter_agrees_with_exact) {
  // The filtered 2D orientation against the exact 3D one of the points lifted to z = 0 (whose
  // differences from (0, 0, 1) are exact), on random and on nearly collinear points at projected
  // coordinate magnitudes (x ≈ 4·10⁵, y ≈ 6·10⁶ m), nudged by 0 or 1 ulp.
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  int zeros = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 shift(4e5, 6e6, 0);
    const Vec3 a = shift + Vec3{u(rng), u(rng), 0}, b = shift + Vec3{u(rng), u(rng), 0};
    Vec3 c = shift + Vec3{u(rng), u(rng), u(rng)};
    if (i % 2 == 1) {
      c = a + (u(rng) / 50) * (b - a);
      if (i % 4 == 1) c[i % 8 < 4 ? 0 : 1] = std::nextafter(c[i % 8 < 4 ? 0 : 1], 1e300);
    }
    Vec3 ae = a, be = b;
    if (i % 16 == 2) {  // exactly collinear: a step of quarter metres and its double, all representable
      const Vec3 step{0.25 * double(int(u(rng))), 0.25 * double(int(u(rng))), 0};
      ae = shift + Vec3{double(int(u(rng))), double(int(u(rng))), 0};
      be = ae + step;
      c = ae + 2.0 * step;
    }
    const Vec3 a2 = ae, b2 = be;
    const int lifted =
        -exact_orientation_slow(Vec3(a2.x(), a2.y(), 0), Vec3(b2.x(), b2.y(), 0), Vec3(c.x(), c.y(), 0), Vec3(0, 0, 1));
    BOOST_TEST(exact_orient2d_sign(a2, b2, c) == lifted);
    zeros += lifted == 0;
  }
  BOOST_TEST(zeros > 0);  // the exactly collinear cases were exercised
  BOOST_TEST(exact_orient2d_sign(Vec3(0, 0, 5), Vec3(1, 0, -2), Vec3(0, 1, 7)) == 1);  // counter-clockwise seen from above
}
