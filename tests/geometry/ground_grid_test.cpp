#define BOOST_TEST_MODULE ground_grid
#include <boost/test/unit_test.hpp>

// The ground grid of `skyband points grid` (geometry/points/ground_grid.h): node positions on the
// S-aligned raster, points on the ground's surface, none inside, on or under a building, and the
// counts of what was left out — each checked by counting cells of boxes whose extents are
// multiples of the spacing (closed forms of the grid, no tolerance but the plane's height).

#include <array>
#include <cmath>
#include <set>
#include <vector>

#include "geometry/core/input_error.h"
#include "geometry/mesh/scene.h"
#include "geometry/points/ground_grid.h"

using namespace skyband;

namespace {

void add_quad(TriangleSoup& s, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, std::uint32_t material) {
  const auto base = std::uint32_t(s.vertices.size());
  s.vertices.insert(s.vertices.end(), {a, b, c, d});
  s.triangles.push_back({base, base + 1, base + 2});
  s.triangles.push_back({base, base + 2, base + 3});
  s.triangle_material.insert(s.triangle_material.end(), {material, material});
}

// A closed box [x0, x1] × [y0, y1] × [z0, z1] of material `m`.
void add_box(TriangleSoup& s, double x0, double y0, double z0, double x1, double y1, double z1, std::uint32_t m) {
  const Vec3 c[8] = {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0},
                     {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}};
  add_quad(s, c[0], c[3], c[2], c[1], m);
  add_quad(s, c[4], c[5], c[6], c[7], m);
  for (int k = 0; k < 4; ++k) add_quad(s, c[k], c[(k + 1) % 4], c[4 + (k + 1) % 4], c[4 + k], m);
}

std::vector<bool> mask_of(const TriangleSoup& s, std::uint32_t ground_material) {
  std::vector<bool> g(s.triangles.size());
  for (std::size_t t = 0; t < g.size(); ++t) g[t] = s.triangle_material[t] == ground_material;
  return g;
}

}  // namespace

// A 10 m box on a floor without ground material, grid 2 m over [−4, 14]²: nodes at the odd
// coordinates −3 … 13 (9 × 9 = 81); the 5 × 5 inside the box's footprint are under it, the other
// 56 stand on the plane of the lowest z (0), H above it.
BOOST_AUTO_TEST_CASE(box_on_a_floor_plane) {
  TriangleSoup s;
  s.material_names = {"building"};
  add_box(s, 0, 0, 0, 10, 10, 10, 0);
  const Scene scene(s);
  GroundGridOptions o;
  o.spacing_m = 2;
  o.height_m = 1.5;
  o.bounds = std::array<double, 4>{-4, -4, 14, 14};
  const GroundGrid g = make_ground_grid(scene, {}, o);
  BOOST_TEST(g.columns == 9u);
  BOOST_TEST(g.rows == 9u);
  BOOST_TEST(g.ix0 == -2);
  BOOST_TEST(g.floor_plane);
  BOOST_TEST(g.under_building == 25u);
  BOOST_TEST(g.points.size() == 56u);
  for (const GroundGridPoint& p : g.points) {
    BOOST_TEST(p.position.z() == 1.5);
    BOOST_TEST(p.position.x() == (double(p.ix) + 0.5) * 2.0);
    BOOST_TEST(p.position.y() == (double(p.iy) + 0.5) * 2.0);
    const bool inside = p.position.x() > 0 && p.position.x() < 10 && p.position.y() > 0 && p.position.y() < 10;
    BOOST_TEST(!inside);
    BOOST_TEST(p.ground_triangle == -1);
  }
}

// Terrain (a ground quad at z = 1 over [−8, 16]²) under a box and a floating slab (a roof
// without walls over [12, 16] × [0, 4] at z = 5): on the 2 m grid the box's 5 × 5 nodes and the
// slab's 2 × 2 are under buildings, every other node stands on the terrain at z = 1. On a 4 m
// grid over [0, 12]² the nodes x, y ∈ {2, 6, 10} put x = 10 or y = 10 on a wall's footprint.
BOOST_AUTO_TEST_CASE(terrain_box_and_overhang) {
  TriangleSoup s;
  s.material_names = {"terrain", "building"};
  add_quad(s, {-8, -8, 1}, {16, -8, 1}, {16, 16, 1}, {-8, 16, 1}, 0);
  add_box(s, 0, 0, 1, 10, 10, 11, 1);
  add_quad(s, {12, 0, 5}, {16, 0, 5}, {16, 4, 5}, {12, 4, 5}, 1);
  const Scene scene(s);
  const std::vector<bool> ground = mask_of(s, 0);
  GroundGridOptions o;
  o.spacing_m = 2;
  const GroundGrid g = make_ground_grid(scene, ground, o);
  // The box of the scene is [−8, 16]²: 12 × 12 nodes.
  BOOST_TEST(g.columns == 12u);
  BOOST_TEST(g.rows == 12u);
  BOOST_TEST(!g.floor_plane);
  BOOST_TEST(g.under_building == 25u + 4u);
  BOOST_TEST(g.off_ground == 0u);
  BOOST_TEST(g.points.size() == 144u - 29u);
  for (const GroundGridPoint& p : g.points) {
    BOOST_TEST(p.position.z() == 1.0);
    BOOST_TEST(p.ground_triangle >= 0);
    BOOST_TEST(ground[std::size_t(p.ground_triangle)]);
  }
  o.spacing_m = 4;
  o.bounds = std::array<double, 4>{0, 0, 12, 12};
  const GroundGrid w = make_ground_grid(scene, ground, o);
  // Nodes x, y ∈ {2, 6, 10}: the 2 × 2 with x, y ∈ {2, 6} are inside the box; the five with
  // x = 10 or y = 10 (and the other ≤ 10) lie on the east or north wall's footprint.
  BOOST_TEST(w.under_building == 9u);
  BOOST_TEST(w.points.empty());
}

// Terrain with a hole (two strips with a gap between): the gap's nodes are off the ground.
BOOST_AUTO_TEST_CASE(nodes_without_ground_are_counted) {
  TriangleSoup s;
  s.material_names = {"road"};
  add_quad(s, {0, 0, 0}, {4, 0, 0}, {4, 12, 0}, {0, 12, 0}, 0);
  add_quad(s, {8, 0, 0}, {12, 0, 0}, {12, 12, 0}, {8, 12, 0}, 0);
  const Scene scene(s);
  GroundGridOptions o;
  o.spacing_m = 2;
  const GroundGrid g = make_ground_grid(scene, mask_of(s, 0), o);
  BOOST_TEST(g.columns * g.rows == 36u);
  BOOST_TEST(g.off_ground == 12u);  // x ∈ {5, 7}, six rows
  BOOST_TEST(g.points.size() == 24u);
}

// Out-of-range parameters are input errors naming the flag.
BOOST_AUTO_TEST_CASE(bad_parameters) {
  TriangleSoup s;
  s.material_names = {"road"};
  add_quad(s, {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0);
  const Scene scene(s);
  const auto message = [&](GroundGridOptions o) {
    try {
      (void)make_ground_grid(scene, mask_of(s, 0), o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  GroundGridOptions o;
  o.spacing_m = 0;
  BOOST_TEST(message(o).starts_with("--spacing 0"));
  o.spacing_m = std::nan("");
  BOOST_TEST(message(o).starts_with("--spacing"));
  o.spacing_m = 1;
  o.height_m = -1;
  BOOST_TEST(message(o).starts_with("--height -1"));
  o.height_m = 0;
  o.bounds = std::array<double, 4>{5, 0, 1, 4};
  BOOST_TEST(message(o).find("x_min < x_max") != std::string::npos);
  o.bounds = std::array<double, 4>{0, 0, 1e7, 1e7};
  BOOST_TEST(message(o).find("grid nodes over the area") != std::string::npos);
}
