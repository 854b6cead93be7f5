// bench_point_memory: peak memory of the per-point jobs as the number of points grows — the
// figure a user sizing a city run needs (bytes per point) and the check that memory is bounded
// by the data, not by a declared count or a per-point cache.
//
//   bench_point_memory [--mesh FILE] [--weather FILE.epw] [--small N] [--large N] [--threads T]
//
// Each job runs in its own child process (fork), so that each peak (getrusage ru_maxrss of the
// child) is its own: load the mesh, make N points (half street, half facade:
// tests/geometry/support/real_mesh_points.h), then either the SVF pass (`skyband svf`:
// compute_sky_factors) or a year of weather (`skyband irradiance --weather`:
// compute_point_climate). Reported: peak RSS at --small and --large points and
// (peak_large − peak_small) / (large − small), the bytes each further point costs.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "geometry/support/real_mesh_points.h"
#include "geometry/visibility/sky_factors.h"
#include "io/epw_reader.h"
#include "io/mesh_reader.h"
#include "lighting/climate/climate_irradiation.h"
#include "lighting/climate/weather_hours.h"
#include "support/child_process.h"

using namespace skyband;

namespace {

struct ChildResult {
  double peak_mb = 0, seconds = 0;
  std::size_t points = 0;
};

// Runs job(n) in a child process; returns its peak RSS and wall time.
template <class Job>
ChildResult in_child(Job&& job, std::size_t n) {
  return bench::in_child([&] {
    const auto t0 = std::chrono::steady_clock::now();
    ChildResult r;
    r.points = job(n);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    r.peak_mb = u.ru_maxrss / 1024.0;
    return r;
  });
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t small = 1000, large = 100000;
  int threads = 2;
  const std::filesystem::path data(SKYBAND_SHARED_DATA);
  std::string weather = (data / "weather" / "NLD_OV_Heino.062780_TMYx.2007-2021.epw").string();
  std::string mesh = (data / "buildings" / "rotterdam_delfshaven_blockA_lod2.obj").string();
  CLI::App app{"bench_point_memory: peak memory of svf and irradiance --weather against the number of points"};
  app.add_option("--mesh", mesh)->capture_default_str();
  app.add_option("--weather", weather)->capture_default_str();
  app.add_option("--small", small)->capture_default_str();
  app.add_option("--large", large)->capture_default_str();
  app.add_option("--threads", threads)->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const auto svf_job = [&](std::size_t n) {
    const Scene scene(read_mesh(mesh));
    const std::vector<QueryPoint> pts = gen::real_mesh_points(scene, n, 21);
    return compute_sky_factors(scene, pts, VisibilityOptions{}, SkyFactorsMethod::automatic, threads).factors.size();
  };
  const auto year_job = [&](std::size_t n) {
    const Scene scene(read_mesh(mesh));
    const std::vector<QueryPoint> pts = gen::real_mesh_points(scene, n, 21);
    const std::vector<WeatherHour> hours = weather_hours(read_epw(weather), {});
    ClimateIrradiationOptions opt;
    opt.threads = threads;
    return compute_point_climate(scene, pts, hours, opt).points.size();
  };
  std::printf("# %s; %s; %d threads; each job in its own process\n", std::filesystem::path(mesh).filename().c_str(),
              std::filesystem::path(weather).filename().c_str(), threads);
  std::printf(
      "| job | points | peak RSS MB | s | points | peak RSS MB | s | bytes per further point "
      "|\n|---|---|---|---|---|---|---|---|\n");
  for (const auto& [name, job] :
       {std::pair<const char*, std::function<std::size_t(std::size_t)>>{"svf", svf_job},
        std::pair<const char*, std::function<std::size_t(std::size_t)>>{"irradiance --weather (year)", year_job}}) {
    const ChildResult a = in_child(job, small), b = in_child(job, large);
    const double per_point = b.points > a.points ? (b.peak_mb - a.peak_mb) * 1048576.0 / double(b.points - a.points) : 0;
    std::printf("| %s | %zu | %.1f | %.2f | %zu | %.1f | %.2f | %.0f |\n", name, a.points, a.peak_mb, a.seconds, b.points,
                b.peak_mb, b.seconds, per_point);
    std::fflush(stdout);
  }
  return 0;
}
