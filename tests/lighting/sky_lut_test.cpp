#define BOOST_TEST_MODULE sky_lut
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <thread>
#include <vector>

#include "geometry/bands/sky_integral.h"
#include "geometry/core/input_error.h"
#include "lighting/integrals/sky_lut.h"
#include "lighting/support/hand_cache.h"

namespace tt = boost::test_tools;
using namespace skyband;
using skyband::test::single_point_cache;

namespace {
constexpr double kLz = 2.5;  // zenith radiance of the test skies, W·m⁻²·sr⁻¹·nm⁻¹ (arbitrary)

void uniform_sky(const Vec3&, Spectrum& out) {
  out = Spectrum::constant(1.0);
}
// CIE standard overcast (Moon–Spencer, reference-notes §3.3): L = L_z (1 + 2 cos Z)/3.
void overcast_sky(const Vec3& d, Spectrum& out) {
  out = Spectrum::constant(kLz * (1.0 + 2.0 * d.z()) / 3.0);
}
// A coloured, anisotropic analytic sky (bluer toward the zenith, brighter toward +x +y): used
// where only an independent quadrature is the oracle.
void coloured_sky(const Vec3& d, Spectrum& out) {
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const double blue = 1.0 - i / 40.0;
    out[i] = (1.0 + 0.8 * blue * d.z()) * (1.2 + 0.5 * d.x() + 0.3 * d.y()) *
             std::exp(2.0 * std::max(0.0, d.dot(Vec3(0.6, 0.5, 0.62).normalized())));
  }
}

// Closed form of reference-notes §1.4 for the overcast sky.
double overcast_primitive(double a, double delta) {
  const double c = std::cos(a);
  return kLz / 3.0 * (a / 2 - std::sin(2 * a) / 4 + 2 * std::sin(delta) * (2.0 / 3.0 - c + c * c * c / 3.0));
}

const Vec3 kNormals[] = {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0.3, -0.8, 0.5), Vec3(-0.2, 0.1, -0.4), Vec3(0.0, 1.0, 1.7)};
}  // namespace

// Uniform sky: E_l(α) = α/2 − sin2α/4 (reference-notes §1.4) for every line of every frame.
// Off-node α: linear interpolation error ≤ h²/8·max|sin2α| = (π/360)²/8 = 9.5e-6 → abs tol 1e-5.
BOOST_AUTO_TEST_CASE(uniform_sky_closed_form) {
  for (const Vec3& n : kNormals) {
    const BandFrame f = BandFrame::make(n);
    const std::vector<double> deltas{f.delta_min_rad, 0.5 * (f.delta_min_rad + f.delta_max_rad), f.delta_max_rad};
    const SkyLut lut(f, deltas, uniform_sky);
    Spectrum e;
    for (std::size_t l = 0; l < deltas.size(); ++l)
      for (int k = 0; k <= 97; ++k) {
        const double a = kPi * k / 97.0;
        lut.primitive(l, a, e);
        BOOST_TEST(std::abs(e[17] - uniform_sky_primitive(a)) <= 1e-5, "α = " << a << ": " << e[17]);
      }
    lut.primitive(0, kPi, e);
    BOOST_TEST(e[0] == kPi / 2, tt::tolerance(1e-12));  // at a node: only GL rounding
  }
}

// CIE overcast: reference-notes §1.4 closed form, valid for any tilt because cos Z = sin α sin δ.
// |f'| ≤ (L_z/3)(1 + 2·(2/√3)) ≈ 1.1 L_z → interpolation error ≤ 1.1e-5 L_z; tolerance 1.5e-5 L_z.
BOOST_AUTO_TEST_CASE(overcast_closed_form) {
  for (const Vec3& n : kNormals) {
    const BandFrame f = BandFrame::make(n);
    std::vector<double> deltas;
    for (int k = 0; k <= 6; ++k) deltas.push_back(f.delta_min_rad + (f.delta_max_rad - f.delta_min_rad) * k / 6.0);
    const SkyLut lut(f, deltas, overcast_sky);
    Spectrum e;
    for (std::size_t l = 0; l < deltas.size(); ++l)
      for (int k = 0; k <= 61; ++k) {
        const double a = kPi * k / 61.0;
        lut.primitive(l, a, e);
        BOOST_TEST(std::abs(e[30] - overcast_primitive(a, deltas[l])) <= 1.5e-5 * kLz);
      }
  }
}

// Open horizontal face under overcast. Band-centre rule, exact for this sky:
//   E/L_z = (1/3)[π W/2 + (8/3) Σ_b w_b sin δ_b] (integrating the closed form over [0, π]),
// which must equal reference-notes §1.7's [C] values (4 decimals → 5e-5 rounding + 1e-5 table
// error) and converge to 7π/9 with the quoted band error.
BOOST_AUTO_TEST_CASE(open_horizontal_face_overcast) {
  const int ns[] = {4, 8, 16, 32, 64};
  const double quoted[] = {2.4958, 2.4623, 2.4502, 2.4458, 2.4443};
  const double exact = 7 * kPi / 9;
  SkyLutCache cache(overcast_sky);
  for (int i = 0; i < 5; ++i) {
    const VisibilityCache vc = single_point_cache(Vec3(0, 0, 1), ns[i]);
    const PointVisibilityView v = vc.view(0);
    const double e = diffuse_sky_irradiance(v, cache)[12] / kLz;
    double sum = 0;
    for (std::size_t b = 0; b < v.band_count(); ++b) sum += v.band_weight(b) * std::sin(v.band(b).delta_rad);
    const double band_rule = (kPi * 2 / 2 + 8.0 / 3.0 * sum) / 3.0;
    BOOST_TEST(e == band_rule, tt::tolerance(1e-6));  // sample lines stored in float; GL exact for this sky
    BOOST_TEST(std::abs(e - quoted[i]) <= 6e-5, "N = " << ns[i] << ": " << e);
    BOOST_TEST(std::abs(e - exact) <= std::abs(quoted[i] - exact) + 6e-5);
  }
  BOOST_TEST(cache.size() == 5u);  // one table per band layout
}

// Open vertical wall under overcast: here s = sin δ, so Σ w_b sin δ_b is the midpoint rule for
// ∫_0^1 s ds, exact for any N: E = L_z(π/6 + 4/9) = 0.9680 L_z exactly (reference-notes §3.3).
// Uniform sky: E = π/2 (SVF 0.5). Tolerances: sample lines stored in float (≈1e-7) and interpolation.
BOOST_AUTO_TEST_CASE(open_wall) {
  for (int n : {3, 16, 64}) {
    const VisibilityCache vc = single_point_cache(Vec3(0.6, -0.8, 0), n);
    SkyLutCache overcast(overcast_sky), uniform(uniform_sky);
    BOOST_TEST(diffuse_sky_irradiance(vc.view(0), overcast)[0] == kLz * (kPi / 6 + 4.0 / 9.0), tt::tolerance(1e-6));
    BOOST_TEST(diffuse_sky_irradiance(vc.view(0), uniform)[40] == kPi / 2, tt::tolerance(1e-6));
  }
}

// Occluded intervals and an anisotropic coloured sky: the table sum must equal an independent
// direct quadrature over the same cache (geometry/bands/sky_integral.h integrate_irradiance, GL on
// pieces ≤ 0.01 rad) channel by channel. Both integrate the same band-centre approximation, so
// only the table's interpolation (~1e-5 relative here) separates them: tolerance 1e-4.
BOOST_AUTO_TEST_CASE(occluded_coloured_sky_matches_direct_quadrature) {
  auto occlusion = [](int band, double delta) {
    std::vector<std::pair<double, double>> iv;
    if (band % 3 == 0) return iv;  // fully blocked band
    iv.push_back({0.0, 0.4 + 0.05 * band});
    iv.push_back({1.0 + 0.3 * std::sin(delta), 2.2});
    iv.push_back({2.9, kPi});
    return iv;
  };
  for (const Vec3& n : kNormals) {
    const VisibilityCache vc = single_point_cache(n, 24, occlusion);
    SkyLutCache cache(coloured_sky);
    const Spectrum e = diffuse_sky_irradiance(vc.view(0), cache);
    for (int ch : {0, 20, 40}) {
      const double direct = integrate_irradiance(
          vc.view(0),
          [ch](const Vec3& d) {
            Spectrum s;
            coloured_sky(d, s);
            return s[ch];
          },
          0.01);
      BOOST_TEST(e[ch] == direct, tt::tolerance(1e-4));
    }
  }
}

// Projected tables (SkyLut::project, SkyLutCache projections): integrating the projected table
// equals projecting the integrated spectrum (both are the same linear map applied in another
// order; rounding only, 1e-12), and spectral access to a projected table is refused.
Spectrum coloured_weights() {
  Spectrum w;
  for (int i = 0; i < kSpectrumSamples; ++i) w[i] = 0.2 + 0.01 * i * (i % 3);
  return w;
}

BOOST_AUTO_TEST_CASE(projected_tables_commute_with_integration) {
  auto occlusion = [](int band, double) {
    std::vector<std::pair<double, double>> iv;
    if (band % 4 == 1) return iv;
    iv.push_back({0.2, 1.3});
    iv.push_back({1.9, kPi});
    return iv;
  };
  const std::vector<Spectrum> w = {Spectrum::constant(1.0), coloured_weights()};
  SkyLutCache cache(coloured_sky, 360, 1e-9, {w});
  for (const Vec3& n : kNormals) {
    const VisibilityCache vc = single_point_cache(n, 24, occlusion);
    const Spectrum e = diffuse_sky_irradiance(vc.view(0), cache);
    const auto projected = cache.projected_for(vc.view(0), 0);
    BOOST_TEST(projected->channels() == 2);
    double out[2];
    diffuse_sky_channels(vc.view(0), *projected, out);
    for (int k = 0; k < 2; ++k) {
      double expect = 0;
      for (int i = 0; i < kSpectrumSamples; ++i) expect += w[static_cast<std::size_t>(k)][i] * e[i];
      BOOST_TEST(out[k] == expect, tt::tolerance(1e-12));
    }
    Spectrum s;
    BOOST_CHECK_THROW(projected->primitive(0, 1.0, s), std::logic_error);
    BOOST_CHECK_THROW(cache.projected_for(vc.view(0), 1), std::out_of_range);
    // A cache that keeps the projections only (the renderer's) serves the same tables, bit for bit.
    SkyLutCache lean(coloured_sky, 360, 1e-9, {w}, false);
    double lean_out[2];
    diffuse_sky_channels(vc.view(0), *lean.projected_for(vc.view(0), 0), lean_out);
    BOOST_TEST(lean_out[0] == out[0]);
    BOOST_TEST(lean_out[1] == out[1]);
    BOOST_CHECK_THROW(lean.lut_for(vc.view(0)), std::logic_error);
  }
}

// The cache: same frame + layout → same table; different normal or band count → new table; the
// result is independent of which thread built it (concurrent lookups return one shared table).
BOOST_AUTO_TEST_CASE(cache_keys_and_threads) {
  VisibilityCache vc;
  vc.append(skyband::test::hand_point(Vec3(1, 0, 0), 16));
  vc.append(skyband::test::hand_point(Vec3(1, 0, 0), 16, [](int, double) {
    return std::vector<std::pair<double, double>>{{0.2, 1.0}};
  }));
  vc.append(skyband::test::hand_point(Vec3(0, 1, 0), 16));
  vc.append(skyband::test::hand_point(Vec3(1, 0, 0), 8));
  SkyLutCache cache(overcast_sky, 180);
  std::vector<std::shared_ptr<const SkyLut>> got(8);
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) threads.emplace_back([&, t] { got[t] = cache.lut_for(vc.view(t % 2)); });
  for (auto& t : threads) t.join();
  for (int t = 1; t < 8; ++t) BOOST_TEST(got[t] == got[0]);
  BOOST_TEST(cache.size() == 1u);
  cache.lut_for(vc.view(2));
  cache.lut_for(vc.view(3));
  BOOST_TEST(cache.size() == 3u);
  // A partially visible point: E = w Σ (E(α1) − E(α0)) with the closed form (1.2e-5 L_z per end).
  const PointVisibilityView v = vc.view(1);
  double expected = 0;
  for (std::size_t b = 0; b < v.band_count(); ++b)
    expected += v.band_weight(b) * (overcast_primitive(1.0, v.band(b).delta_rad) - overcast_primitive(0.2, v.band(b).delta_rad));
  BOOST_TEST(std::abs(diffuse_sky_irradiance(v, cache)[5] - expected) <= 2 * 4.5e-5 * kLz);
}

BOOST_AUTO_TEST_CASE(bad_parameters_throw) {
  BOOST_CHECK_THROW(SkyLutCache c(overcast_sky, 0), InputError);
  BOOST_CHECK_THROW(SkyLutCache c(overcast_sky, 360, 0.0), InputError);
  const BandFrame f = BandFrame::make(Vec3(0, 0, 1));
  const std::vector<double> d{1.0};
  BOOST_CHECK_THROW(SkyLut lut(f, d, overcast_sky, -3), InputError);
}

// A whole visible line [0, π] is served from a per-line value (SkyLut::add_interval's fast path):
// it must equal E_l(π) − E_l(0) from the interpolated primitive, the very expression the general
// path evaluates (bit for bit: the same operations), for spectral and projected tables; and
// splitting the line at any α telescopes to the same value within rounding (1e-12 relative).
BOOST_AUTO_TEST_CASE(whole_line_fast_path_equals_the_general_expression) {
  const BandFrame f = BandFrame::make(Vec3(0.3, -0.8, 0.5).normalized());
  const std::vector<double> deltas = {0.1, 0.7, 1.3, 2.0};
  const SkyLut lut(f, deltas, coloured_sky, 360);
  const Spectrum w[2] = {Spectrum::constant(1.0), Spectrum::constant(0.5)};
  const SkyLut projected = lut.project(w);
  for (std::size_t l = 0; l < deltas.size(); ++l) {
    Spectrum whole, e0, e1;
    lut.add_interval(l, 0.0, kPi, 1.0, whole);
    lut.primitive(l, kPi, e1);
    lut.primitive(l, 0.0, e0);
    for (int i = 0; i < kSpectrumSamples; ++i) BOOST_TEST(whole[i] == e1[i] - e0[i]);  // exact
    for (double split : {0.3, 1.5707, 2.9}) {
      Spectrum parts;
      lut.add_interval(l, 0.0, split, 1.0, parts);
      lut.add_interval(l, split, kPi, 1.0, parts);
      for (int i = 0; i < kSpectrumSamples; ++i) BOOST_TEST(parts[i] == whole[i], tt::tolerance(1e-12));
    }
    double pw[2] = {0, 0}, pp[2] = {0, 0};
    projected.add_interval(l, 0.0, kPi, 2.0, pw);
    projected.add_interval(l, 0.0, 1.0, 2.0, pp);
    projected.add_interval(l, 1.0, kPi, 2.0, pp);
    for (int k = 0; k < 2; ++k) BOOST_TEST(pw[k] == pp[k], tt::tolerance(1e-12));
    BOOST_TEST(pw[0] > 0.0);
  }
}

// The unrolled 3-channel path (SkyLut::add_interval_n<3>, the renderer's diffuse pass) evaluates
// the same expression as the general add_interval, so it must give the same bits, for whole
// lines, partial intervals, ends at 0 or π and intervals inside one α cell; and
// diffuse_sky_channels (which takes it for 3-channel tables) equals the band-by-band sum of
// general add_interval calls exactly.
BOOST_AUTO_TEST_CASE(three_channel_path_is_bit_identical) {
  const Vec3 n = Vec3(0.3, -0.8, 0.5).normalized();
  const VisibilityCache vc = single_point_cache(n, 24, [](int band, double delta) {
    if (band % 5 == 2) return std::vector<std::pair<double, double>>{{0.0, kPi}};
    return std::vector<std::pair<double, double>>{{0.0, 0.4 + 0.1 * delta}, {1.001, 1.003}, {2.2, kPi}};
  });
  const PointVisibilityView v = vc.view(0);
  std::vector<double> deltas;
  for (std::size_t b = 0; b < v.band_count(); ++b) deltas.push_back(v.band(b).delta_rad);
  const SkyLut lut(v.frame(), deltas, coloured_sky, 360);
  const Spectrum w[3] = {Spectrum::constant(1.0), Spectrum::constant(0.5), Spectrum::constant(0.25)};
  const SkyLut projected = lut.project(w);
  for (std::size_t l = 0; l < deltas.size(); ++l)
    for (auto [a0, a1] :
         {std::pair{0.0, kPi}, std::pair{0.0, 0.7}, std::pair{0.5, kPi}, std::pair{1.0001, 1.0002}, std::pair{0.3, 2.9}}) {
      double g[3] = {0.1, 0.2, 0.3}, u[3] = {0.1, 0.2, 0.3};
      projected.add_interval(l, a0, a1, 0.37, g);
      projected.add_interval_n<3>(l, a0, a1, 0.37, u);
      for (int k = 0; k < 3; ++k) BOOST_TEST(u[k] == g[k]);
    }
  double expected[3] = {0, 0, 0}, got[3];
  for (std::size_t b = 0; b < v.band_count(); ++b)
    for (const VisibleInterval& iv : v.visible(b))
      projected.add_interval(b, clamp_alpha(iv.alpha0_rad), clamp_alpha(iv.alpha1_rad), v.band_weight(b), expected);
  diffuse_sky_channels(v, projected, got);
  for (int k = 0; k < 3; ++k) BOOST_TEST(got[k] == expected[k]);
  BOOST_TEST(got[0] > 0.0);
}
