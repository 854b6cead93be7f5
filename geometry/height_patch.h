#pragma once
// Height patches: groups of non-vertical occluders that together are the graph of one continuous
// function over a convex polygon of the ground plane — a piece of terrain, of a road or of a
// pitched roof. The exact visible sky (geometry/exact_sky.h) projects a patch as a whole before its
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
// That is a subset of the patch's projection, so the patch's occluders are still projected after
// it — and are then mostly culled as already occluded. Where P lies strictly above (below) the
// plane of every occluder of the patch, the elevation grows (falls) monotonically along every such
// curve, the subset is the whole projection, and the occluders are skipped (`complete`): a terrain
// patch around a street point, or far terrain seen from a point below it, is one insertion.
//
// Built once per scene (exact decisions only): occluders are grouped greedily across shared
// edges (bit-equal vertex positions) while the outline stays convex, and a group is kept only if
// it passes the exact test of convex_height_outline: all its polygons turned counter-clockwise in
// xy, the boundary 1-chain (interior edges cancel) is one simple cycle, and every cycle vertex lies
// left of or on every cycle edge, with no two cycle vertices at one xy. Then the polygons' xy
// indicators sum to the winding number of the cycle — 1 inside the convex polygon, 0 outside —
// so they tile it once, and across every interior edge both sides share the same 3-D edge: the
// surface is the graph of a continuous function on Q (a T-junction or a crack leaves extra
// boundary edges and fails the test).
#include <cstdint>
#include <vector>

#include "geometry/scene.h"  // Aabb
#include "geometry/vec3.h"

namespace skyband {

struct Occluder;

inline constexpr std::uint32_t kNoPatch = 0xffffffffu;

struct HeightPatch {
  std::uint32_t first_vertex = 0, vertex_count = 0;  // boundary, counter-clockwise in xy
  std::uint32_t first_member = 0, member_count = 0;  // indices of its occluders
  Aabb box;                                          // of all its occluders' vertices
  // Bounds of the occluders' planes z = h_c + a (x − cx) + b (y − cy), heights relative to cz:
  // h_c ∈ [h_min, h_max], |a| ≤ slope_x, |b| ≤ slope_y (metres, dimensionless).
  double cx = 0, cy = 0, cz = 0, h_min = 0, h_max = 0, slope_x = 0, slope_y = 0;
};

struct HeightPatches {
  std::vector<HeightPatch> patches;
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
