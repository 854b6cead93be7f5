#pragma once
// Exact occluded α-intervals on band sample lines (method.md §3) and the per-point visibility
// computation that fills the visibility cache.
//
// Robustness policy (stated once, docs/robustness.md): which side of a sample plane a vertex lies
// on is the exact sign of m·fl(V − P) (the plane's rounded normal and the vertex's rounded offset,
// the same for every triangle sharing the vertex), and whether a triangle's plane contains the
// calculation point is an exact orient3d on the input doubles (floating-point filters with a CGAL
// exact fallback). Constructions (crossing points, their angles α) are computed in floating point
// in a canonical order per edge, so two triangles sharing an edge produce bit-identical interval
// end points, and the clip to the sky half of the plane compares those same bits: a closed mesh
// never leaks light through shared edges. The only float fast paths are conservative culls.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "geometry/bands/band_frame.h"
#include "geometry/bands/visibility_cache.h"
#include "geometry/mesh/scene.h"

namespace skyband {

struct VisibilityOptions {
  // Initial number of equal-weight bands (method.md §2). Must be ≥ 1.
  int bands = 32;
  // Absolute error target for adaptive band refinement, for the SVF and the sky exposure alike; 0
  // disables refinement (then each band is one sample plane at its weight median: the paper's
  // method). With refinement, every band is sampled at its two edges and its δ-midpoint and
  // integrated with the three-node rule for the weight cos(δ − β) (SVF; exact for f quadratic in
  // δ) and Simpson's rule in δ (exposure); each error is estimated as |rule − midpoint| (for the
  // bands against the face's own plane or the horizon, at least the full variation of their lines:
  // a low skyline far away shows on the horizon's line only; at least half of what a bisected
  // band's rule was off by against its halves; plus a bound of what geometry lying between two
  // lines clear over its α-range can hide), and the worst bands are split — at
  // the pencil angle of an axis-parallel edge when the lines show a step there, else at the
  // δ-midpoint — until both estimated totals are ≤ tolerance/2. Measured against the exact union
  // (band_tolerance_test, bench_visibility_profile; 200 points of each shared model): every
  // error within the tolerance, the largest 0.57·tolerance. docs/geometry.md has the derivation.
  double tolerance = 5e-4;
  // A band is split at most this many times.
  int max_refine_depth = 10;
  // Calculation points are evaluated this far in front of their surface (along the normal), so
  // that a point given on a surface in rounded decimal coordinates is not hidden by that surface.
  double surface_offset_m = 1e-6;
  // Method "automatic" uses the exact union instead of the exact horizon on column solids whose
  // faces are finely split (geometry/visibility/sky_visibility.cpp); true keeps the horizon wherever it is
  // valid — for height fields, whose pixel sides continue one another along every row of equal
  // heights and whose union would not be cheaper. Results agree to rounding either way.
  bool prefer_horizon = false;
  // Parts of the scene seen only within this angle of the pencil axis (α < tail or α > π − tail)
  // are not traversed: cosine weighting makes their largest possible effect on the SVF
  // (4/(3π))·W·tail³/2 ≤ 0.43·tail³ = 4.3e-7 at the default (docs/geometry.md); 0 = exhaustive.
  double axis_tail_rad = 0.01;
  // false: test every triangle against every plane (the naive reference the BVH and occlusion
  // culling are checked against; with axis_tail_rad = 0 both give bit-identical intervals).
  bool accelerate = true;
};

// One calculation point.
struct QueryPoint {
  Vec3 position;  // metres
  Vec3 normal;    // unit
};

// Visibility of one point. Thread-compatible: use one BandVisibility per thread.
class BandVisibility {
 public:
  BandVisibility(const Scene& scene, const VisibilityOptions& options);
  ~BandVisibility();
  BandVisibility(const BandVisibility&) = delete;
  BandVisibility& operator=(const BandVisibility&) = delete;

  // Fills `out` with the point's bands and visible intervals.
  void compute(const QueryPoint& q, VisibilityCache::PointResult& out);

  // Visible α-intervals of the single sample half-plane at δ (any δ in [0, π]) through the point,
  // clipped to [0, π]; used for exact sun-shadow tests and reference computations.
  void visible_on_plane(const QueryPoint& q, double delta_rad, std::vector<VisibleInterval>& out);

  // Is the direction (unit, ω·z ≥ 0 and ω·n > 0) unoccluded from the point? Exact shadow test.
  bool direction_visible(const QueryPoint& q, const Vec3& direction);

  // Statistics of the last compute() (for benchmarks).
  std::size_t last_triangle_tests() const;
  std::size_t last_plane_count() const;

 private:
  struct Impl;
  Impl* impl_;
};

// Uniform-sky factors of one point (geometry/bands/sky_integral.h).
struct SkyFactors {
  double svf = 0;           // cosine-weighted sky view factor
  double sky_exposure = 0;  // visible sky solid angle in front of the face / 2π
};

// SVF and sky exposure for many points without keeping their visibility cache: memory stays
// O(points), not O(points × bands). Bit-identical to sky_view_factor/sky_exposure of
// compute_visibility's cache, whatever the thread count.
std::vector<SkyFactors> compute_band_sky_factors(const Scene& scene, std::span<const QueryPoint> points,
                                                 const VisibilityOptions& options, int threads = 0,
                                                 const std::function<void(std::size_t, std::size_t)>& progress = {});

// Computes the cache for many points with `threads` workers (0 = all cores). The result is
// bit-identical whatever the thread count. `progress(done, total)` is called from one thread.
VisibilityCache compute_visibility(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                                   int threads = 0, const std::function<void(std::size_t, std::size_t)>& progress = {});

// The streaming form of the two functions above, for consumers that need more than the two
// uniform-sky numbers but not the whole cache at once (memory O(chunk), not O(points × bands)):
// the points are computed in chunks of consecutive points on `threads` workers, and each finished
// chunk is handed to `consume(first_point, chunk, worker)` on the worker's thread — concurrently
// for different chunks, in no particular order. `chunk.view(i)` is point first_point + i; each
// point is computed alone, so the chunk does not depend on the thread count. `worker` is that
// thread's BandVisibility (e.g. for sun-shadow tests of the chunk's points; its per-point state
// is no longer needed). The consumer may move the chunk away. `progress(done, total)` is called
// from one thread.
using VisibilityChunkConsumer = std::function<void(std::size_t first_point, VisibilityCache& chunk, BandVisibility& worker)>;
void for_each_visibility_chunk(const Scene& scene, std::span<const QueryPoint> points, const VisibilityOptions& options,
                               int threads, const std::function<void(std::size_t, std::size_t)>& progress,
                               const VisibilityChunkConsumer& consume);

}  // namespace skyband
