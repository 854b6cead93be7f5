#include "geometry/points/ground_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "geometry/core/exact_sign.h"
#include "geometry/core/input_error.h"

namespace skyband {

namespace {

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

}  // namespace

GroundGrid make_ground_grid(const Scene& scene, const std::vector<bool>& ground, const GroundGridOptions& o) {
  // Finiteness first: an ordered comparison with a NaN raises FE_INVALID (tests/fp_traps.cpp).
  const double s = o.spacing_m;
  if (!std::isfinite(s) || !(s > 0)) throw InputError("--spacing " + number(s) + ": must be a positive distance in metres");
  if (!std::isfinite(o.height_m) || !(o.height_m >= 0) || o.height_m > 10000)
    throw InputError("--height " + number(o.height_m) + ": must be a height in metres within [0, 10000]");
  const auto& soup = scene.soup();
  if (soup.triangles.empty()) throw InputError("the model has no triangles: no ground to put points on");
  const Aabb& box = scene.bounds();
  std::array<double, 4> area{box.lo.x(), box.lo.y(), box.hi.x(), box.hi.y()};
  if (o.bounds) {
    area = *o.bounds;
    for (double v : area)
      if (!std::isfinite(v)) throw InputError("--bounds: every value must be a finite coordinate in metres");
    if (!(area[0] < area[2] && area[1] < area[3]))
      throw InputError("--bounds " + number(area[0]) + "," + number(area[1]) + "," + number(area[2]) + "," + number(area[3]) +
                       ": needs x_min < x_max and y_min < y_max");
  }
  GroundGrid g;
  const double fx0 = std::floor(area[0] / s), fy0 = std::floor(area[1] / s);
  const double fx1 = std::ceil(area[2] / s), fy1 = std::ceil(area[3] / s);
  const double cols = std::max(1.0, fx1 - fx0), rows = std::max(1.0, fy1 - fy0);
  if (!(cols * rows <= double(o.max_nodes)))
    throw InputError("--spacing " + number(s) + ": " + number(cols) + " × " + number(rows) +
                     " grid nodes over the area, more than " + std::to_string(o.max_nodes) +
                     "; use a larger spacing or --bounds");
  g.ix0 = static_cast<std::int64_t>(fx0), g.iy0 = static_cast<std::int64_t>(fy0);
  g.columns = static_cast<std::size_t>(cols), g.rows = static_cast<std::size_t>(rows);
  const bool has_ground = std::find(ground.begin(), ground.end(), true) != ground.end();
  g.floor_plane = !has_ground;
  const double floor_z = box.lo.z();
  const auto& v = soup.vertices;
  std::vector<std::uint32_t> stack;
  for (std::size_t j = 0; j < g.rows; ++j) {
    for (std::size_t i = 0; i < g.columns; ++i) {
      const std::int64_t ix = g.ix0 + std::int64_t(i), iy = g.iy0 + std::int64_t(j);
      const double x = (double(ix) + 0.5) * s, y = (double(iy) + 0.5) * s;
      const Vec3 q(x, y, 0);
      // The highest surface over the node.
      double top_z = -std::numeric_limits<double>::infinity();
      std::int64_t top = -1;
      bool on_wall = false;
      scene.any_triangle_over(x, y, -std::numeric_limits<double>::infinity(), stack, [&](std::uint32_t t) {
        const auto& tri = soup.triangles[t];
        const Vec3 &A = v[tri[0]], &B = v[tri[1]], &C = v[tri[2]];
        if (std::min({A.x(), B.x(), C.x()}) > x || std::max({A.x(), B.x(), C.x()}) < x || std::min({A.y(), B.y(), C.y()}) > y ||
            std::max({A.y(), B.y(), C.y()}) < y)
          return false;
        const int o0 = exact_orient2d_sign(A, B, C);
        const int o1 = exact_orient2d_sign(A, B, q), o2 = exact_orient2d_sign(B, C, q), o3 = exact_orient2d_sign(C, A, q);
        if (o0 == 0) {  // vertical (or degenerate): the node on its footprint segment is on a wall
          const bool on_segment = o1 == 0 && o2 == 0 && o3 == 0;
          const Vec3 n = (B - A).cross(C - A);
          if (on_segment && n.squaredNorm() > 0) on_wall = true;
          return false;
        }
        if (o1 * o0 < 0 || o2 * o0 < 0 || o3 * o0 < 0) return false;
        // Height of the triangle's plane at (x, y): n·(X − A) = 0.
        const Vec3 n = (B - A).cross(C - A);
        const double z = A.z() - (n.x() * (x - A.x()) + n.y() * (y - A.y())) / n.z();
        const bool is_ground = t < ground.size() && ground[t];
        // Ties go to the non-ground surface: a roof at the height of the terrain hides it.
        if (z > top_z || (z == top_z && top >= 0 && !is_ground)) top_z = z, top = t;
        return false;
      });
      if (on_wall) {
        ++g.under_building;
        continue;
      }
      GroundGridPoint p;
      p.ix = ix, p.iy = iy;
      if (top < 0) {
        if (has_ground) {
          ++g.off_ground;
          continue;
        }
        p.position = Vec3(x, y, floor_z + o.height_m);
      } else {
        if (!(std::size_t(top) < ground.size() && ground[std::size_t(top)])) {
          ++g.under_building;
          continue;
        }
        p.position = Vec3(x, y, top_z + o.height_m);
        p.ground_triangle = top;
      }
      // The exact test of the final point: no non-ground triangle over its xy lies above it or
      // through it (the ground it stands on may round to either side of it).
      const Vec3& P = p.position;
      const bool covered = scene.any_triangle_over(x, y, P.z(), stack, [&](std::uint32_t t) {
        if (t < ground.size() && ground[t]) return false;
        const auto& tri = soup.triangles[t];
        const Vec3 &A = v[tri[0]], &B = v[tri[1]], &C = v[tri[2]];
        if (A.z() < P.z() && B.z() < P.z() && C.z() < P.z()) return false;
        const int o0 = exact_orient2d_sign(A, B, C);
        if (o0 == 0) return false;  // vertical: decided above (on its footprint: no point)
        const int o1 = exact_orient2d_sign(A, B, P), o2 = exact_orient2d_sign(B, C, P), o3 = exact_orient2d_sign(C, A, P);
        if (o1 * o0 < 0 || o2 * o0 < 0 || o3 * o0 < 0) return false;
        // det[A − P, B − P, C − P] has the sign of n·(A − P) with n_z ∝ o0: ≥ 0 · o0 → the
        // triangle's plane is at or above P at P's xy.
        return exact_orientation(A, B, C, P) * o0 >= 0;
      });
      if (covered) {
        ++g.dropped_exact;
        continue;
      }
      g.points.push_back(p);
    }
  }
  return g;
}

}  // namespace skyband
