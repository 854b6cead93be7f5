#include "geometry/visibility/sky_visibility.h"

#include <atomic>
#include <vector>

#include "geometry/bands/sample_lines.h"
#include "geometry/bands/sky_integral.h"
#include "geometry/core/parallel_chunks.h"
#include "geometry/exact/exact_sky.h"
#include "geometry/horizon/column_scene.h"
#include "geometry/horizon/horizon_svf.h"
#include "geometry/points/point_order.h"
#include "geometry/visibility/plane_clearance.h"

namespace skyband {

SkyVisibility::SkyVisibility(const Scene& scene, const VisibilityOptions& options, SkyFactorsMethod method)
    : scene_(scene), options_(options), method_(method) {
  // Both exact methods give the same values to rounding; the horizon is the cheaper where it
  // applies, unless the column solids' faces are finely split (more than half their silhouette
  // candidates continued by a collinear one: a wall split 11 × 11 has 11 candidate edges along its
  // top but is one occluder of the union, whose coplanar regions are merged; not with
  // VisibilityOptions::prefer_horizon). The union's
  // occluders are built only when a point needs them.
  if (method == SkyFactorsMethod::automatic) {
    const ColumnScene& columns = scene.column_scene();
    if (columns.column_solids > 0 && (options.prefer_horizon || 2 * columns.split_edges <= columns.edges.size()))
      horizon_ = std::make_unique<HorizonSvf>(scene, columns, options.surface_offset_m);
  }
}

SkyVisibility::~SkyVisibility() = default;

BandVisibility& SkyVisibility::bands() {
  if (!bands_) bands_ = std::make_unique<BandVisibility>(scene_, options_);
  return *bands_;
}

const VisibleSky& SkyVisibility::compute(const QueryPoint& given, bool region) {
  // Within rounding of a plane seen edge-on, every method would build arcs whose side rounding
  // decides: the point is moved clear first (geometry/visibility/plane_clearance.h).
  given_ = given.position;
  cleared_ = clear_of_planes(scene_, given, options_.surface_offset_m, stack_);
  const QueryPoint& q = cleared_;
  sky_.normal = q.normal;
  sky_.point = q.position + options_.surface_offset_m * q.normal;
  sky_.bands = nullptr;
  sky_.pieces.clear();
  if (horizon_ && horizon_->compute(q, sky_.factors)) {
    sky_.method = SkyMethod::exact_horizon;
    if (region) sky_.assign(horizon_->envelope());
    return sky_;
  }
  if (method_ != SkyFactorsMethod::bands) {
    if (!exact_) exact_ = std::make_unique<ExactSky>(scene_, options_.surface_offset_m);
    sky_.method = SkyMethod::exact_union;
    exact_->compute(q, sky_.factors);
    if (region) sky_.assign(exact_->occluded());
    return sky_;
  }
  sky_.method = SkyMethod::bands;
  bands().compute(q, band_result_);
  band_cache_.clear();
  band_cache_.append(band_result_);
  band_view_ = std::make_unique<PointVisibilityView>(band_cache_.view(0));
  sky_.factors.svf = sky_view_factor(*band_view_);
  sky_.factors.sky_exposure = sky_exposure(*band_view_);
  if (region) sky_.bands = band_view_.get();
  return sky_;
}

bool SkyVisibility::direction_visible(const QueryPoint& given, const Vec3& d) {
  const QueryPoint& q = given.position == given_ ? cleared_ : given;
  if (sky_.exact() && !sky_.pieces.empty()) {
    const int r = sky_.lookup(d);
    if (r >= 0) return r == 1;
  }
  ++exact_tests_;
  return bands().direction_visible(q, d);
}

SkyMethodCounts for_each_visible_sky(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                                     SkyFactorsMethod method, int threads,
                                     const std::function<void(std::size_t, std::size_t)>& progress, bool region,
                                     const VisibleSkyConsumer& consume) {
  std::atomic<std::size_t> counts[3] = {0, 0, 0};
  const std::vector<std::uint32_t> order = xy_morton_order(points);
  // Chunks of 16 points: short enough to balance the end of a run, long enough to amortise.
  for_each_in_chunks(
      points.size(), 16, threads, progress, [&] { return std::make_unique<SkyVisibility>(scene, options, method); },
      [&](SkyVisibility& worker, std::size_t k) {
        const std::size_t i = order[k];
        const VisibleSky& sky = worker.compute(points[i], region);
        counts[int(sky.method)].fetch_add(1, std::memory_order_relaxed);
        consume(i, sky, worker);
      });
  if (progress) progress(points.size(), points.size());
  return {counts[0].load(), counts[1].load(), counts[2].load()};
}

VisibilityCache compute_visibility_cache(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                                         SkyFactorsMethod method, int threads,
                                         const std::function<void(std::size_t, std::size_t)>& progress, SkyMethodCounts* counts) {
  if (method == SkyFactorsMethod::bands) {
    if (counts) *counts = {0, 0, points.size()};
    return compute_visibility(scene, points, options, threads, progress);
  }
  SampleLineOptions lines;
  lines.bands = options.bands;
  lines.tolerance = options.tolerance;
  std::vector<VisibilityCache::PointResult> results(points.size());
  const SkyMethodCounts c = for_each_visible_sky(
      scene, points, options, method, threads, progress, true,
      [&](std::size_t i, const VisibleSky& sky, SkyVisibility&) { sample_lines_of(sky, lines, results[i]); });
  if (counts) *counts = c;
  VisibilityCache cache;
  std::size_t bands = 0;
  for (const auto& r : results) bands += r.bands.size();
  cache.reserve(points.size(), points.empty() ? 0 : bands / points.size() + 1);
  for (auto& r : results) {
    cache.append(r);
    std::vector<BandRecord>().swap(r.bands);
    std::vector<VisibleInterval>().swap(r.intervals);
  }
  return cache;
}

}  // namespace skyband
