#include "geometry/bands/sky_integral.h"

namespace skyband {

double sky_view_factor(const PointVisibilityView& v) {
  double e = 0;
  for (std::size_t b = 0; b < v.band_count(); ++b) {
    double line = 0;
    for (const VisibleInterval& iv : v.visible(b))
      line += uniform_sky_primitive(clamp_alpha(iv.alpha1_rad)) - uniform_sky_primitive(clamp_alpha(iv.alpha0_rad));
    e += v.band_weight(b) * line;
  }
  return e / kPi;
}

double sky_exposure(const PointVisibilityView& v) {
  // Solid angle = Σ_b w_b ∫_visible sin α dα, w_b the line's weight in δ (BandRecord).
  double omega = 0;
  for (std::size_t b = 0; b < v.band_count(); ++b) {
    const double width = v.band(b).exposure_weight;
    double line = 0;
    for (const VisibleInterval& iv : v.visible(b))
      line += std::cos(clamp_alpha(iv.alpha0_rad)) - std::cos(clamp_alpha(iv.alpha1_rad));
    omega += width * line;
  }
  return omega / (2 * kPi);
}

}  // namespace skyband
