#include "lighting/integrals/sky_column_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "geometry/core/gauss_legendre.h"

namespace skyband {

namespace {
constexpr double kHalfPi = 1.57079632679489661923;
constexpr double kTwoPi = 6.28318530717958647692;
constexpr int kNodes = SkyColumnTable::kElevationCells + 1;
constexpr double kDe = kHalfPi / SkyColumnTable::kElevationCells;  // radians
constexpr double kDphi = kTwoPi / SkyColumnTable::kAzimuthCells;   // radians
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
          const double e = (j + 0.5 * (1 + kGauss2Nodes[g])) * kDe, ce = std::cos(e), se = std::sin(e);
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

SkyColumnTable::Cell SkyColumnTable::cell(double phi, double e) const {
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
  return Cell{at(i0, j0), at(i1, j0), at(i0, j0 + 1), at(i1, j0 + 1), fu, fv};
}

void SkyColumnTable::lookup(const Cell& q, double s[kChannels], double c[kChannels]) {
  const double fu = q.fu, fv = q.fv;
  const double w00 = (1 - fu) * (1 - fv), w10 = fu * (1 - fv), w01 = (1 - fu) * fv, w11 = fu * fv;
  for (int k = 0; k < kChannels; ++k) {
    s[k] = w00 * q.a[k] + w10 * q.b[k] + w01 * q.c[k] + w11 * q.d[k];
    c[k] = w00 * q.a[kChannels + k] + w10 * q.b[kChannels + k] + w01 * q.c[kChannels + k] + w11 * q.d[kChannels + k];
  }
}

void SkyColumnTable::integrate_fan(std::span<const SkyFanTriangle> fan, const Vec3& n, double out[kChannels],
                                   double max_step_rad) const {
  for (int k = 0; k < kChannels; ++k) out[k] = 0;
  // The look-ups miss the cache (an 8.3 MB table): each node's cells are prefetched when it is
  // generated and read kAhead nodes later, in the same order (the same sums).
  constexpr int kAhead = 8;
  struct Pending {
    Cell cell;
    double horizontal, w;  // n_x cos φ + n_y sin φ, and the node's weight
  };
  Pending ring[kAhead];
  std::size_t generated = 0;
  const auto consume = [&](const Pending& p) {
    double s[kChannels], c[kChannels];
    lookup(p.cell, s, c);
    for (int k = 0; k < kChannels; ++k) out[k] += p.w * (n.z() * s[k] + p.horizontal * c[k]);
  };
  for_each_fan_azimuth_node(fan, max_step_rad, [&](double phi, double cp, double sp, double e0, double w) {
    Pending& slot = ring[generated % kAhead];
    if (generated >= kAhead) consume(slot);
    slot = Pending{cell(phi, e0), n.x() * cp + n.y() * sp, w};
    for (const float* line : {slot.cell.a, slot.cell.c}) {  // rows j0 and j0 + 1 (b, d: the next entry)
      __builtin_prefetch(line);
      __builtin_prefetch(line + 2 * kChannels);
    }
    ++generated;
  });
  for (std::size_t k = generated > kAhead ? generated - kAhead : 0; k < generated; ++k) consume(ring[k % kAhead]);
}

}  // namespace skyband
