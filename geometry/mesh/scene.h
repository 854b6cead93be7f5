#pragma once
// The scene: a triangle soup plus a bounding-volume hierarchy over it. Built once, read-only
// afterwards and safe to share between threads.
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/core/vec3.h"
#include "geometry/mesh/triangle_soup.h"

namespace skyband {

struct ColumnScene;
struct OccluderSet;

struct Aabb {
  Vec3 lo{+1e300, +1e300, +1e300};
  Vec3 hi{-1e300, -1e300, -1e300};
  void extend(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  Vec3 centre() const { return 0.5 * (lo + hi); }
  bool empty() const { return lo.x() > hi.x(); }
};

// The node of every BVH here (the scene's triangles, the exact horizon's silhouette edges, the
// exact union's occluders): node 0 the root; a leaf holds items [first, first + count) in its
// hierarchy's leaf order (Scene::bvh_triangle_order(), ColumnScene::edges, OccluderSet::occluders).
struct BvhNode {
  Aabb box;                 // of the items' vertices
  std::uint32_t first = 0;  // leaf: first item slot; inner: index of the left child (right = left + 1)
  std::uint32_t count = 0;  // leaf: number of items (> 0); inner: 0
};

struct Ray {
  Vec3 origin;
  Vec3 direction;  // need not be unit
  double t_min = 0;
  double t_max = 1e300;
};

struct RayHit {
  double t = 0;
  std::uint32_t triangle = 0;
  double u = 0, v = 0;  // barycentrics of vertices 1 and 2
};

struct SurfaceHit {
  Vec3 position;  // metres, on the triangle
  Vec3 normal;    // unit, facing the ray's origin
  std::uint32_t triangle = 0;
};

class Scene {
 public:
  explicit Scene(TriangleSoup soup);

  const TriangleSoup& soup() const { return soup_; }
  const Aabb& bounds() const { return nodes_.empty() ? empty_box_ : nodes_[0].box; }
  const std::vector<BvhNode>& bvh_nodes() const { return nodes_; }
  const std::vector<std::uint32_t>& bvh_triangle_order() const { return order_; }
  // A BVH query: calls stop = visit(t) for every triangle t of a leaf reached through boxes for
  // which holds(box) is true (a superset: the caller tests the triangle), until a visit returns
  // true; returns whether one did. `stack` is scratch (no allocation once it has grown).
  template <class Holds, class Visit>
  bool any_triangle_in(Holds&& holds, std::vector<std::uint32_t>& stack, Visit&& visit) const {
    if (nodes_.empty() || !holds(nodes_[0].box)) return false;
    stack.clear();
    stack.push_back(0);
    while (!stack.empty()) {
      const BvhNode& node = nodes_[stack.back()];
      stack.pop_back();
      if (node.count == 0) {
        for (std::uint32_t child : {node.first, node.first + 1})
          if (holds(nodes_[child].box)) stack.push_back(child);
        continue;
      }
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
        if (visit(order_[k])) return true;
    }
    return false;
  }
  // The triangles of leaves whose box holds the vertical line through (x, y) and reaches up to
  // z_min or above, as any_triangle_in.
  template <class Visit>
  bool any_triangle_over(double x, double y, double z_min, std::vector<std::uint32_t>& stack, Visit&& visit) const {
    return any_triangle_in(
        [&](const Aabb& b) { return b.hi.z() >= z_min && b.lo.x() <= x && x <= b.hi.x() && b.lo.y() <= y && y <= b.hi.y(); },
        stack, std::forward<Visit>(visit));
  }
  // Geometric (unnormalised) normal of triangle t by its winding: (v1 − v0) × (v2 − v0).
  Vec3 triangle_normal(std::uint32_t t) const;

  // The scene's column-solid classification (geometry/horizon/column_scene.h), computed on first use
  // (thread-safe) and kept.
  const ColumnScene& column_scene() const;
  // The scene's occluders for the exact visible sky (geometry/exact/occluder_set.h), built on first use
  // (thread-safe) and kept.
  const OccluderSet& occluders() const;

  // Closest hit along the ray (watertight ray/triangle test), or nothing.
  std::optional<RayHit> intersect(const Ray& ray) const;
  // The closest hit as a shading point: the point on the triangle from the barycentrics (more
  // precise than o + t·d) and the unit geometric normal turned to face the ray's origin (meshes
  // may be inconsistently oriented). Nothing if the ray misses or hits a zero-area triangle.
  std::optional<SurfaceHit> surface_hit(const Ray& ray) const;

 private:
  void build();
  TriangleSoup soup_;
  std::vector<BvhNode> nodes_;
  std::vector<std::uint32_t> order_;
  Aabb empty_box_;
  mutable std::once_flag column_once_;
  mutable std::shared_ptr<const ColumnScene> column_scene_;
  mutable std::once_flag occluders_once_;
  mutable std::shared_ptr<const OccluderSet> occluders_;
};

}  // namespace skyband
