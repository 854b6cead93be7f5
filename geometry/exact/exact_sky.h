#pragma once
// The exact visible sky of a point in any triangle soup: the sky hemisphere (directions above the
// point's horizontal plane, in front of its face) minus the union of the occluders' projections,
// computed as that union over azimuth (geometry/exact/occluded_sky.h), with no bands, sampling or
// tolerance.
//
// Per point: the occluders of the scene (geometry/exact/occluder_set.h: triangles and exactly merged
// convex quads) are visited best first — the node of the BVH that can rise highest first — and
// nodes whose whole box is already occluded over its azimuth range are skipped; each occluder
// reached is projected exactly: in each azimuth of its range it covers the elevations between two
// of its edges' great-circle arcs, or, when it lies over (under) the point, from one edge's arc up
// to the zenith (down to the nadir). A height patch (geometry/exact/height_patch.h) is projected from its
// boundary when its first occluder is reached, and its occluders are skipped where that is all of
// it. Nothing depends on orientation, closure or manifoldness:
// open boxes without floors, party walls modelled once or twice, T-junctions, terrain stitched to
// buildings, leaning walls, overhangs, bridges and points under a roof are all the same case.
// Where sky shows below an occluder (a balcony, a bridge) the union simply has more than one
// interval in that azimuth.
//
// The result is integrated in closed form: over each piece of the union, each visible gap between
// a lower arc X and an upper arc Y (or the zenith) is the difference of two fans of spherical
// triangles (zenith, X(t₀), X(t₁)) − (zenith, Y(t₀), Y(t₁)); Lambert's formula (½ Σ Θ_e n·ĝ_e over
// the boundary arcs) gives the projected solid angle, Van Oosterom and Strackee's formula the solid
// angle. The meridian arcs at the pieces' ends cancel where the visible elevations continue, so
// they are summed only where the boundary lists change.
//
// Exact decisions: below the point's horizontal (exact comparisons), the occluder's plane through
// the point (exact orient3d: it hides nothing), the point's xy inside the occluder's (exact
// orient2d), which chain of an occluder is the upper one (exact orient3d). The arcs' values and
// crossings are constructions, and the measure of the visible sky is continuous in them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/bands/band_visibility.h"  // QueryPoint, SkyFactors
#include "geometry/exact/occluded_sky.h"
#include "geometry/exact/occluder_set.h"
#include "geometry/mesh/scene.h"

namespace skyband {

// Per-thread evaluator. The scene must outlive it.
class ExactSky {
 public:
  // `surface_offset_m` as VisibilityOptions::surface_offset_m (the point is evaluated that far in
  // front of its surface).
  ExactSky(const Scene& scene, double surface_offset_m);

  // The visible sky of q: svf and sky_exposure exact (to rounding) for any scene.
  void compute(const QueryPoint& q, SkyFactors& out);

  // The state of the last compute(): the occluded sky over azimuth, the evaluated point, the
  // normal.
  const OccludedSky& occluded() const { return sky_; }
  const Vec3& evaluated_point() const { return p_; }
  const Vec3& normal() const { return n_; }

  // Statistics of the last compute() (benchmarks).
  std::size_t last_occluders_projected() const { return projected_; }
  std::size_t last_nodes_visited() const { return nodes_visited_; }
  std::size_t last_occluders_changing() const { return changing_; }  // projected and changing the union
  std::size_t last_patches_projected() const { return patches_projected_; }
  std::size_t last_occluders_skipped() const { return skipped_; }  // members of wholly projected patches

  // SVF and exposure of an occluded sky seen with normal n (closed forms per piece).
  static SkyFactors integrate(const OccludedSky& sky, const Vec3& n);

 private:
  void insert_back_of_face();
  // The box's culling data: its azimuth range [lo, hi] and the bounds of tan e over it; false when
  // it is at or below the horizontal or behind the face (then hidden whatever the sky).
  struct Bounds {
    double lo, hi, top, bottom;
    bool open;  // over the point's xy: no azimuth range
  };
  bool node_bounds(const Aabb& box, Bounds& b) const;
  bool node_hidden(const Aabb& box) const;
  void project(const Occluder& o);
  // Projects a height patch from its boundary (geometry/exact/height_patch.h); true when that is its
  // whole projection (or it is hidden or below the horizontal): its occluders may be skipped.
  bool project_patch(const HeightPatch& patch);
  bool beyond_every_plane(const HeightPatch& patch, int side) const;
  struct ArcVertex {
    double u, t, wx, wy;  // unwrapped azimuth, diamond angle, unit horizontal direction
  };
  bool member_sides(const HeightPatch& patch);
  bool silhouette_arc(const PatchEdge& edge, double t_ref, ArcVertex& a, ArcVertex& b, std::uint32_t& circle);
  bool insert_between(const std::vector<ArcVertex>& A, const std::vector<std::uint32_t>& ca, const std::vector<ArcVertex>& B,
                      const std::vector<std::uint32_t>& cb, int order);
  void walk();
  bool looks_small(const Occluder& o) const;

  const OccluderSet& set_;
  double offset_m_;
  Vec3 p_{0, 0, 0}, n_{0, 0, 1};
  OccludedSky sky_;
  std::array<std::vector<std::uint32_t>, 128> buckets_;
  std::vector<std::uint32_t> deferred_;      // nodes hidden only if the gaps closed
  std::vector<std::uint32_t> retest_;        // scratch: the deferred nodes being tested again
  std::vector<std::uint32_t> small_;         // occluders seen small, projected last
  double small_fraction_ = 5e-4;             // twice the solid angle (sr) below which an occluder is small
  std::vector<std::uint32_t> opened_;        // per node: == generation_ once it must be opened
  std::vector<std::uint32_t> seen_;          // per occluder: == generation_ once projected (or tried)
  std::vector<std::uint32_t> patch_seen_;    // per height patch: == generation_ once projected
  std::vector<std::uint32_t> patch_whole_;   // == generation_ when that projection was all of it
  std::vector<Vec3> patch_d_;                // scratch: boundary vertices relative to the point
  std::vector<std::uint32_t> patch_circle_;  // scratch: circle per boundary edge
  std::vector<double> patch_t_, patch_u_;    // scratch: their azimuths, and unwrapped
  std::vector<int> patch_side_;              // scratch: the point's side of each member's plane
  std::vector<ArcVertex> near_, far_, edge_arc_ = std::vector<ArcVertex>(2);  // scratch: arc chains
  std::vector<std::uint32_t> near_circles_, far_circles_, edge_circle_ = std::vector<std::uint32_t>(1);
  std::uint32_t generation_ = 0;
  std::size_t projected_ = 0, nodes_visited_ = 0, changing_ = 0, patches_projected_ = 0, skipped_ = 0;
};

}  // namespace skyband
