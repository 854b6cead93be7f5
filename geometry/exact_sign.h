#pragma once
// Exact sign of a dot product m·d of double vectors: the predicate "which side of a sample
// plane (normal m, through the calculation point) does a vertex (offset d) lie on".
// A floating-point filter decides almost every case; the rest fall back to exact rational
// arithmetic (CGAL::Exact_rational, in exact_sign.cpp, so no CGAL header leaks from here).
#include <cmath>

#include "geometry/vec3.h"

namespace skyband {

int exact_dot_sign_slow(const Vec3& m, const Vec3& d);

// Returns the exact sign of m·d and, in `value`, a double approximation of m·d whose sign
// agrees with the returned sign (for interpolation).
inline int exact_dot_sign(const Vec3& m, const Vec3& d, double& value) {
  const double p0 = m.x() * d.x(), p1 = m.y() * d.y(), p2 = m.z() * d.z();
  value = p0 + p1 + p2;
  const double mag = std::abs(p0) + std::abs(p1) + std::abs(p2);
  // |fl(Σ m_i d_i) − Σ m_i d_i| ≤ γ₃·Σ|m_i d_i|, γ₃ = 3u/(1 − 3u) ≈ 3.34e-16 (Higham, Accuracy and
  // Stability of Numerical Algorithms, §3.1); the products themselves must not underflow.
  const double bound = 4e-16 * mag;
  if (mag > 1e-280) {
    if (value > bound) return 1;
    if (value < -bound) return -1;
  }
  const int s = exact_dot_sign_slow(m, d);
  if (s == 0) value = 0;
  else if (value * s <= 0) value = s * 1e-300;  // keep the float value's sign consistent
  return s;
}

}  // namespace skyband
