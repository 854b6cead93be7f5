#include "geometry/support/real_mesh_points.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/support/scene_generators.h"

namespace skyband::gen {

namespace {

// The lowest vertex z within `radius` (xy) of p, or +∞.
double local_ground(const TriangleSoup& soup, const Vec3& p, double radius) {
  double z = std::numeric_limits<double>::infinity();
  for (const Vec3& v : soup.vertices) {
    const double dx = v.x() - p.x(), dy = v.y() - p.y();
    if (dx * dx + dy * dy <= radius * radius) z = std::min(z, v.z());
  }
  return z;
}

}  // namespace

std::vector<QueryPoint> real_mesh_street_points(const Scene& scene, std::size_t count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<QueryPoint> out;
  const Aabb& b = scene.bounds();
  if (b.empty()) return out;
  const Vec3 lo = b.lo + 0.02 * (b.hi - b.lo), hi = b.hi - 0.02 * (b.hi - b.lo);
  const double top = b.hi.z() + 10;
  // Where the vertical ray at (x, y) finds the ground: its height, or NaN where it finds a roof or
  // a wall, or +∞ where nothing lies below.
  const auto ground_hit = [&](double x, double y, double ground) {
    const auto hit = scene.surface_hit(Ray{Vec3(x, y, top), Vec3(0, 0, -1)});
    if (!hit) return std::numeric_limits<double>::infinity();
    if (std::abs(hit->normal.z()) < 0.7 || hit->position.z() > ground + 1.5) return std::nan("");  // a roof or a wall
    return hit->position.z();
  };
  // A random place: its xy and local ground level; false where no vertex lies within 25 m.
  double x = 0, y = 0, ground = 0;
  const auto draw = [&] {
    x = rng.uniform(lo.x(), hi.x()), y = rng.uniform(lo.y(), hi.y());
    ground = local_ground(scene.soup(), Vec3(x, y, 0), 25.0);
    return std::isfinite(ground);
  };
  // A model with a ground surface (terrain, roads, water: at least a tenth of the places with
  // vertices nearby have one below) gets street points on it only — where nothing lies below is
  // outside the model or in a hole of its ground; a model without one (buildings alone) gets them
  // at its local ground level.
  std::size_t tried = 0, on_ground = 0;
  for (std::size_t attempt = 0; attempt < 20000 && tried < 400; ++attempt) {
    if (!draw()) continue;
    ++tried;
    on_ground += std::isfinite(ground_hit(x, y, ground));
  }
  const bool has_ground = 10 * on_ground >= tried && on_ground > 0;
  for (std::size_t attempt = 0; attempt < 200 * count && out.size() < count; ++attempt) {
    if (!draw()) continue;
    double z = ground_hit(x, y, ground);
    if (std::isnan(z)) continue;  // a roof or a wall
    if (std::isinf(z)) {
      if (has_ground) continue;  // outside the model's ground
      z = ground;
    }
    const Vec3 p(x, y, z + 0.05);
    if (scene.intersect(Ray{p, Vec3(0, 0, 1)})) continue;  // under something
    out.push_back({p, Vec3(0, 0, 1)});
  }
  return out;
}

std::vector<QueryPoint> real_mesh_facade_points(const Scene& scene, std::size_t count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<QueryPoint> out;
  const TriangleSoup& soup = scene.soup();
  std::vector<double> cumulative;
  std::vector<std::uint32_t> walls;
  double total = 0;
  for (std::uint32_t t = 0; t < soup.triangles.size(); ++t) {
    const Vec3 m = scene.triangle_normal(t);
    const double area2 = m.norm();
    if (!(area2 > 1e-6) || std::abs(m.z()) > 0.1 * area2) continue;
    walls.push_back(t);
    total += area2;
    cumulative.push_back(total);
  }
  if (walls.empty()) return out;
  while (out.size() < count) {
    const double r = rng.uniform(0, total);
    const std::size_t k =
        std::min(walls.size() - 1, std::size_t(std::lower_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin()));
    const auto& tri = soup.triangles[walls[k]];
    double u = rng.uniform(), v = rng.uniform();
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const Vec3& A = soup.vertices[tri[0]];
    const Vec3 p = A + u * (soup.vertices[tri[1]] - A) + v * (soup.vertices[tri[2]] - A);
    const Vec3 n = scene.triangle_normal(walls[k]).normalized();
    out.push_back({p + 0.05 * n, n});
  }
  return out;
}

std::vector<QueryPoint> real_mesh_points(const Scene& scene, std::size_t count, std::uint64_t seed) {
  std::vector<QueryPoint> out = real_mesh_street_points(scene, count / 2, seed);
  const std::vector<QueryPoint> f = real_mesh_facade_points(scene, count - count / 2, seed + 1);
  out.insert(out.end(), f.begin(), f.end());
  return out;
}

}  // namespace skyband::gen
