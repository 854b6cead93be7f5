#pragma once
// Visibility caches built by hand for lighting tests (no geometry): a point with a given normal,
// N equal-weight bands (geometry/bands/band_frame.h), and per band the visible α-intervals returned by
// a callback (default: the whole sample line [0, π], an unobstructed sky).
#include <functional>
#include <utility>
#include <vector>

#include "geometry/bands/band_frame.h"
#include "geometry/bands/visibility_cache.h"

namespace skyband::test {

// visible(band index, δ of its sample plane) → sorted disjoint [α0, α1] pairs in [0, π].
using VisibleFn = std::function<std::vector<std::pair<double, double>>(int band, double delta_rad)>;

inline VisibilityCache::PointResult hand_point(const Vec3& normal, int band_count, const VisibleFn& visible = {}) {
  VisibilityCache::PointResult r;
  r.normal = normal.normalized();
  const BandFrame frame = BandFrame::make(r.normal);
  const std::vector<Band> bands = equal_weight_bands(frame, band_count);
  for (std::size_t b = 0; b < bands.size(); ++b) {
    BandRecord rec;
    rec.s0 = static_cast<float>(bands[b].s0);
    rec.s1 = static_cast<float>(bands[b].s1);
    rec.delta_rad = static_cast<float>(frame.delta_at(bands[b].s_centre()));
    rec.exposure_weight = static_cast<float>(frame.delta_at(bands[b].s1) - frame.delta_at(bands[b].s0));
    rec.first_interval = static_cast<std::uint32_t>(r.intervals.size());
    if (visible) {
      for (auto [a0, a1] : visible(static_cast<int>(b), rec.delta_rad))
        r.intervals.push_back({static_cast<float>(a0), static_cast<float>(a1)});
    } else {
      r.intervals.push_back({0.0f, static_cast<float>(kPi)});
    }
    r.bands.push_back(rec);
  }
  return r;
}

inline VisibilityCache single_point_cache(const Vec3& normal, int band_count, const VisibleFn& visible = {}) {
  VisibilityCache c;
  c.append(hand_point(normal, band_count, visible));
  return c;
}

}  // namespace skyband::test
