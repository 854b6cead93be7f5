#include "geometry/bands/band_frame.h"

#include <algorithm>
#include <cmath>

namespace skyband {

BandFrame BandFrame::make(const Vec3& normal) {
  BandFrame f;
  f.normal = normal.normalized();
  const Vec3 up(0, 0, 1);
  const Vec3 nxz = f.normal.cross(up);
  // Below this horizontal-component length the normal is treated as vertical: the exact x then
  // no longer matters (any horizontal axis is valid) and the cross product is dominated by noise.
  if (nxz.norm() < 1e-12) {
    f.x = Vec3(std::cos(kHorizontalAxisAzimuth), std::sin(kHorizontalAxisAzimuth), 0);
    f.h = up.cross(f.x);
    f.beta_rad = f.normal.z() > 0 ? kPi / 2 : -kPi / 2;
  } else {
    f.x = nxz.normalized();
    f.h = up.cross(f.x);
    f.beta_rad = std::atan2(f.normal.dot(up), f.normal.dot(f.h));
  }
  f.delta_min_rad = std::max(0.0, f.beta_rad - kPi / 2);
  f.delta_max_rad = std::min(kPi, f.beta_rad + kPi / 2);
  if (f.delta_max_rad < f.delta_min_rad) f.delta_max_rad = f.delta_min_rad;
  f.s_min = std::sin(f.delta_min_rad - f.beta_rad);
  f.s_max = std::sin(f.delta_max_rad - f.beta_rad);
  return f;
}

double BandFrame::delta_at(double s) const {
  return beta_rad + std::asin(std::clamp(s, -1.0, 1.0));
}

Vec3 BandFrame::direction(double alpha_rad, double delta_rad) const {
  const double sa = std::sin(alpha_rad);
  return std::cos(alpha_rad) * x + sa * (std::cos(delta_rad) * h + std::sin(delta_rad) * z);
}

void BandFrame::angles_of(const Vec3& dir, double& alpha_rad, double& delta_rad) const {
  const double a = dir.dot(x), ph = dir.dot(h), pz = dir.dot(z);
  const double rho = std::hypot(ph, pz);
  alpha_rad = std::atan2(rho, a);
  delta_rad = std::atan2(pz, ph);
}

std::vector<Band> equal_weight_bands(const BandFrame& frame, int band_count) {
  std::vector<Band> bands;
  if (band_count <= 0 || frame.total_weight() <= 0) return bands;
  bands.reserve(static_cast<std::size_t>(band_count));
  const double w = frame.total_weight() / band_count;
  for (int l = 0; l < band_count; ++l) {
    Band b;
    b.s0 = frame.s_min + l * w;
    b.s1 = (l + 1 == band_count) ? frame.s_max : frame.s_min + (l + 1) * w;
    bands.push_back(b);
  }
  return bands;
}

}  // namespace skyband
