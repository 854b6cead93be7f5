#pragma once
// Exact sky view factor and sky exposure of a point in a column scene (geometry/horizon/column_scene.h)
// by its horizon: no bands, no sampling, no tolerance.
//
// In a column scene, seen from a point outside every column solid, a sky direction is occluded
// exactly when it lies below the highest scene point in its azimuth (docs/geometry.md, "Exact
// horizon"). Every triangle's highest point in an azimuth lies on one of its edges (the point is
// not below the triangle), and an edge seen from the point traces a great-circle arc, so the
// visible sky is the region above the upper envelope of the edges' arcs, the horizon and the
// face's own plane — a spherical polygon whose edges are great-circle arcs. Its projected solid
// angle follows from Lambert's formula (½ Σ Θ_e n·ĝ_e over the boundary arcs) and its solid angle
// from Van Oosterom and Strackee's triangle formula, both in closed form.
//
// The envelope (geometry/horizon/horizon_envelope.h) is kept over a pseudo-angle of azimuth as sorted
// pieces, each one arc; the BVH is walked best first, the node that can rise highest first, and
// nodes wholly below the current envelope (a conservative bound of their highest elevation
// against binned minima of the envelope over their azimuth range) are skipped. Decisions that change the answer's topology are
// exact: which triangles lie wholly below the point's horizontal (exact comparisons), whether the point is under a triangle
// (exact orient2d / orient3d). Envelope values are constructions (rounding-level errors, and
// continuous in them: no decision among nearly equal arcs can change the result by more than
// their difference).
#include <cstddef>
#include <memory>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/exact/sky_fan.h"
#include "geometry/horizon/column_scene.h"
#include "geometry/mesh/scene.h"

namespace skyband {

class HorizonEnvelope;

// Per-thread evaluator. The scene and the classification must outlive it.
class HorizonSvf {
 public:
  // `surface_offset_m` as VisibilityOptions::surface_offset_m (the point is evaluated that far in
  // front of its surface).
  HorizonSvf(const Scene& scene, const ColumnScene& columns, double surface_offset_m);
  ~HorizonSvf();
  HorizonSvf(const HorizonSvf&) = delete;
  HorizonSvf& operator=(const HorizonSvf&) = delete;

  // Fills `out` and returns true when the method is valid for q: the scene is a column scene
  // from q's evaluated point, the point is outside every column solid (no triangle reaching above
  // it lies over it), and the normal does not face down (n_z ≥ 0). Otherwise returns false and
  // another method must be used (the dispatcher takes the exact union).
  bool compute(const QueryPoint& q, SkyFactors& out);

  // The visible sky of the last compute() that returned true, as a fan of spherical triangles
  // (geometry/exact/sky_fan.h) in counter-clockwise order: for irradiance under any sky.
  void visible_fan(std::vector<SkyFanTriangle>& out) const;

  // The envelope of the last compute() that returned true: the sky is visible above it.
  const HorizonEnvelope& envelope() const;

  // Statistics of the last compute() (benchmarks).
  std::size_t last_edge_tests() const;  // silhouette candidates tested (not culled by their node)
  std::size_t last_envelope_pieces() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace skyband
