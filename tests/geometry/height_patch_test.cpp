// Height patches (geometry/exact/height_patch.h): which occluders are grouped, and the visible sky of
// points around, over and under them against the exact union oracle (lambert_oracle.h) — the
// patch's boundary projection claims only what its occluders hide, and skipping them where it is
// their whole projection loses nothing.
#define BOOST_TEST_MODULE height_patch
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>

#include "geometry/core/exact_sign.h"
#include "geometry/exact/exact_sky.h"
#include "geometry/exact/height_patch.h"
#include "geometry/exact/occluder_set.h"
#include "geometry/support/lambert_oracle.h"
#include "geometry/support/scene_generators.h"

using namespace skyband;

namespace {

constexpr double kExact = 1e-9;   // rounding of arcs and Lambert's sums; the oracle's own < 1e-9
constexpr double kOffset = 1e-6;  // VisibilityOptions::surface_offset_m

void add_triangle(TriangleSoup& s, const Vec3& a, const Vec3& b, const Vec3& c) {
  const auto base = std::uint32_t(s.vertices.size());
  s.vertices.insert(s.vertices.end(), {a, b, c});
  s.triangles.push_back({base, base + 1, base + 2});
}

// An n × n grid TIN of `cell` metres from (x0, y0) with heights z(i, j); every other cell's
// diagonal flipped, and every third triangle wound the other way (winding means nothing here).
void add_tin(TriangleSoup& s, int n, double x0, double y0, double cell, const std::function<double(int, int)>& z) {
  std::vector<double> h((n + 1) * (n + 1));  // each vertex's height once: shared bit for bit
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) h[j * (n + 1) + i] = z(i, j);
  const auto at = [&](int i, int j) { return Vec3(x0 + i * cell, y0 + j * cell, h[j * (n + 1) + i]); };
  int k = 0;
  const auto tri = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    if (++k % 3 == 0)
      add_triangle(s, a, c, b);
    else
      add_triangle(s, a, b, c);
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if ((i + j) % 2 == 0) {
        tri(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        tri(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      } else {
        tri(at(i, j), at(i + 1, j), at(i, j + 1));
        tri(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
      }
    }
}

double xy_area(const Vec3* v, std::uint32_t k) {  // shoelace, signed
  double a = 0;
  for (std::uint32_t i = 0; i < k; ++i) a += v[i].x() * v[(i + 1) % k].y() - v[(i + 1) % k].x() * v[i].y();
  return 0.5 * a;
}

struct Totals {
  std::size_t patches = 0, skipped = 0;
  double worst = 0;
};

void check_against_oracle(const TriangleSoup& soup, const std::vector<QueryPoint>& pts, const char* what, Totals& totals) {
  const Scene scene(soup);
  ExactSky sky(scene, kOffset);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    SkyFactors f;
    sky.compute(pts[i], f);
    totals.patches += sky.last_patches_projected();
    totals.skipped += sky.last_occluders_skipped();
    const oracle::UnionSkyFactors ref = oracle::sky_union_oracle(pts[i].position + kOffset * pts[i].normal, pts[i].normal, soup);
    totals.worst = std::max({totals.worst, std::abs(f.svf - ref.svf), std::abs(f.sky_exposure - ref.sky_exposure)});
    BOOST_TEST(std::abs(f.svf - ref.svf) < kExact, what << " point " << i << ": svf " << f.svf << " oracle " << ref.svf);
    BOOST_TEST(std::abs(f.sky_exposure - ref.sky_exposure) < kExact,
               what << " point " << i << ": exposure " << f.sky_exposure << " oracle " << ref.sky_exposure);
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(patches_tile_their_convex_outlines) {
  // Every patch's members cover its outline once: their xy areas sum to the outline's (shoelace,
  // to rounding), the outline turns left (or runs straight) at every vertex, and each member
  // lies inside it.
  gen::Rng rng(3);
  TriangleSoup soup;
  add_tin(soup, 10, 0, 0, 4, [&](int, int) { return rng.uniform(0, 2); });
  const OccluderSet set = build_occluder_set(soup);
  const HeightPatches& hp = set.height_patches;
  BOOST_TEST_REQUIRE(!hp.patches.empty());
  std::uint32_t largest = 0, grouped = 0;
  for (std::size_t p = 0; p < hp.patches.size(); ++p) {
    const HeightPatch& patch = hp.patches[p];
    const Vec3* v = hp.vertices.data() + patch.first_vertex;
    const std::uint32_t k = patch.vertex_count;
    for (std::uint32_t i = 0; i < k; ++i) BOOST_TEST(exact_orient2d_sign(v[i], v[(i + 1) % k], v[(i + 2) % k]) >= 0);
    double members = 0;
    for (std::uint32_t m = 0; m < patch.member_count; ++m) {
      const Occluder& o = set.occluders[hp.members[patch.first_member + m]];
      BOOST_TEST(o.patch == p);
      members += std::abs(xy_area(o.v.data(), o.count));
      for (std::uint32_t c = 0; c < o.count; ++c)
        for (std::uint32_t i = 0; i < k; ++i) BOOST_TEST(exact_orient2d_sign(v[i], v[(i + 1) % k], o.v[c]) >= 0);
    }
    BOOST_TEST(std::abs(members - xy_area(v, k)) < 1e-12 * members,
               "patch " << p << ": members " << members << " outline " << xy_area(v, k));
    largest = std::max(largest, patch.member_count);
    grouped += patch.member_count;
  }
  BOOST_TEST(largest >= 4u);  // a grid of squares grows beyond one cell
  BOOST_TEST(grouped >= soup.triangles.size() / 2);
}

BOOST_AUTO_TEST_CASE(cracks_folds_and_t_junctions_are_not_grouped) {
  // Three pairs of triangles that look like one surface from above but are not the graph of one
  // continuous function: none may share a patch.
  TriangleSoup soup;
  // A crack: the shared xy edge at two heights on the two sides.
  add_triangle(soup, {0, 0, 0}, {4, 0, 0}, {0, 4, 0});
  add_triangle(soup, {4, 0, 0.1}, {4, 4, 0}, {0, 4, 0.1});
  // A fold: the second triangle doubles back over the first (they overlap in xy).
  add_triangle(soup, {10, 0, 0}, {14, 0, 0}, {10, 4, 0});
  add_triangle(soup, {14, 0, 0}, {10, 4, 0}, {11, 1, 1});
  // A T-junction: one triangle's edge against two, whose shared vertex lies above that edge.
  add_triangle(soup, {20, 0, 0}, {24, 0, 0}, {20, 4, 0});
  add_triangle(soup, {24, 0, 0}, {24, 4, 0}, {22, 2, 0.2});
  add_triangle(soup, {22, 2, 0.2}, {24, 4, 0}, {20, 4, 0});
  const OccluderSet set = build_occluder_set(soup);
  for (const HeightPatch& patch : set.height_patches.patches) {
    const Occluder& first = set.occluders[set.height_patches.members[patch.first_member]];
    BOOST_TEST(first.v[0].x() >= 20);  // only the T-junction's two small triangles may pair up
    BOOST_TEST(patch.member_count <= 2u);
  }
}

BOOST_AUTO_TEST_CASE(points_around_over_and_under_patches_against_the_oracle) {
  gen::Rng rng(17);
  Totals totals;
  const auto points = [&](const Scene& scene, double lo, double hi, double below, double above, int n) {
    std::vector<QueryPoint> pts;
    for (int i = 0; i < n; ++i) {
      const double x = rng.uniform(lo, hi), y = rng.uniform(lo, hi);
      double z = rng.uniform(below, above);
      if (i % 3 == 0)  // on the surface's lower or upper side, 5 cm away
        if (const auto hit = scene.surface_hit(Ray{Vec3(x, y, 100), Vec3(0, 0, -1)}))
          z = hit->position.z() + (i % 2 ? -0.05 : 0.05);
      QueryPoint q{Vec3(x, y, z), Vec3(0, 0, 1)};
      if (i % 4 == 1) q.normal = rng.unit_normal(0, kPi, 0, 6.28);
      pts.push_back(q);
    }
    return pts;
  };
  {  // gentle terrain (slopes ~1 %): points over it, beside it, below and above its level
    TriangleSoup soup;
    add_tin(soup, 8, 0, 0, 5, [&](int i, int j) { return 0.01 * i + 0.005 * j + rng.uniform(0, 0.02); });
    check_against_oracle(soup, points(Scene(soup), -20, 60, -1, 2, 36), "gentle terrain", totals);
  }
  {  // rough terrain with a building standing in it
    TriangleSoup soup;
    add_tin(soup, 8, 0, 0, 5, [&](int, int) { return rng.uniform(0, 1.5); });
    const Vec3 b[4] = {{12, 12, -0.5}, {22, 12, -0.5}, {22, 20, -0.5}, {12, 20, -0.5}};
    for (int k = 0; k < 4; ++k) {
      const Vec3 &p = b[k], &q = b[(k + 1) % 4];
      add_triangle(soup, p, q, q + Vec3(0, 0, 9));
      add_triangle(soup, p, q + Vec3(0, 0, 9), p + Vec3(0, 0, 9));
    }
    add_triangle(soup, b[0] + Vec3(0, 0, 9), b[1] + Vec3(0, 0, 9), b[2] + Vec3(0, 0, 9));
    add_triangle(soup, b[0] + Vec3(0, 0, 9), b[2] + Vec3(0, 0, 9), b[3] + Vec3(0, 0, 9));
    check_against_oracle(soup, points(Scene(soup), -10, 50, -1, 3, 36), "rough terrain", totals);
  }
  {  // a floating sheet (a canopy 4–5 m up): points under it, beside it and above it
    TriangleSoup soup;
    add_tin(soup, 6, 0, 0, 3, [&](int i, int j) { return 4 + 0.1 * i + rng.uniform(0, 0.5); });
    check_against_oracle(soup, points(Scene(soup), -10, 28, 0, 7, 36), "floating sheet", totals);
  }
  {  // steep ground (a 30 % slope) with a valley
    TriangleSoup soup;
    add_tin(soup, 8, 0, 0, 4, [&](int i, int j) { return 0.3 * std::abs(i - 4) * 4 + 0.05 * j + rng.uniform(0, 0.1); });
    check_against_oracle(soup, points(Scene(soup), -5, 37, 0, 6, 36), "steep valley", totals);
  }
  BOOST_TEST_MESSAGE("height patches: largest difference from the oracle "
                     << totals.worst << ", " << totals.patches << " patch projections, " << totals.skipped << " members skipped");
  BOOST_TEST(totals.patches > 100u);  // the patch paths ran
  BOOST_TEST(totals.skipped > 100u);
}
