#include "geometry/support/scene_generators.h"

#include <cmath>

namespace skyband::gen {

void append_box(TriangleSoup& soup, const OrientedBox& box) {
  const auto base = static_cast<std::uint32_t>(soup.vertices.size());
  for (int k = 0; k < 8; ++k) soup.vertices.push_back(box.corner(k));
  // Quads as corner indices, counter-clockwise seen from outside (same construction as
  // OrientedBox::faces: (bi, bj) follow the cyclic axis order).
  for (int axis = 0; axis < 3; ++axis) {
    const std::uint32_t bi = 1u << ((axis + 1) % 3), bj = 1u << ((axis + 2) % 3);
    for (std::uint32_t side = 0; side < 2; ++side) {
      const std::uint32_t o = side ? (1u << axis) : 0u;
      std::uint32_t q[4] = {o, o | bi, o | bi | bj, o | bj};
      if (side == 0) std::swap(q[1], q[3]);  // reverse orientation for the − side
      soup.triangles.push_back({base + q[0], base + q[1], base + q[2]});
      soup.triangles.push_back({base + q[0], base + q[2], base + q[3]});
    }
  }
}

TriangleSoup boxes_to_soup(const std::vector<OrientedBox>& boxes) {
  TriangleSoup soup;
  soup.vertices.reserve(8 * boxes.size());
  soup.triangles.reserve(12 * boxes.size());
  for (const OrientedBox& b : boxes) append_box(soup, b);
  return soup;
}

std::vector<OrientedBox> random_boxes(const RandomBoxParams& pr, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<OrientedBox> out;
  for (int i = 0; i < pr.count; ++i) {
    OrientedBox b;
    const double cx = rng.uniform(-pr.extent_m, pr.extent_m);
    const double cy = rng.uniform(-pr.extent_m, pr.extent_m);
    const double sx = rng.uniform(pr.size_lo_m, pr.size_hi_m);
    const double sy = rng.uniform(pr.size_lo_m, pr.size_hi_m);
    const double h = rng.uniform(pr.height_lo_m, pr.height_hi_m);
    b.centre = Vec3(cx, cy, 0.5 * h);
    b.size = Vec3(sx, sy, h);
    b.yaw_rad = rng.uniform(0, kPi);
    out.push_back(b);
  }
  return out;
}

std::vector<OrientedBox> street_canyon(double width_m, double height_m, double length_m, double thickness_m) {
  OrientedBox south, north;
  south.size = north.size = Vec3(length_m, thickness_m, height_m);
  south.centre = Vec3(0, -0.5 * thickness_m, 0.5 * height_m);
  north.centre = Vec3(0, width_m + 0.5 * thickness_m, 0.5 * height_m);
  return {south, north};
}

City make_city(const CityParams& pr) {
  City city;
  city.params = pr;
  Rng rng(pr.seed);
  const double pitch = city.pitch_m();
  const double lot = pr.block_m / pr.lots;
  constexpr double kMinSetback = 0.5;  // metres: neighbouring buildings never touch
  for (int bx = 0; bx < pr.blocks; ++bx)
    for (int by = 0; by < pr.blocks; ++by)
      for (int lx = 0; lx < pr.lots; ++lx)
        for (int ly = 0; ly < pr.lots; ++ly) {
          const double x0 = bx * pitch + 0.5 * pr.street_m + lx * lot;
          const double y0 = by * pitch + 0.5 * pr.street_m + ly * lot;
          const double s_w = rng.uniform(kMinSetback, pr.setback_max_m), s_e = rng.uniform(kMinSetback, pr.setback_max_m);
          const double s_s = rng.uniform(kMinSetback, pr.setback_max_m), s_n = rng.uniform(kMinSetback, pr.setback_max_m);
          const double h = rng.uniform(pr.height_lo_m, pr.height_hi_m);
          OrientedBox b;
          b.size = Vec3(lot - s_w - s_e, lot - s_s - s_n, h);
          b.centre = Vec3(x0 + s_w + 0.5 * b.size.x(), y0 + s_s + 0.5 * b.size.y(), 0.5 * h);
          city.buildings.push_back(b);
        }
  city.soup = boxes_to_soup(city.buildings);
  // Ground grid over [−pitch, size + pitch]², z = 0.
  const double lo = -pitch, hi = city.size_m() + pitch;
  const int n = pr.ground_cells;
  const auto base = static_cast<std::uint32_t>(city.soup.vertices.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      city.soup.vertices.emplace_back(lo + (hi - lo) * i / n, lo + (hi - lo) * j / n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t v00 = base + j * (n + 1) + i, v10 = v00 + 1, v01 = v00 + (n + 1), v11 = v01 + 1;
      city.soup.triangles.push_back({v00, v10, v11});
      city.soup.triangles.push_back({v00, v11, v01});
    }
  return city;
}

CityParams city_params_for_triangles(std::size_t triangles, std::uint64_t seed) {
  CityParams p;
  p.lots = 2;
  // blocks² · (12 · lots²) building triangles + 2 · (blocks + 2)² ground triangles.
  const double per_block = 12.0 * p.lots * p.lots + 2.0;
  p.blocks = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(triangles) / per_block))));
  p.ground_cells = p.blocks + 2;
  p.seed = seed;
  return p;
}

std::vector<QueryPoint> street_points(const City& city, std::size_t count, std::uint64_t seed) {
  Rng rng(seed);
  const double pitch = city.pitch_m(), size = city.size_m();
  const double half = 0.45 * city.params.street_m;  // stay 5 % of the width off the kerb line
  std::vector<QueryPoint> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const bool along_x = rng.uniform() < 0.5;
    const double street_centre = pitch * static_cast<double>(rng.below(city.params.blocks + 1));
    const double along = rng.uniform(0, size);
    const double across = street_centre + rng.uniform(-half, half);
    QueryPoint q;
    q.position = along_x ? Vec3(along, across, 0) : Vec3(across, along, 0);
    q.normal = Vec3(0, 0, 1);
    out.push_back(q);
  }
  return out;
}

std::vector<QueryPoint> facade_points(const std::vector<OrientedBox>& buildings, std::size_t count,
                                      double offset_m, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<QueryPoint> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const OrientedBox& b = buildings[rng.below(buildings.size())];
    const int side = static_cast<int>(rng.below(4));  // 0: +x, 1: −x, 2: +y, 3: −y (local)
    const double t = rng.uniform(0.05, 0.95) - 0.5;   // along the wall, fraction of its length
    const double z = b.centre.z() + (rng.uniform(0.05, 0.95) - 0.5) * b.size.z();
    Vec3 local_n, local_p;
    if (side < 2) {
      const double sgn = side == 0 ? 1.0 : -1.0;
      local_n = Vec3(sgn, 0, 0);
      local_p = Vec3(sgn * (0.5 * b.size.x() + offset_m), t * b.size.y(), 0);
    } else {
      const double sgn = side == 2 ? 1.0 : -1.0;
      local_n = Vec3(0, sgn, 0);
      local_p = Vec3(t * b.size.x(), sgn * (0.5 * b.size.y() + offset_m), 0);
    }
    const double c = std::cos(b.yaw_rad), s = std::sin(b.yaw_rad);
    auto rotate = [&](const Vec3& v) { return Vec3(c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()); };
    QueryPoint q;
    q.position = Vec3(b.centre.x(), b.centre.y(), z) + rotate(local_p);
    q.normal = rotate(local_n);
    out.push_back(q);
  }
  return out;
}

void translate(TriangleSoup& soup, const Vec3& offset) {
  for (Vec3& v : soup.vertices) v += offset;
}

void translate(std::vector<QueryPoint>& points, const Vec3& offset) {
  for (QueryPoint& q : points) q.position += offset;
}

}  // namespace skyband::gen
