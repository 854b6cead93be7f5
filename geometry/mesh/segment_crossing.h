#pragma once
// Exact segment–triangle incidence, and the BVH walk that finds the triangles near a segment.
//
// segment_triangle_crossing(p, q, a, b, c) classifies the closed segment pq against the closed
// triangle abc from signs of orientation determinants only (geometry/core/exact_sign.h, exact on the
// given coordinates; no intersection point is constructed):
//   none   — they do not meet;
//   proper — pq passes through the triangle's interior, its endpoints strictly on either side
//            of the triangle's plane;
//   touch  — they meet in any other way: through an edge or a vertex, with an endpoint on the
//            triangle, or with the segment lying in the triangle's plane and meeting it there
//            (decided in the axis projection in which the triangle is not degenerate).
// Degenerate triangles (collinear corners) are never met: callers skip zero-area faces.
//
// for_each_triangle_near_segment visits the triangles of every BVH leaf whose box the segment
// meets (a superset of the triangles it meets: the boxes are padded so that the floating-point
// slab test never misses one).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/core/vec3.h"
#include "geometry/mesh/scene.h"

namespace skyband {

enum class SegmentCrossing : std::uint8_t { none, proper, touch };

SegmentCrossing segment_triangle_crossing(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c);

// Whether a, b, c are exactly collinear (or coincide): the triangle has zero area.
bool triangle_is_degenerate(const Vec3& a, const Vec3& b, const Vec3& c);

// Whether the segment pq may meet the box: the slab test on the box padded by 1e-9 of the
// coordinates' magnitude plus 1 µm (far beyond the slab test's rounding), so never a false "no".
inline bool segment_may_meet_box(const Vec3& p, const Vec3& q, const Aabb& box) {
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 3; ++k) {
    const double pad = 1e-6 + 1e-9 * (std::abs(box.lo[k]) + std::abs(box.hi[k]));
    const double lo = box.lo[k] - pad, hi = box.hi[k] + pad, d = q[k] - p[k];
    if (d == 0) {
      if (p[k] < lo || p[k] > hi) return false;
      continue;
    }
    double ta = (lo - p[k]) / d, tb = (hi - p[k]) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

// Calls visit(t) for every triangle t of the leaves whose box the segment may meet. `stack` is
// scratch (no allocation once it has grown).
template <class Visit>
void for_each_triangle_near_segment(const Scene& scene, const Vec3& p, const Vec3& q, std::vector<std::uint32_t>& stack,
                                    Visit&& visit) {
  const std::vector<BvhNode>& nodes = scene.bvh_nodes();
  const std::vector<std::uint32_t>& order = scene.bvh_triangle_order();
  if (nodes.empty() || !segment_may_meet_box(p, q, nodes[0].box)) return;
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const BvhNode& node = nodes[stack.back()];
    stack.pop_back();
    if (node.count == 0) {
      for (std::uint32_t child : {node.first, node.first + 1})
        if (segment_may_meet_box(p, q, nodes[child].box)) stack.push_back(child);
      continue;
    }
    for (std::uint32_t k = node.first; k < node.first + node.count; ++k) visit(order[k]);
  }
}

}  // namespace skyband
