#pragma once
// Exact signs of the two predicates of the band-visibility core, each a floating-point filter
// that decides almost every case, with an exact fallback (CGAL, in exact_sign.cpp, so no CGAL
// header leaks from here):
//   exact_dot_sign     — sign of m·d: which side of a sample plane (normal m, through the
//                        calculation point) a vertex (offset d) lies on; exact for the doubles
//                        given, i.e. for the rounded offset d = fl(V − P) the caller forms once
//                        per vertex (docs/robustness.md);
//   exact_orientation  — sign of the orientation of four points: whether a triangle's plane
//                        contains the calculation point (the triangle is then seen edge-on).
// and, built on them, the 2D orientation of xy-projections and a betweenness test by comparisons.
#include <cmath>

#include "geometry/core/vec3.h"

namespace skyband {

int exact_dot_sign_slow(const Vec3& m, const Vec3& d);
int exact_orientation_slow(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

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
  if (s == 0)
    value = 0;
  else if (value * s <= 0)
    value = s * 1e-300;  // keep the float value's sign consistent
  return s;
}

// Sign of det[a − d, b − d, c − d] (the negative of CGAL::orientation(a, b, c, d)); 0 exactly when
// the four points are coplanar.
// Filter: Shewchuk's orient3d stage-A bound (Adaptive Precision Floating-Point Arithmetic and
// Fast Robust Geometric Predicates, 1997, §4.3): with the differences rounded, the computed
// determinant is within (7 + 56ε)ε·P of the exact one, P the permanent (the same expansion with
// absolute values), ε = 2⁻⁵³. Tiny permanents (possible underflow) go to the exact path.
inline int exact_orientation(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y(), adz = a.z() - d.z();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y(), bdz = b.z() - d.z();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y(), cdz = c.z() - d.z();
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                           (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                           (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
  constexpr double kEps = 0x1p-53;
  const double bound = (7.0 + 56.0 * kEps) * kEps * permanent;
  if (permanent > 1e-250) {
    if (det > bound) return 1;
    if (det < -bound) return -1;
  }
  return exact_orientation_slow(a, b, c, d);
}

// Sign of the orientation of the xy-projections of a, b, c: +1 counter-clockwise seen from above
// (the triangle's normal points up), −1 clockwise, 0 collinear (a vertical or degenerate triangle).
// The 2D determinant is the 3D one of the points lifted to z = 0 against (0, 0, 1), whose
// differences are exact: det[a − d, b − d, c − d] = −orient2d(a, b, c).
// Filter: Shewchuk's orient2d stage-A bound ((3 + 16ε)ε × the permanent; 1997, §4.2).
inline int exact_orient2d_sign(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double l = (b.x() - a.x()) * (c.y() - a.y()), r = (b.y() - a.y()) * (c.x() - a.x());
  const double det = l - r;
  constexpr double kEps = 0x1p-53;
  const double bound = (3.0 + 16.0 * kEps) * kEps * (std::abs(l) + std::abs(r));
  if (std::abs(l) + std::abs(r) > 1e-250) {
    if (det > bound) return 1;
    if (det < -bound) return -1;
  }
  return -exact_orientation(Vec3(a.x(), a.y(), 0), Vec3(b.x(), b.y(), 0), Vec3(c.x(), c.y(), 0), Vec3(0, 0, 1));
}

// Exact (comparisons only): does v lie strictly between u and w in xy, for v on their common xy
// line? Decided along a coordinate in which u and w differ.
inline bool strictly_between_xy(const Vec3& u, const Vec3& v, const Vec3& w) {
  for (int a = 0; a < 2; ++a)
    if (u[a] != w[a]) return (u[a] < v[a] && v[a] < w[a]) || (w[a] < v[a] && v[a] < u[a]);
  return false;
}

}  // namespace skyband
