// bench_climate: a whole year of weather at city points against `skyband svf` on the same points,
// side by side in one run (the machine is shared: the ratio is the figure to read).
//
//   bench_climate [--points N] [--weather FILE.epw] [--mesh FILE] [--threads T] [--large N]
//
// Default: 2,000 points of the Rotterdam LoD2 block (../shared/data/buildings, half street and
// half facade, tests/geometry/support/real_mesh_points.h) and the Heino TMYx year (8760 h,
// ../shared/data/weather). Reports the seconds of the SVF pass and of the year (lighting/
// climate_irradiation.h: the time-integrated Perez sky, one sky integral, 8760 sun look-ups and
// one ground pass per point), their ratio (target ≤ 10), and with --large N the wall time and
// peak memory of the year at N points.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "geometry/support/real_mesh_points.h"
#include "geometry/visibility/sky_factors.h"
#include "io/epw_reader.h"
#include "io/mesh_reader.h"
#include "lighting/climate/climate_irradiation.h"
#include "lighting/climate/weather_hours.h"

using namespace skyband;

namespace {
double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}
}  // namespace

int main(int argc, char** argv) {
  std::size_t points = 2000, large = 0;
  int threads = 2;
  const std::filesystem::path data(SKYBAND_SHARED_DATA);
  std::string weather = (data / "weather" / "NLD_OV_Heino.062780_TMYx.2007-2021.epw").string();
  std::string mesh = (data / "buildings" / "rotterdam_delfshaven_blockA_lod2.obj").string();
  CLI::App app{"bench_climate: a year of weather against svf on the same points"};
  app.add_option("--points", points)->capture_default_str();
  app.add_option("--weather", weather)->capture_default_str();
  app.add_option("--mesh", mesh)->capture_default_str();
  app.add_option("--threads", threads)->capture_default_str();
  app.add_option("--large", large, "also the year at this many points (wall time, peak memory)");
  CLI11_PARSE(app, argc, argv);

  const Scene scene(read_mesh(mesh));
  const WeatherSeries series = read_epw(weather);
  const std::vector<WeatherHour> hours = weather_hours(series, {});
  ClimateIrradiationOptions opt;
  opt.threads = threads;
  std::printf("# %s, %zu triangles; %s, %zu intervals; %d threads\n", std::filesystem::path(mesh).filename().c_str(),
              scene.soup().triangle_count(), std::filesystem::path(weather).filename().c_str(), hours.size(), threads);
  std::printf(
      "| points | svf s | year s | year / svf | svf points/s | year points/s | peak RSS MB |\n|---|---|---|---|---|---|---|\n");
  const auto row = [&](std::size_t n) {
    const std::vector<QueryPoint> pts = gen::real_mesh_points(scene, n, 21);
    // The fastest of two runs of each (noise on a shared machine only slows).
    double t_svf = 1e300, t_year = 1e300;
    for (int r = 0; r < 2; ++r) {
      auto t0 = std::chrono::steady_clock::now();
      const SkyFactorsRun svf = compute_sky_factors(scene, pts, VisibilityOptions{}, SkyFactorsMethod::automatic, threads);
      t_svf = std::min(t_svf, since(t0));
      t0 = std::chrono::steady_clock::now();
      const ClimateRun year = compute_point_climate(scene, pts, hours, opt);
      t_year = std::min(t_year, since(t0));
      if (svf.factors.size() != year.points.size()) return;
    }
    std::printf("| %zu | %.3f | %.3f | **%.1f×** | %.0f | %.0f | %.0f |\n", pts.size(), t_svf, t_year, t_year / t_svf,
                pts.size() / t_svf, pts.size() / t_year, peak_rss_mb());
    std::fflush(stdout);
  };
  row(points);
  if (large > 0) row(large);
  return 0;
}
