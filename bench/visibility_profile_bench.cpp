// Where the geometry core spends its time: per configuration, points/s, planes per point, bands
// per point (after refinement), triangle tests per point and cache bytes per point, on the
// procedural city of tests/geometry/support (street and facade points). Single thread, CPU time.
//   bench_visibility_profile [--triangles N] [--points K]
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>

#include <CLI/CLI.hpp>

#include "geometry/band_visibility.h"
#include "geometry/sky_integral.h"
#include "geometry/support/scene_generators.h"

using namespace skyband;

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  CLI::App app{"geometry core profile"};
  std::size_t triangles = 10000, count = 2000;
  app.add_option("--triangles", triangles);
  app.add_option("--points", count);
  CLI11_PARSE(app, argc, argv);
  const gen::City city = gen::make_city(gen::city_params_for_triangles(triangles, 1));
  const Scene scene(city.soup);
  std::printf("city: %zu triangles, %zu buildings\n", city.soup.triangle_count(), city.buildings.size());
  struct Set { const char* name; std::vector<QueryPoint> pts; };
  const Set sets[] = {{"street", gen::street_points(city, count, 2)},
                      {"facade", gen::facade_points(city.buildings, count, 0.0, 3)}};
  struct Config { const char* name; int bands; double tol; };
  const Config configs[] = {{"N=32 fixed", 32, 0}, {"N=64 fixed", 64, 0}, {"N=256 fixed", 256, 0}, {"default (N=32, tol 5e-4)", 32, 5e-4},
                            {"N=32, tol 2.5e-4", 32, 2.5e-4}, {"N=32, tol 1e-3", 32, 1e-3},
                            {"N=16, tol 2.5e-4", 16, 2.5e-4}, {"N=32, tol 1e-4", 32, 1e-4}, {"N=16, tol 1e-3", 16, 1e-3}, {"N=16, tol 2e-3", 16, 2e-3}};
  std::printf("%-8s %-28s %10s %8s %8s %10s %9s %8s %9s %9s\n", "points", "options", "points/s", "planes", "bands",
              "tri tests", "bytes/pt", "mean svf", "max|err|", "mean|err|");
  for (const Set& set : sets) {
    // Reference: 4096 fixed bands (not independent of the method; the exact-oracle comparison is
    // bench_svf). Error columns are against it.
    std::vector<double> ref;
    {
      VisibilityOptions opt;
      opt.bands = 4096;
      opt.tolerance = 0;
      const VisibilityCache c = compute_visibility(scene, set.pts, opt, 0);
      for (std::size_t i = 0; i < c.size(); ++i) ref.push_back(sky_view_factor(c.view(i)));
    }
    for (const Config& c : configs) {
      VisibilityOptions opt;
      opt.bands = c.bands;
      opt.tolerance = c.tol;
      BandVisibility bv(scene, opt);
      VisibilityCache cache;
      VisibilityCache::PointResult r;
      double planes = 0, tests = 0;
      const std::clock_t t0 = std::clock();  // CPU time: steadier than wall time on a shared machine
      for (const QueryPoint& q : set.pts) {
        bv.compute(q, r);
        planes += double(bv.last_plane_count());
        tests += double(bv.last_triangle_tests());
        cache.append(r);
      }
      const double s = double(std::clock() - t0) / CLOCKS_PER_SEC;
      double svf = 0, max_err = 0, sum_err = 0;
      for (std::size_t i = 0; i < cache.size(); ++i) {
        const double v = sky_view_factor(cache.view(i));
        svf += v;
        max_err = std::max(max_err, std::abs(v - ref[i]));
        sum_err += std::abs(v - ref[i]);
      }
      const double n = double(set.pts.size());
      std::printf("%-8s %-28s %10.0f %8.1f %8.1f %10.1f %9.0f %8.4f %9.2e %9.2e\n", set.name, c.name, n / s, planes / n,
                  double(cache.bands().size()) / n, tests / n, cache.bytes_per_point(), svf / n, max_err, sum_err / n);
    }
  }
}
