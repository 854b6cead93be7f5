// Sky-model benchmark (skyband sky): cost of the NREL SPA, of one SkyModel construction per
// model (physical single/multiple, CIE with its physical spectral shape), of a radiance look-up
// through the SkyModel variant, of spectrum → XYZ → sRGB, and of a 512² fisheye render.
// Timings are this thread's CPU time (CLOCK_THREAD_CPUTIME_ID) so that other jobs on the shared
// machine do not inflate them; the multiple-scattering table build uses TBB on all cores, so
// constructions report wall time as well.
// Usage: bench_sky_model [--lookups N]
#include <chrono>
#include <cstdio>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "lighting/sky/sky_model.h"
#include "lighting/spectrum/colour.h"
#include "lighting/sun/sun.h"
#include "lighting/sun/sun_position.h"

using namespace skyband;

namespace {
double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
double deg(double d) {
  return d * kPi / 180.0;
}
volatile double g_sink = 0;  // keeps results alive
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sky model benchmark"};
  int lookups = 1000000;
  app.add_option("--lookups", lookups, "radiance look-ups per model");
  CLI11_PARSE(app, argc, argv);

  std::printf("%-44s %14s %14s\n", "operation", "cpu per op", "wall per op");
  // SPA.
  {
    SpaInput in;
    in.latitude_deg = 52.0;
    in.longitude_deg = 4.4;
    const int n = 200000;
    const double c0 = cpu_now(), w0 = wall_now();
    for (int i = 0; i < n; ++i) {
      in.time = LocalDateTime{2026, 6, 21, 0, 0, 60.0 * (i % 1440) * 0.999, 2.0};
      g_sink = g_sink + sun_position_spa(in).zenith_deg;
    }
    std::printf("%-44s %11.3f us %11.3f us\n", "NREL SPA (full, with nutation)", 1e6 * (cpu_now() - c0) / n,
                1e6 * (wall_now() - w0) / n);
  }
  // spectrum → sRGB
  {
    const int n = 2000000;
    Spectrum s = cie_d65();
    const double c0 = cpu_now(), w0 = wall_now();
    for (int i = 0; i < n; ++i) {
      s[i % kSpectrumSamples] += 1e-9;
      g_sink = g_sink + spectrum_to_linear_srgb(s).x();
    }
    std::printf("%-44s %11.3f ns %11.3f ns\n", "spectrum -> XYZ -> linear sRGB", 1e9 * (cpu_now() - c0) / n,
                1e9 * (wall_now() - w0) / n);
  }

  const Vec3 sun = direction_from_altitude_azimuth(deg(30), deg(180));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<Vec3> dirs(4096);
  for (auto& d : dirs) {  // uniform on the upper hemisphere
    const double z = u01(rng), a = 2 * kPi * u01(rng), r = std::sqrt(1 - z * z);
    d = Vec3(r * std::sin(a), r * std::cos(a), z);
  }
  for (const char* model : {"single", "multiple", "cie-12", "cie-overcast"}) {
    const double c0 = cpu_now(), w0 = wall_now();
    const SkyModel sky(AtmosphereParams{}, sun, parse_sky_model(model, "--model"));
    std::printf("%-44s %11.1f ms %11.1f ms\n", (std::string("build SkyModel ") + model).c_str(), 1e3 * (cpu_now() - c0),
                1e3 * (wall_now() - w0));
    Spectrum l;
    const double c1 = cpu_now(), w1 = wall_now();
    for (int i = 0; i < lookups; ++i) {
      sky.radiance_into(dirs[static_cast<std::size_t>(i) & 4095], l);
      g_sink = g_sink + l[20];
    }
    std::printf("%-44s %11.1f ns %11.1f ns\n", (std::string("  radiance look-up ") + model).c_str(),
                1e9 * (cpu_now() - c1) / lookups, 1e9 * (wall_now() - w1) / lookups);
    const double c2 = cpu_now(), w2 = wall_now();
    const int n = 512;
    for (int row = 0; row < n; ++row)
      for (int col = 0; col < n; ++col) {
        const double x = 2.0 * (col + 0.5) / n - 1.0, y = 1.0 - 2.0 * (row + 0.5) / n, r = std::hypot(x, y);
        if (r >= 1.0) continue;
        const double zen = r * 0.5 * kPi, az = std::atan2(-x, y);
        sky.radiance_into(Vec3(std::sin(az) * std::sin(zen), std::cos(az) * std::sin(zen), std::cos(zen)), l);
        g_sink = g_sink + spectrum_to_linear_srgb(l).y();
      }
    std::printf("%-44s %11.1f ms %11.1f ms\n", (std::string("  512x512 fisheye render ") + model).c_str(), 1e3 * (cpu_now() - c2),
                1e3 * (wall_now() - w2));
  }
  // A relit variant: a new sun, the same atmosphere (its multiple-scattering table is shared, so
  // only the sun-dependent sky table is rebuilt). CPU time is the calling thread's only.
  {
    const double c0 = cpu_now(), w0 = wall_now();
    const SkyModel sky(AtmosphereParams{}, direction_from_altitude_azimuth(deg(8), deg(250)),
                       parse_sky_model("multiple", "--model"));
    std::printf("%-44s %11.1f ms %11.1f ms\n", "rebuild SkyModel multiple, new sun", 1e3 * (cpu_now() - c0),
                1e3 * (wall_now() - w0));
  }
  return 0;
}
