#pragma once
// Integrals over the visible sky of one cached point (method.md §2):
//   E = Σ_bands w_b · Σ_visible [α0, α1] ∫ L(ω(α, δ_b)) sin²α dα      (seed eq. 1, band weights w_b)
// with ω(α, δ) from the point's band frame. Uniform sky: ∫ sin²α dα = [α/2 − sin 2α/4].
#include <algorithm>
#include <cmath>

#include "geometry/visibility_cache.h"

namespace skyband {

// ∫_0^α sin²α' dα' (uniform-sky look-up table in closed form).
inline double uniform_sky_primitive(double alpha_rad) {
  return 0.5 * alpha_rad - 0.25 * std::sin(2.0 * alpha_rad);
}

// Interval end points are stored as float; float(π) rounds above π, so clamp on the way out.
inline double clamp_alpha(float alpha_rad) { return std::min(static_cast<double>(alpha_rad), kPi); }

// Cosine-weighted sky view factor E/π under a uniform sky: 1 for an open horizontal face,
// 0.5 for an open vertical one.
double sky_view_factor(const PointVisibilityView& v);

// Visible sky solid angle in front of the face divided by 2π (0.5 for an open wall).
double sky_exposure(const PointVisibilityView& v);

// Irradiance E = ∫_visible L(ω) (n·ω) dω for any radiance function L(ω) (units of L × sr),
// integrated along each visible interval with Gauss–Legendre quadrature on sub-intervals of at
// most `max_step_rad`. `radiance(const Vec3& world_direction) -> double`.
template <class Radiance>
double integrate_irradiance(const PointVisibilityView& v, Radiance&& radiance, double max_step_rad = 0.05) {
  // 4-point Gauss–Legendre nodes/weights on [−1, 1].
  static constexpr double xg[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static constexpr double wg[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  const BandFrame& f = v.frame();
  double total = 0;
  for (std::size_t b = 0; b < v.band_count(); ++b) {
    const double delta = v.band(b).delta_rad;
    double line = 0;
    for (const VisibleInterval& iv : v.visible(b)) {
      const double a0 = clamp_alpha(iv.alpha0_rad), a1 = clamp_alpha(iv.alpha1_rad);
      const int pieces = std::max(1, static_cast<int>(std::ceil((a1 - a0) / max_step_rad)));
      const double h = (a1 - a0) / pieces;
      for (int k = 0; k < pieces; ++k) {
        const double mid = a0 + (k + 0.5) * h;
        for (int g = 0; g < 4; ++g) {
          const double a = mid + 0.5 * h * xg[g];
          const double s = std::sin(a);
          line += 0.5 * h * wg[g] * radiance(f.direction(a, delta)) * s * s;
        }
      }
    }
    total += v.band_weight(b) * line;
  }
  return total;
}

}  // namespace skyband
