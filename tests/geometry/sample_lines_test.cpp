#define BOOST_TEST_MODULE sample_lines
#include <boost/test/unit_test.hpp>

// The exact visible sky cut along band sample lines (geometry/bands/sample_lines.h) against an
// independent exact computation of the same lines: the band method's own sample-plane
// intersection with every triangle (BandVisibility::visible_on_plane, exact predicates, no
// culling near the pencil axis). Also the doubling of the band count against the region's exact
// SVF and exposure, and the renderer's cache by either method.

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/bands/sample_lines.h"
#include "geometry/bands/sky_integral.h"
#include "geometry/support/scene_generators.h"
#include "geometry/visibility/sky_visibility.h"

using namespace skyband;

namespace {

Vec3 unit_normal(double tilt, double az) {
  return Vec3(std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt));
}

void add_triangle(TriangleSoup& s, const Vec3& a, const Vec3& b, const Vec3& c) {
  const auto base = std::uint32_t(s.vertices.size());
  s.vertices.insert(s.vertices.end(), {a, b, c});
  s.triangles.push_back({base, base + 1, base + 2});
}
void add_quad(TriangleSoup& s, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  add_triangle(s, a, b, c);
  add_triangle(s, a, c, d);
}
void add_box(TriangleSoup& s, const Vec3& lo, const Vec3& hi) {
  gen::append_box(s, gen::OrientedBox{0.5 * (lo + hi), hi - lo, 0.0});
}

// Measure (radians of α) of the symmetric difference of two sorted disjoint interval lists.
double difference(const std::vector<VisibleInterval>& a, const std::vector<VisibleInterval>& b) {
  std::vector<std::pair<double, int>> ev;
  for (const auto& i : a) ev.push_back({i.alpha0_rad, 1}), ev.push_back({i.alpha1_rad, -1});
  for (const auto& i : b) ev.push_back({i.alpha0_rad, 2}), ev.push_back({i.alpha1_rad, -2});
  std::sort(ev.begin(), ev.end());
  double out = 0, prev = 0;
  int in_a = 0, in_b = 0;
  for (const auto& [x, k] : ev) {
    if ((in_a > 0) != (in_b > 0)) out += x - prev;
    prev = x;
    if (k == 1) ++in_a;
    if (k == -1) --in_a;
    if (k == 2) ++in_b;
    if (k == -2) --in_b;
  }
  return out;
}

VisibilityOptions exhaustive_bands() {
  VisibilityOptions o;
  o.tolerance = 0;
  o.axis_tail_rad = 0;
  return o;
}

// Every line of every point, by both computations. The end points are stored as float (~1e-7
// rad apart at π), so the two agree to a few 1e-7 per boundary crossed.
void check_lines(const TriangleSoup& soup, const std::vector<QueryPoint>& pts, const char* what) {
  const Scene scene(soup);
  SkyVisibility exact(scene, VisibilityOptions{}, SkyFactorsMethod::exact);
  BandVisibility bands(scene, exhaustive_bands());
  double worst = 0;
  std::size_t lines = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const VisibleSky& sky = exact.compute(pts[i]);
    const BandFrame frame = BandFrame::make(pts[i].normal);
    for (int k = 0; k <= 24; ++k) {
      const double delta = frame.delta_min_rad + (frame.delta_max_rad - frame.delta_min_rad) * (k + 0.37) / 25.37;
      std::vector<VisibleInterval> mine, theirs;
      visible_on_sample_line(sky, frame, delta, mine);
      bands.visible_on_plane(pts[i], delta, theirs);
      const double d = difference(mine, theirs);
      worst = std::max(worst, d);
      ++lines;
      BOOST_TEST(d < 2e-6, what << " point " << i << " line δ = " << delta << ": the lines differ by " << d << " rad");
      for (std::size_t j = 0; j < mine.size(); ++j) {
        BOOST_TEST(mine[j].alpha0_rad < mine[j].alpha1_rad);
        if (j > 0) BOOST_TEST(mine[j - 1].alpha1_rad < mine[j].alpha0_rad);
      }
    }
  }
  BOOST_TEST_MESSAGE(what << ": " << lines << " lines, largest difference " << worst << " rad");
}

}  // namespace

BOOST_AUTO_TEST_CASE(lines_of_a_city_with_bridges_overhangs_and_tilted_faces) {
  TriangleSoup soup;
  add_quad(soup, Vec3(-40, -40, 0), Vec3(40, -40, 0), Vec3(40, 40, 0), Vec3(-40, 40, 0));
  add_box(soup, Vec3(-12, -4, 0), Vec3(-4, 4, 15));
  add_box(soup, Vec3(4, -4, 0), Vec3(12, 4, 12));
  add_box(soup, Vec3(-4, -1, 6), Vec3(4, 1, 7));                                             // a bridge: sky below it
  add_box(soup, Vec3(4, 4, 3), Vec3(7, 5.5, 3.2));                                           // a balcony slab
  add_quad(soup, Vec3(-4, -4, 15), Vec3(-2.5, -4, 15), Vec3(-2.5, 4, 15), Vec3(-4, 4, 15));  // an eave
  std::vector<QueryPoint> pts = {
      {Vec3(0, 0, 0.05), Vec3(0, 0, 1)},      {Vec3(0, -3, 0.05), Vec3(0, 0, 1)},      {Vec3(5.5, 5.0, 0.5), Vec3(0, 0, 1)},
      {Vec3(5.5, 6.0, 0.5), Vec3(0, 1, 0)},   {Vec3(-3.0, 0, 10), Vec3(1, 0, 0)},      {Vec3(0, 0, 7.5), Vec3(0, 0, 1)},
      {Vec3(0, 3, 3), unit_normal(2.0, 1.0)}, {Vec3(1, -2, 2), unit_normal(0.7, 4.0)}, {Vec3(-20, 7, 0.1), unit_normal(1.3, 5.5)},
  };
  check_lines(soup, pts, "bridges");
}

BOOST_AUTO_TEST_CASE(lines_of_random_triangle_soups) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    gen::Rng rng(seed);
    TriangleSoup soup;
    for (int t = 0; t < 14; ++t) {
      const Vec3 c{rng.uniform(-8, 8), rng.uniform(-8, 8), rng.uniform(0, 8)};
      const Vec3 a = c + Vec3{rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-3, 3)};
      const Vec3 b = c + Vec3{rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-3, 3)};
      add_triangle(soup, a, b, c + Vec3{rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-3, 3)});
    }
    std::vector<QueryPoint> pts;
    for (int i = 0; i < 6; ++i)
      pts.push_back({Vec3{rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(0, 5)},
                     i == 0 ? Vec3(0, 0, 1) : rng.unit_normal(0, kPi, 0, 6.28)});
    check_lines(soup, pts, "soup");
  }
}

BOOST_AUTO_TEST_CASE(lines_of_a_closed_box_city_by_the_exact_horizon) {
  // A column scene: the dispatcher's exact horizon hands over its envelope.
  gen::CityParams cp;
  cp.blocks = 2;
  const gen::City city = gen::make_city(cp);
  std::vector<QueryPoint> pts = gen::street_points(city, 6, 3);
  for (const QueryPoint& q : gen::facade_points(city.buildings, 6, 0.05, 4)) pts.push_back(q);
  const Scene scene(city.soup);
  SkyVisibility automatic(scene, VisibilityOptions{}, SkyFactorsMethod::automatic);
  BandVisibility bands(scene, exhaustive_bands());
  for (const QueryPoint& q : pts) {
    const VisibleSky& sky = automatic.compute(q);
    BOOST_TEST((sky.method == SkyMethod::exact_horizon));
    const BandFrame frame = BandFrame::make(q.normal);
    for (int k = 0; k < 16; ++k) {
      const double delta = frame.delta_min_rad + (frame.delta_max_rad - frame.delta_min_rad) * (k + 0.5) / 16;
      std::vector<VisibleInterval> mine, theirs;
      visible_on_sample_line(sky, frame, delta, mine);
      bands.visible_on_plane(q, delta, theirs);
      BOOST_TEST(difference(mine, theirs) < 2e-6);
    }
  }
}

BOOST_AUTO_TEST_CASE(doubling_holds_the_lines_to_the_exact_values) {
  // A low skyline far away (the band method's hard case) and street points among open boxes:
  // the lines' SVF and exposure within half the tolerance of the exact region's, or the limit.
  gen::OpenBoxCityParams p;
  p.per_side = 6;
  const gen::OpenBoxCity city = gen::make_open_box_city(p);
  std::vector<QueryPoint> pts = gen::open_city_street_points(city, 6, 5, 300);
  for (const QueryPoint& q : gen::open_city_street_points(city, 6, 6)) pts.push_back(q);
  for (const QueryPoint& q : gen::open_city_facade_points(city, 6, 7)) pts.push_back(q);
  const Scene scene(city.soup);
  SkyVisibility exact(scene, VisibilityOptions{}, SkyFactorsMethod::exact);
  SampleLineOptions opt;
  opt.bands = 8;
  opt.tolerance = 2e-4;
  opt.max_doublings = 9;
  int doubled = 0;
  for (const QueryPoint& q : pts) {
    const VisibleSky& sky = exact.compute(q);
    VisibilityCache::PointResult r;
    const int n = sample_lines_of(sky, opt, r);
    BOOST_TEST(r.bands.size() == std::size_t(n));
    doubled += n > opt.bands;
    VisibilityCache c;
    c.append(r);
    const double svf = sky_view_factor(c.view(0)), exposure = sky_exposure(c.view(0));
    if (n < opt.bands << opt.max_doublings) {
      BOOST_TEST(std::abs(svf - sky.factors.svf) <= 0.5 * opt.tolerance);
      BOOST_TEST(std::abs(exposure - sky.factors.sky_exposure) <= 0.5 * opt.tolerance);
    }
    // Without doubling: the fixed lines (the paper's method).
    SampleLineOptions fixed = opt;
    fixed.tolerance = 0;
    BOOST_TEST(sample_lines_of(sky, fixed, r) == opt.bands);
  }
  BOOST_TEST(doubled > 0);  // 8 lines do not reach 1e-4 everywhere
}

BOOST_AUTO_TEST_CASE(the_renderers_cache_is_the_same_by_either_method) {
  // Fixed N: both methods put the lines at the same weight medians, so the caches hold the same
  // lines to float rounding, and any sky integral over them agrees.
  gen::CityParams cp;
  cp.blocks = 2;
  const gen::City city = gen::make_city(cp);
  std::vector<QueryPoint> pts = gen::street_points(city, 10, 8);
  for (const QueryPoint& q : gen::facade_points(city.buildings, 10, 0.05, 9)) pts.push_back(q);
  const Scene scene(city.soup);
  VisibilityOptions o = exhaustive_bands();
  o.bands = 24;
  SkyMethodCounts counts;
  const VisibilityCache exact = compute_visibility_cache(scene, pts, o, SkyFactorsMethod::exact, 2, {}, &counts);
  BOOST_TEST(counts.by_exact == pts.size());
  const VisibilityCache bands = compute_visibility_cache(scene, pts, o, SkyFactorsMethod::bands, 1);
  BOOST_TEST_REQUIRE(exact.size() == pts.size());
  BOOST_TEST_REQUIRE(bands.size() == pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const PointVisibilityView a = exact.view(i), b = bands.view(i);
    BOOST_TEST_REQUIRE(a.band_count() == b.band_count());
    for (std::size_t k = 0; k < a.band_count(); ++k) {
      BOOST_TEST(a.band(k).delta_rad == b.band(k).delta_rad);
      std::vector<VisibleInterval> va(a.visible(k).begin(), a.visible(k).end()), vb(b.visible(k).begin(), b.visible(k).end());
      BOOST_TEST(difference(va, vb) < 2e-6, "point " << i << " band " << k);
    }
    BOOST_TEST(std::abs(sky_view_factor(a) - sky_view_factor(b)) < 1e-6);
    BOOST_TEST(std::abs(sky_exposure(a) - sky_exposure(b)) < 1e-6);
  }
  // Thread independence of the exact cache.
  const VisibilityCache one = compute_visibility_cache(scene, pts, o, SkyFactorsMethod::exact, 1);
  BOOST_TEST(one.intervals().size() == exact.intervals().size());
  BOOST_TEST(std::equal(one.intervals().begin(), one.intervals().end(), exact.intervals().begin(),
                        [](const VisibleInterval& x, const VisibleInterval& y) {
                          return x.alpha0_rad == y.alpha0_rad && x.alpha1_rad == y.alpha1_rad;
                        }));
}
