#include "lighting/brdf/cook_torrance.h"

#include <cmath>

#include "lighting/brdf/beckmann.h"

namespace skyband {

double cook_torrance_fs(const Vec3& n, const Vec3& l, const Vec3& v, double roughness_m, double fresnel, bool paper_scale) {
  MicrofacetCosines c;
  if (!microfacet_cosines(n, l, v, c)) return 0.0;
  return fresnel * cook_torrance_lobe(c, roughness_m, paper_scale);
}

double cook_torrance_albedo(double roughness_m, double theta_v_rad, int nodes, bool paper_scale) {
  // Frame: N = z, V in the xz-plane.
  const Vec3 n(0, 0, 1);
  const Vec3 v(std::sin(theta_v_rad), 0, std::cos(theta_v_rad));
  const double n_dot_v = v.z();
  if (n_dot_v <= 0.0 || nodes <= 0) return 0.0;
  double sum = 0;
  for (int i = 0; i < nodes; ++i) {
    const double w = (i + 0.5) / nodes;
    const double tan_h = roughness_m * std::sqrt(-std::log1p(-w));
    const double cos_h = 1.0 / std::sqrt(1.0 + tan_h * tan_h);
    const double sin_h = tan_h * cos_h;
    for (int j = 0; j < nodes; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / nodes;
      const Vec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
      const double v_dot_h = v.dot(h);
      if (v_dot_h <= 0.0) continue;
      const Vec3 l = 2.0 * v_dot_h * h - v;  // mirror of V about the facet normal
      const double n_dot_l = l.z();
      if (n_dot_l <= 0.0) continue;
      const double g = cook_torrance_g(cos_h, n_dot_v, n_dot_l, v_dot_h);
      sum += g * v_dot_h / (n_dot_v * cos_h);
    }
  }
  const double albedo = sum / (static_cast<double>(nodes) * nodes);
  return paper_scale ? kPaperScale * albedo : albedo;
}

}  // namespace skyband
