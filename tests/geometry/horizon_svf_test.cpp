#define BOOST_TEST_MODULE horizon_svf
#include <boost/test/unit_test.hpp>

// The exact horizon method (geometry/horizon/horizon_svf.h) and its validity test (column_scene.h)
// against the exact, independent oracles of tests/geometry/support/lambert_oracle.h (Lambert's
// contour formula over exact 2D unions on the occluders' faces), the closed forms of
// reference-notes §5, and the band method where the horizon method must refuse.

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/bands/sky_integral.h"
#include "geometry/horizon/column_scene.h"
#include "geometry/horizon/horizon_svf.h"
#include "geometry/support/lambert_oracle.h"
#include "geometry/support/scene_generators.h"
#include "geometry/visibility/sky_factors.h"

using namespace skyband;
using namespace skyband::oracle;

namespace {

// The method is exact; its results carry only rounding (arcs, Lambert's sum over ~10² pieces)
// and the oracle's own rounding (< 1e-9, lambert_oracle_test).
constexpr double kExact = 1e-9;

bool inside_footprint(const OrientedBox& b, const Vec3& p, double margin) {
  const double c = std::cos(-b.yaw_rad), s = std::sin(-b.yaw_rad);
  const Vec3 d = p - b.centre;
  return std::abs(c * d.x() - s * d.y()) <= 0.5 * b.size.x() + margin &&
         std::abs(s * d.x() + c * d.y()) <= 0.5 * b.size.y() + margin;
}

Vec3 unit_normal(double tilt, double az) {
  return Vec3(std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt));
}

// The band method as a reference: 4096 fixed bands, no refinement, no axis tail.
VisibilityOptions fine_bands() {
  VisibilityOptions fine;
  fine.bands = 4096;
  fine.tolerance = 0;
  fine.axis_tail_rad = 0;
  return fine;
}

// `count` random points within 12 m of the origin, up to 4 m high, outside the boxes' footprints
// (5 cm margin), with random normals up to horizontal; the first `horizontal` of them face up.
std::vector<QueryPoint> points_around(const std::vector<OrientedBox>& boxes, std::uint64_t seed, std::size_t count,
                                      std::size_t horizontal) {
  std::vector<QueryPoint> pts;
  gen::Rng rng(seed);
  while (pts.size() < count) {
    QueryPoint q{Vec3{rng.uniform(-12, 12), rng.uniform(-12, 12), rng.uniform(0, 4)}, rng.unit_normal(0, kPi / 2, 0, 6.28)};
    if (pts.size() < horizontal) q.normal = Vec3(0, 0, 1);
    if (std::none_of(boxes.begin(), boxes.end(), [&](const OrientedBox& b) { return inside_footprint(b, q.position, 0.05); }))
      pts.push_back(q);
  }
  return pts;
}

// Six random rotated boxes within 10 m of the origin: the band-agreement tests' scene.
std::vector<OrientedBox> six_boxes(std::uint64_t seed) {
  gen::RandomBoxParams params;
  params.count = 6;
  params.extent_m = 10;
  return gen::random_boxes(params, seed);
}

}  // namespace

BOOST_AUTO_TEST_CASE(classification_of_components) {
  TriangleSoup box;
  append_box(box, Vec3(0, 0, 0), Vec3(2, 3, 5));
  ColumnScene c = classify_column_scene(box);
  BOOST_TEST(c.column_solids == 1u);
  BOOST_TEST(c.other_components == 0u);
  BOOST_TEST(c.max_column_floor_z == 0.0);
  BOOST_TEST(c.valid_from_height(-10.0));  // (column floors are checked per point by the method)
  // Silhouette candidates: the 4 roof edges (vertical edges, the floor's edges at the lowest floor
  // and the faces' inner diagonals are not).
  BOOST_TEST(c.edges.size() == 4u);

  // Inward-wound: still a column solid (orientation from the signed volume).
  TriangleSoup inward = box;
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  BOOST_TEST(classify_column_scene(inward).column_solids == 1u);

  // Four walls and a roof, no floor (the boundary lies in the floor plane: the solid capped there),
  // with one wall wound the other way (windings are made consistent, not read): a column solid;
  // without a wall instead the boundary rises to the roof: a column solid only for points at or
  // above that height (its floor height is the highest point of its open edges).
  TriangleSoup floorless = box;
  floorless.triangles.erase(floorless.triangles.begin(), floorless.triangles.begin() + 2);
  std::swap(floorless.triangles[2][1], floorless.triangles[2][2]);
  std::swap(floorless.triangles[3][1], floorless.triangles[3][2]);
  c = classify_column_scene(floorless);
  BOOST_TEST(c.column_solids == 1u);
  BOOST_TEST(c.edges.size() == 4u);
  TriangleSoup wall_missing = floorless;
  wall_missing.triangles.erase(wall_missing.triangles.begin() + 2, wall_missing.triangles.begin() + 4);
  c = classify_column_scene(wall_missing);
  BOOST_TEST(c.column_solids == 1u);
  BOOST_TEST(c.max_column_floor_z == 5.0);

  // A box floating above a grounded one: both column solids, floors 0 and 4.
  TriangleSoup two = box;
  append_box(two, Vec3(10, 0, 4), Vec3(11, 1, 6));
  c = classify_column_scene(two);
  BOOST_TEST(c.column_solids == 2u);
  BOOST_TEST(c.min_column_floor_z == 0.0);
  BOOST_TEST(c.max_column_floor_z == 4.0);
  BOOST_TEST(c.edges.size() == 12u);  // 4 roof edges each, and the floating floor's 4

  // An open box (roof removed): its open edges reach 5 m, so it is a column solid only from there
  // up. Two fins on one of its top edges (three triangles on one edge) make it other components,
  // valid only above their highest vertex.
  TriangleSoup open = box;
  open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4);
  c = classify_column_scene(open);
  BOOST_TEST(c.column_solids == 1u);
  BOOST_TEST(c.max_column_floor_z == 5.0);
  TriangleSoup finned = open;
  {
    std::uint32_t top[2], n = 0;  // the edge at z = 5 of a wall triangle of the open box
    for (const auto& t : finned.triangles) {
      n = 0;
      for (std::uint32_t v : t)
        if (finned.vertices[v].z() == 5.0) top[n++] = v;
      if (n == 2) break;
    }
    BOOST_TEST_REQUIRE(n == 2u);
    for (const Vec3& apex : {Vec3(1, 1.5, 8), Vec3(1.2, 1.4, 7)}) {  // two fins: the edge in three triangles
      finned.vertices.push_back(apex);
      finned.triangles.push_back({top[0], top[1], std::uint32_t(finned.vertices.size() - 1)});
    }
  }
  c = classify_column_scene(finned);
  BOOST_TEST(c.column_solids == 0u);
  BOOST_TEST(c.other_components == 3u);  // the open box and each fin
  BOOST_TEST(c.max_other_z == 8.0);

  // An overhang: a T-shaped solid (a slab on a post) faces down above its floor.
  TriangleSoup t_shape;
  append_box(t_shape, Vec3(0, 0, 0), Vec3(1, 1, 3));
  append_box(t_shape, Vec3(-2, -2, 3), Vec3(3, 3, 4));  // shares no vertex with the post: 2 components
  c = classify_column_scene(t_shape);
  BOOST_TEST(c.column_solids == 2u);  // each box alone is a column solid; the slab floats at z = 3
  BOOST_TEST(c.max_column_floor_z == 3.0);
}

BOOST_AUTO_TEST_CASE(open_sky_closed_forms) {
  TriangleSoup ground;  // a ground sheet at z = 0 (an open component, wholly below the points)
  ground.vertices = {Vec3(-50, -50, 0), Vec3(50, -50, 0), Vec3(50, 50, 0), Vec3(-50, 50, 0)};
  ground.triangles = {{0, 1, 2}, {0, 2, 3}};
  const Scene scene(ground);
  const ColumnScene columns = classify_column_scene(scene.soup());
  HorizonSvf h(scene, columns, 1e-6);
  SkyFactors f;
  for (double tilt : {0.0, 0.3, 1.0, kPi / 2}) {
    BOOST_TEST_REQUIRE(h.compute(QueryPoint{Vec3(1, 2, 0), unit_normal(tilt, 0.7)}, f));
    // SVF (1 + cos tilt)/2 and exposure 1/2 + β/π, β = π/2 − tilt (reference-notes §5).
    BOOST_TEST(std::abs(f.svf - 0.5 * (1 + std::cos(tilt))) < 1e-15);
    BOOST_TEST(std::abs(f.sky_exposure - (0.5 + (kPi / 2 - tilt) / kPi)) < 1e-15);
  }
  BOOST_TEST(h.compute(QueryPoint{Vec3(1, 2, 0), Vec3(0, 0, 1)}, f));
  BOOST_TEST(f.svf == 1.0);
  // Facing down: refused (the band method handles it).
  BOOST_TEST(!h.compute(QueryPoint{Vec3(1, 2, 1), unit_normal(2.0, 0.1)}, f));
}

BOOST_AUTO_TEST_CASE(single_wall_and_canyon_closed_forms) {
  // A wall of height H at distance D from a ground point, infinitely long in the limit: the
  // finite wall's exact SVF is Lambert's perpendicular-rectangle form factor (reference-notes §5).
  TriangleSoup wall;
  append_box(wall, Vec3(-500, 3, 0), Vec3(500, 4, 7));
  const Scene scene(wall);
  const ColumnScene columns = classify_column_scene(scene.soup());
  HorizonSvf h(scene, columns, 0.0);
  SkyFactors f;
  BOOST_TEST_REQUIRE(h.compute(QueryPoint{Vec3(0, 0, 0), Vec3(0, 0, 1)}, f));
  // Hidden: the wall's face at y = 3 (a 1000 × 7 rectangle, perpendicular to the ground, the
  // point at distance 3 from its plane, centred) — twice the half-rectangle factor; the wall's
  // top is hidden behind that face.
  const double hidden = 2 * perpendicular_rectangle_form_factor(500, 7, 3);
  BOOST_TEST(std::abs(f.svf - (1 - hidden)) < kExact, "svf " << f.svf << " expected " << 1 - hidden);

  // Street canyon W = 10, H = 20, walls 400 km long (their ends change the SVF by ~1e-13 and
  // the exposure by ~1e-9 here): floor and wall points (reference-notes §5).
  const auto boxes = gen::street_canyon(10, 20, 4e5);
  const TriangleSoup soup = gen::boxes_to_soup(boxes);
  const Scene canyon(soup);
  const ColumnScene cc = classify_column_scene(canyon.soup());
  HorizonSvf hc(canyon, cc, 1e-6);
  // The sky exposure of an infinite canyon in closed form: the sky hidden by an infinitely long
  // horizontal edge at height h and horizontal distance d is the lune between the horizon and the
  // great circle through the edge, of solid angle 2·atan(h/d) (twice its dihedral angle).
  BOOST_TEST_REQUIRE(hc.compute(QueryPoint{Vec3(0, 3, 0), Vec3(0, 0, 1)}, f));
  // (The point is evaluated 1 µm in front of its face: walls 1 µm lower, or 1 µm farther.)
  const double wall_h = 20 - 1e-6;
  BOOST_TEST(std::abs(f.svf - canyon_floor_svf(3, 10, wall_h)) < 1e-9);
  BOOST_TEST(std::abs(f.sky_exposure - (2 * kPi - 2 * std::atan(wall_h / 3.0) - 2 * std::atan(wall_h / 7.0)) / (2 * kPi)) < 1e-8);
  BOOST_TEST_REQUIRE(hc.compute(QueryPoint{Vec3(0, 0, 12), Vec3(0, 1, 0)}, f));
  const double w = 10 - 1e-6;
  BOOST_TEST(std::abs(f.svf - canyon_wall_svf(12, w, 20)) < 1e-9);
  BOOST_TEST(std::abs(f.sky_exposure - (kPi - 2 * std::atan(8 / w)) / (2 * kPi)) < 1e-8);
}

BOOST_AUTO_TEST_CASE(integration_reproduces_the_open_sky) {
  // A 1 cm box 1 km away (hiding ~1e-10 of the sky) makes the method integrate the whole fan
  // instead of returning the closed form: the fan must reproduce the closed forms.
  TriangleSoup speck;
  append_box(speck, Vec3(1000, 0, 0), Vec3(1000.01, 0.01, 0.01));
  const Scene scene(speck);
  const ColumnScene columns = classify_column_scene(scene.soup());
  HorizonSvf h(scene, columns, 0.0);
  for (double tilt : {0.0, 0.3, 1.0, kPi / 2})
    for (double az : {0.0, 0.7, 2.0, 3.5, 5.0}) {
      SkyFactors f;
      BOOST_TEST_REQUIRE(h.compute(QueryPoint{Vec3(0, 0, 0.005), unit_normal(tilt, az)}, f));
      BOOST_TEST(std::abs(f.svf - 0.5 * (1 + std::cos(tilt))) < 1e-9, "tilt " << tilt << " az " << az << " svf " << f.svf);
      BOOST_TEST(std::abs(f.sky_exposure - (0.5 + (kPi / 2 - tilt) / kPi)) < 1e-9,
                 "tilt " << tilt << " az " << az << " exposure " << f.sky_exposure);
    }
}

BOOST_AUTO_TEST_CASE(random_box_scenes_match_the_union_oracle) {
  // Overlapping, rotated boxes on the ground; ground points, tilted points above the ground, and
  // facade points on and off the walls. The union oracle is exact.
  gen::RandomBoxParams params;
  params.count = 8;
  params.extent_m = 12;
  double worst = 0;
  std::size_t n = 0;
  for (int seed = 1; seed <= 10; ++seed) {
    const auto boxes = gen::random_boxes(params, 300 + seed);
    const TriangleSoup soup = gen::boxes_to_soup(boxes);
    const Scene scene(soup);
    const ColumnScene columns = classify_column_scene(scene.soup());
    BOOST_TEST(columns.column_solids == boxes.size());
    HorizonSvf h(scene, columns, 1e-6);
    gen::Rng rng(900 + seed);
    std::vector<QueryPoint> pts;
    while (pts.size() < 8) {
      const bool ground = pts.size() < 4;
      QueryPoint q{Vec3{rng.uniform(-14, 14), rng.uniform(-14, 14), ground ? 0.0 : rng.uniform(0, 6)}, Vec3(0, 0, 1)};
      if (std::any_of(boxes.begin(), boxes.end(), [&](const OrientedBox& b) { return inside_footprint(b, q.position, 0.05); }))
        continue;
      if (!ground) q.normal = rng.unit_normal(0.05, kPi / 2, 0, 2 * kPi);
      pts.push_back(q);
    }
    for (double off : {0.0, 0.05})
      for (const QueryPoint& q : gen::facade_points(boxes, 5, off, 1000 + seed))
        if (std::none_of(boxes.begin(), boxes.end(), [&](const OrientedBox& b) {
              return inside_footprint(b, q.position, -1e-9) && q.position.z() < b.size.z();
            }))
          pts.push_back(q);
    for (const QueryPoint& q : pts) {
      SkyFactors f;
      if (!h.compute(q, f)) continue;  // facade points inside an intersecting box
      const Vec3 p = q.position + 1e-6 * q.normal;
      const double exact = svf_union_oracle(p, q.normal, soup);
      worst = std::max(worst, std::abs(f.svf - exact));
      ++n;
      BOOST_TEST(std::abs(f.svf - exact) < kExact, "seed " << seed << " p " << q.position.transpose() << " n "
                                                           << q.normal.transpose() << " horizon " << f.svf << " exact " << exact);
    }
  }
  BOOST_TEST_MESSAGE("random box scenes: max |horizon − oracle| " << worst << " over " << n << " points");
  BOOST_TEST(n >= 100u);
}

BOOST_AUTO_TEST_CASE(agrees_with_the_band_method_at_many_bands) {
  // The band method is exact in α and converges in δ. Its SVF at 4096 bands is a reference to
  // ~1e-5; its exposure converges more slowly (the bands against the face's own plane are
  // ~√(2/N) rad wide in δ and sampled at their weight median), to ~1e-3 here.
  const auto boxes = six_boxes(77);
  const Scene scene(gen::boxes_to_soup(boxes));
  const ColumnScene columns = classify_column_scene(scene.soup());
  HorizonSvf h(scene, columns, 1e-6);
  const std::vector<QueryPoint> pts = points_around(boxes, 5, 12, 0);
  const VisibilityCache cache = compute_visibility(scene, pts, fine_bands(), 1);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    SkyFactors f;
    BOOST_TEST_REQUIRE(h.compute(pts[i], f));
    BOOST_TEST(std::abs(f.sky_exposure - sky_exposure(cache.view(i))) < 1e-3);
    BOOST_TEST(std::abs(f.svf - sky_view_factor(cache.view(i))) < 2e-5);
  }
}

BOOST_AUTO_TEST_CASE(refuses_points_under_or_inside_solids_and_the_driver_falls_back) {
  TriangleSoup soup;
  append_box(soup, Vec3(0, 0, 0), Vec3(4, 4, 4));
  append_box(soup, Vec3(10, 0, 3), Vec3(12, 2, 5));  // floats 3 m above the ground
  const Scene scene(soup);
  const ColumnScene columns = classify_column_scene(scene.soup());
  HorizonSvf h(scene, columns, 1e-6);
  SkyFactors f;
  BOOST_TEST(!h.compute(QueryPoint{Vec3(2, 2, 2), Vec3(0, 0, 1)}, f));    // below the floating floor, which it sees
  BOOST_TEST(!h.compute(QueryPoint{Vec3(6, 1, 0), Vec3(0, 0, 1)}, f));    // on the ground, seeing the floating box
  BOOST_TEST(h.compute(QueryPoint{Vec3(2, 2, 4), Vec3(0, 0, 1)}, f));     // on the roof: valid
  BOOST_TEST(f.svf < 1.0);                                                // the floating box is higher
  BOOST_TEST(!h.compute(QueryPoint{Vec3(2, 2, 3.5), Vec3(0, 0, 1)}, f));  // inside the first box

  // The driver: inside → 0 by the exact visible sky; on the roof and beside → the horizon.
  const std::vector<QueryPoint> pts = {
      {Vec3(2, 2, 3.5), Vec3(0, 0, 1)}, {Vec3(2, 2, 4), Vec3(0, 0, 1)}, {Vec3(6, 6, 4), Vec3(0, 0, 1)}};
  const SkyFactorsRun run = compute_sky_factors(scene, pts, VisibilityOptions{}, SkyFactorsMethod::automatic, 1);
  BOOST_TEST(run.by_exact == 1u);
  BOOST_TEST(run.by_horizon == 2u);
  BOOST_TEST(run.factors[0].svf == 0.0);
  const SkyFactorsRun bands = compute_sky_factors(scene, pts, VisibilityOptions{}, SkyFactorsMethod::bands, 1);
  for (std::size_t i = 1; i < pts.size(); ++i) BOOST_TEST(std::abs(run.factors[i].svf - bands.factors[i].svf) < 1e-3);
}

BOOST_AUTO_TEST_CASE(city_points_threads_and_projected_coordinates) {
  gen::CityParams cp;
  cp.blocks = 4;
  const gen::City city = gen::make_city(cp);
  std::vector<QueryPoint> pts = gen::street_points(city, 40, 3);
  for (const QueryPoint& q : gen::facade_points(city.buildings, 40, 0.0, 4)) pts.push_back(q);
  const Scene scene(city.soup);
  const SkyFactorsRun one = compute_sky_factors(scene, pts, VisibilityOptions{}, SkyFactorsMethod::automatic, 1);
  const SkyFactorsRun two = compute_sky_factors(scene, pts, VisibilityOptions{}, SkyFactorsMethod::automatic, 2);
  BOOST_TEST(one.by_horizon == pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) BOOST_TEST(one.factors[i].svf == two.factors[i].svf);
  // Against the oracle on a few points (exact union of the city's front faces).
  for (std::size_t i = 0; i < pts.size(); i += 10) {
    const SvfBounds b =
        svf_union_oracle_culled(pts[i].position + 1e-6 * pts[i].normal, pts[i].normal, city.soup, 1e9, 1e-9, true, 1e9);
    BOOST_TEST(std::abs(one.factors[i].svf - b.estimate()) < kExact,
               "point " << i << " horizon " << one.factors[i].svf << " oracle " << b.estimate());
  }
  // Projected coordinates (x ≈ 4·10⁵, y ≈ 6·10⁶ m): the same answers to ~1e-9.
  TriangleSoup moved = city.soup;
  std::vector<QueryPoint> moved_pts = pts;
  gen::translate(moved, gen::kProjectedOffset);
  gen::translate(moved_pts, gen::kProjectedOffset);
  const SkyFactorsRun there = compute_sky_factors(Scene(moved), moved_pts, VisibilityOptions{}, SkyFactorsMethod::automatic, 1);
  BOOST_TEST(there.by_horizon == pts.size());
  double worst = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) worst = std::max(worst, std::abs(there.factors[i].svf - one.factors[i].svf));
  BOOST_TEST_MESSAGE("projected coordinates: max |ΔSVF| " << worst);
  BOOST_TEST(worst < 1e-9);
}

BOOST_AUTO_TEST_CASE(irradiance_over_the_visible_fan) {
  // The fan's quadrature (geometry/exact/sky_fan.h): under a uniform sky L = 1 it must give π·SVF (the
  // definition of the cosine-weighted SVF) to quadrature accuracy — 1e-5 relative at 0.2 rad, the
  // level of the band path's quadrature (docs/sky.md): an edge passing close to the point makes
  // the arc's elevation e₀(φ) nearly a step in azimuth (measured worst 3e-6); under a smooth non-uniform sky
  // it must agree with the band method's exact-in-α integral at 4096 bands (a reference to
  // ~1e-5 here, as in agrees_with_the_band_method_at_many_bands).
  const auto boxes = six_boxes(91);
  const Scene scene(gen::boxes_to_soup(boxes));
  HorizonSvf h(scene, scene.column_scene(), 1e-6);
  const std::vector<QueryPoint> pts = points_around(boxes, 17, 10, 3);
  const VisibilityCache cache = compute_visibility(scene, pts, fine_bands(), 1);
  const auto sky = [](const Vec3& w) { return 1.0 + 2.0 * w.z() + w.x() * w.x() - 0.5 * w.y(); };  // > 0 on the upper hemisphere
  std::vector<SkyFanTriangle> fan;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    SkyFactors f;
    BOOST_TEST_REQUIRE(h.compute(pts[i], f));
    h.visible_fan(fan);
    double e_uniform, e_sky;
    integrate_fan_channels<1>(
        fan, pts[i].normal, [](const Vec3&, double* c) { c[0] = 1.0; }, &e_uniform, 0.2);
    integrate_fan_channels<1>(
        fan, pts[i].normal, [&](const Vec3& w, double* c) { c[0] = sky(w); }, &e_sky, 0.2);
    BOOST_TEST(std::abs(e_uniform - kPi * f.svf) < 1e-5 * kPi,
               "point " << i << ": " << e_uniform - kPi * f.svf << " n " << pts[i].normal.transpose());
    const double band = integrate_irradiance(cache.view(i), sky, 0.05);
    BOOST_TEST(std::abs(e_sky - band) < 1e-4 * std::max(1.0, band), "point " << i << ": fan " << e_sky << " bands " << band);
  }
}

BOOST_AUTO_TEST_CASE(other_components_hidden_behind_column_solids_do_not_matter) {
  // A long tall wall (a column solid) and, behind it, lower than the wall, an open box (its roof
  // removed: a column solid only from 10 m up, the top of its open edges) and two boxes sharing a
  // wall modelled twice (four triangles on its horizontal edges: other components): from in front
  // of the wall both are wholly below the horizon the wall makes, so the method is valid there and
  // exact (union oracle); from behind the wall, where they show, it declines (and the exact union
  // runs).
  TriangleSoup soup;
  append_box(soup, Vec3(-200, 0, 0), Vec3(200, 2, 30));
  TriangleSoup open;
  append_box(open, Vec3(-5, 20, 0), Vec3(5, 30, 10));
  open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4);  // as in classification_of_components
  soup.append(open);
  append_box(soup, Vec3(20, 20, 0), Vec3(25, 25, 12));
  append_box(soup, Vec3(25, 20, 0), Vec3(30, 25, 12));
  const Scene scene(soup);
  const ColumnScene& c = scene.column_scene();
  BOOST_TEST(c.column_solids == 2u);
  BOOST_TEST(c.max_column_floor_z == 10.0);
  // Each box's five other faces, and each of the four triangles of the wall modelled twice (its
  // diagonal too is in four triangles, so nothing links them).
  BOOST_TEST(c.other_components == 6u);
  BOOST_TEST(!c.valid_from_height(0.0));
  BOOST_TEST(c.max_other_z == 12.0);
  HorizonSvf h(scene, c, 1e-6);
  SkyFactors f;
  for (const QueryPoint& q : {QueryPoint{Vec3(0, -10, 0), Vec3(0, 0, 1)}, QueryPoint{Vec3(3, -1, 4), Vec3(0, -1, 0)},
                              QueryPoint{Vec3(-20, -30, 1), unit_normal(0.7, 1.0)}}) {
    BOOST_TEST_REQUIRE(h.compute(q, f));
    const double exact = svf_union_oracle(q.position + 1e-6 * q.normal, q.normal, soup);
    BOOST_TEST(std::abs(f.svf - exact) < kExact, "horizon " << f.svf << " exact " << exact);
  }
  BOOST_TEST(!h.compute(QueryPoint{Vec3(0, 15, 0), Vec3(0, 0, 1)}, f));    // sees the open box (below its floor height)
  BOOST_TEST(!h.compute(QueryPoint{Vec3(25, 15, 0), Vec3(0, 0, 1)}, f));   // sees the boxes with the shared wall
  BOOST_TEST(!h.compute(QueryPoint{Vec3(25, 15, 11), Vec3(0, 0, 1)}, f));  // above the open box, below the others' top
  const std::vector<QueryPoint> pts = {{Vec3(0, -10, 0), Vec3(0, 0, 1)},
                                       {Vec3(0, 15, 0), Vec3(0, 0, 1)},
                                       {Vec3(25, 15, 0), Vec3(0, 0, 1)},
                                       {Vec3(-20, 25, 10), Vec3(0, 0, 1)}};  // level with the open box's top, beside it
  const SkyFactorsRun run = compute_sky_factors(scene, pts, VisibilityOptions{}, SkyFactorsMethod::automatic, 1);
  BOOST_TEST(run.by_horizon == 1u);
  BOOST_TEST(run.by_exact == 3u);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double exact = svf_union_oracle(pts[i].position + 1e-6 * pts[i].normal, pts[i].normal, soup);
    BOOST_TEST(std::abs(run.factors[i].svf - exact) < kExact, "point " << i);
  }
}

BOOST_AUTO_TEST_CASE(floorless_boxes_with_random_windings_on_a_ground) {
  // The synthetic city most tools are tried on — boxes of four walls and a roof, no floor, on one
  // ground quad — with every face's winding drawn at random: a column scene from street and facade
  // points, exact against the union oracle.
  gen::OpenBoxCityParams p;
  p.per_side = 4;
  gen::OpenBoxCity city = gen::make_open_box_city(p);
  gen::Rng rng(12);
  for (std::size_t t = 0; t + 1 < city.soup.triangles.size(); t += 2)
    if (rng.uniform() < 0.5)
      for (std::size_t k : {t, t + 1}) std::swap(city.soup.triangles[k][1], city.soup.triangles[k][2]);
  const Scene scene(city.soup);
  BOOST_TEST(scene.column_scene().column_solids == 16u);
  std::vector<QueryPoint> pts = gen::open_city_street_points(city, 8, 3);
  for (const QueryPoint& q : gen::open_city_facade_points(city, 6, 4)) pts.push_back(q);
  const SkyFactorsRun run = compute_sky_factors(scene, pts, VisibilityOptions{}, SkyFactorsMethod::automatic, 1);
  BOOST_TEST(run.by_horizon == pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double exact = svf_union_oracle(pts[i].position + 1e-6 * pts[i].normal, pts[i].normal, city.soup);
    BOOST_TEST(std::abs(run.factors[i].svf - exact) < kExact, "point " << i << ": " << run.factors[i].svf << " oracle " << exact);
  }
}

BOOST_AUTO_TEST_CASE(columns_touching_along_a_vertical_edge_or_a_vertex) {
  // Two boxes of one height touching diagonally: their shared vertical edge (1,1,0)–(1,1,4)
  // belongs to four triangles. Traversed twice up and twice down once oriented: one column solid,
  // whatever each box's winding. A third box touching the first only at the vertex (0,0,0) is a
  // second orientation region of the same component, wound inward.
  TriangleSoup soup;
  append_box(soup, Vec3(0, 0, 0), Vec3(1, 1, 4));
  append_box(soup, Vec3(1, 1, 0), Vec3(2.5, 3, 4));
  TriangleSoup inward;
  append_box(inward, Vec3(-1.5, -2, 0), Vec3(0, 0, 6));
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  soup.append(inward);
  const Scene scene(soup);
  BOOST_TEST(scene.column_scene().column_solids == 3u);  // each box its own closed surface
  BOOST_TEST(scene.column_scene().other_components == 0u);
  // Points around them (outside the footprints), the horizon method against the union oracle.
  std::vector<QueryPoint> pts;
  gen::Rng rng(31);
  const auto inside = [](const Vec3& p, double x0, double y0, double x1, double y1) {
    return p.x() > x0 - 0.05 && p.x() < x1 + 0.05 && p.y() > y0 - 0.05 && p.y() < y1 + 0.05;
  };
  while (pts.size() < 40) {
    QueryPoint q{Vec3{rng.uniform(-5, 6), rng.uniform(-5, 6), rng.uniform(0, 3)}, rng.unit_normal(0, kPi / 2, 0, 6.28)};
    if (pts.size() < 10) q.normal = Vec3(0, 0, 1);
    if (inside(q.position, 0, 0, 1, 1) || inside(q.position, 1, 1, 2.5, 3) || inside(q.position, -1.5, -2, 0, 0)) continue;
    pts.push_back(q);
  }
  const SkyFactorsRun run = compute_sky_factors(scene, pts, VisibilityOptions{}, SkyFactorsMethod::automatic, 1);
  BOOST_TEST(run.by_horizon == pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const UnionSkyFactors exact = sky_union_oracle(pts[i].position + 1e-6 * pts[i].normal, pts[i].normal, soup);
    BOOST_TEST(std::abs(run.factors[i].svf - exact.svf) < kExact,
               "point " << i << ": " << run.factors[i].svf << " oracle " << exact.svf);
    BOOST_TEST(std::abs(run.factors[i].sky_exposure - exact.sky_exposure) < kExact, "point " << i);
  }

  // Two boxes sharing a whole wall (a party wall modelled twice): its horizontal edges belong to
  // four triangles — not a column solid.
  TriangleSoup party;
  append_box(party, Vec3(0, 0, 0), Vec3(1, 1, 4));
  append_box(party, Vec3(1, 0, 0), Vec3(2, 1, 4));
  BOOST_TEST(classify_column_scene(party).column_solids == 0u);
}

BOOST_AUTO_TEST_CASE(a_floor_following_the_terrain_and_a_broken_neighbour_at_a_corner) {
  // A box whose floor follows a slope (its vertices at x = 10 lifted to 0.3 m: the floor one tilted
  // plane facing down): a column solid whose floor height is 0.3 m. Touching it at the vertex
  // (0, 0, 0), a box with two fins on a roof edge (that edge in three triangles: other
  // components). The first box is a column solid of its own: points at or above 0.3 m that do not
  // see the broken box go by the exact horizon, points below 0.3 m that see the first box, and
  // points that see the broken one, are declined (union oracle for all of them).
  TriangleSoup soup;
  append_box(soup, Vec3(0, 0, 0), Vec3(10, 8, 12));
  for (Vec3& v : soup.vertices)
    if (v.x() == 10 && v.z() == 0) v.z() = 0.3;
  TriangleSoup broken;
  append_box(broken, Vec3(-6, -5, 0), Vec3(0, 0, 6));
  const auto corner = [&](const Vec3& v) {
    return std::uint32_t(std::find(broken.vertices.begin(), broken.vertices.end(), v) - broken.vertices.begin());
  };
  const std::uint32_t a = corner(Vec3(0, 0, 6)), b = corner(Vec3(0, -5, 6));  // a roof edge
  BOOST_TEST_REQUIRE((a < 8 && b < 8));
  for (const Vec3& apex : {Vec3(-1, -2, 9), Vec3(-2, -3, 8)}) {
    broken.vertices.push_back(apex);
    broken.triangles.push_back({a, b, std::uint32_t(broken.vertices.size() - 1)});
  }
  soup.append(broken);
  const Scene scene(soup);
  const ColumnScene& c = scene.column_scene();
  BOOST_TEST(c.column_solids == 1u);
  BOOST_TEST(c.other_components == 3u);     // the broken box and each fin
  BOOST_TEST(c.min_column_floor_z == 0.0);  // the base floor (the lowest vertex) …
  BOOST_TEST(c.max_column_floor_z == 0.3);  // … and the floor's top: every roof edge lies over it
  for (const SilhouetteEdge& e : c.edges) BOOST_TEST(e.floor_z == 0.3);
  BOOST_TEST(c.max_other_z == 9.0);

  HorizonSvf h(scene, c, 1e-6);
  SkyFactors f;
  const QueryPoint beyond{Vec3(14, 4, 0.35), Vec3(0, 0, 1)};  // the broken box hidden behind the first
  const QueryPoint wall{Vec3(10.1, 2, 3), Vec3(1, 0, 0)};     // on the first box's far wall
  const QueryPoint low{Vec3(14, 4, 0.2), Vec3(0, 0, 1)};      // below its floor height
  const QueryPoint seeing_broken{Vec3(-20, -20, 0.5), Vec3(0, 0, 1)};
  BOOST_TEST(h.compute(beyond, f));
  BOOST_TEST(h.compute(wall, f));
  BOOST_TEST(!h.compute(low, f));
  BOOST_TEST(!h.compute(seeing_broken, f));
  const std::vector<QueryPoint> pts = {beyond, wall, low, seeing_broken, {Vec3(13, 6, 2), unit_normal(0.4, 0.3)}};
  const SkyFactorsRun run = compute_sky_factors(scene, pts, VisibilityOptions{}, SkyFactorsMethod::automatic, 1);
  BOOST_TEST(run.by_horizon == 3u);  // beyond, wall and the last
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const UnionSkyFactors exact = sky_union_oracle(pts[i].position + 1e-6 * pts[i].normal, pts[i].normal, soup);
    BOOST_TEST(std::abs(run.factors[i].svf - exact.svf) < kExact,
               "point " << i << ": " << run.factors[i].svf << " oracle " << exact.svf);
    BOOST_TEST(std::abs(run.factors[i].sky_exposure - exact.sky_exposure) < kExact, "point " << i);
  }
}

BOOST_AUTO_TEST_CASE(an_overhang_raises_the_floor_height_only_of_the_edges_over_it) {
  // One closed surface: an L-shaped profile in x–z extruded along y (0 … 8 m), a block 10 m wide
  // and 10 m high whose upper storey overhangs 4 m towards +x from 6 m up. The overhang's soffit
  // (z = 6, x from 10 to 14) faces down: the parts of edges over it (in xy) have floor height 6 m,
  // the rest the floor's 0 m — whole edges where the upper edges are split at x = 10, the part
  // beyond x = 10 of the roof's and the ends' top edges where they are not. From the −x side at
  // street level the parts over the soffit are hidden behind the near roof edge: exact horizon;
  // from under or beside the overhang they show: declined (sky below the soffit), and the exact
  // union answers. Union oracle for all.
  for (const bool split : {true, false}) {
    BOOST_TEST_CONTEXT((split ? "upper edges split at x = 10" : "upper edges whole")) {
      std::vector<std::array<double, 2>> profile{{0, 0}, {10, 0}, {10, 6}, {14, 6}, {14, 10}, {0, 10}};
      std::vector<std::array<std::uint32_t, 3>> ends{{0, 1, 2}, {0, 2, 5}, {2, 3, 4}, {2, 4, 5}};
      if (split) {
        profile.insert(profile.begin() + 5, {10, 10});
        ends = {{0, 1, 2}, {0, 2, 6}, {2, 5, 6}, {2, 3, 4}, {2, 4, 5}};
      }
      const auto n = std::uint32_t(profile.size());
      TriangleSoup soup;
      for (double y : {0.0, 8.0})
        for (const auto& xz : profile) soup.vertices.push_back(Vec3(xz[0], y, xz[1]));
      // The two ends (the profile cut into triangles), then a quad along each profile edge.
      for (const auto& t : ends) {
        soup.triangles.push_back({t[0], t[2], t[1]});
        soup.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});
      }
      for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t j = (i + 1) % n;
        soup.triangles.push_back({i, j, j + n});
        soup.triangles.push_back({i, j + n, i + n});
      }
      const Scene scene(soup);
      const ColumnScene& c = scene.column_scene();
      BOOST_TEST(c.column_solids == 1u);
      BOOST_TEST(c.min_column_floor_z == 0.0);
      BOOST_TEST(c.max_column_floor_z == 6.0);
      std::size_t over = 0;
      for (const SilhouetteEdge& e : c.edges) {
        const bool meets = std::max(e.a.x(), e.b.x()) > 10 || (e.a.z() == 6 && e.b.z() == 6);  // or the soffit's own edge
        BOOST_TEST(e.floor_z == (meets ? 6.0 : 0.0), "edge " << e.a.transpose() << " – " << e.b.transpose());
        over += meets;
      }
      BOOST_TEST(over >= 3u);

      HorizonSvf h(scene, c, 1e-6);
      SkyFactors f;
      const std::vector<QueryPoint> taken = {
          {Vec3(-5, 4, 0.05), Vec3(0, 0, 1)}, {Vec3(-12, 5, 1), Vec3(0, 0, 1)}, {Vec3(-0.1, 2, 3), Vec3(-1, 0, 0)}};
      const std::vector<QueryPoint> declined = {{Vec3(12, 4, 0.05), Vec3(0, 0, 1)},  // under the overhang
                                                {Vec3(20, 4, 0.05), Vec3(0, 0, 1)},
                                                {Vec3(10.1, 4, 3), Vec3(1, 0, 0)},
                                                {Vec3(-12, -3, 1), Vec3(0, 0, 1)}};  // sees under it past the corner
      for (const QueryPoint& q : taken) BOOST_TEST(h.compute(q, f), "declined at " << q.position.transpose());
      for (const QueryPoint& q : declined) BOOST_TEST(!h.compute(q, f), "taken at " << q.position.transpose());
      std::vector<QueryPoint> pts = taken;
      pts.insert(pts.end(), declined.begin(), declined.end());
      // And random points around it (outside the block and the overhang, any height up to 12 m).
      gen::Rng rng(47);
      while (pts.size() < taken.size() + declined.size() + 60) {
        const Vec3 p(rng.uniform(-15, 30), rng.uniform(-10, 18), rng.uniform(0, 12));
        const bool in_block = p.x() > -0.05 && p.x() < 10.05 && p.y() > -0.05 && p.y() < 8.05 && p.z() < 10.05;
        const bool in_upper = p.x() > -0.05 && p.x() < 14.05 && p.y() > -0.05 && p.y() < 8.05 && p.z() > 5.95 && p.z() < 10.05;
        if (in_block || in_upper) continue;
        pts.push_back({p, pts.size() % 2 ? Vec3(0, 0, 1) : rng.unit_normal(0, kPi / 2, 0, 6.28)});
      }
      const SkyFactorsRun run = compute_sky_factors(scene, pts, VisibilityOptions{}, SkyFactorsMethod::automatic, 1);
      BOOST_TEST(run.by_horizon >= taken.size() + 10);
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const UnionSkyFactors exact = sky_union_oracle(pts[i].position + 1e-6 * pts[i].normal, pts[i].normal, soup);
        BOOST_TEST(std::abs(run.factors[i].svf - exact.svf) < kExact,
                   "point " << i << ": " << run.factors[i].svf << " oracle " << exact.svf);
        BOOST_TEST(std::abs(run.factors[i].sky_exposure - exact.sky_exposure) < kExact, "point " << i);
      }
    }
  }
}
