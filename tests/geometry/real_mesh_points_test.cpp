#define BOOST_TEST_MODULE real_mesh_points
#include <boost/test/unit_test.hpp>

// The calculation points the benchmarks and several suites place on real meshes
// (geometry/support/real_mesh_points.h): street points stand 5 cm above a ground surface where the
// model has one, and 5 cm above the local ground level where it has none; facade points 5 cm in
// front of wall triangles. Checked by independent vertical rays through the scene.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "geometry/mesh/scene.h"
#include "geometry/support/real_mesh_points.h"
#include "io/mesh_reader.h"
#include "shared_data.h"

using namespace skyband;

namespace {

Scene load(const char* name) {
  return Scene(read_mesh(std::filesystem::path(SKYBAND_SHARED_DATA) / "buildings" / name));
}

}  // namespace

// The Delft 3dfier tile has terrain, roads and water, over a footprint that covers about half of
// its bounding box: every street point stands 5 cm above a surface of it (the first hit of a
// downward ray from above is that surface, 5 cm below the point), none outside the footprint.
BOOST_AUTO_TEST_CASE(street_points_on_a_model_with_ground_stand_on_it, *skyband::test::needs_shared_data()) {
  const Scene scene = load("delft_3dfier_testarea_lod1.obj");
  const auto pts = gen::real_mesh_street_points(scene, 300, 21);
  BOOST_TEST(pts.size() == 300u);
  const double top = scene.bounds().hi.z() + 10;
  for (const QueryPoint& q : pts) {
    const auto hit = scene.surface_hit(Ray{Vec3(q.position.x(), q.position.y(), top), Vec3(0, 0, -1)});
    BOOST_TEST_REQUIRE(bool(hit));
    BOOST_TEST(std::abs(q.position.z() - 0.05 - hit->position.z()) < 1e-9);
    BOOST_TEST(!scene.intersect(Ray{q.position, Vec3(0, 0, 1)}));  // open above
  }
}

// The Rotterdam block is buildings alone (no ground surface): street points stand 5 cm above the
// local ground level (the lowest vertex within 25 m), with nothing below or above them.
BOOST_AUTO_TEST_CASE(street_points_on_a_model_without_ground, *skyband::test::needs_shared_data()) {
  const Scene scene = load("rotterdam_delfshaven_blockA_lod2.obj");
  const auto pts = gen::real_mesh_street_points(scene, 200, 21);
  BOOST_TEST(pts.size() == 200u);
  const double top = scene.bounds().hi.z() + 10;
  for (const QueryPoint& q : pts) {
    BOOST_TEST(!scene.surface_hit(Ray{Vec3(q.position.x(), q.position.y(), top), Vec3(0, 0, -1)}));
    double ground = std::numeric_limits<double>::infinity();
    for (const Vec3& v : scene.soup().vertices)
      if (std::hypot(v.x() - q.position.x(), v.y() - q.position.y()) <= 25.0) ground = std::min(ground, v.z());
    BOOST_TEST(std::abs(q.position.z() - 0.05 - ground) < 1e-9);
  }
}

// Facade points: 5 cm in front of a wall triangle (normal within 6° of horizontal), along it (a
// ray back along the normal meets the wall at 5 cm; within a millimetre where it passes a
// triangle's edge to a neighbour that leans by a hair, or meets a party wall modelled twice).
BOOST_AUTO_TEST_CASE(facade_points_face_their_wall, *skyband::test::needs_shared_data()) {
  const Scene scene = load("rotterdam_delfshaven_blockA_lod2.obj");
  for (const QueryPoint& q : gen::real_mesh_facade_points(scene, 100, 22)) {
    BOOST_TEST(std::abs(q.normal.norm() - 1) < 1e-12);
    BOOST_TEST(std::abs(q.normal.z()) <= 0.1);
    const auto hit = scene.intersect(Ray{q.position, -q.normal});
    BOOST_TEST_REQUIRE(bool(hit));
    BOOST_TEST(std::abs(hit->t - 0.05) < 1e-3);
  }
}
