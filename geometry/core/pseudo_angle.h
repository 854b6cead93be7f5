#pragma once
// A cheap strictly monotone stand-in for the angle of a vector (x, y) ("diamond angle"): the
// angle measured along the diamond |x| + |y| = 1 instead of the unit circle. The geometry core
// orders, merges and culls angular ranges in these units (no trigonometry in the hot loop) and
// converts to radians only for output. Two forms of the one proxy: pseudo_angle over a half plane
// (α and δ of the band method, y ≥ 0: [0, 2]) and diamond_angle over the full turn (azimuths of
// the exact horizon and the exact union: [0, 4)).
#include <cmath>

namespace skyband {

inline double pseudo_angle(double x, double y) {
  const double s = std::abs(x) + y;
  if (s == 0) return 0;
  const double r = y / s;
  return x >= 0 ? r : 2.0 - r;
}

// Inverse: the angle in radians ∈ [0, π] of pseudo-angle p ∈ [0, 2].
inline double angle_of_pseudo(double p) {
  if (p <= 1) return std::atan2(p, 1.0 - p);
  const double q = 2.0 - p;
  return std::atan2(q, q - 1.0);
}

// Diamond angle of the horizontal direction (x, y) ≠ 0: 0 at +x, 1 at +y, 2 at −x, 3 at −y;
// strictly monotone in the angle, and t(−w) = t(w) ± 2 (an arc shorter than π spans less than 2).
inline double diamond_angle(double x, double y) {
  if (y >= 0) {
    if (x >= 0) {
      const double s = x + y;
      return s > 0 ? y / s : 0.0;
    }
    return 1.0 - x / (y - x);
  }
  if (x < 0) return 2.0 - y / (-x - y);
  return 3.0 + x / (x - y);
}

// Unit horizontal direction of diamond angle t ∈ [0, 4].
inline void diamond_direction(double t, double& wx, double& wy) {
  double x, y;
  if (t < 1)
    x = 1 - t, y = t;
  else if (t < 2)
    x = 1 - t, y = 2 - t;
  else if (t < 3)
    x = t - 3, y = 2 - t;
  else
    x = t - 3, y = t - 4;
  const double r = 1.0 / std::sqrt(x * x + y * y);
  wx = x * r;
  wy = y * r;
}

}  // namespace skyband
