#define BOOST_TEST_MODULE scene_hit
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "geometry/mesh/scene.h"
#include "geometry/mesh/triangle_soup.h"

namespace tt = boost::test_tools;
using namespace skyband;

// Scene::surface_hit on the box [0,2]×[0,2]×[0,1] (append_box): the hit point lies exactly on the
// face it hits (a coordinate equal to the face's, from the barycentrics), the normal is unit and
// faces the ray's origin whichever way the face is wound, and misses give nothing.
BOOST_AUTO_TEST_CASE(hit_point_on_face_and_normal_toward_origin) {
  TriangleSoup soup;
  append_box(soup, Vec3(0, 0, 0), Vec3(2, 2, 1));
  const Scene scene(soup);
  struct Case {
    Vec3 origin, dir, normal;
    int axis;
    double value;
  };
  const Case cases[] = {
      {Vec3(0.7, 1.3, 5), Vec3(0.01, -0.02, -1), Vec3(0, 0, 1), 2, 1.0},  // roof from above
      {Vec3(0.7, 1.3, -5), Vec3(0.02, 0.01, 1), Vec3(0, 0, -1), 2, 0.0},  // floor from below
      {Vec3(-4, 0.9, 0.4), Vec3(1, 0.03, 0.01), Vec3(-1, 0, 0), 0, 0.0},  // west wall
      {Vec3(1.1, 0.8, 0.5), Vec3(0.1, 0.2, 1), Vec3(0, 0, -1), 2, 1.0},   // roof from inside
  };
  for (const Case& c : cases) {
    const auto h = scene.surface_hit(Ray{c.origin, c.dir});
    BOOST_REQUIRE(h.has_value());
    BOOST_TEST(h->position[c.axis] == c.value, tt::tolerance(1e-15));
    BOOST_TEST(h->normal.norm() == 1.0, tt::tolerance(1e-15));
    BOOST_TEST(h->normal.dot(c.normal) == 1.0, tt::tolerance(1e-15));
    BOOST_TEST(h->normal.dot(c.dir) < 0.0);
    const auto raw = scene.intersect(Ray{c.origin, c.dir});
    BOOST_TEST(raw->triangle == h->triangle);
  }
  BOOST_TEST(!scene.surface_hit(Ray{Vec3(5, 5, 5), Vec3(0, 0, 1)}).has_value());
}
