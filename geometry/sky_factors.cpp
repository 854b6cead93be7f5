#include "geometry/sky_factors.h"

#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/column_scene.h"
#include "geometry/exact_sky.h"
#include "geometry/horizon_svf.h"
#include "geometry/parallel_chunks.h"
#include "geometry/point_order.h"

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
  if (method == SkyFactorsMethod::exact) {
    run.factors.resize(points.size());
    run.by_exact = points.size();
    const std::vector<std::uint32_t> order = xy_morton_order(points);
    for_each_in_chunks(
        points.size(), 16, threads, progress, [&] { return std::make_unique<ExactSky>(scene, options.surface_offset_m); },
        [&](ExactSky& exact, std::size_t k) { exact.compute(points[order[k]], run.factors[order[k]]); });
    return run;
  }
  const ColumnScene& columns = scene.column_scene();
  run.column_solids = columns.column_solids;
  run.other_components = columns.other_components;
  run.factors.resize(points.size());

  // Pass 1: the exact horizon; points where it is not valid are marked.
  std::vector<char> done_by_horizon(points.size(), 0);
  const std::vector<std::uint32_t> order = xy_morton_order(points);  // cache locality; no result changes
  for_each_in_chunks(
      points.size(), 16, threads, progress,
      [&] { return std::make_unique<HorizonSvf>(scene, columns, options.surface_offset_m); },
      [&](HorizonSvf& horizon, std::size_t k) {
        const std::size_t i = order[k];
        done_by_horizon[i] = horizon.compute(points[i], run.factors[i]);
      });

  // Pass 2: the exact visible sky on the rest.
  const PointSubset rest = points_not_done(points, done_by_horizon);
  run.by_exact = rest.points.size();
  run.by_horizon = points.size() - rest.points.size();
  if (!rest.points.empty()) {
    const std::vector<std::uint32_t> rest_order = xy_morton_order(rest.points);
    for_each_in_chunks(
        rest.points.size(), 16, threads, {}, [&] { return std::make_unique<ExactSky>(scene, options.surface_offset_m); },
        [&](ExactSky& exact, std::size_t k) {
          const std::size_t i = rest_order[k];
          exact.compute(rest.points[i], run.factors[rest.index[i]]);
        });
  }
  if (progress) progress(points.size(), points.size());
  return run;
}

PointSubset points_not_done(std::span<const QueryPoint> points, const std::vector<char>& done) {
  PointSubset rest;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!done[i]) {
      rest.points.push_back(points[i]);
      rest.index.push_back(i);
    }
  return rest;
}

}  // namespace skyband
