#pragma once
// A cheap strictly monotone stand-in for the angle of a vector (x, y) with y ≥ 0 ("diamond
// angle"): 0 at +x, 1 at +y, 2 at −x. The geometry core orders, merges and culls α- and δ-ranges
// in these units (no trigonometry in the hot loop) and converts to radians only for output.
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

}  // namespace skyband
