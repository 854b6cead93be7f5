#pragma once
// Microfacet slope distribution and shadowing of the Cook–Torrance model (method.md §5;
// reference-notes §4.1–4.2).
//
// Normalised Beckmann distribution of facet normals, m the RMS slope (dimensionless):
//   D_n(θ_h) = exp(−tan²θ_h / m²) / (π m² cos⁴θ_h),   ∫_hemisphere D_n cos θ_h dω_h = 1.
// Cook & Torrance's printed D_CT = exp(−tan²θ_h/m²)/(m² cos⁴θ_h) is π·D_n (reference-notes §4.2).
// Unit: sr⁻¹. Domain: cos θ_h ∈ (0, 1], m > 0; D_n = 0 for facets facing away (cos θ_h ≤ 0).
#include <algorithm>
#include <cmath>

#include "geometry/core/vec3.h"

namespace skyband {

// `exp_neg(x)` = e^{−x} (std::exp or the tabulated fast_exp.h).
template <class ExpNeg>
inline double beckmann_d_with(double cos_theta_h, double m, ExpNeg&& exp_neg) {
  if (cos_theta_h <= 0.0) return 0.0;
  const double c2 = cos_theta_h * cos_theta_h;
  const double tan2 = (1.0 - c2) / c2;
  const double m2 = m * m;
  return exp_neg(tan2 / m2) / (kPi * m2 * c2 * c2);
}

inline double beckmann_d(double cos_theta_h, double m) {
  return beckmann_d_with(cos_theta_h, m, [](double x) { return std::exp(-x); });
}

// Geometric attenuation (masking/shadowing by V-grooves), Cook & Torrance 1982 eq. for G:
//   G = min{1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·L)/(V·H)}   (V·H = L·H).
// Dimensionless, in [0, 1]; 0 when either direction is below the surface or V·H ≤ 0.
inline double cook_torrance_g(double n_dot_h, double n_dot_v, double n_dot_l, double v_dot_h) {
  if (n_dot_v <= 0.0 || n_dot_l <= 0.0 || v_dot_h <= 0.0 || n_dot_h <= 0.0) return 0.0;
  const double k = 2.0 * n_dot_h / v_dot_h;
  return std::min(1.0, std::min(k * n_dot_v, k * n_dot_l));
}

}  // namespace skyband
