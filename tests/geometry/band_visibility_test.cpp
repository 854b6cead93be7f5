#define BOOST_TEST_MODULE band_visibility
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

#include "geometry/bands/band_visibility.h"
#include "geometry/bands/sky_integral.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {

double svf_at(const Scene& scene, const Vec3& p, const Vec3& n, VisibilityOptions opt = {}) {
  BandVisibility bv(scene, opt);
  VisibilityCache cache;
  VisibilityCache::PointResult r;
  bv.compute({p, n.normalized()}, r);
  cache.append(r);
  return sky_view_factor(cache.view(0));
}

}  // namespace

// Closed form: unobstructed face tilted by θ has SVF (1 + cos θ)/2 (method.md §8).
BOOST_AUTO_TEST_CASE(open_sky_tilted_faces) {
  const Scene empty{TriangleSoup{}};
  for (double tilt_deg : {0.0, 30.0, 60.0, 90.0, 120.0, 180.0}) {
    const double t = tilt_deg * kPi / 180;
    const Vec3 n(std::sin(t), 0.2 * std::sin(t), std::cos(t));
    const double expected = 0.5 * (1 + n.normalized().z());  // cos of the normal's tilt
    // Only float storage of interval ends and band edges rounds: 1e-6 is far above that.
    BOOST_TEST(svf_at(empty, Vec3(1, 2, 3), n) == expected, tt::tolerance(1e-6));
  }
}

// A point inside a closed box sees no sky at all; one on its top face sees all of it — exactly,
// whatever the band count (the box's own face must not hide the sky above it).
BOOST_AUTO_TEST_CASE(closed_box_inside_and_on_top) {
  TriangleSoup s;
  append_box(s, Vec3(0, 0, 0), Vec3(4, 3, 2));
  const Scene scene(s);
  for (int bands : {1, 7, 64}) {
    VisibilityOptions opt;
    opt.bands = bands;
    for (const Vec3& n : {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0.3, -0.5, 0.8)}) {
      BOOST_TEST(svf_at(scene, Vec3(1.3, 1.1, 0.7), n, opt) == 0.0);  // a generic interior point
      BOOST_TEST(svf_at(scene, Vec3(2, 1.5, 1.0), n, opt) == 0.0);    // the centre of the box
    }
    // On a vertex and on an edge of the box, facing into it: evaluated 1 µm inside
    // (surface_offset_m), where every sample plane passes through the box's corner or along its
    // edge — still no gap between the faces meeting there.
    BOOST_TEST(svf_at(scene, Vec3(0, 0, 0), Vec3(1, 1, 1), opt) == 0.0);    // bottom vertex
    BOOST_TEST(svf_at(scene, Vec3(2, 0, 1), Vec3(0, 1, 0), opt) == 0.0);    // on the face y = 0
    BOOST_TEST(svf_at(scene, Vec3(4, 3, 1), Vec3(-1, -1, 0), opt) == 0.0);  // vertical edge
    // The same vertex and edge facing out of the box: the box then lies wholly behind the face's
    // plane, so the point sees the open sky of its tilt, (1 + cos θ)/2 (method.md §8):
    // cos θ = 1/√3 at the top vertex facing (1, 1, 1), 0 on the vertical edge facing (1, 1, 0).
    // Only float storage of interval ends and band edges rounds, as in open_sky_tilted_faces.
    BOOST_TEST(svf_at(scene, Vec3(4, 3, 2), Vec3(1, 1, 1), opt) == 0.5 * (1 + 1 / std::sqrt(3.0)), tt::tolerance(1e-6));
    BOOST_TEST(svf_at(scene, Vec3(4, 3, 1), Vec3(1, 1, 0), opt) == 0.5, tt::tolerance(1e-6));
    BOOST_TEST(svf_at(scene, Vec3(1.3, 1.1, 2.0), Vec3(0, 0, 1), opt) == 1.0, tt::tolerance(1e-12));
    BOOST_TEST(svf_at(scene, Vec3(2.0, 1.5, 2.0), Vec3(0, 0, 1), opt) == 1.0, tt::tolerance(1e-12));
    BOOST_TEST(svf_at(scene, Vec3(4.0, 3.0, 2.0), Vec3(0, 0, 1), opt) == 1.0, tt::tolerance(1e-12));
  }
}

// Closed form (method.md §8): a horizontal point at distance d from an infinitely long wall of
// height H has SVF ½[1 + d/√(d² + H²)]. The wall here is 2000 m long (±1000 m) and 1 m thick: at
// d = 1 the finite length changes the value by ~H²·d/(2·1000²)... below 1e-6 (checked by
// lengthening it tenfold below).
BOOST_AUTO_TEST_CASE(long_wall_closed_form) {
  for (double len : {1000.0, 10000.0}) {
    TriangleSoup s;
    append_box(s, Vec3(-len, 1, 0), Vec3(len, 2, 3));
    const Scene scene(s);
    for (double d : {0.5, 1.0, 3.0}) {
      const double H = 3;
      const double expected = 0.5 * (1 + d / std::sqrt(d * d + H * H));
      BOOST_TEST(svf_at(scene, Vec3(0, 1 - d, 0), Vec3(0, 0, 1)) == expected, tt::tolerance(2e-3));
    }
  }
}

// Naive (every triangle against every plane) and accelerated (BVH + occlusion culling) give
// bit-identical visible intervals on random box scenes when the axis tail is traversed too.
BOOST_AUTO_TEST_CASE(naive_equals_accelerated) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int scene_id = 0; scene_id < 5; ++scene_id) {
    TriangleSoup s;
    for (int b = 0; b < 40; ++b) {
      const Vec3 lo{u(rng) * 100, u(rng) * 100, 0};
      append_box(s, lo, lo + Vec3{2 + 10 * u(rng), 2 + 10 * u(rng), 1 + 30 * u(rng)});
    }
    const Scene scene(s);
    // Without refinement: which edges are recorded as refinement breakpoints depends on the
    // order triangles are met in, so refined band layouts may differ (their SVFs agree within
    // the tolerance, checked in svf_oracle_test); the intervals on given planes may not.
    VisibilityOptions fast, naive;
    fast.tolerance = naive.tolerance = 0;
    fast.axis_tail_rad = naive.axis_tail_rad = 0;
    naive.accelerate = false;
    BandVisibility a(scene, fast), b(scene, naive);
    for (int i = 0; i < 20; ++i) {
      const QueryPoint q{Vec3{u(rng) * 100, u(rng) * 100, u(rng) * 5}, Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng)}.normalized()};
      VisibilityCache::PointResult ra, rb;
      a.compute(q, ra);
      b.compute(q, rb);
      BOOST_TEST_REQUIRE(ra.bands.size() == rb.bands.size());
      BOOST_TEST_REQUIRE(ra.intervals.size() == rb.intervals.size());
      for (std::size_t k = 0; k < ra.intervals.size(); ++k) {
        BOOST_TEST(ra.intervals[k].alpha0_rad == rb.intervals[k].alpha0_rad);
        BOOST_TEST(ra.intervals[k].alpha1_rad == rb.intervals[k].alpha1_rad);
      }
    }
  }
}

// The sun's shadow test stops at the first triangle hiding the direction (any-hit) instead of
// building the sun plane's whole occluded list: it must decide exactly as the full line does
// (the naive reference: every triangle, then the look-up), also for directions aimed at box
// corners and edge midpoints, where spans of neighbouring faces touch.
BOOST_AUTO_TEST_CASE(shadow_test_equals_full_line) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  int hidden = 0, open = 0;
  for (int scene_id = 0; scene_id < 4; ++scene_id) {
    TriangleSoup s;
    std::vector<Vec3> corners;
    for (int b = 0; b < 40; ++b) {
      const Vec3 lo{u(rng) * 100, u(rng) * 100, 0};
      const Vec3 hi = lo + Vec3{2 + 10 * u(rng), 2 + 10 * u(rng), 1 + 30 * u(rng)};
      append_box(s, lo, hi);
      corners.push_back(hi);
      corners.push_back(Vec3(lo.x(), hi.y(), hi.z()));
      corners.push_back(Vec3(0.5 * (lo.x() + hi.x()), lo.y(), hi.z()));  // a roof edge's midpoint
    }
    const Scene scene(s);
    VisibilityOptions fast, naive;
    naive.accelerate = false;
    BandVisibility a(scene, fast), b(scene, naive);
    for (int i = 0; i < 150; ++i) {
      const QueryPoint q{Vec3{u(rng) * 100, u(rng) * 100, u(rng) * 5}, Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng)}.normalized()};
      Vec3 dir = i % 2 ? Vec3{u(rng) - 0.5, u(rng) - 0.5, 0.05 + u(rng)}.normalized()
                       : (corners[i % corners.size()] - q.position).normalized();
      if (dir.dot(q.normal) <= 0) dir = -dir;
      if (dir.z() < 0) continue;
      const bool va = a.direction_visible(q, dir), vb = b.direction_visible(q, dir);
      BOOST_TEST(va == vb);
      (vb ? open : hidden) += 1;
    }
  }
  // Both outcomes must be exercised for the comparison to mean anything.
  BOOST_TEST(hidden > 50);
  BOOST_TEST(open > 50);
}
