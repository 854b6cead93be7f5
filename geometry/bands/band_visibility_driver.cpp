// The parallel driver of the band method: points in chunks on the workers (for_each_chunk,
// geometry/core/parallel_chunks.h), each with its own BandVisibility, the chunks' caches gathered in point order
// (compute_visibility) or reduced to sky factors at once (compute_band_sky_factors). Declared in band_visibility.h.
#include <algorithm>
#include <map>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <memory>
#include <mutex>

#include <tbb/task_arena.h>

#include "geometry/bands/band_visibility.h"
#include "geometry/bands/sky_integral.h"
#include "geometry/core/parallel_chunks.h"

namespace skyband {

namespace {
// Points per chunk: at most 256 (the hand-over is a few µs against ~1 ms per point, and a large
// run keeps few, large parts), and at least 16 chunks per worker, so that the last chunk of a
// small run (2,000 points: 62 per chunk, not 256) leaves the other core idle only briefly.
std::size_t chunk_size(std::size_t points, int workers) {
  const std::size_t per = points / (16 * static_cast<std::size_t>(std::max(workers, 1)));
  return std::clamp<std::size_t>(per, 16, 256);
}
}  // namespace

void for_each_visibility_chunk(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                               int threads, const std::function<void(std::size_t, std::size_t)>& progress,
                               const VisibilityChunkConsumer& consume) {
  const int n = threads > 0 ? threads : tbb::this_task_arena::max_concurrency();
  for_each_chunk(
      points.size(), chunk_size(points.size(), n), n, progress, [&] { return std::make_unique<BandVisibility>(scene, options); },
      [&](BandVisibility& worker, std::size_t first, std::size_t last) {
        VisibilityCache::PointResult result;
        VisibilityCache part;
        part.reserve(last - first, static_cast<std::size_t>(options.bands) + 8);
        for (std::size_t i = first; i < last; ++i) {
          worker.compute(points[i], result);
          part.append(result);
        }
        consume(first, part, worker);
      });
  if (progress) progress(points.size(), points.size());
}

VisibilityCache compute_visibility(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                                   int threads, const std::function<void(std::size_t, std::size_t)>& progress) {
  // Parts keyed by their first point (chunks arrive in any order), then concatenated in order.
  std::map<std::size_t, VisibilityCache> parts;
  std::mutex parts_mutex;
  for_each_visibility_chunk(scene, points, options, threads, progress,
                            [&](std::size_t first, VisibilityCache& part, BandVisibility&) {
                              std::lock_guard lock(parts_mutex);
                              parts.emplace(first, std::move(part));
                            });
  VisibilityCache cache;
  std::size_t bands = 0;
  for (const auto& [first, part] : parts) bands += part.bands().size();
  cache.reserve(points.size(), points.empty() ? 0 : bands / points.size() + 1);
  // Each part is released once copied, and every 32 parts the freed heap pages are handed back
  // to the system (glibc keeps freed blocks of this size mapped otherwise): the resident peak is
  // then about the cache plus 32 parts, not twice the cache.
  std::size_t released = 0;
  for (auto& [first, part] : parts) {
    cache.append(part);
    part = VisibilityCache{};
#ifdef __GLIBC__
    if (++released % 32 == 0) malloc_trim(0);
#endif
  }
  return cache;
}

std::vector<SkyFactors> compute_band_sky_factors(const Scene& scene, std::span<const QueryPoint> points,
                                                 const VisibilityOptions& options, int threads,
                                                 const std::function<void(std::size_t, std::size_t)>& progress) {
  std::vector<SkyFactors> out(points.size());
  for_each_visibility_chunk(scene, points, options, threads, progress,
                            [&](std::size_t first, VisibilityCache& part, BandVisibility&) {
                              for (std::size_t i = 0; i < part.size(); ++i) {
                                const PointVisibilityView v = part.view(i);
                                out[first + i] = SkyFactors{sky_view_factor(v), sky_exposure(v)};
                              }
                            });
  return out;
}

}  // namespace skyband
