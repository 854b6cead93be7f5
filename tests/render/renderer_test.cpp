#define BOOST_TEST_MODULE renderer
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstring>
#include <set>
#include <vector>

#include "geometry/core/input_error.h"
#include "geometry/mesh/camera.h"
#include "lighting/spectrum/colour.h"
#include "lighting/sun/sun.h"
#include "render/renderer.h"

namespace tt = boost::test_tools;
using namespace skyband;

namespace {

void add_quad(TriangleSoup& s, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, std::uint32_t slot) {
  const auto i = static_cast<std::uint32_t>(s.vertices.size());
  s.vertices.insert(s.vertices.end(), {a, b, c, d});
  s.triangles.push_back({i, i + 1, i + 2});
  s.triangles.push_back({i, i + 2, i + 3});
  s.triangle_material.insert(s.triangle_material.end(), {slot, slot});
}

// Ground square of half-size g (slot 0); with `box`, the box [-1,1]×[-1,1]×[0,2] (slot 1), its
// faces wound inconsistently on purpose (the renderer must flip normals toward the camera).
TriangleSoup ground_scene(double g, bool box) {
  TriangleSoup s;
  s.material_names = {"ground", "box"};
  add_quad(s, {-g, -g, 0}, {g, -g, 0}, {g, g, 0}, {-g, g, 0}, 0);
  if (box) {
    add_quad(s, {-1, -1, 0}, {1, -1, 0}, {1, -1, 2}, {-1, -1, 2}, 1);
    add_quad(s, {1, -1, 0}, {1, 1, 0}, {1, 1, 2}, {1, -1, 2}, 1);
    add_quad(s, {-1, 1, 0}, {-1, 1, 2}, {1, 1, 2}, {1, 1, 0}, 1);  // reversed winding
    add_quad(s, {-1, 1, 0}, {-1, -1, 0}, {-1, -1, 2}, {-1, 1, 2}, 1);
    add_quad(s, {-1, -1, 2}, {-1, 1, 2}, {1, 1, 2}, {1, -1, 2}, 1);  // reversed winding
  }
  return s;
}

Material white_diffuse(double rho) {
  Material m;
  m.name = "test-white";
  m.diffuse_albedo = Spectrum::constant(rho);
  m.specular_weight = 0;
  return m;
}

SkyLight uniform_sky(double l, const Vec3& sun, double e_dn) {
  SkyLight s;
  s.radiance = [l](const Vec3& d, Spectrum& out) { out = d.z() > 0 ? Spectrum::constant(l) : Spectrum{}; };
  s.sun_direction = sun;
  s.sun_direct_normal = Spectrum::constant(e_dn);
  return s;
}

bool bit_equal(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

bool all_finite(const RenderLayers& L) {
  for (const auto* v : {&L.sun_diffuse, &L.sun_specular, &L.sky_diffuse, &L.sky_specular, &L.total})
    for (float x : *v)
      if (!std::isfinite(x)) return false;
  return true;
}

// A camera at `position` looking at `look_at` (z up, default field of view), width × height pixels.
CameraSpec camera_spec(const Vec3& position, const Vec3& look_at, int width, int height) {
  CameraSpec cs;
  cs.position = position;
  cs.look_at = look_at;
  cs.width = width;
  cs.height = height;
  return cs;
}

}  // namespace

BOOST_AUTO_TEST_CASE(sample_pattern_is_stratified_and_deterministic) {
  // Property of the rank-1 lattice (camera.h): each of the S column strata and each of the S row
  // strata holds exactly one sample; S = 1 is the pixel centre.
  const auto one = pixel_sample_offsets(1);
  BOOST_TEST(one.size() == 1u);
  BOOST_TEST(one[0].x() == 0.5);
  BOOST_TEST(one[0].y() == 0.5);
  for (int s : {2, 3, 4, 5, 8, 9, 16, 17, 64}) {
    const auto o = pixel_sample_offsets(s);
    std::set<int> cols, rows;
    for (const Vec2& p : o) {
      BOOST_TEST((p.x() >= 0 && p.x() < 1 && p.y() >= 0 && p.y() < 1));
      cols.insert(static_cast<int>(p.x() * s));
      rows.insert(static_cast<int>(p.y() * s));
    }
    BOOST_TEST(static_cast<int>(cols.size()) == s);
    BOOST_TEST(static_cast<int>(rows.size()) == s);
    BOOST_TEST((pixel_sample_offsets(s) == o));
  }
  BOOST_CHECK_THROW(pixel_sample_offsets(0), InputError);
}

BOOST_AUTO_TEST_CASE(camera_rejects_bad_specs) {
  CameraSpec c;
  c.look_at = c.position;
  BOOST_CHECK_THROW(PinholeCamera{c}, InputError);
  c = CameraSpec{};
  c.up = Vec3(0, 1, 0);  // parallel to the view direction (default looks along +y)
  BOOST_CHECK_THROW(PinholeCamera{c}, InputError);
  c = CameraSpec{};
  c.vertical_fov_deg = 180;
  BOOST_CHECK_THROW(PinholeCamera{c}, InputError);
  c = CameraSpec{};
  c.width = 0;
  BOOST_CHECK_THROW(PinholeCamera{c}, InputError);
}

BOOST_AUTO_TEST_CASE(white_plane_under_uniform_sky_has_radiance_rho_L) {
  // Closed form (method.md §2): an unobstructed horizontal Lambertian face under a uniform sky L
  // receives E = πL and reflects ρE/π = ρL. The sun is switched off (E_dn = 0).
  constexpr double kRho = 0.8, kL = 3.0;
  const Scene scene(ground_scene(1e4, false));
  // Looks down at the ground; upper rows see the sky.
  const PinholeCamera cam(camera_spec(Vec3(0, 0, 5), Vec3(0, 20, 0), 32, 24));
  RenderSettings rs;
  rs.visibility.bands = 16;
  rs.visibility.tolerance = 0;
  GeometryPass pass = trace_geometry(scene, cam, rs);
  const SkyLight light = uniform_sky(kL, Vec3(0, 0, 1), 0.0);
  update_sun(pass, scene, light.sun_direction, rs);
  const Material white = white_diffuse(kRho);
  const Material* mats[] = {&white, &white};
  const RenderLayers L = shade(pass, light, mats, rs);
  const Vec3 expected = spectrum_to_linear_srgb(Spectrum::constant(kRho * kL));
  const Vec3 sky_rgb = spectrum_to_linear_srgb(Spectrum::constant(kL));
  std::size_t ground = 0, sky = 0;
  for (std::size_t p = 0; p < L.total.size() / 3; ++p) {
    const bool hit = pass.sample_surface[p] != GeometryPass::kBackground;
    const Vec3& e = hit ? expected : sky_rgb;
    (hit ? ground : sky)++;
    for (int c = 0; c < 3; ++c) {
      // 1e-6 relative: the band sum is exact for a uniform sky (E_l tables integrate sin²α with
      // Gauss–Legendre to ~1e-12; the band weights sum to W = 2 exactly); what remains is the
      // float storage of the image (6e-8) and the 0.5° sky grid's bilinear interpolation, exact
      // for a constant sky.
      BOOST_TEST(L.total[p * 3 + c] == e[c], tt::tolerance(1e-6));
      if (hit) BOOST_TEST(L.sky_diffuse[p * 3 + c] == e[c], tt::tolerance(1e-6));
    }
  }
  BOOST_TEST(ground > 100u);
  BOOST_TEST(sky > 100u);
}

BOOST_AUTO_TEST_CASE(box_shadow_edge_is_where_geometry_puts_it) {
  // Sun due south at 45°: s = (0, −cos45°, sin45°). A ground point (x, y, 0) is shadowed by the
  // box [-1,1]×[-1,1]×[0,2] iff its ray toward the sun, (x, y − t, t) for t ∈ [0, 2], enters the
  // box: |x| < 1 and y ∈ (−1, 3) — the top edge y = 1, z = 2 projects along s onto y = 3.
  const Scene scene(ground_scene(1e4, true));
  CameraSpec cs;
  cs.position = Vec3(0.013, 2.007, 30);  // straight down over the shadow, off any symmetry line
  cs.look_at = Vec3(0.013, 2.007, 0);
  cs.up = Vec3(0, 1, 0);
  cs.vertical_fov_deg = 20;
  cs.width = 64;
  cs.height = 48;
  const PinholeCamera cam(cs);
  RenderSettings rs;
  rs.visibility.bands = 8;
  rs.visibility.tolerance = 0;
  GeometryPass pass = trace_geometry(scene, cam, rs);
  const Vec3 sun = direction_from_altitude_azimuth(kPi / 4, kPi);
  const SkyLight light = uniform_sky(0.0, sun, 1.0);  // black sky, E_dn = 1 W·m⁻²·nm⁻¹
  update_sun(pass, scene, sun, rs);
  const Material white = white_diffuse(0.5);
  const Material* mats[] = {&white, &white};
  const RenderLayers L = shade(pass, light, mats, rs);
  // Pixel footprint on the ground: 2·30·tan(10°)/48 m.
  const double footprint = 2.0 * 30.0 * std::tan(10.0 * kPi / 180.0) / 48.0;
  // Lit ground radiance, closed form: ρ/π·E_dn·sin 45° per nm → sRGB of that constant spectrum.
  const Vec3 lit = spectrum_to_linear_srgb(Spectrum::constant(0.5 / kPi * std::sin(kPi / 4)));
  std::size_t checked = 0, shadowed = 0, near_edge = 0;
  for (std::size_t p = 0; p < pass.sample_surface.size(); ++p) {
    const std::uint32_t k = pass.sample_surface[p];
    BOOST_REQUIRE(k != GeometryPass::kBackground);
    const Vec3 q = pass.surfaces[k].position;
    if (std::abs(q.z()) > 1e-9) continue;  // box top: not ground
    if (std::abs(q.x()) < 1 && std::abs(q.y()) < 1) continue;
    const bool in = std::abs(q.x()) < 1 && q.y() > -1 && q.y() < 3;
    // Distance to the shadow's outline (x = ±1 for y ∈ [1, 3], y = 3 for |x| ≤ 1).
    const double d_edge = std::min({std::abs(std::abs(q.x()) - 1.0) + (q.y() > 3 ? q.y() - 3 : 0.0),
                                    std::abs(q.y() - 3.0) + (std::abs(q.x()) > 1 ? std::abs(q.x()) - 1 : 0.0)});
    if (d_edge < footprint) {  // within one pixel of the analytic edge: either answer is allowed
      ++near_edge;
      continue;
    }
    ++checked;
    if (in) ++shadowed;
    const float v = L.sun_diffuse[p * 3 + 1];
    if (in)
      BOOST_TEST(v == 0.0f);
    else
      BOOST_TEST(v == lit[1], tt::tolerance(1e-6));  // float storage only
  }
  BOOST_TEST(checked > 1000u);
  BOOST_TEST(shadowed > 40u);    // the 2 m × 2 m shadow is ~83 pixels of 0.22 m, less the edge band
  BOOST_TEST(near_edge < 200u);  // outline ~6 m long, a 2-pixel band of 0.22 m pixels: ~55
  // The edge itself: along the image column through x ≈ 0, the last shadowed pixel and the first
  // lit pixel beyond y = 3 straddle y = 3 within one pixel footprint.
  double last_in = -1e9, first_out = 1e9;
  for (std::size_t p = 0; p < pass.sample_surface.size(); ++p) {
    const Vec3 q = pass.surfaces[pass.sample_surface[p]].position;
    if (std::abs(q.x()) > footprint || std::abs(q.z()) > 1e-9 || q.y() < 1) continue;
    if (L.sun_diffuse[p * 3 + 1] == 0.0f)
      last_in = std::max(last_in, q.y());
    else
      first_out = std::min(first_out, q.y());
  }
  BOOST_TEST(last_in <= 3.0);
  BOOST_TEST(first_out >= 3.0);
  BOOST_TEST(first_out - last_in <= footprint * 1.01);
}

BOOST_AUTO_TEST_CASE(exact_and_band_visibility_give_the_same_sky_light) {
  // The default geometry pass cuts the exact visible sky along the sample lines; the band method
  // intersects the same lines (fixed N: the same weight medians) with every triangle itself. Both
  // are exact on each line, so the sky layers agree to float storage. The sky is a CIE clear sky
  // (not uniform), lighting the box's walls and its shadowed ground.
  const Scene scene(ground_scene(1e4, true));
  const PinholeCamera cam(camera_spec(Vec3(7, -9, 5), Vec3(0, 0, 1), 40, 30));
  RenderSettings exact;
  exact.visibility.bands = 16;
  exact.visibility.tolerance = 0;
  exact.visibility.axis_tail_rad = 0;  // the band method culls nothing either
  RenderSettings bands = exact;
  bands.method = SkyFactorsMethod::bands;
  GeometryPass a = trace_geometry(scene, cam, exact), b = trace_geometry(scene, cam, bands);
  const SkyModel sky(AtmosphereParams{}, direction_from_altitude_azimuth(0.5, 2.0), parse_sky_model("cie-12", "test"));
  update_sun(a, scene, sky.sun_direction(), exact);
  update_sun(b, scene, sky.sun_direction(), bands);
  const Material white = white_diffuse(0.6);
  const Material* mats[] = {&white, &white};
  const RenderLayers la = shade(a, sky, mats, exact), lb = shade(b, sky, mats, bands);
  BOOST_TEST_REQUIRE(la.sky_diffuse.size() == lb.sky_diffuse.size());
  float peak = 0;
  for (const float v : lb.sky_diffuse) peak = std::max(peak, v);
  BOOST_TEST(peak > 0.0f);
  for (std::size_t i = 0; i < la.sky_diffuse.size(); ++i) {
    BOOST_TEST(la.sky_diffuse[i] == lb.sky_diffuse[i], tt::tolerance(1e-5f));
    BOOST_TEST(la.sun_diffuse[i] == lb.sun_diffuse[i]);
  }
}

BOOST_AUTO_TEST_CASE(physical_sky_images_are_finite_and_relighting_is_bit_identical) {
  const Scene scene(ground_scene(5000, true));
  const PinholeCamera cam(camera_spec(Vec3(-6, -8, 1.6), Vec3(0, 0, 1), 40, 30));
  RenderSettings rs;
  rs.samples_per_pixel = 2;
  rs.visibility.bands = 16;
  rs.visibility.tolerance = 0;
  const AtmosphereParams atmosphere;
  const SkyModel sky_a(atmosphere, direction_from_altitude_azimuth(50 * kPi / 180, 215 * kPi / 180), SkyModelSpec{});
  const SkyModel sky_b(atmosphere, direction_from_altitude_azimuth(4 * kPi / 180, 250 * kPi / 180), SkyModelSpec{});
  const Material* mats[] = {&find_material("ground"), &find_material("aluminium-panel")};
  const Material* mats2[] = {&find_material("window-glass"), &find_material("ceramic-tile")};

  // Relit: geometry once, sun A, then B.
  GeometryPass pass = trace_geometry(scene, cam, rs);
  update_sun(pass, scene, sky_a.sun_direction(), rs);
  const RenderLayers a = shade(pass, sky_a, mats, rs);
  update_sun(pass, scene, sky_b.sun_direction(), rs);
  const RenderLayers b_relit = shade(pass, sky_b, mats, rs);
  const RenderLayers c_relit = shade(pass, sky_b, mats2, rs);
  // From scratch with sun B, on one thread.
  RenderSettings rs1 = rs;
  rs1.threads = 1;
  GeometryPass fresh = trace_geometry(scene, cam, rs1);
  update_sun(fresh, scene, sky_b.sun_direction(), rs1);
  const RenderLayers b_fresh = shade(fresh, sky_b, mats, rs1);
  const RenderLayers c_fresh = shade(fresh, sky_b, mats2, rs1);
  for (const RenderLayers* L : {&a, &b_relit, &c_relit, &b_fresh}) BOOST_TEST(all_finite(*L));
  BOOST_TEST(bit_equal(b_relit.total, b_fresh.total));
  BOOST_TEST(bit_equal(b_relit.sun_diffuse, b_fresh.sun_diffuse));
  BOOST_TEST(bit_equal(b_relit.sky_specular, b_fresh.sky_specular));
  BOOST_TEST(bit_equal(c_relit.total, c_fresh.total));
  // The relit image differs from the first one (the sun moved): the test can fail.
  BOOST_TEST(!bit_equal(a.total, b_relit.total));
  // On surfaces total = the sum of the four layers (renderer.h), to float rounding.
  for (std::size_t i = 0; i < a.total.size(); ++i) {
    if (pass.sample_surface[(i / 3) * 2] == GeometryPass::kBackground ||
        pass.sample_surface[(i / 3) * 2 + 1] == GeometryPass::kBackground)
      continue;
    const double sum = double(a.sun_diffuse[i]) + a.sun_specular[i] + a.sky_diffuse[i] + a.sky_specular[i];
    BOOST_TEST(a.total[i] == sum, tt::tolerance(1e-5));  // four float roundings
  }
}

BOOST_AUTO_TEST_CASE(shade_refuses_a_stale_sun) {
  const Scene scene(ground_scene(100, false));
  CameraSpec cs;
  cs.width = 8;
  cs.height = 6;
  const PinholeCamera cam(cs);
  RenderSettings rs;
  rs.visibility.bands = 4;
  GeometryPass pass = trace_geometry(scene, cam, rs);
  const SkyLight light = uniform_sky(1.0, Vec3(0, 0, 1), 1.0);
  const Material white = white_diffuse(0.5);
  const Material* mats[] = {&white, &white};
  BOOST_CHECK_THROW(shade(pass, light, mats, rs), std::logic_error);  // update_sun never called
  update_sun(pass, scene, Vec3(0, 0.6, 0.8), rs);
  BOOST_CHECK_THROW(shade(pass, light, mats, rs), std::logic_error);  // for another sun
}

// Image-space reuse of the specular sky term (specular_reuse.h): a glossy ground around a box,
// seen at 96×72, under the physical sky. Against the exact image (reuse off): every pixel's
// specular sky is within 2 × the reuse tolerance (1%) of the largest exact value within a block's
// reach (the check is a posteriori at five points per block, relative to the block's largest
// value, so elsewhere the deviation can exceed the tolerance somewhat; 2× is the margin). Reuse
// really happens on the flat ground (at least `min_share` of the glossy samples), the other
// layers are untouched, and the result is thread-count independent.
void check_specular_reuse(const char* ground_material, double min_share) {
  BOOST_TEST_CONTEXT("ground " << ground_material) {
    const Scene scene(ground_scene(60, true));
    const CameraSpec cs = camera_spec(Vec3(-7, -9, 2.5), Vec3(0, 0, 0.5), 96, 72);
    const PinholeCamera cam(cs);
    RenderSettings rs;
    rs.visibility.bands = 32;
    rs.visibility.tolerance = 0;
    const SkyModel sky(AtmosphereParams{}, direction_from_altitude_azimuth(30 * kPi / 180, 200 * kPi / 180), SkyModelSpec{});
    const Material* mats[] = {&find_material(ground_material), &find_material("aluminium-panel")};
    GeometryPass pass = trace_geometry(scene, cam, rs);
    update_sun(pass, scene, sky.sun_direction(), rs);
    RenderSettings exact = rs;
    exact.specular_reuse_block = 1;
    const RenderLayers e = shade(pass, sky, mats, exact);
    const RenderLayers r = shade(pass, sky, mats, rs);
    BOOST_TEST(e.specular_interpolated == 0u);
    BOOST_TEST(r.specular_interpolated >= min_share * static_cast<double>(e.specular_exact));
    BOOST_TEST(r.specular_exact + r.specular_interpolated == e.specular_exact);
    double peak = 0;
    for (float v : e.sky_specular) peak = std::max(peak, double(v));
    BOOST_TEST(peak > 0.0);
    // The reuse check bounds the interpolation error relative to the largest value of a block (up
    // to 16 pixels across): compare against the largest exact value within ±16 pixels.
    auto local_max = [&](std::size_t i) {
      const int p = static_cast<int>(i / 3), ch = static_cast<int>(i % 3), row = p / cs.width, col = p % cs.width;
      double m = 0;
      for (int y = std::max(0, row - 16); y <= std::min(cs.height - 1, row + 16); ++y)
        for (int x = std::max(0, col - 16); x <= std::min(cs.width - 1, col + 16); ++x)
          m = std::max(m, double(e.sky_specular[static_cast<std::size_t>((y * cs.width + x) * 3 + ch)]));
      return m;
    };
    std::size_t differ = 0;
    for (std::size_t i = 0; i < e.sky_specular.size(); ++i) {
      const double d = std::abs(double(r.sky_specular[i]) - e.sky_specular[i]);
      BOOST_TEST(d <= 2 * rs.specular_reuse_tolerance * local_max(i),
                 "value " << i << ": " << r.sky_specular[i] << " vs exact " << e.sky_specular[i] << " peak " << peak);
      differ += d > 0;
    }
    BOOST_TEST(differ > 0u);  // interpolation changed something: the comparison can fail
    BOOST_TEST(bit_equal(r.sun_diffuse, e.sun_diffuse));
    BOOST_TEST(bit_equal(r.sky_diffuse, e.sky_diffuse));
    RenderSettings one = rs;
    one.threads = 1;
    BOOST_TEST(bit_equal(shade(pass, sky, mats, one).sky_specular, r.sky_specular));
  }
}

BOOST_AUTO_TEST_CASE(specular_reuse_is_close_to_exact_and_deterministic) {
  check_specular_reuse("ceramic-tile", 1.0 / 3.0);  // a third or more: mostly flat ground
}

// A near-mirror ground (window glass, m = 0.01, below the reuse roughness): interpolated only
// where a sample's lobe window is wholly open or wholly closed sky (lobe_window_sky), which
// the open ground far from the box's reflection and the horizon is; the same bound holds. The
// share (≥ 10%) only asserts that reuse happens; the margin is wide.
BOOST_AUTO_TEST_CASE(near_mirror_reuse_is_close_to_exact_and_deterministic) {
  check_specular_reuse("window-glass", 0.1);
}
