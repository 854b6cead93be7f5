#define BOOST_TEST_MODULE polygon_triangulation
#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "geometry/mesh/polygon_triangulation.h"

using namespace skyband;
namespace tt = boost::test_tools;
using Triangles = std::vector<std::array<std::uint32_t, 3>>;

namespace {

std::vector<std::uint32_t> iota_ring(std::size_t n) {
  std::vector<std::uint32_t> r(n);
  std::iota(r.begin(), r.end(), 0u);
  return r;
}

// Sum of the triangles' vector areas (½ (b−a)×(c−a)), relative to `origin` for precision.
Vec3 vector_area(const std::vector<Vec3>& p, const Triangles& tris, const Vec3& origin) {
  Vec3 s = Vec3::Zero();
  for (const auto& t : tris) s += 0.5 * (p[t[1]] - origin - (p[t[0]] - origin)).cross(p[t[2]] - origin - (p[t[0]] - origin));
  return s;
}

double unsigned_area(const std::vector<Vec3>& p, const Triangles& tris) {
  double s = 0;
  for (const auto& t : tris) s += 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
  return s;
}

// Shoelace formula in the xy plane (independent of the triangulation), relative to the first point.
double shoelace_xy(const std::vector<Vec3>& p) {
  double s = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 a = p[i] - p[0], b = p[(i + 1) % p.size()] - p[0];
    s += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * s;
}

bool uses_only_polygon_vertices(const Triangles& tris, const std::vector<std::uint32_t>& ring) {
  for (const auto& t : tris)
    for (auto i : t)
      if (std::find(ring.begin(), ring.end(), i) == ring.end()) return false;
  return true;
}

// U-shaped octagon: the 3×3 square minus the 1×2 notch [1,2]×[1,3]; shoelace area 9 − 2 = 7.
std::vector<Vec3> u_shape(const Vec3& offset) {
  std::vector<Vec3> p{{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {2, 3, 0}, {2, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}};
  for (auto& v : p) v += offset;
  return p;
}

}  // namespace

BOOST_AUTO_TEST_CASE(triangle_is_returned_unchanged_even_when_degenerate) {
  const std::vector<Vec3> p{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  const std::vector<std::uint32_t> ring{2, 0, 1};
  const auto r = triangulate_polygon_with_method(p, ring);
  BOOST_TEST(r.method == PolygonTriangulationMethod::kTriangle);
  BOOST_REQUIRE_EQUAL(r.triangles.size(), 1u);
  BOOST_TEST((r.triangles[0] == std::array<std::uint32_t, 3>{2, 0, 1}));
}

BOOST_AUTO_TEST_CASE(convex_quad_gives_two_triangles_with_its_area_and_orientation) {
  const std::vector<Vec3> p{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  const auto r = triangulate_polygon_with_method(p, iota_ring(4));
  BOOST_TEST(r.method == PolygonTriangulationMethod::kConstrainedDelaunay);
  BOOST_TEST(r.triangles.size() == 2u);
  // Closed form: 2 × 1 rectangle, counter-clockwise seen from +z → vector area (0, 0, 2).
  // Tolerance: exact small integers, sums of 2 products: only the last bit can differ.
  const Vec3 a = vector_area(p, r.triangles, p[0]);
  BOOST_TEST(a.z() == 2.0, tt::tolerance(1e-15));
  BOOST_TEST(std::abs(a.x()) + std::abs(a.y()) == 0.0);
}

BOOST_AUTO_TEST_CASE(non_convex_polygon_is_not_fanned) {
  // A fan from vertex 0 would cover the notch (area 9 with overlaps); the correct area is the
  // shoelace area 7. n − 2 = 6 triangles.
  const auto p = u_shape(Vec3::Zero());
  const auto ring = iota_ring(p.size());
  const auto r = triangulate_polygon_with_method(p, ring);
  BOOST_TEST(r.triangles.size() == 6u);
  BOOST_TEST(uses_only_polygon_vertices(r.triangles, ring));
  const double expected = shoelace_xy(p);
  BOOST_TEST(expected == 7.0);
  // Tolerance: half-integer coordinates, a few roundings in the cross products.
  BOOST_TEST(vector_area(p, r.triangles, p[0]).z() == expected, tt::tolerance(1e-14));
  BOOST_TEST(unsigned_area(p, r.triangles) == expected, tt::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(clockwise_ring_keeps_its_orientation) {
  auto p = u_shape(Vec3::Zero());
  std::reverse(p.begin(), p.end());
  const auto r = triangulate_polygon_with_method(p, iota_ring(p.size()));
  // Reversed ring: vector area (0, 0, −7) (shoelace of the reversed ring).
  BOOST_TEST(vector_area(p, r.triangles, p[0]).z() == shoelace_xy(p), tt::tolerance(1e-14));
  BOOST_TEST(shoelace_xy(p) == -7.0);
}

BOOST_AUTO_TEST_CASE(large_projected_coordinates_tilted_plane) {
  // The U shape at UTM-like coordinates, tilted into the plane z = z0 + 0.5·x (a roof): the
  // area is the xy shoelace area divided by cos(tilt) = 1/√(1 + 0.5²) (closed form).
  const Vec3 origin(678040.189, 5403913.006, 414.907);
  auto p = u_shape(Vec3::Zero());
  for (auto& v : p) v = origin + Vec3(v.x(), v.y(), 0.5 * v.x());
  const auto ring = iota_ring(p.size());
  const auto r = triangulate_polygon_with_method(p, ring);
  BOOST_TEST(r.method == PolygonTriangulationMethod::kConstrainedDelaunay);
  BOOST_TEST(r.triangles.size() == 6u);
  BOOST_TEST(uses_only_polygon_vertices(r.triangles, ring));
  // Tolerance: coordinates of 5·10⁶ m carry ~1e-9 m absolute rounding, relative 1e-9 on area 7.
  BOOST_TEST(unsigned_area(p, r.triangles) == 7.0 * std::sqrt(1.25), tt::tolerance(1e-9));
  const Vec3 a = vector_area(p, r.triangles, origin);
  BOOST_TEST(a.z() > 0.0);  // counter-clockwise seen from above, as the ring
}

BOOST_AUTO_TEST_CASE(keyhole_polygon_with_repeated_vertices) {
  // Square 4×4 with a 2×2 square hole, joined by a bridge 0→4 traversed twice (indices 0 and 4
  // repeated), the way assimp_concave_polygon.obj encodes its ring. Area 16 − 4 = 12.
  const std::vector<Vec3> p{{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0},   // outer, ccw
                            {1, 1, 0}, {1, 3, 0}, {3, 3, 0}, {3, 1, 0}};  // hole, cw
  const std::vector<std::uint32_t> ring{0, 1, 2, 3, 0, 4, 5, 6, 7, 4};
  const auto r = triangulate_polygon_with_method(p, ring);
  BOOST_TEST(r.method == PolygonTriangulationMethod::kConstrainedDelaunay);
  BOOST_TEST(unsigned_area(p, r.triangles) == 12.0, tt::tolerance(1e-14));
  BOOST_TEST(vector_area(p, r.triangles, p[0]).z() == 12.0, tt::tolerance(1e-14));
  BOOST_TEST(r.triangles.size() == 8u);  // an annulus of 8 vertices: 8 triangles
}

BOOST_AUTO_TEST_CASE(collinear_vertex_on_an_edge_is_used) {
  // A square with an extra vertex in the middle of its bottom edge: area 1, 3 triangles.
  const std::vector<Vec3> p{{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const auto r = triangulate_polygon_with_method(p, iota_ring(5));
  BOOST_TEST(r.triangles.size() == 3u);
  BOOST_TEST(unsigned_area(p, r.triangles) == 1.0, tt::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(slightly_non_planar_quad) {
  // One corner lifted by 3 mm (as in val3dity_building_nearly-collinear.off): still 2 triangles
  // covering the quad; the area differs from the planar 10 m × 5 m by O(h²) only.
  const std::vector<Vec3> p{{0, 0, 0}, {10, 0, 0}, {10, 5, 0.003}, {0, 5, 0}};
  const auto r = triangulate_polygon_with_method(p, iota_ring(4));
  BOOST_TEST(r.method == PolygonTriangulationMethod::kConstrainedDelaunay);
  BOOST_TEST(r.triangles.size() == 2u);
  // Tolerance: the lift changes each triangle's area by at most ~h²·…/area ≈ 1e-6 relative.
  BOOST_TEST(unsigned_area(p, r.triangles) == 50.0, tt::tolerance(1e-5));
}

BOOST_AUTO_TEST_CASE(zero_area_polygon_is_fanned_not_dropped) {
  const std::vector<Vec3> p{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  const auto r = triangulate_polygon_with_method(p, iota_ring(4));
  BOOST_TEST(r.method == PolygonTriangulationMethod::kFanZeroArea);
  BOOST_TEST(r.triangles.size() == 2u);
}

BOOST_AUTO_TEST_CASE(self_crossing_ring_is_fanned_not_dropped) {
  // Asymmetric bow tie (shoelace area 1.5, so the Newell normal is not zero): edges 0→1 and
  // 2→3 cross at (2, 2/3); a triangulation would need a new vertex there.
  const std::vector<Vec3> p{{0, 0, 0}, {3, 1, 0}, {3, 0, 0}, {0, 2, 0}};
  const auto r = triangulate_polygon_with_method(p, iota_ring(4));
  BOOST_TEST(r.method == PolygonTriangulationMethod::kFanSelfIntersecting);
  BOOST_TEST(r.triangles.size() == 2u);
}

BOOST_AUTO_TEST_CASE(vertical_wall_polygon) {
  // A wall in the plane y = 7 (Newell normal along −y or +y): the projection drops y.
  const std::vector<Vec3> p{{0, 7, 0}, {0, 7, 3}, {2, 7, 3}, {2, 7, 1}, {1, 7, 1}, {1, 7, 0}};  // L shape
  const auto r = triangulate_polygon_with_method(p, iota_ring(6));
  BOOST_TEST(r.triangles.size() == 4u);
  // Closed form: 2×3 rectangle minus the 1×1 corner = 5.
  BOOST_TEST(unsigned_area(p, r.triangles) == 5.0, tt::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(invalid_arguments_throw) {
  const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::uint32_t> two{0, 1}, bad{0, 1, 3};
  BOOST_CHECK_THROW(triangulate_polygon(p, two), std::invalid_argument);
  BOOST_CHECK_THROW(triangulate_polygon(p, bad), std::invalid_argument);
}
