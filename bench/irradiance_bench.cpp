// Irradiance at calculation points (`skyband irradiance`, lighting/integrals/point_irradiance.h) on the
// procedural cities of bench_svf: points/s of the SVF alone and of the irradiance (SVF + sky
// quadrature + sun shadow test), and the sky quadrature's error against a 4× finer step.
//
// Usage: bench_irradiance [--points N] [--quick] [--large] [--max-threads 1|2] [--method auto|bands|both]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "geometry/bands/band_visibility.h"
#include "geometry/support/scene_generators.h"
#include "geometry/visibility/sky_factors.h"
#include "lighting/integrals/point_irradiance.h"
#include "lighting/sun/sun.h"

using namespace skyband;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The methods to run: "auto", "bands" or "both" (--method).
std::vector<SkyFactorsMethod> g_methods{SkyFactorsMethod::automatic, SkyFactorsMethod::bands};

void run_city(const char* label, std::size_t triangles, std::size_t n_points, int max_threads) {
  const gen::City city = gen::make_city(gen::city_params_for_triangles(triangles, 2024));
  const Scene scene(city.soup);
  std::vector<QueryPoint> pts = gen::street_points(city, n_points / 2, 11);
  for (const QueryPoint& q : gen::facade_points(city.buildings, n_points - pts.size(), 0.05, 12)) pts.push_back(q);
  auto t0 = Clock::now();
  const SkyModel sky(AtmosphereParams{}, direction_from_altitude_azimuth(35 * kPi / 180, 200 * kPi / 180), SkyModelSpec{});
  const double t_sky = seconds_since(t0);
  std::printf("%s: %zu triangles, %zu points (half street, half facade); sky model %.2f s\n", label, city.soup.triangle_count(),
              pts.size(), t_sky);
  std::printf("| method | threads | svf points/s | irradiance points/s | irradiance / svf time | sun visible |\n");
  std::printf("|--------|---------|--------------|---------------------|-----------------------|-------------|\n");
  (void)scene.column_scene();  // the exact horizon's classification, once per scene (not timed)
  for (SkyFactorsMethod method : g_methods)
    for (int threads = 1; threads <= max_threads; ++threads) {
      t0 = Clock::now();
      const auto f = compute_sky_factors(scene, pts, VisibilityOptions{}, method, threads);
      const double t_svf = seconds_since(t0);
      PointIrradianceOptions o;
      o.threads = threads;
      o.method = method;
      t0 = Clock::now();
      const auto r = compute_point_irradiance(scene, pts, sky, o);
      const double t_irr = seconds_since(t0);
      const auto lit = std::count_if(r.begin(), r.end(), [](const PointIrradiance& x) { return x.sun_visible; });
      std::printf("| %-6s | %7d | %12.0f | %19.0f | %21.2f | %5.1f %%     |\n",
                  method == SkyFactorsMethod::bands ? "bands" : "auto", threads, double(pts.size()) / t_svf,
                  double(pts.size()) / t_irr, t_irr / t_svf, 100.0 * double(lit) / double(pts.size()));
      if (f.factors.size() != r.size()) std::printf("size mismatch\n");
    }
  // Sums over a day of moments (hourly, sun from 5° to 65° and back): cost per moment, once and
  // per point, from two runs with 12 and 24 moments.
  {
    auto day = [](int n) {
      std::vector<SunMoment> m;
      for (int k = 0; k < n; ++k) {
        const double f = (k + 0.5) / n;
        m.push_back(
            {direction_from_altitude_azimuth((5 + 60 * std::sin(kPi * f)) * kPi / 180, (90 + 180 * f) * kPi / 180), 24.0 / n});
      }
      return m;
    };
    PointIrradianceOptions o;
    o.threads = max_threads;
    double t[2];
    const int counts[2] = {12, 24};
    for (int i = 0; i < 2; ++i) {
      const auto moments = day(counts[i]);
      t0 = Clock::now();
      const auto r = compute_point_irradiation(scene, pts, AtmosphereParams{}, SkyModelSpec{}, moments, o);
      t[i] = seconds_since(t0);
    }
    const double per_moment = (t[1] - t[0]) / 12;
    std::printf(
        "sums over moments (%d threads): 12 moments %.2f s, 24 moments %.2f s -> %.3f s per moment for %zu points "
        "(%.0f us per moment and point, sky model and grid included)\n\n",
        max_threads, t[0], t[1], per_moment, pts.size(), 1e6 * per_moment / double(pts.size()));
  }
  // Quadrature error of the sky term against a fine step (0.0125 rad), same visibility, and its cost.
  const std::size_t n = std::min<std::size_t>(pts.size(), 400);
  std::vector<QueryPoint> subset(pts.begin(), pts.begin() + static_cast<std::ptrdiff_t>(n / 2));
  subset.insert(subset.end(), pts.end() - static_cast<std::ptrdiff_t>(n / 2), pts.end());
  for (SkyFactorsMethod method : g_methods) {
    PointIrradianceOptions fine;
    fine.max_step_rad = 0.0125;
    fine.threads = 1;
    fine.method = method;
    const auto ref = compute_point_irradiance(scene, subset, sky, fine);
    std::printf("sky quadrature against step 0.0125 rad (%zu points, 1 thread, method %s):\n", subset.size(),
                method == SkyFactorsMethod::bands ? "bands" : "auto");
    std::printf("| step rad | max relative | max absolute W/m2 | points/s |\n|---|---|---|---|\n");
    for (double step : {0.05, 0.1, 0.2, 0.4}) {
      PointIrradianceOptions o;
      o.max_step_rad = step;
      o.threads = 1;
      o.method = method;
      t0 = Clock::now();
      const auto a = compute_point_irradiance(scene, subset, sky, o);
      const double t = seconds_since(t0);
      double max_rel = 0, max_abs = 0;
      for (std::size_t i = 0; i < subset.size(); ++i) {
        max_abs = std::max(max_abs, std::abs(a[i].sky_W_m2 - ref[i].sky_W_m2));
        if (ref[i].sky_W_m2 > 1e-3) max_rel = std::max(max_rel, std::abs(a[i].sky_W_m2 / ref[i].sky_W_m2 - 1));
      }
      std::printf("| %8.4f | %12.1e | %17.1e | %8.0f |\n", step, max_rel, max_abs, double(subset.size()) / t);
    }
    std::printf("\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_irradiance: SVF vs irradiance throughput on the procedural cities"};
  std::size_t points = 2000;
  bool large = false, quick = false;
  int max_threads = 2;
  app.add_option("--points", points, "query points per city (half street, half facade)")->check(CLI::Range(4, 100000000));
  app.add_flag("--large", large, "also the ~1M-triangle city");
  app.add_flag("--quick", quick, "at most 500 points");
  app.add_option("--max-threads", max_threads, "1: single-thread rows only")->check(CLI::Range(1, 2));
  std::string method = "both";
  app.add_option("--method", method, "auto, bands or both (profiling one path)")->check(CLI::IsMember({"auto", "bands", "both"}));
  CLI11_PARSE(app, argc, argv);
  if (method == "auto") g_methods = {SkyFactorsMethod::automatic};
  if (method == "bands") g_methods = {SkyFactorsMethod::bands};
  if (quick) points = std::min<std::size_t>(points, 500);
  run_city("city 10k", 10000, points, max_threads);
  if (large) run_city("city 1M", 1000000, points, max_threads);
  return 0;
}
