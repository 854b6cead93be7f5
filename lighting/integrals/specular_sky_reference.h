#pragma once
// The oracle of the specular sky march's tests and benchmarks: the same integral as
// specular_sky_radiance (specular_sky.h) over every band and visible interval, without truncation,
// with an independent rule.
#include <type_traits>

#include "geometry/core/gauss_legendre.h"
#include "lighting/integrals/specular_sky.h"

namespace skyband {

// Reference: the same integral over every band and visible interval without truncation.
// Pieces in δ and α are ≤ min(step_per_m·m, max_step_rad); 3-point GL in δ (weight cos(δ − β)),
// 4-point GL along α. Perfect mirrors (m < opt.mirror_below_m) use the same look-up as above.
template <class Radiance>
Spectrum specular_sky_reference(const PointVisibilityView& view, const Vec3& view_dir, const SpecularLobe& lobe, Radiance&& sky,
                                double step_per_m = 0.5, double max_step_rad = 0.02, const SpecularSkyOptions& opt = {},
                                SpecularSkyStats* stats_out = nullptr) {
  using namespace specular_detail;
  SpecularSkyStats stats;
  Spectrum acc;
  PointContext c;
  SpectralReflection<std::remove_reference_t<Radiance>> p{sky, lobe.fresnel};
  if (trivial_case(view, view_dir, lobe, p, opt, c, stats, acc)) {
    if (stats_out) *stats_out = stats;
    return acc;
  }
  const BandFrame& f = view.frame();
  const double step = std::min(step_per_m * lobe.roughness_m, max_step_rad);
  Spectrum val;
  for (std::size_t b = 0; b < view.band_count(); ++b) {
    const double d0 = f.delta_at(view.band(b).s0), d1 = f.delta_at(view.band(b).s1);
    const int kd = std::max(1, static_cast<int>(std::ceil((d1 - d0) / step)));
    const double hd = (d1 - d0) / kd;
    for (int pc = 0; pc < kd; ++pc)
      for (int gd = 0; gd < 3; ++gd) {
        Line line;
        line.band = b;
        line.delta_rad = d0 + (pc + 0.5) * hd + 0.5 * hd * kGauss3Nodes[gd];
        line.u = std::cos(line.delta_rad) * f.h + std::sin(line.delta_rad) * f.z;
        line.weight = 0.5 * hd * kGauss3Weights[gd] * std::cos(line.delta_rad - f.beta_rad);
        line = with_dots(c, line);
        Spectrum line_sum;
        for (const VisibleInterval& iv : view.visible(b)) {
          const double a0 = clamp_alpha(iv.alpha0_rad), a1 = clamp_alpha(iv.alpha1_rad);
          if (!(a1 > a0)) continue;
          const int ka = std::max(1, static_cast<int>(std::ceil((a1 - a0) / step)));
          const double ha = (a1 - a0) / ka;
          for (int q = 0; q < ka; ++q)
            for (int ga = 0; ga < 4; ++ga) {
              const double a = a0 + (q + 0.5) * ha + 0.5 * ha * kGauss4Nodes[ga];
              if (integrand(c, line, a, p, val, stats) > 0.0) line_sum += val * (0.5 * ha * kGauss4Weights[ga]);
            }
        }
        acc += line_sum * line.weight;
        ++stats.lines;
      }
  }
  if (stats_out) *stats_out = stats;
  return acc;
}

}  // namespace skyband
