#pragma once
// The scene's occluders for the exact visible sky (geometry/exact/exact_sky.h): planar convex polygons
// of 3 or 4 vertices and a bounding-volume hierarchy over them. Built once per scene
// (Scene::occluders()), read-only afterwards.
//
// Every triangle of the soup that is not exactly degenerate (collinear or repeated vertices: it
// hides a set of measure zero) is an occluder, except where exactly coplanar triangles are merged:
//  * a region of ≥ 3 triangles connected through shared edges (bit-equal vertex positions) and
//    lying in one plane (exact orient3d) whose boundary is one strictly convex polygon (exact
//    orientations in the plane; the argument is in occluder_set.cpp) becomes that polygon, cut
//    into a fan of convex quads: a wall split into a grid of cells is one occluder again;
//  * two remaining triangles sharing an edge, coplanar and forming a strictly convex
//    quadrilateral, become that quad.
// Either covers exactly the same points as the triangles it replaces. A wall or roof rectangle is
// then one occluder, not two or hundreds, and internal edges do not split the occluded sky.
// Nothing depends on orientation, closure or manifoldness.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/exact/height_patch.h"
#include "geometry/mesh/scene.h"
#include "geometry/mesh/triangle_soup.h"

namespace skyband {

// A planar convex polygon, vertices in order around it (either orientation). The first three are
// never collinear.
struct Occluder {
  std::array<Vec3, 4> v;  // metres; v[3] unused when count == 3
  std::uint32_t count = 3;
  std::uint32_t triangle = 0;  // a source triangle of the soup (for reports)
  // Orientation of the xy-projections of v[0], v[1], v[2] (exact: +1 counter-clockwise seen from
  // above, −1 clockwise, 0 a vertical polygon).
  int xy_sign = 0;
  // A vertical polygon's upper chain: the vertices bounding it from above, in order along it (a
  // static property: seen from any point outside its plane, higher is higher in elevation), and
  // the highest vertex of its lower chain. From a point at or above that height the polygon covers
  // the sky from the ground up to the upper chain's arcs. `across` are two vertices with distinct
  // xy (the plane is the vertical through them).
  std::uint8_t upper[4] = {0, 0, 0, 0};
  std::uint8_t upper_count = 0;  // 0: not vertical
  std::uint8_t across[2] = {0, 0};
  double lower_top_z = 0;          // metres
  std::uint32_t patch = kNoPatch;  // the height patch it belongs to (geometry/exact/height_patch.h)
  double area2_m2 = 0;             // twice its area
};

struct OccluderSet {
  std::vector<Occluder> occluders;       // in the order of the leaves of `nodes`
  std::vector<BvhNode> nodes;            // node 0 the root
  std::size_t degenerate_triangles = 0;  // dropped: collinear or repeated vertices (no area)
  std::size_t merged_quads = 0;          // pairs of triangles merged into one quad
  std::size_t merged_regions = 0;        // regions of ≥ 3 coplanar triangles merged into a convex polygon
  double max_z = -1e300;                 // metres, the highest vertex
  HeightPatches height_patches;          // groups of occluders projected as one first
  // Per non-vertical occluder, the vertical ones (walls) that share one of its edges and lie
  // below it: support[support_first[i] .. support_first[i + 1]). The walk projects them before
  // an occluder floating above the point (the wall under a roof's eave before the roof), an order
  // that changes what the union costs, not what it is.
  std::vector<std::uint32_t> support_first, support;
};

OccluderSet build_occluder_set(const TriangleSoup& soup);

}  // namespace skyband
