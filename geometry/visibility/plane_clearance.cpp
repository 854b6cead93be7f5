#include "geometry/visibility/plane_clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/exact_sign.h"

namespace skyband {

QueryPoint clear_of_planes(const Scene& scene, const QueryPoint& q, double offset_m, std::vector<std::uint32_t>& stack) {
  QueryPoint out = q;
  const TriangleSoup& soup = scene.soup();
  constexpr double kUlp = std::numeric_limits<double>::epsilon();
  for (int round = 0; round < 4; ++round) {
    const Vec3 p = out.position + offset_m * out.normal;
    if (!p.allFinite()) return out;
    const double delta = 64 * kUlp * std::max({1.0, std::abs(p.x()), std::abs(p.y()), std::abs(p.z())});
    Vec3 move(0, 0, 0);
    bool near = false;
    // The side of a plane with unit normal u the point is on: exact sign s, else the normal's.
    // Exactly in a plane the predicates see it so too (the plane hides nothing, its edges have no
    // azimuth range) and nothing is moved for it.
    const auto push = [&](int s, const Vec3& u) {
      if (s == 0) return;
      move += double(s) * u;
      near = true;
    };
    // Triangles of leaves whose box's xy, widened by δ, holds the point's.
    const auto near_column = [&](const Aabb& b) {
      return b.lo.x() - delta <= p.x() && p.x() <= b.hi.x() + delta && b.lo.y() - delta <= p.y() && p.y() <= b.hi.y() + delta;
    };
    scene.any_triangle_in(near_column, stack, [&](std::uint32_t t) {
      const auto& tri = soup.triangles[t];
      const Vec3 &a = soup.vertices[tri[0]], &b = soup.vertices[tri[1]], &c = soup.vertices[tri[2]];
      const Vec3 m = (b - a).cross(c - a);
      const double mn = m.norm();
      if (!(mn > 0)) return false;
      if (std::abs(m.dot(p - a)) <= delta * mn)
        push(-exact_orientation(a, b, c, p), m / mn);  // det[a − p, b − p, c − p] = −(p − a)·m
      // The vertical plane of each edge, where the point's xy lies along the edge.
      const Vec3* v[3] = {&a, &b, &c};
      for (int e = 0; e < 3; ++e) {
        const Vec3 &u = *v[e], &w = *v[(e + 1) % 3];
        const double hx = w.x() - u.x(), hy = w.y() - u.y(), len = std::hypot(hx, hy);
        if (!(len > 0)) continue;
        const double px = p.x() - u.x(), py = p.y() - u.y();
        const double along = (px * hx + py * hy) / len;
        if (along < -delta || along > len + delta) continue;
        if (std::abs(hx * py - hy * px) > delta * len) continue;
        push(exact_orient2d_sign(u, w, p), Vec3(-hy / len, hx / len, 0));  // + : left of u → w
      }
      return false;  // every triangle near the column
    });
    if (!near) return out;
    const double mlen = move.norm();
    if (!(mlen > 1e-9)) return out;  // pushed both ways at once: left as it is
    out.position += (4 * delta / mlen) * move;
  }
  return out;
}

}  // namespace skyband
