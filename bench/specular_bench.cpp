// Speed-up and error of the ε-truncated partial-sky specular integration (seed §3,
// lighting/integrals/specular_sky.h) against the full reference integral over the same visibility cache,
// for Beckmann roughness m ∈ {0.02, 0.1, 0.3, 0.5}. Sky: CIE general sky type 12 (clear, sun at
// 35° altitude, reference-notes §3.3) with a blue zenith tint; 64 bands per point; points: open
// and partly occluded horizontal, vertical and tilted faces; views spread over each hemisphere.
// Errors: relative to the reference of the same point (max_err%, mean_err%), and relative to
// the reference of the same face and view with the sky unobstructed (max_err_open%): where an
// occluder hides the lobe's core, what remains is its tails, which ε truncates by design (the
// seed's G has no visibility in it), so the first measure can be large on a tiny value.
// xyz_us, xyz_ns/eval: the renderer's path, the same march in CIE XYZ on the sky resampled on
// the stereographic grid (specular_sky_colour.h; Fresnel rank 4 for aluminium, 1 for
// dielectrics), time per point (best of 5 passes, one thread) and per sky evaluation;
// xyz_evals: its evaluations per point; xyz_max_err%, xyz_mean_err%: its Y
// against the full reference integrated over the same gridded sky (truncation only, plus the
// aluminium Fresnel separation's ≤ 3·10⁻⁴).
// Usage: bench_specular [--views N] [--epsilon E] [--alpha-step-per-m C] [--delta-step-per-m C]
//                       [--single-line-per-m C] [--max-alpha-step R] [--max-delta-step R] [--m M ...]
//                       [--material NAME] [--xyz-only]
// (defaults: 8 views per point, the library's SpecularSkyOptions, aluminium-panel's Fresnel
// table and specular weight).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "geometry/core/input_error.h"
#include "lighting/brdf/material.h"
#include "lighting/integrals/specular_sky.h"
#include "lighting/integrals/specular_sky_reference.h"
#include "lighting/sky/sky_radiance_grid.h"
#include "lighting/spectrum/colour.h"
#include "lighting/support/analytic_sky.h"
#include "lighting/support/hand_cache.h"
#include "render/specular_sky_colour.h"

using namespace skyband;

namespace {
struct ClearSky {
  Vec3 sun = Vec3(std::cos(0.61) * 0.8, std::cos(0.61) * -0.6, std::sin(0.61));
  void operator()(const Vec3& d, Spectrum& out) const { test::clear_sky_radiance(sun, d, out); }
};

using test::view_at;
double sum(const Spectrum& s) {
  return test::channel_sum(s);
}
}  // namespace

int main(int argc, char** argv) {
  int views = 8;
  SpecularSkyOptions opt;
  std::vector<double> roughness = {0.02, 0.1, 0.3, 0.5};
  CLI::App app{"bench_specular: epsilon-truncated vs full specular sky integral"};
  app.add_option("--views", views, "views per point")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--epsilon", opt.epsilon)->capture_default_str();
  app.add_option("--alpha-step-per-m", opt.alpha_step_per_m)->capture_default_str();
  app.add_option("--delta-step-per-m", opt.delta_step_per_m)->capture_default_str();
  app.add_option("--single-line-per-m", opt.single_line_per_m)->capture_default_str();
  app.add_option("--max-alpha-step", opt.max_alpha_step_rad, "radians")->capture_default_str();
  app.add_option("--max-delta-step", opt.max_delta_step_rad, "radians")->capture_default_str();
  app.add_option("--min-compression", opt.min_compression)->capture_default_str();
  app.add_option("--m", roughness, "Beckmann roughness values")->capture_default_str();
  bool xyz_only = false;
  app.add_flag("--xyz-only", xyz_only, "time only the XYZ march (the other columns print 0)");
  std::string material = "aluminium-panel";
  app.add_option("--material", material, "built-in material whose Fresnel table and weight are used")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const ClearSky sky;
  const Material* al_ptr = nullptr;
  try {
    al_ptr = &find_material(material, "--material");
  } catch (const InputError& e) {
    std::fprintf(stderr, "bench_specular: %s\n", e.what());
    return 2;
  }
  const Material& al = *al_ptr;
  const SkyRadianceGrid grid(sky, 1);
  const ColourSpecularSky colour(grid, &al.fresnel);

  VisibilityCache cache;
  const Vec3 normals[] = {Vec3(0, 0, 1), Vec3(0.8, 0.6, 0), Vec3(-0.3, 0.4, 0.8)};
  for (const Vec3& n : normals) {
    cache.append(skyband::test::hand_point(n, 64));
    cache.append(skyband::test::hand_point(n, 64, [](int band, double delta) {
      std::vector<std::pair<double, double>> iv;
      if (band % 7 == 3) return iv;
      iv.push_back({0.0, 1.1});
      iv.push_back({1.3 + 0.2 * std::sin(3.0 * delta), 2.5});
      iv.push_back({2.7, kPi});
      return iv;
    }));
  }

  std::printf("specular sky: truncated (eps = %g) vs full reference; %zu points x %d views, 64 bands, CIE clear sky, %s\n",
              opt.epsilon, cache.size(), views, material.c_str());
  std::printf("%6s %12s %12s %9s %12s %12s %10s %10s %14s %10s %12s %10s %12s %12s\n", "m", "trunc_us", "full_us", "speedup",
              "trunc_evals", "full_evals", "max_err%", "mean_err%", "max_err_open%", "xyz_us", "xyz_ns/eval", "xyz_evals",
              "xyz_max_err%", "xyz_mean_err%");
  using clock = std::chrono::steady_clock;
  for (double m : roughness) {
    const SpecularLobe lobe{m, al.specular_weight, &al.fresnel, false};
    double t_fast = 0, t_full = 0, max_err = 0, sum_err = 0, max_err_open = 0, xyz_max_err = 0, xyz_sum_err = 0;
    std::size_t xyz_cases = 0;
    std::vector<double> open_ref(static_cast<std::size_t>(views), 0.0);  // points come in (open, occluded) pairs
    std::size_t e_fast = 0, e_full = 0, cases = 0;
    for (std::size_t p = 0; p < cache.size() && !xyz_only; ++p) {
      const PointVisibilityView v = cache.view(p);
      for (int k = 0; k < views; ++k) {
        // Views on a spiral over the hemisphere, θ up to 80°.
        const double theta = std::acos(1.0 - (k + 0.5) / views * (1.0 - std::cos(80.0 * kPi / 180)));
        const Vec3 view = view_at(v.frame().normal, theta, 2.39996 * k);
        SpecularSkyStats sf, sr;
        auto t0 = clock::now();
        const Spectrum fast = specular_sky_radiance(v, view, lobe, sky, opt, &sf);
        auto t1 = clock::now();
        const Spectrum ref = specular_sky_reference(v, view, lobe, sky, 0.5, 0.02, opt, &sr);
        auto t2 = clock::now();
        t_fast += std::chrono::duration<double, std::micro>(t1 - t0).count();
        t_full += std::chrono::duration<double, std::micro>(t2 - t1).count();
        e_fast += sf.radiance_evals;
        e_full += sr.radiance_evals;
        if (p % 2 == 0) open_ref[static_cast<std::size_t>(k)] = sum(ref);
        const double floor = 1e-6 * kSpectrumSamples;  // lobes entirely below the horizon reflect ~0
        if (open_ref[static_cast<std::size_t>(k)] > floor)
          max_err_open = std::max(max_err_open, std::abs(sum(fast) - sum(ref)) / open_ref[static_cast<std::size_t>(k)]);
        // The XYZ march (renderer path, gridded sky) against the full reference over the same
        // gridded sky, converted to XYZ: truncation (and the rank-4 aluminium Fresnel
        // separation, ≤ 3·10⁻⁴ relative; dielectrics are exact) only. Over the same cases as
        // max_err% (lobes almost wholly below the horizon, reference below `floor`, skipped).
        const double xyz_ref = spectrum_to_xyz(specular_sky_reference(v, view, lobe, grid, 0.5, 0.02, opt)).Y;
        if (xyz_ref > 0.0 && sum(ref) > floor) {
          const double e = std::abs(colour.radiance_xyz(v, view, lobe, opt).Y - xyz_ref) / xyz_ref;
          xyz_max_err = std::max(xyz_max_err, e);
          xyz_sum_err += e;
          ++xyz_cases;
        }
        if (sum(ref) <= floor) continue;
        const double err = std::abs(sum(fast) - sum(ref)) / sum(ref);
        max_err = std::max(max_err, err);
        sum_err += err;
        ++cases;
      }
    }
    // The renderer's XYZ march over the same points and views: best of 5 passes.
    double t_xyz = 1e300, sink = 0;
    std::size_t e_xyz = 0;
    for (int pass = 0; pass < 5; ++pass) {
      std::size_t evals = 0;
      const auto t0 = clock::now();
      for (std::size_t p = 0; p < cache.size(); ++p) {
        const PointVisibilityView v = cache.view(p);
        for (int k = 0; k < views; ++k) {
          const double theta = std::acos(1.0 - (k + 0.5) / views * (1.0 - std::cos(80.0 * kPi / 180)));
          SpecularSkyStats st;
          sink += colour.radiance_xyz(v, view_at(v.frame().normal, theta, 2.39996 * k), lobe, opt, &st).Y;
          evals += st.radiance_evals;
        }
      }
      t_xyz = std::min(t_xyz, std::chrono::duration<double, std::micro>(clock::now() - t0).count());
      e_xyz = evals;
    }
    if (!std::isfinite(sink)) std::printf("non-finite XYZ march result\n");
    const double n = static_cast<double>(cache.size()) * views;
    std::printf("%6.2f %12.1f %12.1f %9.1f %12.0f %12.0f %10.3f %10.3f %14.3f %10.1f %12.1f %10.0f %12.3f %12.3f\n", m,
                t_fast / n, t_full / n, t_fast > 0 ? t_full / t_fast : 0.0, e_fast / n, e_full / n, 100 * max_err,
                cases ? 100 * sum_err / cases : 0.0, 100 * max_err_open, t_xyz / n,
                e_xyz ? 1e3 * t_xyz / static_cast<double>(e_xyz) : 0.0, e_xyz / n, 100 * xyz_max_err,
                xyz_cases ? 100 * xyz_sum_err / xyz_cases : 0.0);
  }
  return 0;
}
