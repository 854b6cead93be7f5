#include "geometry/exact_sign.h"

#include <CGAL/Exact_rational.h>

namespace skyband {

int exact_dot_sign_slow(const Vec3& m, const Vec3& d) {
  using Q = CGAL::Exact_rational;  // every finite double converts exactly
  const Q v = Q(m.x()) * Q(d.x()) + Q(m.y()) * Q(d.y()) + Q(m.z()) * Q(d.z());
  return CGAL::sign(v);
}

}  // namespace skyband
