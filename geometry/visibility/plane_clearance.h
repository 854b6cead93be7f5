#pragma once
// Calculation points within rounding of a plane seen edge-on, moved clear of it.
//
// Every exact method computes the arcs of edges seen from the point from the differences v − p,
// which rounding perturbs by about an ulp of the coordinates. Where the point lies within a few
// ulps of an occluder's plane — or of the vertical plane through an edge that passes over or
// under it — those arcs are nearly great circles through the zenith whose side rounding can
// flip, while the exact predicates (which side, which chain, over or under) see the true side:
// the two disagree and the region is wrong by up to the half of the sky that the plane bounds
// (a point of a grid at the foot of a slanted wall, 10⁻¹⁶ m outside it). Measured from a point
// 256 ulps away the arcs' errors are below the rounding of the result again.
//
// So the point is moved, before any method sees it, by 4δ (δ = 64 ulps of its largest
// coordinate, at least of 1 m) along the sum of the unit normals of such planes, each turned to
// the side the point lies on (exact orient3d / orient2d); repeated while it is still within δ of
// one (a corner), at most four times. A point exactly in a plane is not moved for it: the exact
// predicates see it there too (the plane hides nothing, its edges have no azimuth range), and the
// result is that of the point as given.
// The move is 10⁻¹⁴ m at coordinates of 1 m and ~3·10⁻⁹ m at UTM coordinates: below anything a
// points file resolves, and every method sees the same point.
#include "geometry/bands/band_visibility.h"  // QueryPoint
#include "geometry/mesh/scene.h"

namespace skyband {

// q moved clear of the planes within rounding of its evaluated point q.position + offset_m·normal
// (unchanged where none is). `stack` is scratch.
QueryPoint clear_of_planes(const Scene& scene, const QueryPoint& q, double offset_m, std::vector<std::uint32_t>& stack);

}  // namespace skyband
