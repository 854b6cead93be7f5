#include "geometry/bands/band_rule.h"

#include <cmath>

namespace skyband {

BandRule band_rule(double d0, double d1, double beta) {
  const double h = 0.5 * (d1 - d0), g = 0.5 * (d0 + d1) - beta;
  double s1, s2;  // ∫_0^h t sin t dt, ∫_0^h t² cos t dt (Taylor series where they cancel)
  if (h < 0.05) {
    const double h2 = h * h, h3 = h2 * h;
    s1 = h3 * (1.0 / 3 - h2 * (1.0 / 30 - h2 * (1.0 / 840 - h2 / 45360)));
    s2 = h3 * (1.0 / 3 - h2 * (1.0 / 10 - h2 * (1.0 / 168 - h2 / 6480)));
  } else {
    s1 = std::sin(h) - h * std::cos(h);
    s2 = (h * h - 2) * std::sin(h) + 2 * h * std::cos(h);
  }
  BandRule r;
  r.m0 = 2 * std::sin(h) * std::cos(g);
  const double m1 = -2 * std::sin(g) * s1, m2 = 2 * std::cos(g) * s2;
  if (h <= 0) return {0, 0, 0, 0};
  r.w0 = (m2 - h * m1) / (2 * h * h);
  r.wm = (h * h * r.m0 - m2) / (h * h);
  r.w1 = (m2 + h * m1) / (2 * h * h);
  return r;
}

}  // namespace skyband
