// `skyband map --dsm` against the shadow-casting estimate the DSM tools of the field use, side by
// side on the same rasters.
//
// Baseline: the sky view factor of a DSM by shadow casting (Ratti and Richens 2004; the
// estimator of Lindberg and Grimmond 2010 that UMEP's SVF tool implements, written here from the
// papers): the sky split into 153 patches — annuli 12° high centred at altitudes 6°, 18°, …,
// 78° with 31, 30, 28, 24, 19, 13, 7 patches and a zenith cap — each patch seen from a pixel when
// no pixel in its azimuth rises above its altitude (the DSM stepped one pixel along the dominant
// axis at a time); SVF = Σ visible patches' cosine weights, (sin² β_hi − sin² β_lo) / patches of
// the annulus. skyband: every pixel's exact SVF over the pixel columns (geometry/mesh/height_field.h,
// the horizon of a column solid), as `skyband map --dsm` computes it.
// Printed per raster: pixels, both methods' pixels/s and their ratio, and the baseline's max and
// mean |error| against the exact values (the error of a 153-patch discretisation: what a DSM tool
// user gets).
//
// Usage: bench_dsm_map [--size N] [--threads T]   (N: side of the synthetic raster, default 200)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <CLI/CLI.hpp>

#include "geometry/mesh/height_field.h"
#include "geometry/mesh/scene.h"
#include "geometry/support/scene_generators.h"
#include "geometry/visibility/sky_factors.h"

using namespace skyband;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}
constexpr double kPi = 3.14159265358979323846;

// Shadow-casting SVF of every pixel (NaN pixels: NaN), on `threads` threads over rows.
std::vector<double> shadow_casting_svf(const HeightField& f, int threads) {
  static constexpr int kCounts[8] = {31, 30, 28, 24, 19, 13, 7, 1};
  const double pixel = std::abs(f.dx);  // square pixels assumed (the synthetic rasters are)
  double lo = 1e300, hi = -1e300;
  for (double h : f.heights)
    if (!std::isnan(h)) lo = std::min(lo, h), hi = std::max(hi, h);
  std::vector<double> svf(f.heights.size(), 0.0);
  const long cols = long(f.columns), rows = long(f.rows);
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<long>(0, rows), [&](const tbb::blocked_range<long>& rr) {
      for (int a = 0; a < 8; ++a) {
        const double alt_lo = a * 12.0, alt_hi = a == 7 ? 90.0 : a * 12.0 + 12.0, alt = a == 7 ? 90.0 : a * 12.0 + 6.0;
        const double s_lo = std::sin(alt_lo * kPi / 180), s_hi = std::sin(alt_hi * kPi / 180);
        const double weight = (s_hi * s_hi - s_lo * s_lo) / kCounts[a];
        const double tan_alt = a == 7 ? 1e300 : std::tan(alt * kPi / 180);
        for (int k = 0; k < kCounts[a]; ++k) {
          const double az = 2 * kPi * k / kCounts[a];
          const double ex = std::sin(az), ny = std::cos(az);  // towards the patch: east, north
          const double m = std::max(std::abs(ex), std::abs(ny));
          const double ux = ex / m, uy = ny / m, step_m = pixel / m;  // one pixel on the dominant axis
          const long max_steps = a == 7 ? 0 : long(std::ceil((hi - lo) / (tan_alt * step_m))) + 1;
          for (long r = rr.begin(); r != rr.end(); ++r)
            for (long c = 0; c < cols; ++c) {
              const double h = f.heights[std::size_t(r * cols + c)];
              if (std::isnan(h)) continue;
              bool shadow = false;
              for (long s = 1; s <= max_steps && !shadow; ++s) {
                const long qc = c + std::lround(double(s) * ux), qr = r - std::lround(double(s) * uy);  // rows run south
                if (qc < 0 || qr < 0 || qc >= cols || qr >= rows) break;
                const double hq = f.heights[std::size_t(qr * cols + qc)];
                shadow = !std::isnan(hq) && hq - double(s) * step_m * tan_alt > h;
              }
              if (!shadow) svf[std::size_t(r * cols + c)] += weight;
            }
        }
      }
    });
  });
  for (std::size_t i = 0; i < svf.size(); ++i)
    if (std::isnan(f.heights[i])) svf[i] = std::nan("");
  return svf;
}

void run(const char* name, const HeightField& f, int threads) {
  const auto t0 = Clock::now();
  const Scene scene(height_field_mesh(f, height_field_floor(f)));
  std::vector<QueryPoint> pts;
  for (std::size_t r = 0; r < f.rows; ++r)
    for (std::size_t c = 0; c < f.columns; ++c)
      if (!std::isnan(f.height(c, r))) pts.push_back({Vec3(f.centre_x(c), f.centre_y(r), f.height(c, r)), Vec3(0, 0, 1)});
  VisibilityOptions o;
  o.prefer_horizon = true;
  const SkyFactorsRun exact = compute_sky_factors(scene, pts, o, SkyFactorsMethod::automatic, threads);
  const double t_exact = seconds_since(t0);
  const auto t1 = Clock::now();
  const std::vector<double> sc = shadow_casting_svf(f, threads);
  const double t_sc = seconds_since(t1);
  double max_err = 0, mean_err = 0;
  std::size_t k = 0;
  for (std::size_t i = 0; i < f.heights.size(); ++i) {
    if (std::isnan(f.heights[i])) continue;
    const double e = std::abs(sc[i] - exact.factors[k++].svf);
    max_err = std::max(max_err, e), mean_err += e;
  }
  mean_err /= double(std::max<std::size_t>(k, 1));
  const double n = double(pts.size());
  std::printf("| %s | %zu × %zu | %zu | %.0f | %.0f | **%.2f×** | %.3f / %.4f | %zu horizon |\n", name, f.columns, f.rows,
              scene.soup().triangle_count(), n / t_exact, n / t_sc, t_sc / t_exact, max_err, mean_err, exact.by_horizon);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"skyband map --dsm against shadow casting (UMEP's estimator) on the same rasters"};
  std::size_t size = 200;
  int threads = 2;
  app.add_option("--size", size, "side of the synthetic rasters in pixels (1 m)");
  app.add_option("--threads", threads, "worker threads for both methods");
  CLI11_PARSE(app, argc, argv);
  if (size < 40) size = 40;
  std::printf("# %d threads; skyband: exact SVF of every pixel (time includes meshing and the column-solid classification)\n",
              threads);
  std::printf(
      "| raster | pixels | column triangles | skyband pixels/s | shadow casting (153 patches) pixels/s | ratio | shadow casting "
      "|error| max / mean | skyband method |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  run("synthetic city, flat ground", gen::synthetic_city_dsm(size, 5, false), threads);
  run("synthetic city, 0.3 m rough ground", gen::synthetic_city_dsm(size, 5, true), threads);
  return 0;
}
