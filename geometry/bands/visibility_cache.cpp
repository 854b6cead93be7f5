#include "geometry/bands/visibility_cache.h"

namespace skyband {

PointVisibilityView::PointVisibilityView(const VisibilityCache& cache, std::size_t point) : cache_(&cache) {
  const PointRecord& p = cache.points()[point];
  frame_ = BandFrame::make(Vec3(p.normal[0], p.normal[1], p.normal[2]));
  bands_ = cache.bands().subspan(p.first_band, p.band_count);
}

std::span<const VisibleInterval> PointVisibilityView::visible(std::size_t b) const {
  const auto all_bands = cache_->bands();
  const std::size_t global = static_cast<std::size_t>(&bands_[b] - all_bands.data());
  const std::uint32_t first = bands_[b].first_interval;
  const std::uint32_t last = global + 1 < all_bands.size() ? all_bands[global + 1].first_interval
                                                           : static_cast<std::uint32_t>(cache_->intervals().size());
  return cache_->intervals().subspan(first, last - first);
}

void VisibilityCache::reserve(std::size_t points, std::size_t bands_per_point) {
  points_.reserve(points);
  bands_.reserve(points * bands_per_point);
  intervals_.reserve(points * bands_per_point * 2);
}

void VisibilityCache::append(const PointResult& r) {
  PointRecord p;
  p.normal[0] = r.normal.x();
  p.normal[1] = r.normal.y();
  p.normal[2] = r.normal.z();
  p.first_band = static_cast<std::uint32_t>(bands_.size());
  p.band_count = static_cast<std::uint32_t>(r.bands.size());
  const auto base = static_cast<std::uint32_t>(intervals_.size());
  for (BandRecord b : r.bands) {
    b.first_interval += base;
    bands_.push_back(b);
  }
  intervals_.insert(intervals_.end(), r.intervals.begin(), r.intervals.end());
  points_.push_back(p);
}

void VisibilityCache::append(const VisibilityCache& other) {
  const auto band_base = static_cast<std::uint32_t>(bands_.size());
  const auto interval_base = static_cast<std::uint32_t>(intervals_.size());
  for (PointRecord p : other.points_) {
    p.first_band += band_base;
    points_.push_back(p);
  }
  for (BandRecord b : other.bands_) {
    b.first_interval += interval_base;
    bands_.push_back(b);
  }
  intervals_.insert(intervals_.end(), other.intervals_.begin(), other.intervals_.end());
}

std::size_t VisibilityCache::bytes() const {
  return points_.size() * sizeof(PointRecord) + bands_.size() * sizeof(BandRecord) + intervals_.size() * sizeof(VisibleInterval);
}

}  // namespace skyband
