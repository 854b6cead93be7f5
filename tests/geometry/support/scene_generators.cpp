#include "geometry/support/scene_generators.h"

#include <algorithm>
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
    for (int i = 0; i <= n; ++i) city.soup.vertices.emplace_back(lo + (hi - lo) * i / n, lo + (hi - lo) * j / n, 0.0);
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

std::vector<QueryPoint> facade_points(const std::vector<OrientedBox>& buildings, std::size_t count, double offset_m,
                                      std::uint64_t seed) {
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

namespace skyband::gen {

OpenBoxCity make_open_box_city(const OpenBoxCityParams& pr) {
  OpenBoxCity city;
  city.params = pr;
  Rng rng(pr.seed);
  TriangleSoup& soup = city.soup;
  const int s = std::max(1, pr.splits);
  for (int i = 0; i < pr.per_side; ++i)
    for (int j = 0; j < pr.per_side; ++j) {
      const double wx = rng.uniform(pr.footprint_lo_m, pr.footprint_hi_m), wy = rng.uniform(pr.footprint_lo_m, pr.footprint_hi_m);
      const double h = rng.uniform(pr.height_lo_m, pr.height_hi_m);
      const double cx = (i + 0.5) * pr.pitch_m, cy = (j + 0.5) * pr.pitch_m;
      const Vec3 lo(cx - 0.5 * wx, cy - 0.5 * wy, 0), hi(cx + 0.5 * wx, cy + 0.5 * wy, h);
      city.boxes.push_back({lo, hi});
      // One lattice per box: coordinate k of axis a is lo + (hi − lo)·k/s, so faces meeting at an
      // edge share its vertices bit for bit.
      const auto lattice = [&](int axis, int k) { return k == s ? hi[axis] : lo[axis] + (hi[axis] - lo[axis]) * k / s; };
      // A face: the lattice points varying along axes (a, b) at the fixed coordinate c = value.
      const auto face = [&](int a, int b, int c, double value, bool flip) {
        const auto base = std::uint32_t(soup.vertices.size());
        for (int v = 0; v <= s; ++v)
          for (int u = 0; u <= s; ++u) {
            Vec3 p;
            p[a] = lattice(a, u);
            p[b] = lattice(b, v);
            p[c] = value;
            soup.vertices.push_back(p);
          }
        for (int v = 0; v < s; ++v)
          for (int u = 0; u < s; ++u) {
            const std::uint32_t q0 = base + v * (s + 1) + u, q1 = q0 + 1, q3 = q0 + (s + 1), q2 = q3 + 1;
            if (flip) {
              soup.triangles.push_back({q0, q2, q1});
              soup.triangles.push_back({q0, q3, q2});
            } else {
              soup.triangles.push_back({q0, q1, q2});
              soup.triangles.push_back({q0, q2, q3});
            }
          }
      };
      // Walls (outward winding) and the roof; no floor.
      face(1, 2, 0, lo.x(), false);  // x = lo: (y, z), normal −x
      face(1, 2, 0, hi.x(), true);   // x = hi
      face(0, 2, 1, lo.y(), true);   // y = lo: (x, z), normal −y
      face(0, 2, 1, hi.y(), false);  // y = hi
      face(0, 1, 2, hi.z(), false);  // roof, normal +z
    }
  const double m = pr.margin_m, size = city.size_m();
  const auto base = std::uint32_t(soup.vertices.size());
  soup.vertices.push_back(Vec3(-m, -m, 0));
  soup.vertices.push_back(Vec3(size + m, -m, 0));
  soup.vertices.push_back(Vec3(size + m, size + m, 0));
  soup.vertices.push_back(Vec3(-m, size + m, 0));
  soup.triangles.push_back({base, base + 1, base + 2});
  soup.triangles.push_back({base, base + 2, base + 3});
  return city;
}

std::vector<QueryPoint> open_city_street_points(const OpenBoxCity& city, std::size_t count, std::uint64_t seed, double beyond_m) {
  Rng rng(seed);
  std::vector<QueryPoint> out;
  const double size = city.size_m();
  while (out.size() < count) {
    Vec3 p;
    if (beyond_m > 0) {
      // A ring beyond the edge: a random side, then a random position along it.
      const double along = rng.uniform(-beyond_m, size + beyond_m), off = rng.uniform(1.0, beyond_m);
      switch (rng.below(4)) {
        case 0:
          p = Vec3(along, -off, 0.05);
          break;
        case 1:
          p = Vec3(along, size + off, 0.05);
          break;
        case 2:
          p = Vec3(-off, along, 0.05);
          break;
        default:
          p = Vec3(size + off, along, 0.05);
          break;
      }
    } else {
      p = Vec3{rng.uniform(0, size), rng.uniform(0, size), 0.05};
    }
    bool clear = true;
    for (const auto& b : city.boxes)
      if (p.x() > b[0].x() - 0.5 && p.x() < b[1].x() + 0.5 && p.y() > b[0].y() - 0.5 && p.y() < b[1].y() + 0.5) clear = false;
    if (clear) out.push_back({p, Vec3(0, 0, 1)});
  }
  return out;
}

std::vector<QueryPoint> open_city_facade_points(const OpenBoxCity& city, std::size_t count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<QueryPoint> out;
  while (out.size() < count) {
    const auto& b = city.boxes[rng.below(city.boxes.size())];
    const Vec3 size = b[1] - b[0];
    // A wall chosen by area (perimeter length), a point uniform on it.
    const double perimeter = 2 * (size.x() + size.y());
    double s = rng.uniform(0, perimeter);
    const double z = rng.uniform(0, size.z());
    Vec3 p, n;
    if (s < size.x())
      p = Vec3(b[0].x() + s, b[0].y(), z), n = Vec3(0, -1, 0);
    else if ((s -= size.x()) < size.y())
      p = Vec3(b[1].x(), b[0].y() + s, z), n = Vec3(1, 0, 0);
    else if ((s -= size.y()) < size.x())
      p = Vec3(b[1].x() - s, b[1].y(), z), n = Vec3(0, 1, 0);
    else
      s -= size.x(), p = Vec3(b[0].x(), b[1].y() - s, z), n = Vec3(-1, 0, 0);
    out.push_back({p + 0.05 * n, n});
  }
  return out;
}

HeightField synthetic_city_dsm(std::size_t n, std::uint64_t seed, bool rough) {
  HeightField f;
  f.columns = f.rows = n;
  f.x0 = 85000, f.y0 = 447000 + double(n);
  f.dx = 1, f.dy = -1;
  f.heights.assign(n * n, 0.0);
  Rng rng(seed);
  for (std::size_t b = 0; b < n * n / 650; ++b) {
    const std::size_t x = rng.below(n - 20), y = rng.below(n - 20), w = 5 + rng.below(15), d = 5 + rng.below(15);
    const double z = rng.uniform(5, 40);
    for (std::size_t r = y; r < y + d; ++r)
      for (std::size_t col = x; col < x + w; ++col) f.heights[r * n + col] = std::max(f.heights[r * n + col], z);
  }
  if (rough)
    for (double& h : f.heights)
      if (h == 0) h = 0.3 * rng.uniform();
  return f;
}

}  // namespace skyband::gen
