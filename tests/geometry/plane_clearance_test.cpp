#define BOOST_TEST_MODULE plane_clearance
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "geometry/core/exact_sign.h"
#include "geometry/mesh/scene.h"
#include "geometry/visibility/plane_clearance.h"
#include "geometry/visibility/sky_factors.h"

using namespace skyband;

namespace {

// A closed box turned 45° about z: walls in the planes |x| + |y| = 1, 0 ≤ z ≤ 1 (the slanted
// walls' planes hold no grid point exactly, so points a few ulps from them are the common case).
TriangleSoup diamond() {
  TriangleSoup s;
  s.vertices = {{1, 0, 1}, {0, 1, 1}, {-1, 0, 1}, {0, -1, 1}, {0, -1, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}};
  const auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    s.triangles.push_back({a, b, c});
    s.triangles.push_back({a, c, d});
  };
  quad(0, 1, 2, 3), quad(4, 5, 0, 3), quad(5, 6, 1, 0), quad(6, 7, 2, 1), quad(3, 2, 7, 4), quad(7, 6, 5, 4);
  return s;
}

// Points on the foot of the wall from (0, −1) to (−1, 0), each moved k ulps in x and y.
std::vector<QueryPoint> foot_points() {
  std::vector<QueryPoint> pts;
  for (const double t : {0.15, 0.3, 0.5, 0.77})
    for (int k = -4; k <= 4; ++k) {
      double x = -t, y = -(1 - t);
      for (int i = 0; i < std::abs(k); ++i) {
        x = std::nextafter(x, k < 0 ? 0.0 : -2.0);
        y = std::nextafter(y, k < 0 ? 0.0 : -2.0);
      }
      pts.push_back({Vec3(x, y, 0), Vec3(0, 0, 1)});
    }
  return pts;
}

}  // namespace

BOOST_AUTO_TEST_CASE(points_ulps_from_a_slanted_wall_get_the_limit_of_their_side_by_every_method) {
  // A point at the foot of a face of a convex solid, outside it, sees the half of the sky in front
  // of the face's plane: SVF and exposure 1/2 (the solid fills the half-space behind it near the
  // point); inside the solid, nothing. The point given and the point moved clear differ by about
  // 10⁻¹³ m here, which changes the SVF by about as much.
  const Scene scene(diamond());
  const std::vector<QueryPoint> pts = foot_points();
  for (const SkyFactorsMethod m : {SkyFactorsMethod::automatic, SkyFactorsMethod::exact, SkyFactorsMethod::bands}) {
    const SkyFactorsRun run = compute_sky_factors(scene, pts, VisibilityOptions{}, m, 1);
    const double tol = m == SkyFactorsMethod::bands ? 1e-5 : 1e-12;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      // Exactly on the plane: the point as given, on the surface (either limit is defensible).
      const int side = exact_orient2d_sign(Vec3(0, -1, 0), Vec3(-1, 0, 0), pts[i].position);
      if (side == 0) continue;
      const double expected = side > 0 ? 0.5 : 0.0;  // left of (0, −1) → (−1, 0): outside (the centre is right)
      BOOST_TEST(std::abs(run.factors[i].svf - expected) < tol,
                 "method " << int(m) << " point " << i << " side " << side << ": svf " << run.factors[i].svf);
      BOOST_TEST(std::abs(run.factors[i].sky_exposure - expected) < tol,
                 "method " << int(m) << " point " << i << ": exposure " << run.factors[i].sky_exposure);
    }
  }
}

BOOST_AUTO_TEST_CASE(only_points_within_rounding_of_a_plane_are_moved_and_to_their_own_side) {
  const Scene scene(diamond());
  std::vector<std::uint32_t> stack;
  for (const QueryPoint& q : foot_points()) {
    const QueryPoint c = clear_of_planes(scene, q, 1e-6, stack);
    const int before = exact_orient2d_sign(Vec3(0, -1, 0), Vec3(-1, 0, 0), q.position);
    const int after = exact_orient2d_sign(Vec3(0, -1, 0), Vec3(-1, 0, 0), c.position);
    if (before == 0) {
      BOOST_TEST((c.position == q.position));  // exactly in the plane: as given
      continue;
    }
    BOOST_TEST(after == before);
    BOOST_TEST((c.position - q.position).norm() < 1e-12);
    // Clear of the plane by far more than the rounding of v − p (~1e-16 here).
    BOOST_TEST(std::abs(c.position.x() + c.position.y() + 1) > 1e-14);
  }
  // Far from every plane (1 mm): unchanged, bit for bit.
  const QueryPoint far{Vec3(-0.3, -0.701, 0.2), Vec3(0, 0, 1)};
  BOOST_TEST((clear_of_planes(scene, far, 1e-6, stack).position == far.position));
  // A facade point 1 µm in front of the wall, as its offset puts it: unchanged.
  const Vec3 n = Vec3(-1, -1, 0).normalized();
  const QueryPoint facade{Vec3(-0.5, -0.5, 0.5), n};
  BOOST_TEST((clear_of_planes(scene, facade, 1e-6, stack).position == facade.position));
}
