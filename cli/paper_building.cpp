#include "cli/paper_building.h"

#include <algorithm>
#include <string>
#include <vector>

namespace skyband::cli {
namespace {

enum Slot : std::uint32_t { kWall = 0, kFrame, kGlass, kRoof, kGround, kNeighbour };

struct Builder {
  TriangleSoup& s;
  void quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, std::uint32_t slot) {
    const auto i = static_cast<std::uint32_t>(s.vertices.size());
    s.vertices.insert(s.vertices.end(), {a, b, c, d});
    s.triangles.push_back({i, i + 1, i + 2});
    s.triangles.push_back({i, i + 2, i + 3});
    s.triangle_material.push_back(slot);
    s.triangle_material.push_back(slot);
  }
  void box(const Vec3& lo, const Vec3& hi, std::uint32_t side, std::uint32_t top) {
    const double x0 = lo.x(), y0 = lo.y(), z0 = lo.z(), x1 = hi.x(), y1 = hi.y(), z1 = hi.z();
    quad({x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}, side);
    quad({x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}, side);
    quad({x1, y1, z0}, {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, side);
    quad({x0, y1, z0}, {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, side);
    quad({x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}, top);
  }
};

constexpr double kStorey_m = 3.3, kSill_m = 0.9, kWindowHeight_m = 1.8, kWindowWidth_m = 1.6;
constexpr double kReveal_m = 0.2, kFrame_m = 0.07;
constexpr int kStoreys = 5;

// One facade: lower-left corner `o` seen from outside, `u` unit to the right (horizontal), length
// L, `windows` per storey evenly spaced. Outward normal = u × z.
void facade(Builder& b, const Vec3& o, const Vec3& u, double length, int windows) {
  const Vec3 z(0, 0, 1), out = u.cross(z), in = -out;
  // Grid lines along u and z: every window edge (conforming quads, no T-junctions).
  std::vector<double> us = {0.0, length}, zs = {0.0, kStoreys * kStorey_m};
  const double pitch = length / windows;
  for (int w = 0; w < windows; ++w) {
    const double c = (w + 0.5) * pitch;
    us.push_back(c - 0.5 * kWindowWidth_m);
    us.push_back(c + 0.5 * kWindowWidth_m);
  }
  for (int k = 0; k < kStoreys; ++k) {
    zs.push_back(k * kStorey_m + kSill_m);
    zs.push_back(k * kStorey_m + kSill_m + kWindowHeight_m);
  }
  std::sort(us.begin(), us.end());
  std::sort(zs.begin(), zs.end());
  auto P = [&](double uu, double zz, double depth) { return Vec3(o + uu * u + zz * z + depth * in); };
  for (std::size_t i = 0; i + 1 < us.size(); ++i)
    for (std::size_t j = 0; j + 1 < zs.size(); ++j) {
      const double u0 = us[i], u1 = us[i + 1], z0 = zs[j], z1 = zs[j + 1];
      // Window cells: odd intervals of both sorted lists (between a window's two edges).
      const bool window = (i % 2 == 1) && (j % 2 == 1);
      if (!window) {
        b.quad(P(u0, z0, 0), P(u1, z0, 0), P(u1, z1, 0), P(u0, z1, 0), kWall);
        continue;
      }
      // Reveals (wall material), from the facade plane to the recess depth.
      b.quad(P(u0, z0, 0), P(u1, z0, 0), P(u1, z0, kReveal_m), P(u0, z0, kReveal_m), kWall);  // sill
      b.quad(P(u0, z1, 0), P(u0, z1, kReveal_m), P(u1, z1, kReveal_m), P(u1, z1, 0), kWall);  // head
      b.quad(P(u0, z0, 0), P(u0, z0, kReveal_m), P(u0, z1, kReveal_m), P(u0, z1, 0), kWall);  // left jamb
      b.quad(P(u1, z0, 0), P(u1, z1, 0), P(u1, z1, kReveal_m), P(u1, z0, kReveal_m), kWall);  // right jamb
      // Back plane: 3×3 grid, the centre cell is glass, the ring is frame.
      const double uu[4] = {u0, u0 + kFrame_m, u1 - kFrame_m, u1};
      const double zz[4] = {z0, z0 + kFrame_m, z1 - kFrame_m, z1};
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c)
          b.quad(P(uu[a], zz[c], kReveal_m), P(uu[a + 1], zz[c], kReveal_m), P(uu[a + 1], zz[c + 1], kReveal_m),
                 P(uu[a], zz[c + 1], kReveal_m), (a == 1 && c == 1) ? kGlass : kFrame);
    }
}

}  // namespace

PaperBuilding make_paper_building() {
  PaperBuilding pb;
  TriangleSoup& s = pb.soup;
  s.material_names = {"wall", "frame", "glass", "roof", "ground", "neighbour"};
  Builder b{s};
  b.quad({-5000, -5000, 0}, {5000, -5000, 0}, {5000, 5000, 0}, {-5000, 5000, 0}, kGround);
  const double x0 = -12, x1 = 12, y0 = -7, y1 = 7, h = kStoreys * kStorey_m;
  facade(b, {x0, y0, 0}, {1, 0, 0}, x1 - x0, 6);   // south, outward −y
  facade(b, {x1, y0, 0}, {0, 1, 0}, y1 - y0, 3);   // east, outward +x
  facade(b, {x1, y1, 0}, {-1, 0, 0}, x1 - x0, 6);  // north, outward +y
  facade(b, {x0, y1, 0}, {0, -1, 0}, y1 - y0, 3);  // west, outward −x
  b.quad({x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}, kRoof);
  b.box({14, -26, 0}, {24, -14, 22}, kNeighbour, kRoof);  // the neighbour, south-east
  pb.camera.position = Vec3(-36, -46, 1.6);
  pb.camera.look_at = Vec3(3, -5, 9.0);
  pb.camera.up = Vec3(0, 0, 1);
  pb.camera.vertical_fov_deg = 30;
  return pb;
}

}  // namespace skyband::cli
