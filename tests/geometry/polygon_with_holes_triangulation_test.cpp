#define BOOST_TEST_MODULE polygon_with_holes_triangulation
#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/mesh/polygon_with_holes_triangulation.h"

using namespace skyband;
namespace tt = boost::test_tools;
using Triangles = std::vector<std::array<std::uint32_t, 3>>;
using Rings = std::vector<std::vector<std::uint32_t>>;

namespace {

// Sum of the triangles' vector areas ½ (b−a)×(c−a), relative to `origin` for precision.
Vec3 vector_area(const std::vector<Vec3>& p, const Triangles& tris, const Vec3& origin) {
  Vec3 s = Vec3::Zero();
  for (const auto& t : tris) s += 0.5 * (p[t[1]] - origin - (p[t[0]] - origin)).cross(p[t[2]] - origin - (p[t[0]] - origin));
  return s;
}

double unsigned_area(const std::vector<Vec3>& p, const Triangles& tris, const Vec3& origin) {
  double s = 0;
  for (const auto& t : tris)
    s += 0.5 * (p[t[1]] - origin - (p[t[0]] - origin)).cross(p[t[2]] - origin - (p[t[0]] - origin)).norm();
  return s;
}

// Does any triangle's centroid lie strictly inside the axis-aligned xy box (lo, hi)?
bool centroid_inside(const std::vector<Vec3>& p, const Triangles& tris, double lo_x, double lo_y, double hi_x, double hi_y,
                     const Vec3& origin) {
  for (const auto& t : tris) {
    const Vec3 c = ((p[t[0]] - origin) + (p[t[1]] - origin) + (p[t[2]] - origin)) / 3.0;
    if (c.x() > lo_x && c.x() < hi_x && c.y() > lo_y && c.y() < hi_y) return true;
  }
  return false;
}

// 10 × 10 square (counter-clockwise seen from +z) with square holes; `offset` shifts everything
// (real coordinates: RD New x ≈ 8·10⁴, y ≈ 4.5·10⁵ m).
struct Square {
  std::vector<Vec3> p;
  Rings rings;
};
Square square_with_holes(const Vec3& offset, bool holes_clockwise) {
  Square s;
  s.p = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0},  // outer 0..3
         {2, 2, 0}, {5, 2, 0},  {5, 5, 0},   {2, 5, 0},   // hole 3 × 3 = 9, indices 4..7
         {6, 6, 0}, {8, 6, 0},  {8, 8, 0},   {6, 8, 0}};  // hole 2 × 2 = 4, indices 8..11
  for (auto& v : s.p) v += offset;
  s.rings = {{0, 1, 2, 3}, {4, 5, 6, 7}, {8, 9, 10, 11}};
  if (holes_clockwise)
    for (std::size_t r = 1; r < 3; ++r) std::reverse(s.rings[r].begin(), s.rings[r].end());
  return s;
}

}  // namespace

BOOST_AUTO_TEST_CASE(square_with_two_holes_has_outer_minus_holes_area_in_either_hole_orientation) {
  for (const bool cw : {true, false})
    for (const Vec3& offset : {Vec3(0, 0, 0), Vec3(84616.468, 447422.999, 3.25)}) {
      const Square s = square_with_holes(offset, cw);
      const auto r = triangulate_polygon_with_holes(s.p, s.rings);
      BOOST_TEST(r.method == PolygonTriangulationMethod::kConstrainedDelaunay);
      BOOST_TEST(!r.holes_dropped);
      // Closed form: 10² − 3² − 2² = 87 m², all counter-clockwise seen from +z (as the outer ring).
      // Tolerance: shifted by ≈ 4.5·10⁵ the corners are rounded to ≤ ½ ulp = 2.9·10⁻¹¹ m, so each
      // edge of the ≤ 10 m rings is off by ≤ 6·10⁻¹¹ m: relative area error ≤ ~10⁻¹¹ per
      // triangle; 10⁻¹⁰ relative bounds 14 of them (the unshifted case is exact).
      const Vec3 a = vector_area(s.p, r.triangles, s.p[0]);
      BOOST_TEST(a.z() == 87.0, tt::tolerance(1e-10));
      BOOST_TEST(unsigned_area(s.p, r.triangles, s.p[0]) == 87.0, tt::tolerance(1e-10));
      // No triangle inside a hole.
      BOOST_TEST(!centroid_inside(s.p, r.triangles, 2, 2, 5, 5, s.p[0]));
      BOOST_TEST(!centroid_inside(s.p, r.triangles, 6, 6, 8, 8, s.p[0]));
      // Euler: a polygon of V = 12 vertices with h = 2 holes triangulates into V + 2h − 2 = 14 triangles.
      BOOST_TEST(r.triangles.size() == 14u);
    }
}

BOOST_AUTO_TEST_CASE(clockwise_outer_ring_gives_clockwise_triangles) {
  Square s = square_with_holes(Vec3(0, 0, 0), false);
  std::reverse(s.rings[0].begin(), s.rings[0].end());
  const auto r = triangulate_polygon_with_holes(s.p, s.rings);
  // Closed form: the outer ring is now clockwise seen from +z: vector area (0, 0, −87).
  BOOST_TEST(vector_area(s.p, r.triangles, s.p[0]).z() == -87.0, tt::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(vertical_wall_with_window_hole) {
  // Wall in the xz plane (normal −y for this ring order): 4 m × 3 m with a 1 m × 1.5 m window.
  const std::vector<Vec3> p{{0, 0, 0}, {4, 0, 0}, {4, 0, 3}, {0, 0, 3}, {1, 0, 1}, {1, 0, 2.5}, {2, 0, 2.5}, {2, 0, 1}};
  const Rings rings{{0, 1, 2, 3}, {4, 5, 6, 7}};
  const auto r = triangulate_polygon_with_holes(p, rings);
  BOOST_TEST(r.method == PolygonTriangulationMethod::kConstrainedDelaunay);
  // Closed form: 12 − 1.5 = 10.5 m²; outer ring (0,0,0)→(4,0,0)→(4,0,3) has normal x̂ × ẑ = −ŷ.
  const Vec3 a = vector_area(p, r.triangles, p[0]);
  BOOST_TEST(a.y() == -10.5, tt::tolerance(1e-14));
  BOOST_TEST(std::abs(a.x()) + std::abs(a.z()) == 0.0);
}

BOOST_AUTO_TEST_CASE(hole_touching_outer_ring_at_a_vertex) {
  // The hole's corner (0, 0) is the outer ring's corner (same index and a duplicate position).
  const std::vector<Vec3> p{{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {2, 0.5, 0}, {2, 2, 0}, {0.5, 2, 0}, {0, 0, 0}};
  for (const std::uint32_t corner : {0u, 7u}) {
    const Rings rings{{0, 1, 2, 3}, {corner, 6, 5, 4}};
    const auto r = triangulate_polygon_with_holes(p, rings);
    BOOST_TEST(r.method == PolygonTriangulationMethod::kConstrainedDelaunay);
    // Closed form: 16 − area of the hole quad (0,0),(2,0.5),(2,2),(0.5,2) by the shoelace
    // formula: ½ |0·0.5−2·0 + 2·2−2·0.5 + 2·2−0.5·2 + 0.5·0−0·2| = ½ (3 + 3) = 3 → 13.
    BOOST_TEST(vector_area(p, r.triangles, p[0]).z() == 13.0, tt::tolerance(1e-14));
    for (const auto& t : r.triangles)
      for (auto i : t) BOOST_TEST(i != 7u);  // the first index at a point names it: 0 (outer ring)
  }
}

BOOST_AUTO_TEST_CASE(crossing_rings_drop_the_holes_and_say_so) {
  // The "hole" sticks out of the outer ring: a crossing needs a new vertex, so the outer ring is
  // triangulated alone (filled) and holes_dropped is set.
  const std::vector<Vec3> p{{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {1, 1, 0}, {6, 1, 0}, {6, 2, 0}, {1, 2, 0}};
  const auto r = triangulate_polygon_with_holes(p, Rings{{0, 1, 2, 3}, {4, 5, 6, 7}});
  BOOST_TEST(r.holes_dropped);
  BOOST_TEST(vector_area(p, r.triangles, p[0]).z() == 16.0, tt::tolerance(1e-14));  // the 4 × 4 outer square
}

BOOST_AUTO_TEST_CASE(no_holes_is_triangulate_polygon) {
  const std::vector<Vec3> p{{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {2, 3, 0}, {2, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}};
  const Rings rings{{0, 1, 2, 3, 4, 5, 6, 7}};
  const auto r = triangulate_polygon_with_holes(p, rings);
  const auto expected = triangulate_polygon_with_method(p, rings[0]);
  BOOST_TEST(r.method == expected.method);
  BOOST_TEST(r.triangles == expected.triangles);
}

BOOST_AUTO_TEST_CASE(zero_area_outer_ring_is_fanned) {
  const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {1.5, 0, 0}, {2.5, 0, 0}, {2, 0, 0}};
  const auto r = triangulate_polygon_with_holes(p, Rings{{0, 1, 2, 3}, {4, 5, 6}});
  BOOST_TEST(r.method == PolygonTriangulationMethod::kFanZeroArea);
  BOOST_TEST(r.triangles.size() == 2u);  // fan of the 4-vertex outer ring
}

BOOST_AUTO_TEST_CASE(bad_arguments_throw) {
  const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  BOOST_CHECK_THROW(triangulate_polygon_with_holes(p, Rings{}), std::invalid_argument);
  BOOST_CHECK_THROW(triangulate_polygon_with_holes(p, Rings{{0, 1, 2}, {0, 1}}), std::invalid_argument);
  BOOST_CHECK_THROW(triangulate_polygon_with_holes(p, Rings{{0, 1, 3}}), std::invalid_argument);
}
