#pragma once
// The visibility cache (method.md §3): per calculation point, its band frame and, per band, the
// sorted disjoint *visible* α-intervals of the band's sample line. It holds no sky, sun or
// material, so one geometry pass serves any number of skies, sun positions and materials.
//
// Storage is contiguous and compact: one PointRecord per point, one BandRecord per band, one
// VisibleInterval per interval, all in flat arrays (bytes_per_point() reports the cost).
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/bands/band_frame.h"
#include "geometry/core/vec3.h"

namespace skyband {

struct VisibleInterval {
  float alpha0_rad;  // 0 ≤ alpha0 < alpha1 ≤ π, along the sample line from +x
  float alpha1_rad;
};

struct BandRecord {
  float s0, s1;                  // weight-space edges (s = sin(δ − β)), weight = s1 − s0
  float delta_rad;               // sample plane of the band (its weight median)
  std::uint32_t first_interval;  // index into the interval array
  // The line's weight in δ (radians) for the solid angle Σ_b w_b ∫_visible sin α dα: with
  // refinement Simpson's weights (Δδ/6, 4Δδ/6, Δδ/6) per band, else the band's δ-width.
  float exposure_weight = 0;
};

struct PointRecord {
  double normal[3];  // unit normal (the frame is rebuilt from it, bit-identically)
  std::uint32_t first_band;
  std::uint32_t band_count;
};

class VisibilityCache;

// A read-only view of one point's cached visibility.
class PointVisibilityView {
 public:
  PointVisibilityView(const VisibilityCache& cache, std::size_t point);
  const BandFrame& frame() const { return frame_; }
  std::size_t band_count() const { return bands_.size(); }
  const BandRecord& band(std::size_t b) const { return bands_[b]; }
  double band_weight(std::size_t b) const { return double(bands_[b].s1) - double(bands_[b].s0); }
  std::span<const VisibleInterval> visible(std::size_t b) const;

 private:
  const VisibilityCache* cache_;
  BandFrame frame_;
  std::span<const BandRecord> bands_;
};

class VisibilityCache {
 public:
  // Per-point result as produced by the visibility computation, before packing.
  struct PointResult {
    Vec3 normal;
    std::vector<BandRecord> bands;  // first_interval relative to `intervals`
    std::vector<VisibleInterval> intervals;
  };

  void reserve(std::size_t points, std::size_t bands_per_point);
  void clear() { points_.clear(), bands_.clear(), intervals_.clear(); }  // keeps the capacity
  void append(const PointResult& r);
  void append(const VisibilityCache& other);  // concatenation in order

  std::size_t size() const { return points_.size(); }
  PointVisibilityView view(std::size_t point) const { return PointVisibilityView(*this, point); }
  std::size_t bytes() const;
  double bytes_per_point() const { return points_.empty() ? 0.0 : double(bytes()) / double(points_.size()); }

  std::span<const PointRecord> points() const { return points_; }
  std::span<const BandRecord> bands() const { return bands_; }
  std::span<const VisibleInterval> intervals() const { return intervals_; }

 private:
  std::vector<PointRecord> points_;
  std::vector<BandRecord> bands_;
  std::vector<VisibleInterval> intervals_;
};

}  // namespace skyband
