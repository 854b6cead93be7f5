#pragma once
// Height patches: groups of non-vertical occluders that together are the graph of one continuous
// function over a convex polygon of the ground plane — a piece of terrain, of a road or of a
// pitched roof. The exact visible sky (geometry/exact/exact_sky.h) projects a patch as a whole before its
// occluders, from its boundary alone, by the intermediate value theorem:
//
//  * seen from a point P whose xy lies outside the polygon Q, a sight line's vertical half-plane in
//    an azimuth of Q's range cuts Q in one segment (Q is convex), and the patch in one continuous
//    curve from a point of its boundary over Q's near side to one over the far side; the
//    elevations seen along a continuous curve form an interval, so every elevation between those
//    of the two boundary points is occluded — between the arcs of the two boundary chains;
//  * seen from P over (under) Q, the curve runs from directly below (above) P to the boundary:
//    everything from the nadir up to the boundary's arcs (from them up to the zenith) is occluded.
//
// Along such a curve the elevation is monotone within each occluder — growing where P lies above
// its plane, falling where below — so it turns only at *silhouette edges*, the interior edges
// between occluders on opposite sides of P. Where P lies strictly above (below) every occluder's
// plane there are none: the interval between the two chains is the whole projection (a terrain
// patch around a street point, far terrain seen from below it, is one insertion). Else the
// extremes along each sight line lie on the boundary or on silhouette edges, and the projection is
// the union of the intervals between the near chain and the far chain and between the near chain
// and each silhouette edge (from over or under Q: from the nadir, or to the zenith, up to each of
// them). Either way the occluders themselves need not be projected; where no such decision is safe
// (P in an occluder's plane, on the boundary's or a silhouette edge's vertical) they are.
//
// Built once per scene (exact decisions only): occluders are grouped greedily across shared
// edges (bit-equal vertex positions) while the outline stays convex, and a group is kept only if
// it passes the exact test of convex_height_outline: all its polygons turned counter-clockwise in
// xy, the boundary 1-chain (interior edges cancel) is one simple cycle (geometry/mesh/boundary_cycle.h),
// every turn of it left (or straight through a vertex strictly between its neighbours) with
// exactly one lowest vertex in (y, x) order — one turn round — and no two cycle vertices at one
// xy. Then the polygons' xy indicators sum to the winding number of the cycle — 1 inside the
// convex polygon, 0 outside — so they tile it once, and across every interior edge both sides share the same 3-D edge: the
// surface is the graph of a continuous function on Q (a T-junction or a crack leaves extra
// boundary edges and fails the test).
#include <cstdint>
#include <vector>

#include "geometry/core/vec3.h"
#include "geometry/mesh/scene.h"  // Aabb

namespace skyband {

struct Occluder;

inline constexpr std::uint32_t kNoPatch = 0xffffffffu;

struct HeightPatch {
  std::uint32_t first_vertex = 0, vertex_count = 0;  // boundary, counter-clockwise in xy
  std::uint32_t first_member = 0, member_count = 0;  // indices of its occluders
  std::uint32_t first_edge = 0, edge_count = 0;      // its interior edges
  Aabb box;                                          // of all its occluders' vertices
  // Bounds of the occluders' planes z = h_c + a (x − cx) + b (y − cy), heights relative to cz:
  // h_c ∈ [h_min, h_max], |a| ≤ slope_x, |b| ≤ slope_y (metres, dimensionless).
  double cx = 0, cy = 0, cz = 0, h_min = 0, h_max = 0, slope_x = 0, slope_y = 0;
};

// An edge shared by two members of one patch: its end points, and the two members' positions in
// the patch's member list.
struct PatchEdge {
  Vec3 a, b;
  std::uint32_t member[2];
};

struct HeightPatches {
  std::vector<HeightPatch> patches;
  std::vector<PatchEdge> edges;        // the patches' interior edges
  std::vector<Vec3> vertices;          // the patches' boundaries
  std::vector<std::uint32_t> members;  // the patches' occluders
};

// Groups the non-vertical occluders (xy_sign != 0) into patches of 2 … max_members occluders and
// sets each grouped occluder's `patch`.
HeightPatches build_height_patches(std::vector<Occluder>& occluders, std::uint32_t max_members = 32);

// Conservative, with a margin above rounding: is z strictly above (sign > 0) or strictly below
// (sign < 0) the plane of every occluder of the patch at (x, y)?
bool strictly_beyond_every_plane(const HeightPatch& patch, double x, double y, double z, int sign);

}  // namespace skyband
