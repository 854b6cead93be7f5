#pragma once
// Integrals over the visible sky of one cached point (method.md §2):
//   E = Σ_bands w_b · Σ_visible [α0, α1] ∫ L(ω(α, δ_b)) sin²α dα      (seed eq. 1, band weights w_b)
// with ω(α, δ) from the point's band frame. Uniform sky: ∫ sin²α dα = [α/2 − sin 2α/4].
#include <algorithm>
#include <cmath>

#include "geometry/bands/visibility_cache.h"
#include "geometry/core/gauss_legendre.h"

namespace skyband {

// ∫_0^α sin²α' dα' (uniform-sky look-up table in closed form).
inline double uniform_sky_primitive(double alpha_rad) {
  return 0.5 * alpha_rad - 0.25 * std::sin(2.0 * alpha_rad);
}

// Interval end points are stored as float; float(π) rounds above π, so clamp on the way out.
inline double clamp_alpha(float alpha_rad) {
  return std::min(static_cast<double>(alpha_rad), kPi);
}

// Cosine-weighted sky view factor E/π under a uniform sky: 1 for an open horizontal face,
// 0.5 for an open vertical one.
double sky_view_factor(const PointVisibilityView& v);

// Visible sky solid angle in front of the face divided by 2π (0.5 for an open wall).
double sky_exposure(const PointVisibilityView& v);

// Irradiance in N channels at once, E_k = ∫_visible c_k(ω) (n·ω) dω, for any radiance function
// `radiance_into(const Vec3& unit_world_direction, double* c)` writing c[0..N) (e.g. radiometric
// and photometric projections of a spectral sky; units of c × sr): out[k] = E_k. Each visible
// interval is integrated with 4-point Gauss–Legendre on equal sub-intervals of at most
// `max_step_rad` (error ~h⁸·|f⁽⁸⁾| for smooth f = c·sin²α; sin²α alone is integrated to ~1e-13 at
// 0.05 rad). The nodes' cos/sin advance by rotation from piece to piece (one sincos per node of
// the first piece and one per interval for the step: a few ulp after the ≤ 63 pieces of a line).
template <int N, class RadianceInto>
void integrate_irradiance_channels(const PointVisibilityView& v, RadianceInto&& radiance_into, double* out,
                                   double max_step_rad = 0.05) {
  const BandFrame& f = v.frame();
  for (int k = 0; k < N; ++k) out[k] = 0;
  double line[N], c[N];
  for (std::size_t b = 0; b < v.band_count(); ++b) {
    const double delta = v.band(b).delta_rad;
    const Vec3 u = std::cos(delta) * f.h + std::sin(delta) * f.z;  // ω(α, δ) = cos α·x + sin α·u
    for (int k = 0; k < N; ++k) line[k] = 0;
    for (const VisibleInterval& iv : v.visible(b)) {
      const double a0 = clamp_alpha(iv.alpha0_rad), a1 = clamp_alpha(iv.alpha1_rad);
      const int pieces = std::max(1, static_cast<int>(std::ceil((a1 - a0) / max_step_rad)));
      const double h = (a1 - a0) / pieces;
      const double ch = std::cos(h), sh = std::sin(h);
      double cs[4], sn[4], w[4];
      for (int g = 0; g < 4; ++g) {
        const double a = a0 + 0.5 * h * (1 + kGauss4Nodes[g]);
        cs[g] = std::cos(a);
        sn[g] = std::sin(a);
        w[g] = 0.5 * h * kGauss4Weights[g];
      }
      for (int p = 0; p < pieces; ++p) {
        for (int g = 0; g < 4; ++g) {
          radiance_into(cs[g] * f.x + sn[g] * u, c);
          const double wt = w[g] * sn[g] * sn[g];
          for (int k = 0; k < N; ++k) line[k] += wt * c[k];
          const double cn = cs[g] * ch - sn[g] * sh;  // advance by h
          sn[g] = sn[g] * ch + cs[g] * sh;
          cs[g] = cn;
        }
      }
    }
    const double bw = v.band_weight(b);
    for (int k = 0; k < N; ++k) out[k] += bw * line[k];
  }
}

// Irradiance E = ∫_visible L(ω) (n·ω) dω for any radiance function L(ω) (units of L × sr), as
// integrate_irradiance_channels. `radiance(const Vec3& world_direction) -> double`.
template <class Radiance>
double integrate_irradiance(const PointVisibilityView& v, Radiance&& radiance, double max_step_rad = 0.05) {
  double e;
  integrate_irradiance_channels<1>(
      v, [&](const Vec3& d, double* c) { c[0] = radiance(d); }, &e, max_step_rad);
  return e;
}

}  // namespace skyband
