#define BOOST_TEST_MODULE point_irradiance
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

#include "geometry/bands/sky_integral.h"
#include "geometry/core/input_error.h"
#include "lighting/integrals/point_irradiance.h"
#include "lighting/spectrum/colour.h"
#include "lighting/sun/sun.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {

constexpr double kDeg = kPi / 180.0;

SkyModel make_sky(double altitude_deg, double azimuth_deg, const std::string& model) {
  return SkyModel(AtmosphereParams{}, direction_from_altitude_azimuth(altitude_deg * kDeg, azimuth_deg * kDeg),
                  parse_sky_model(model, "--model"));
}

// A closed 10 m cube [0,10]³ (our own geometry).
TriangleSoup cube() {
  TriangleSoup soup;
  append_box(soup, Vec3(0, 0, 0), Vec3(10, 10, 10));
  return soup;
}

QueryPoint at(double x, double y, double z, Vec3 n = Vec3(0, 0, 1)) {
  return QueryPoint{Vec3(x, y, z), n.normalized()};
}

// Random boxes standing on z = 0 (corners in a square of side box_span_m, sizes 3–11 × 3–11 ×
// 2–22 m) and points up to 6 m high in a square of side point_span_m with random upward-ish
// normals; deterministic per seed.
struct RandomBlock {
  TriangleSoup soup;
  std::vector<QueryPoint> points;
};
RandomBlock random_block(std::uint64_t seed, int boxes, double box_span_m, int points, double point_span_m) {
  RandomBlock b;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < boxes; ++i) {
    const Vec3 lo{box_span_m * (u(rng) - 0.5), box_span_m * (u(rng) - 0.5), 0};
    append_box(b.soup, lo, lo + Vec3{3 + 8 * u(rng), 3 + 8 * u(rng), 2 + 20 * u(rng)});
  }
  for (int i = 0; i < points; ++i) {
    const Vec3 n{u(rng) - 0.5, u(rng) - 0.5, u(rng)};
    const double x = point_span_m * (u(rng) - 0.5), y = point_span_m * (u(rng) - 0.5);
    b.points.push_back(at(x, y, 6 * u(rng), n));
  }
  return b;
}

}  // namespace

// CIE standard overcast sky, L = L_z(1 + 2 sin e)/3 (e = elevation): closed forms
// E_h = (7π/9)·L_z on an open horizontal face and E_v = (π/6 + 4/9)·L_z on an open wall
// (∫ over the front hemisphere above the horizon: (1/3)·(π/2) + (2/3)·2·∫₀^{π/2} sin e cos²e de).
// Tolerance 1e-3: the sky is resampled on the stereographic grid (bilinear, error ~h²/8·|L''|
// with h ≈ 0.3–0.6°) and the points' band quadrature carries the refinement error (≤ 5e-4).
BOOST_AUTO_TEST_CASE(open_faces_under_the_overcast_sky_match_closed_forms) {
  const SkyModel sky = make_sky(35, 180, "cie-overcast");
  const Spectrum lz = sky.radiance(Vec3(0, 0, 1));
  const Scene scene(cube());
  const std::vector<QueryPoint> pts = {at(5, 5, 10),                    // the cube's top face: open horizontal
                                       at(-0.0, 5, 5, Vec3(-1, 0, 0)),  // its west wall: open wall
                                       at(3000, 3000, 0)};              // far away on the ground
  const auto r = compute_point_irradiance(scene, pts, sky, PointIrradianceOptions{});
  const double eh = 7 * kPi / 9, ev = kPi / 6 + 4.0 / 9;
  BOOST_TEST(r[0].sky_W_m2 == eh * lz.integral_nm(), tt::tolerance(1e-3));
  BOOST_TEST(r[0].sky_lx == eh * luminous(lz), tt::tolerance(1e-3));
  BOOST_TEST(r[1].sky_W_m2 == ev * lz.integral_nm(), tt::tolerance(1e-3));
  BOOST_TEST(r[1].sky_lx == ev * luminous(lz), tt::tolerance(1e-3));
  BOOST_TEST(r[2].sky_W_m2 == eh * lz.integral_nm(), tt::tolerance(1e-3));
  // sky_ratio: exactly 1 on the open horizontal face (same method, same quadrature); far away the
  // exact horizon sees the cube as a sliver (~1e-9 of the sky), and its fan, cut there, is
  // integrated by different Gauss–Legendre pieces: 1 within the quadrature's error (~1e-6, see
  // geometry/exact/sky_fan.h). On the open wall the vertical sky component, (π/6 + 4/9)/(7π/9) = 0.39624 — the 39.6 % maximum VSC
  // of an unobstructed window that BRE 209 (Littlefair, Site layout planning for daylight and sunlight, 2nd ed. 2011, §2.2)
  // publishes.
  BOOST_TEST(r[0].sky_ratio == 1.0, tt::tolerance(1e-12));
  BOOST_TEST(r[2].sky_ratio == 1.0, tt::tolerance(1e-6));
  BOOST_TEST(r[1].sky_ratio == ev / eh, tt::tolerance(1e-3));
  BOOST_TEST(std::abs(100 * r[1].sky_ratio - 39.6) < 0.05);
  // The overcast sky hides the sun (cie_sky.h): no direct term anywhere.
  for (const auto& x : r) {
    BOOST_TEST(!x.sun_visible);
    BOOST_TEST(x.sun_W_m2 == 0.0);
  }
}

// CIE type 5 is the sky of uniform luminance (a = 0, c = 0, e = 0: L = L_z everywhere above the
// horizon), so E_sky = π·L_z·SVF exactly, with the SVF of the same visibility: an identity for any
// occlusion. Random points around random boxes, by both methods. Tolerance 1e-5 of the open
// sky's π·L_z (the quadrature's error is set by the shape of the visible region over the whole
// hemisphere, not by the point's share of it): a constant is interpolated exactly by the grid.
// Band method: the Gauss–Legendre pieces integrate sin²α to ~1e-13; what remains is the grid's
// float storage (~6e-8 relative) and the interval ends stored as float. Exact horizon: the SVF
// is exact, the fan's quadrature within ~3e-6 relative (geometry/exact/sky_fan.h) — here at most
// 1.2e-6 of π·L_z (1.0e-4 W·m⁻² at a point of SVF 0.041, 2.8e-5 of its own value).
BOOST_AUTO_TEST_CASE(uniform_sky_irradiance_is_pi_L_times_svf) {
  const RandomBlock block = random_block(5, 12, 60, 40, 70);
  const Scene scene(block.soup);
  const std::vector<QueryPoint>& pts = block.points;
  const SkyModel sky = make_sky(40, 200, "cie-5");
  const double lz = sky.radiance(Vec3(0, 0, 1)).integral_nm();
  BOOST_TEST_REQUIRE(lz > 0);
  BOOST_TEST(sky.radiance(Vec3(0.8, 0, 0.6)).integral_nm() == lz, tt::tolerance(1e-12));  // uniform indeed
  for (SkyFactorsMethod method : {SkyFactorsMethod::automatic, SkyFactorsMethod::bands}) {
    PointIrradianceOptions opt;
    opt.method = method;
    const auto r = compute_point_irradiance(scene, pts, sky, opt);
    int occluded = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      BOOST_TEST(std::abs(r[i].sky_W_m2 - kPi * lz * r[i].svf) <= 1e-5 * kPi * lz,
                 "point " << i << ": " << r[i].sky_W_m2 << " W/m2 against pi L svf " << kPi * lz * r[i].svf);
      occluded += r[i].svf < (1 + pts[i].normal.z()) / 2 - 1e-3;
    }
    BOOST_TEST(occluded > 10);  // the identity was tested on occluded points, not only open ones
  }
}

// The two methods on the same points (random boxes on the ground, points around them, the
// physical sky with its aureole and a low sun): the sun's shadow test is the same exact test, so
// identical; the SVF agrees within the band method's error (≤ 1e-3, the accuracy the default options
// promise, svf_oracle_test; measured ≤ 5e-4); the sky irradiance within that plus the two quadratures' (~1e-5 each), relative to
// the open sky's. Points inside a box go to the band method in both (exact zeros).
BOOST_AUTO_TEST_CASE(exact_horizon_and_band_method_agree) {
  const RandomBlock block = random_block(9, 10, 50, 60, 60);
  const Scene scene(block.soup);
  const std::vector<QueryPoint>& pts = block.points;
  const SkyModel sky = make_sky(20, 230, "multiple");
  PointIrradianceOptions exact, bands;
  bands.method = SkyFactorsMethod::bands;
  const auto a = compute_point_irradiance(scene, pts, sky, exact);
  const auto b = compute_point_irradiance(scene, pts, sky, bands);
  const auto open = compute_point_irradiance(Scene(TriangleSoup{}), std::vector<QueryPoint>{at(0, 0, 0)}, sky, bands);
  int lit = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    BOOST_TEST(a[i].sun_visible == b[i].sun_visible);
    BOOST_TEST(a[i].sun_W_m2 == b[i].sun_W_m2);
    BOOST_TEST(std::abs(a[i].svf - b[i].svf) <= 1e-3);
    BOOST_TEST(std::abs(a[i].sky_W_m2 - b[i].sky_W_m2) <= 1.2e-3 * open[0].sky_W_m2);
    lit += a[i].sun_visible;
  }
  BOOST_TEST(lit > 5);
  BOOST_TEST(lit < int(pts.size()) - 5);  // both lit and shaded points were compared
}

// An open horizontal face under the physical sky: the diffuse term equals the sky's horizontal
// irradiance by an independent quadrature (SkyModel horizontal_irradiance: midpoint rule on
// 0.5° cells of the hemisphere, no visibility), and the sun term is E_n·sin(altitude).
// Tolerance 3e-3 on the sky: both quadratures resolve the circumsolar peak only to ~0.5°.
BOOST_AUTO_TEST_CASE(open_horizontal_face_under_the_physical_sky) {
  const double alt = 30;
  const SkyModel sky = make_sky(alt, 180, "multiple");
  const Scene scene(cube());
  const auto r = compute_point_irradiance(scene, std::vector<QueryPoint>{at(5, 5, 10)}, sky, PointIrradianceOptions{});
  const Spectrum eh = horizontal_irradiance([&](const Vec3& d, Spectrum& s) { sky.radiance_into(d, s); }, 180);
  BOOST_TEST(r[0].sky_W_m2 == eh.integral_nm(), tt::tolerance(3e-3));
  BOOST_TEST(r[0].sky_lx == luminous(eh), tt::tolerance(3e-3));
  const Spectrum& dn = sky.sun_direct_normal();
  BOOST_TEST_REQUIRE(dn.integral_nm() > 100);
  BOOST_TEST(r[0].sun_visible);
  BOOST_TEST(r[0].cos_incidence == std::sin(alt * kDeg), tt::tolerance(1e-12));
  BOOST_TEST(r[0].sun_W_m2 == dn.integral_nm() * std::sin(alt * kDeg), tt::tolerance(1e-12));
  BOOST_TEST(r[0].sun_lx == luminous(dn) * std::sin(alt * kDeg), tt::tolerance(1e-12));
}

// The cube's shadow on the ground: sun at 30° from the south (azimuth 180°), so a ground point
// north of the cube at distance d from its north face is shadowed exactly when d·tan 30° < 10 m,
// i.e. d < 17.32 m (closed-form geometry). Walls: the south wall sees the sun at cos i = cos 30°,
// the north wall has the sun behind it.
BOOST_AUTO_TEST_CASE(shadow_and_incidence_follow_the_geometry) {
  const SkyModel sky = make_sky(30, 180, "multiple");
  const Scene scene(cube());
  const std::vector<QueryPoint> pts = {at(5, 10 + 17.0, 0), at(5, 10 + 17.7, 0), at(5, -3, 0), at(5, -0.0, 5, Vec3(0, -1, 0)),
                                       at(5, 10, 5, Vec3(0, 1, 0))};
  const auto r = compute_point_irradiance(scene, pts, sky, PointIrradianceOptions{});
  const double dn = sky.sun_direct_normal().integral_nm();
  BOOST_TEST(!r[0].sun_visible);
  BOOST_TEST(r[0].sun_W_m2 == 0.0);
  BOOST_TEST(r[0].sky_W_m2 > 0.0);
  BOOST_TEST(r[1].sun_visible);
  BOOST_TEST(r[1].sun_W_m2 == dn * 0.5, tt::tolerance(1e-12));
  BOOST_TEST(r[2].sun_visible);  // south of the cube: in the sun
  BOOST_TEST(r[3].sun_visible);
  BOOST_TEST(r[3].cos_incidence == std::cos(30 * kDeg), tt::tolerance(1e-12));
  BOOST_TEST(r[3].sun_W_m2 == dn * std::cos(30 * kDeg), tt::tolerance(1e-12));
  BOOST_TEST(r[4].cos_incidence < 0.0);
  BOOST_TEST(!r[4].sun_visible);
  BOOST_TEST(r[4].sun_W_m2 == 0.0);
  // The walls see half the open sky (SVF 0.5, geometry closed form) but not the same radiance:
  // the south wall faces the sun's half of the sky.
  BOOST_TEST(r[3].svf == 0.5, tt::tolerance(1e-9));
  BOOST_TEST(r[4].svf == 0.5, tt::tolerance(1e-9));
  BOOST_TEST(r[3].sky_W_m2 > r[4].sky_W_m2);
}

// Inside a closed box nothing arrives (the band core's exact zero, method.md §8), with any sun.
BOOST_AUTO_TEST_CASE(inside_a_closed_box_everything_is_zero) {
  const Scene scene(cube());
  for (double alt : {5.0, 60.0}) {
    const auto r = compute_point_irradiance(scene, std::vector<QueryPoint>{at(5, 5, 5), at(2, 3, 0.5, Vec3(1, 0, 0))},
                                            make_sky(alt, 120, "multiple"), PointIrradianceOptions{});
    for (const auto& x : r) {
      BOOST_TEST(x.svf == 0.0);
      BOOST_TEST(x.sky_W_m2 == 0.0);
      BOOST_TEST(x.sky_lx == 0.0);
      BOOST_TEST(!x.sun_visible);
      BOOST_TEST(x.sun_W_m2 == 0.0);
    }
  }
}

// Below the horizon there is no direct sun, only twilight sky.
BOOST_AUTO_TEST_CASE(sun_below_the_horizon_gives_no_direct_term) {
  const Scene scene(cube());
  const auto r = compute_point_irradiance(scene, std::vector<QueryPoint>{at(5, 5, 10)}, make_sky(-3, 270, "multiple"),
                                          PointIrradianceOptions{});
  BOOST_TEST(!r[0].sun_visible);
  BOOST_TEST(r[0].sun_W_m2 == 0.0);
  BOOST_TEST(std::isfinite(r[0].sky_W_m2));
  BOOST_TEST(r[0].sky_W_m2 >= 0.0);
}

// Results do not depend on the thread count (each point computed alone; 600 points = several chunks).
BOOST_AUTO_TEST_CASE(results_do_not_depend_on_threads) {
  TriangleSoup soup = cube();
  append_box(soup, Vec3(20, -5, 0), Vec3(26, 15, 18));
  const Scene scene(soup);
  std::vector<QueryPoint> pts;
  for (int i = 0; i < 600; ++i) pts.push_back(at(-10 + 0.07 * i, -8 + 0.05 * i, 0.01 * (i % 7)));
  const SkyModel sky = make_sky(25, 140, "multiple");
  for (SkyFactorsMethod method : {SkyFactorsMethod::automatic, SkyFactorsMethod::bands}) {
    PointIrradianceOptions one, two;
    one.threads = 1;
    two.threads = 2;
    one.method = two.method = method;
    const auto a = compute_point_irradiance(scene, pts, sky, one);
    const auto b = compute_point_irradiance(scene, pts, sky, two);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      BOOST_TEST(a[i].sky_W_m2 == b[i].sky_W_m2);
      BOOST_TEST(a[i].sun_W_m2 == b[i].sun_W_m2);
      BOOST_TEST(a[i].svf == b[i].svf);
    }
  }
}

BOOST_AUTO_TEST_CASE(bad_quadrature_step_is_an_input_error) {
  const Scene scene(cube());
  PointIrradianceOptions o;
  o.max_step_rad = 0;
  BOOST_CHECK_THROW(compute_point_irradiance(scene, std::vector<QueryPoint>{at(5, 5, 10)}, make_sky(30, 180, "multiple"), o),
                    InputError);
}

// Irradiation over moments equals the hours-weighted sum of the single-moment irradiances
// computed independently (one SkyModel and grid per moment): the sky through the summed grid
// (linear interpolation and quadrature: equal up to the grids' float storage, 1e-5), the sun
// term and the sun hours exactly. Moments: the cube's north ground point is shadowed by the sun
// from the south at 30° (shadow 17.3 m long, the point 12 m away) and lit by a sun from the north;
// a sun below the horizon adds twilight sky only.
BOOST_AUTO_TEST_CASE(irradiation_is_the_weighted_sum_of_moments) {
  const Scene scene(cube());
  const std::vector<QueryPoint> pts = {at(5, 22, 0), at(5, 5, 10), at(5, -0.0, 5, Vec3(0, -1, 0))};
  const std::vector<SunMoment> moments = {{direction_from_altitude_azimuth(30 * kDeg, 180 * kDeg), 0.5},
                                          {direction_from_altitude_azimuth(40 * kDeg, 10 * kDeg), 1.5},
                                          {direction_from_altitude_azimuth(-2 * kDeg, 300 * kDeg), 1.0}};
  const AtmosphereParams atm;
  const SkyModelSpec spec = parse_sky_model("multiple", "--model");
  const auto cum = compute_point_irradiation(scene, pts, atm, spec, moments, PointIrradianceOptions{});
  std::vector<PointIrradiation> sum(pts.size());
  for (const SunMoment& m : moments) {
    const auto r = compute_point_irradiance(scene, pts, SkyModel(atm, m.sun_dir, spec), PointIrradianceOptions{});
    for (std::size_t i = 0; i < pts.size(); ++i) {
      sum[i].sky_Wh_m2 += m.hours * r[i].sky_W_m2;
      sum[i].sky_lxh += m.hours * r[i].sky_lx;
      sum[i].sun_Wh_m2 += m.hours * r[i].sun_W_m2;
      sum[i].sun_lxh += m.hours * r[i].sun_lx;
      sum[i].sun_hours += r[i].sun_visible ? m.hours : 0.0;
    }
  }
  for (std::size_t i = 0; i < pts.size(); ++i) {
    BOOST_TEST(cum[i].sky_Wh_m2 == sum[i].sky_Wh_m2, tt::tolerance(1e-5));
    BOOST_TEST(cum[i].sky_lxh == sum[i].sky_lxh, tt::tolerance(1e-5));
    BOOST_TEST(cum[i].sun_Wh_m2 == sum[i].sun_Wh_m2, tt::tolerance(1e-12));
    BOOST_TEST(cum[i].sun_lxh == sum[i].sun_lxh, tt::tolerance(1e-12));
    BOOST_TEST(cum[i].sun_hours == sum[i].sun_hours);
  }
  BOOST_TEST(cum[0].sun_hours == 1.5);  // north ground point: only the northern sun
  BOOST_TEST(cum[1].sun_hours == 2.0);  // the roof: both suns above the horizon
  BOOST_TEST(cum[2].sun_hours == 0.5);  // the south wall: only the southern sun
  BOOST_TEST(cum[0].sky_Wh_m2 > 0.0);

  const std::vector<SunMoment> bad = {{direction_from_altitude_azimuth(30 * kDeg, 180 * kDeg), -1.0}};
  BOOST_CHECK_THROW(compute_point_irradiation(scene, pts, atm, spec, bad, PointIrradianceOptions{}), InputError);
}
