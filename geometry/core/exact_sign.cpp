#include "geometry/core/exact_sign.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>

namespace skyband {

int exact_dot_sign_slow(const Vec3& m, const Vec3& d) {
  using Q = CGAL::Exact_rational;  // every finite double converts exactly
  const Q v = Q(m.x()) * Q(d.x()) + Q(m.y()) * Q(d.y()) + Q(m.z()) * Q(d.z());
  return CGAL::sign(v);
}

int exact_orientation_slow(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using P = K::Point_3;
  // det[a − d, b − d, c − d] = −det[b − a, c − a, d − a], and CGAL::orientation is the sign of the latter.
  return -static_cast<int>(
      CGAL::orientation(P(a.x(), a.y(), a.z()), P(b.x(), b.y(), b.z()), P(c.x(), c.y(), c.z()), P(d.x(), d.y(), d.z())));
}

}  // namespace skyband
