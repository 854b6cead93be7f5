#include "geometry/sky_factors.h"

#include <atomic>
#include <memory>
#include <mutex>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "geometry/column_scene.h"
#include "geometry/horizon_svf.h"

namespace skyband {

SkyFactorsRun compute_sky_factors(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                                  SkyFactorsMethod method, int threads,
                                  const std::function<void(std::size_t, std::size_t)>& progress) {
  SkyFactorsRun run;
  if (method == SkyFactorsMethod::bands) {
    run.factors = compute_sky_factors(scene, points, options, threads, progress);
    run.by_bands = points.size();
    return run;
  }
  const ColumnScene& columns = scene.column_scene();
  run.column_solids = columns.column_solids;
  run.other_components = columns.other_components;
  run.factors.resize(points.size());

  // Pass 1: the exact horizon; points where it is not valid are marked.
  std::vector<char> done_by_horizon(points.size(), 0);
  const int n = threads > 0 ? threads : tbb::this_task_arena::max_concurrency();
  constexpr std::size_t kChunk = 64;
  const std::size_t chunks = (points.size() + kChunk - 1) / kChunk;
  tbb::enumerable_thread_specific<std::unique_ptr<HorizonSvf>> workers;
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  tbb::task_arena arena(n);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& range) {
      auto& worker = workers.local();
      if (!worker) worker = std::make_unique<HorizonSvf>(scene, columns, options.surface_offset_m);
      for (std::size_t c = range.begin(); c != range.end(); ++c) {
        const std::size_t first = c * kChunk, last = std::min(points.size(), first + kChunk);
        for (std::size_t i = first; i < last; ++i) done_by_horizon[i] = worker->compute(points[i], run.factors[i]);
        const std::size_t now = done += (last - first);
        if (progress) {
          std::unique_lock lock(progress_mutex, std::try_to_lock);
          if (lock.owns_lock()) progress(now, points.size());
        }
      }
    });
  });

  // Pass 2: the band method on the rest.
  std::vector<QueryPoint> rest;
  std::vector<std::size_t> rest_index;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!done_by_horizon[i]) {
      rest.push_back(points[i]);
      rest_index.push_back(i);
    }
  run.by_bands = rest.size();
  run.by_horizon = points.size() - rest.size();
  if (!rest.empty()) {
    const std::vector<SkyFactors> banded = compute_sky_factors(scene, rest, options, threads);
    for (std::size_t k = 0; k < rest.size(); ++k) run.factors[rest_index[k]] = banded[k];
  }
  if (progress) progress(points.size(), points.size());
  return run;
}

}  // namespace skyband
