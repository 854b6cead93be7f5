#include "lighting/integrals/daylight_coefficients.h"

#include <algorithm>
#include <cmath>

#include "geometry/bands/sample_lines.h"
#include "geometry/bands/sky_integral.h"
#include "geometry/bands/visibility_cache.h"
#include "geometry/core/gauss_legendre.h"
#include "lighting/sky/sky_radiance_grid.h"

namespace skyband {

namespace {

constexpr int kCells = kDaylightCoefficientCells, kNodes1 = kCells + 1;

// Σ over the point's lines of w_b ∫ φ_j sin²α dα, scattered into the nodes' coefficients.
void scatter_lines(const PointVisibilityView& v, std::span<float> out) {
  const BandFrame& f = v.frame();
  constexpr double kStep = 0.05;
  std::vector<double> acc(out.size(), 0.0);
  for (std::size_t b = 0; b < v.band_count(); ++b) {
    const double delta = v.band(b).delta_rad, wb = v.band_weight(b);
    const Vec3 u = std::cos(delta) * f.h + std::sin(delta) * f.z;
    for (const VisibleInterval& iv : v.visible(b)) {
      const double a0 = clamp_alpha(iv.alpha0_rad), a1 = clamp_alpha(iv.alpha1_rad);
      const int pieces = std::max(1, static_cast<int>(std::ceil((a1 - a0) / kStep)));
      const double h = (a1 - a0) / pieces;
      for (int p = 0; p < pieces; ++p)
        for (int g = 0; g < 4; ++g) {
          const double a = a0 + h * (p + 0.5 * (1 + kGauss4Nodes[g]));
          const double sa = std::sin(a);
          const Vec3 d = std::cos(a) * f.x + sa * u;
          if (!(d.z() > 0)) continue;
          const double k = 1.0 / (1.0 + d.z());
          const double gx = (d.x() * k + 1.0) * 0.5 * kCells, gy = (d.y() * k + 1.0) * 0.5 * kCells;
          const int ix = std::clamp(static_cast<int>(gx), 0, kCells - 1), iy = std::clamp(static_cast<int>(gy), 0, kCells - 1);
          const double fx = std::clamp(gx - ix, 0.0, 1.0), fy = std::clamp(gy - iy, 0.0, 1.0);
          const double w = wb * 0.5 * h * kGauss4Weights[g] * sa * sa;
          const std::size_t n00 = static_cast<std::size_t>(iy) * kNodes1 + static_cast<std::size_t>(ix);
          acc[n00] += w * (1 - fx) * (1 - fy);
          acc[n00 + 1] += w * fx * (1 - fy);
          acc[n00 + kNodes1] += w * (1 - fx) * fy;
          acc[n00 + kNodes1 + 1] += w * fx * fy;
        }
    }
  }
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = static_cast<float>(acc[j]);
}

}  // namespace

const std::vector<DaylightNode>& daylight_nodes() {
  static const std::vector<DaylightNode> nodes = [] {
    std::vector<DaylightNode> n(kDaylightCoefficientNodes);
    const double step = 2.0 / kCells;
    for (int iy = 0; iy < kNodes1; ++iy)
      for (int ix = 0; ix < kNodes1; ++ix) {
        const double px = -1.0 + ix * step, py = -1.0 + iy * step, r = std::hypot(px, py);
        DaylightNode& d = n[static_cast<std::size_t>(iy) * kNodes1 + static_cast<std::size_t>(ix)];
        d.da = sky_grid_disk_direction(px, py);
        if (r > 1.0) {  // 2·L(rim) − L(mirror point at radius 2 − r)
          const double k = (2.0 - r) / r;
          d.db = sky_grid_disk_direction(px * k, py * k);
          d.a = 2;
          d.b = -1;
        } else {
          d.db = d.da;
        }
      }
    return n;
  }();
  return nodes;
}

void daylight_coefficients(const VisibleSky& sky, const VisibilityOptions& visibility, std::span<float> out) {
  if (!sky.exact()) {
    scatter_lines(*sky.bands, out);
    return;
  }
  thread_local VisibilityCache::PointResult lines;
  SampleLineOptions opt;
  opt.bands = std::max(visibility.bands, kDaylightCoefficientLines);
  opt.tolerance = visibility.tolerance;
  opt.max_doublings = kDaylightCoefficientDoublings;
  sample_lines_of(sky, opt, lines);
  thread_local VisibilityCache cache;
  cache.clear();
  cache.append(lines);
  scatter_lines(cache.view(0), out);
}

}  // namespace skyband
