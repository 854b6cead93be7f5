#pragma once
// The one place that decides how the visible sky of a calculation point is computed, and the
// parallel driver every per-point job (skyband svf, skyband irradiance) goes through.
//
// Methods, in the order tried (SkyFactorsMethod, geometry/visibility/sky_factors.h):
//   automatic  the exact horizon (geometry/horizon/horizon_svf.h) where the scene seen from the point is a
//              column scene (closed extruded buildings): its special case is the fastest; every
//              other point by the exact union of the occluders' projections (geometry/exact/exact_sky.h),
//              which holds for any triangle soup. Both are exact to rounding.
//   exact      the exact union everywhere.
//   bands      the band method (geometry/bands/band_visibility.h) everywhere, with its options.
// A further method is a new file and a case here.
//
// The sun (or any direction) is tested by looking it up in the point's visible sky; only a
// direction within rounding of the region's boundary, or a point computed by the band method,
// goes to the exact shadow test on a sample plane (BandVisibility::direction_visible).
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/mesh/scene.h"
#include "geometry/visibility/sky_factors.h"
#include "geometry/visibility/visible_sky.h"

namespace skyband {

class HorizonSvf;
class ExactSky;

// Per-thread evaluator (thread-compatible). The scene must outlive it.
class SkyVisibility {
 public:
  SkyVisibility(const Scene& scene, const VisibilityOptions& options, SkyFactorsMethod method);
  ~SkyVisibility();
  SkyVisibility(const SkyVisibility&) = delete;
  SkyVisibility& operator=(const SkyVisibility&) = delete;

  // The visible sky of q (valid until the next call). `region`: keep what the lighting needs
  // beyond SVF and exposure — the exact methods' region, the band method's cache view.
  const VisibleSky& compute(const QueryPoint& q, bool region = true);

  // Exact: is the unit direction d (e.g. the sun's) visible from q, the point of the last
  // compute(q, true)? A look-up in its visible sky, an exact sample-plane test only near a boundary.
  bool direction_visible(const QueryPoint& q, const Vec3& d);

  std::size_t exact_tests() const { return exact_tests_; }  // direction tests that needed the exact test

 private:
  BandVisibility& bands();
  const Scene& scene_;
  VisibilityOptions options_;
  SkyFactorsMethod method_;
  std::unique_ptr<HorizonSvf> horizon_;
  std::unique_ptr<ExactSky> exact_;
  std::unique_ptr<BandVisibility> bands_;
  VisibilityCache band_cache_;
  VisibilityCache::PointResult band_result_;
  std::unique_ptr<PointVisibilityView> band_view_;
  VisibleSky sky_;
  Vec3 given_{std::nan(""), 0, 0};  // the last point given to compute(), and that point moved clear of planes
  QueryPoint cleared_;
  std::vector<std::uint32_t> stack_;
  std::size_t exact_tests_ = 0;
};

struct SkyMethodCounts {
  std::size_t by_horizon = 0, by_exact = 0, by_bands = 0;
};

// Every point's visible sky, in Z-order of (x, y) (neighbours share cached nodes; no result
// depends on the order or on `threads`, 0 = all cores), in chunks on the workers:
// consume(i, sky, worker) for point i on the worker's thread (concurrently for different points).
// `progress(done, total)` from one thread.
using VisibleSkyConsumer = std::function<void(std::size_t, const VisibleSky&, SkyVisibility&)>;
SkyMethodCounts for_each_visible_sky(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                                     SkyFactorsMethod method, int threads,
                                     const std::function<void(std::size_t, std::size_t)>& progress, bool region,
                                     const VisibleSkyConsumer& consume);

// The visibility cache (geometry/bands/visibility_cache.h: α-intervals on band sample lines, what the
// renderer's lighting reads) of many points. The band method fills it with its own geometry
// pass; the exact methods cut each point's exact visible sky along sample lines
// (geometry/bands/sample_lines.h: options.bands lines, doubled until the lines' SVF and exposure are
// within options.tolerance/2 of the exact values). In input order; the same whatever `threads`.
VisibilityCache compute_visibility_cache(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                                         SkyFactorsMethod method, int threads = 0,
                                         const std::function<void(std::size_t, std::size_t)>& progress = {},
                                         SkyMethodCounts* counts = nullptr);

}  // namespace skyband
