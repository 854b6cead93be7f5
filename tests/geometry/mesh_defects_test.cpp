#define BOOST_TEST_MODULE mesh_defects
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "geometry/mesh/mesh_defects.h"

using namespace skyband;

namespace {

// Regular tetrahedron-like closed solid, outward (consistently) oriented.
TriangleSoup tetrahedron() {
  TriangleSoup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  s.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return s;
}

}  // namespace

// Every expected count below is counted by hand from the listed triangles.

BOOST_AUTO_TEST_CASE(closed_consistent_solid_has_no_defects) {
  const MeshDefects d = analyse_defects(tetrahedron());
  BOOST_TEST(!d.any());
  BOOST_TEST(d.welded_vertices == 4u);
  BOOST_TEST(d.summary() == "no defects");
}

BOOST_AUTO_TEST_CASE(single_triangle_has_three_boundary_edges) {
  TriangleSoup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}};
  s.triangles = {{0, 1, 2}};
  const MeshDefects d = analyse_defects(s);
  BOOST_TEST(d.boundary_edges == 3u);
  BOOST_TEST(d.unreferenced_vertices == 1u);
  BOOST_TEST(d.non_manifold_edges == 0u);
}

BOOST_AUTO_TEST_CASE(flipped_face_gives_three_inconsistent_edges) {
  TriangleSoup s = tetrahedron();
  std::swap(s.triangles[3][1], s.triangles[3][2]);
  const MeshDefects d = analyse_defects(s);
  BOOST_TEST(d.inconsistently_oriented_edges == 3u);
  BOOST_TEST(d.boundary_edges == 0u);
}

BOOST_AUTO_TEST_CASE(three_triangles_on_one_edge_is_non_manifold) {
  TriangleSoup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  s.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const MeshDefects d = analyse_defects(s);
  BOOST_TEST(d.non_manifold_edges == 1u);
  BOOST_TEST(d.boundary_edges == 6u);
}

BOOST_AUTO_TEST_CASE(duplicate_positions_are_welded_including_signed_zero) {
  // Two triangles of a square stored with separate vertices; -0.0 equals +0.0.
  TriangleSoup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-0.0, 0, 0}, {1, 1, -0.0}, {0, 1, 0}};
  s.triangles = {{0, 1, 2}, {3, 4, 5}};
  const MeshDefects d = analyse_defects(s);
  BOOST_TEST(d.duplicate_vertex_positions == 2u);
  BOOST_TEST(d.vertices_in_duplicate_positions == 4u);
  BOOST_TEST(d.welded_vertices == 4u);
  BOOST_TEST(d.boundary_edges == 4u);  // the diagonal is shared once welded
}

BOOST_AUTO_TEST_CASE(zero_area_is_exact_at_large_coordinates) {
  // p, p + d, p + 2d with exactly representable d are exactly collinear; moving the middle
  // point by one ulp in y makes the triangle non-degenerate (area ~1e-10 m²), which only an
  // exact predicate sees at coordinates of 5·10⁶ m.
  const Vec3 p(678040.0, 5403912.0, 414.5), d(0.25, 0.5, 0.125);
  TriangleSoup s;
  s.vertices = {p, p + d, p + 2 * d, Vec3(p.x() + d.x(), std::nextafter(p.y() + d.y(), 1e300), p.z() + d.z())};
  s.triangles = {{0, 1, 2}, {0, 3, 2}};
  const MeshDefects d1 = analyse_defects(s);
  BOOST_TEST(d1.zero_area_triangles == 1u);
}

BOOST_AUTO_TEST_CASE(repeated_index_and_duplicate_triangles) {
  TriangleSoup s = tetrahedron();
  s.triangles.push_back({0, 0, 1});  // repeated index: zero area too
  s.triangles.push_back({2, 1, 0});  // same vertex set as triangle 0
  const MeshDefects d = analyse_defects(s);
  BOOST_TEST(d.degenerate_index_triangles == 1u);
  BOOST_TEST(d.zero_area_triangles == 1u);
  BOOST_TEST(d.duplicate_triangles == 1u);
}

BOOST_AUTO_TEST_CASE(two_fans_at_a_vertex_is_non_manifold_vertex) {
  // Two triangles touching only at vertex 0 (a bow tie).
  TriangleSoup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  s.triangles = {{0, 1, 2}, {0, 3, 4}};
  const MeshDefects d = analyse_defects(s);
  BOOST_TEST(d.non_manifold_vertices == 1u);
  BOOST_TEST(analyse_defects(tetrahedron()).non_manifold_vertices == 0u);
}
