#define BOOST_TEST_MODULE height_field
#include <boost/test/unit_test.hpp>

// The height-field mesh of a DSM (geometry/mesh/height_field.h): its topology (one column solid, so
// that pixel tops get the exact horizon method), and its sky view factors against the exact
// union oracle of tests/geometry/support/lambert_oracle.h and a closed form.

#include <cmath>
#include <limits>
#include <vector>

#include "geometry/core/input_error.h"
#include "geometry/horizon/column_scene.h"
#include "geometry/mesh/height_field.h"
#include "geometry/mesh/scene.h"
#include "geometry/support/lambert_oracle.h"
#include "geometry/support/scene_generators.h"
#include "geometry/visibility/sky_factors.h"

using namespace skyband;
using namespace skyband::oracle;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

HeightField field(std::size_t columns, std::size_t rows, std::vector<double> heights, double dx = 1, double dy = -1) {
  HeightField f;
  f.columns = columns;
  f.rows = rows;
  f.x0 = 1000;
  f.y0 = 2000;
  f.dx = dx;
  f.dy = dy;
  f.heights = std::move(heights);
  return f;
}

// One point on the top of every pixel with a height, facing up.
std::vector<QueryPoint> pixel_tops(const HeightField& f) {
  std::vector<QueryPoint> pts;
  for (std::size_t r = 0; r < f.rows; ++r)
    for (std::size_t c = 0; c < f.columns; ++c)
      if (!std::isnan(f.height(c, r))) pts.push_back({Vec3(f.centre_x(c), f.centre_y(r), f.height(c, r)), Vec3(0, 0, 1)});
  return pts;
}

// What `skyband map --dsm` uses: the horizon even where pixel sides continue one another.
VisibilityOptions horizon_first() {
  VisibilityOptions o;
  o.prefer_horizon = true;
  return o;
}

}  // namespace

BOOST_AUTO_TEST_CASE(flat_field_is_one_column_solid_with_the_open_sky) {
  const HeightField f = field(3, 3, std::vector<double>(9, 5.0));
  const TriangleSoup soup = height_field_mesh(f, height_field_floor(f));
  // 9 tops of 2 triangles; the 12 boundary sides each a wall from the floor to 5 m (2 triangles).
  BOOST_TEST(soup.triangle_count() == 18u + 24u);
  BOOST_TEST(height_field_floor(f) == 4.0);  // 5 − max(1, 1 % of a zero range)
  const Scene scene(soup);
  BOOST_TEST(scene.column_scene().column_solids == 1u);
  BOOST_TEST(scene.column_scene().other_components == 0u);
  const std::vector<QueryPoint> pts = pixel_tops(f);
  const SkyFactorsRun run = compute_sky_factors(scene, pts, horizon_first(), SkyFactorsMethod::automatic, 1);
  BOOST_TEST(run.by_horizon == pts.size());
  for (const SkyFactors& s : run.factors) {
    BOOST_TEST(std::abs(s.svf - 1.0) < 1e-12);  // nothing rises above the tops: the open sky
    BOOST_TEST(std::abs(s.sky_exposure - 1.0) < 1e-12);
  }
}

BOOST_AUTO_TEST_CASE(random_fields_match_the_union_oracle_in_both_raster_orientations) {
  // Random heights on a few levels (so that equal neighbours, diagonal touching and many walls
  // meeting at a corner all occur) and some pixels without height; north-up (dy < 0) and
  // south-up (dy > 0) rasters, square and oblong pixels.
  gen::Rng rng(7);
  for (const auto& [dx, dy] : {std::pair{1.0, -1.0}, std::pair{0.5, 0.75}, std::pair{-2.0, -1.0}}) {
    std::vector<double> h(6 * 5);
    for (double& z : h) z = rng.uniform() < 0.1 ? kNaN : 2.0 * double(rng.below(4)) + (rng.uniform() < 0.2 ? 0.37 : 0.0);
    const HeightField f = field(6, 5, h, dx, dy);
    const TriangleSoup soup = height_field_mesh(f, height_field_floor(f));
    const Scene scene(soup);
    BOOST_TEST(scene.column_scene().column_solids == 1u);
    BOOST_TEST(scene.column_scene().other_components == 0u);
    const std::vector<QueryPoint> pts = pixel_tops(f);
    const SkyFactorsRun run = compute_sky_factors(scene, pts, horizon_first(), SkyFactorsMethod::automatic, 1);
    BOOST_TEST(run.by_horizon == pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const UnionSkyFactors exact = sky_union_oracle(pts[i].position + 1e-6 * pts[i].normal, pts[i].normal, soup);
      // Both exact: rounding only (horizon_svf_test's kExact).
      BOOST_TEST(std::abs(run.factors[i].svf - exact.svf) < 1e-9,
                 "dx " << dx << " point " << i << ": " << run.factors[i].svf << " oracle " << exact.svf);
      BOOST_TEST(std::abs(run.factors[i].sky_exposure - exact.sky_exposure) < 1e-9, "dx " << dx << " point " << i);
    }
  }
}

BOOST_AUTO_TEST_CASE(checkerboard_touches_diagonally_everywhere) {
  std::vector<double> h(4 * 4);
  for (std::size_t i = 0; i < h.size(); ++i) h[i] = ((i % 4) + (i / 4)) % 2 ? 3.0 : 1.0;
  const TriangleSoup soup = height_field_mesh(field(4, 4, h), 0.0);
  BOOST_TEST(classify_column_scene(soup).column_solids == 1u);
}

BOOST_AUTO_TEST_CASE(long_wall_closed_form) {
  // A row of pixels H = 2 m high along x, 400 m long, beside rows at 0: a point on the low side at
  // distance d = 1.5 m from the wall, mid-way along it. Beside an infinite wall the SVF of a
  // horizontal element is ½(1 + d/√(d² + H²)) (its view factor to the infinite strip is
  // ½(1 − d/√(d² + H²))). The infinite wall's parts beyond 200 m on each side are seen below
  // elevation β = atan(H/200); directions below β over at most π of azimuth carry at most
  // ½·sin²β ≈ 5e-5 of the SVF (their projected solid angle π·½sin²β, over π): 1e-4 for both.
  const std::size_t n = 400;
  std::vector<double> h(n * 3, 0.0);
  for (std::size_t c = 0; c < n; ++c) h[c] = 2.0;  // row 0 (north)
  const HeightField f = field(n, 3, h);
  const Scene scene(height_field_mesh(f, -1.0));
  const QueryPoint q{Vec3(f.centre_x(n / 2), f.corner_y(1) - 1.5, 0.0), Vec3(0, 0, 1)};
  const SkyFactorsRun run =
      compute_sky_factors(scene, std::vector<QueryPoint>{q}, horizon_first(), SkyFactorsMethod::automatic, 1);
  BOOST_TEST(run.by_horizon == 1u);
  const double d = 1.5, H = 2.0;
  BOOST_TEST(std::abs(run.factors[0].svf - 0.5 * (1 + d / std::hypot(d, H))) < 1e-4);
}

BOOST_AUTO_TEST_CASE(bad_fields_are_input_errors) {
  BOOST_CHECK_THROW(height_field_mesh(field(0, 0, {}), 0.0), InputError);
  BOOST_CHECK_THROW(height_field_mesh(field(2, 1, {1.0}), 0.0), InputError);
  BOOST_CHECK_THROW(height_field_mesh(field(1, 1, {1.0}, 0.0, 1.0), 0.0), InputError);
  BOOST_CHECK_THROW(height_field_mesh(field(1, 1, {std::numeric_limits<double>::infinity()}), 0.0), InputError);
  BOOST_CHECK_THROW(height_field_mesh(field(1, 1, {1.0}), 1.0), InputError);  // floor not below
  BOOST_CHECK_THROW(height_field_floor(field(1, 1, {kNaN})), InputError);
}
