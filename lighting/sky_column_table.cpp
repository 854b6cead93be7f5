#include "lighting/sky_column_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace skyband {

namespace {
constexpr double kHalfPi = 1.57079632679489661923;
constexpr double kTwoPi = 6.28318530717958647692;
constexpr int kNodes = SkyColumnTable::kElevationCells + 1;
constexpr double kDe = kHalfPi / SkyColumnTable::kElevationCells;  // radians
constexpr double kDphi = kTwoPi / SkyColumnTable::kAzimuthCells;   // radians
constexpr double x2[2] = {-0.5773502691896258, 0.5773502691896258};  // ±1/√3, weights 1
}  // namespace

SkyColumnTable::SkyColumnTable(const ProjectedSkyGrid& grid, int threads)
    : data_(static_cast<std::size_t>(kAzimuthCells) * kNodes * 2 * kChannels, 0.0f) {
  if (grid.channels() != kChannels) throw std::invalid_argument("SkyColumnTable: the sky grid must have 2 channels");
  tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  arena.execute([&] {
    tbb::parallel_for(0, kAzimuthCells, [&](int i) {
      const double phi = i * kDphi, cp = std::cos(phi), sp = std::sin(phi);
      double s[kChannels] = {0, 0}, c[kChannels] = {0, 0}, l[kChannels];
      // From the zenith down: node j holds the integrals over [e_j, π/2].
      for (int j = kElevationCells - 1; j >= 0; --j) {
        for (int g = 0; g < 2; ++g) {  // 2-node Gauss–Legendre per 0.25° cell: exact for cubics
          const double e = (j + 0.5 * (1 + x2[g])) * kDe, ce = std::cos(e), se = std::sin(e);
          grid.lookup_n<kChannels>(Vec3(ce * cp, ce * sp, se), l);
          const double w = 0.5 * kDe;
          for (int k = 0; k < kChannels; ++k) {
            s[k] += w * l[k] * se * ce;
            c[k] += w * l[k] * ce * ce;
          }
        }
        float* node = data_.data() + (static_cast<std::size_t>(j) * kAzimuthCells + i) * 2 * kChannels;
        for (int k = 0; k < kChannels; ++k) {
          node[k] = s[k];
          node[kChannels + k] = c[k];
        }
      }
    });
  });
}

void SkyColumnTable::lookup(double phi, double e, double s[kChannels], double c[kChannels]) const {
  double u = phi / kDphi;
  u -= kAzimuthCells * std::floor(u / kAzimuthCells);  // [0, cells)
  int i0 = static_cast<int>(u);
  if (i0 >= kAzimuthCells) i0 = kAzimuthCells - 1;
  const double fu = u - i0;
  const int i1 = i0 + 1 == kAzimuthCells ? 0 : i0 + 1;
  const double v = std::clamp(e / kDe, 0.0, double(kElevationCells));
  const int j0 = std::min(static_cast<int>(v), kElevationCells - 1);
  const double fv = v - j0;
  const auto at = [&](int i, int j) { return data_.data() + (static_cast<std::size_t>(j) * kAzimuthCells + i) * 2 * kChannels; };
  const float* a = at(i0, j0);
  const float* b = at(i1, j0);
  const float* cc = at(i0, j0 + 1);
  const float* d = at(i1, j0 + 1);
  const double w00 = (1 - fu) * (1 - fv), w10 = fu * (1 - fv), w01 = (1 - fu) * fv, w11 = fu * fv;
  for (int k = 0; k < kChannels; ++k) {
    s[k] = w00 * a[k] + w10 * b[k] + w01 * cc[k] + w11 * d[k];
    c[k] = w00 * a[kChannels + k] + w10 * b[kChannels + k] + w01 * cc[kChannels + k] + w11 * d[kChannels + k];
  }
}

void SkyColumnTable::integrate_fan(std::span<const SkyFanTriangle> fan, const Vec3& n, double out[kChannels],
                                   double max_step_rad) const {
  for (int k = 0; k < kChannels; ++k) out[k] = 0;
  double s[kChannels], c[kChannels];
  for_each_fan_azimuth_node(fan, max_step_rad, [&](double phi, double cp, double sp, double e0, double w) {
    lookup(phi, e0, s, c);
    const double horizontal = n.x() * cp + n.y() * sp;
    for (int k = 0; k < kChannels; ++k) out[k] += w * (n.z() * s[k] + horizontal * c[k]);
  });
}

}  // namespace skyband
