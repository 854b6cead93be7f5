#include "geometry/visibility/sky_factors.h"

#include "geometry/horizon/column_scene.h"
#include "geometry/visibility/sky_visibility.h"

namespace skyband {

SkyFactorsRun compute_sky_factors(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                                  SkyFactorsMethod method, int threads,
                                  const std::function<void(std::size_t, std::size_t)>& progress) {
  SkyFactorsRun run;
  run.factors.resize(points.size());
  if (method == SkyFactorsMethod::automatic) {
    const ColumnScene& columns = scene.column_scene();
    run.column_solids = columns.column_solids;
    run.other_components = columns.other_components;
  }
  const SkyMethodCounts counts =
      for_each_visible_sky(scene, points, options, method, threads, progress, false,
                           [&](std::size_t i, const VisibleSky& sky, SkyVisibility&) { run.factors[i] = sky.factors; });
  run.by_horizon = counts.by_horizon;
  run.by_exact = counts.by_exact;
  run.by_bands = counts.by_bands;
  return run;
}

}  // namespace skyband
