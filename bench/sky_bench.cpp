// Sky benchmark: cost of the atmosphere tables, of one SkyTable per sun position (single and
// multiple scattering), of a table look-up and of a direct integral, and the effect of multiple
// scattering on the low-sun sky (ratios multiple/single of the zenith radiance and of the diffuse
// horizontal irradiance at the paper's solar altitudes 4°, 8°, 17°, 60°).
// Usage: bench_sky [--lookups N]
#include <chrono>
#include <cstdio>
#include <ctime>
#include <random>
#include <vector>

#include <CLI/CLI.hpp>

#include "lighting/atmosphere/atmosphere.h"
#include "lighting/atmosphere/sky_table.h"
#include "lighting/spectrum/colour.h"
#include "lighting/sun/sun.h"

using namespace skyband;

namespace {
// Timings are this thread's CPU time (CLOCK_THREAD_CPUTIME_ID), so that other jobs sharing the
// machine do not inflate them; the multiple-scattering table is built by TBB on all cores, so
// its row reports wall time instead.
struct Clock {
  using time_point = double;
  static double now() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
};
double seconds_since(double t0) {
  return Clock::now() - t0;
}
double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
double deg(double d) {
  return d * kPi / 180.0;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sky atmosphere / sky table benchmark"};
  int lookups = 2000000;
  app.add_option("--lookups", lookups, "number of table look-ups to time")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);

  const AtmosphereParams params;  // defaults: AOD550 0.1, α 1.3, 300 DU, sea level, albedo 0.1
  auto t0 = Clock::now();
  const Atmosphere atm(params);
  const double t_atm = seconds_since(t0);
  const double w0 = wall_now();
  Spectrum scratch;
  atm.multiple_scattering_transfer(atm.observer_radius_m(), 0.5, scratch);  // builds the Ψ_ms table
  const double t_ms = wall_now() - w0;

  std::printf("# skyband sky benchmark (defaults: AOD550 %.2f, alpha %.2f, ozone %.0f DU, albedo %.2f)\n", params.aod550,
              params.angstrom_alpha, params.ozone_du, params.ground_albedo);
  std::printf("%-48s %12.3f ms\n", "Atmosphere construction (column table 64x256)", 1e3 * t_atm);
  std::printf("%-48s %12.3f ms\n", "multiple-scattering table (16x32, once; WALL)", 1e3 * t_ms);

  const Vec3 sun17 = direction_from_altitude_azimuth(deg(17), deg(240));
  for (auto orders : {ScatteringOrders::Single, ScatteringOrders::Multiple}) {
    t0 = Clock::now();
    const SkyTable table(atm, sun17, orders);
    const double t_table = seconds_since(t0);
    std::printf(
        "%-48s %12.3f ms\n",
        orders == ScatteringOrders::Single ? "SkyTable build, single (48x48 nodes)" : "SkyTable build, multiple (48x48 nodes)",
        1e3 * t_table);
    // Look-ups at pre-generated random upper-hemisphere directions.
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    std::vector<Vec3> dirs(4096);
    for (auto& d : dirs) {
      const double z = U(rng), phi = 2.0 * kPi * U(rng), s = std::sqrt(1.0 - z * z);
      d = Vec3(s * std::cos(phi), s * std::sin(phi), z);
    }
    Spectrum out;
    double sink = 0;
    t0 = Clock::now();
    for (int k = 0; k < lookups; ++k) {
      table.radiance_into(dirs[static_cast<std::size_t>(k) & 4095], out);
      sink += out[20];
    }
    const double t_lookup = seconds_since(t0) / lookups;
    t0 = Clock::now();
    const int direct_n = 2000;
    for (int k = 0; k < direct_n; ++k) sink += atm.sky_radiance(dirs[static_cast<std::size_t>(k)], sun17, orders)[20];
    const double t_direct = seconds_since(t0) / direct_n;
    std::printf("%-48s %12.1f ns   (checksum %.3g)\n", "  radiance_into per look-up (41 samples)", 1e9 * t_lookup, sink);
    std::printf("%-48s %12.1f ns\n", "  direct sky_radiance per direction", 1e9 * t_direct);
  }

  std::printf("\n# multiple/single ratios (sun azimuth 240 deg); zenith radiance and diffuse horizontal irradiance\n");
  std::printf("%8s | %10s %10s %10s %12s | %10s %10s %10s %12s\n", "sun alt", "Lz 450nm", "Lz 550nm", "Lz 650nm", "Lz lumin.",
              "Ed 450nm", "Ed 550nm", "Ed 650nm", "Ed illum.");
  for (double alt : {4.0, 8.0, 17.0, 60.0}) {
    const Vec3 sun = direction_from_altitude_azimuth(deg(alt), deg(240));
    const SkyTable single(atm, sun, ScatteringOrders::Single);
    const SkyTable multiple(atm, sun, ScatteringOrders::Multiple);
    const Spectrum lz1 = atm.sky_radiance(Vec3(0, 0, 1), sun, ScatteringOrders::Single);
    const Spectrum lz2 = atm.sky_radiance(Vec3(0, 0, 1), sun, ScatteringOrders::Multiple);
    const Spectrum ed1 = single.horizontal_irradiance();
    const Spectrum ed2 = multiple.horizontal_irradiance();
    std::printf("%7.0f° | %10.3f %10.3f %10.3f %12.3f | %10.3f %10.3f %10.3f %12.3f\n", alt, lz2[7] / lz1[7], lz2[17] / lz1[17],
                lz2[27] / lz1[27], luminous(lz2) / luminous(lz1), ed2[7] / ed1[7], ed2[17] / ed1[17], ed2[27] / ed1[27],
                luminous(ed2) / luminous(ed1));
  }
  std::printf("\n# absolute values with multiple scattering (zenith luminance cd/m2, diffuse / direct-normal illuminance klx)\n");
  std::printf("%8s %14s %14s %14s\n", "sun alt", "Lz cd/m2", "Ed klx", "Edn klx");
  for (double alt : {4.0, 8.0, 17.0, 60.0}) {
    const Vec3 sun = direction_from_altitude_azimuth(deg(alt), deg(240));
    const SkyTable multiple(atm, sun, ScatteringOrders::Multiple);
    std::printf("%7.0f° %14.0f %14.2f %14.2f\n", alt, luminous(atm.sky_radiance(Vec3(0, 0, 1), sun, ScatteringOrders::Multiple)),
                luminous(multiple.horizontal_irradiance()) / 1e3, luminous(atm.sun_direct_normal(deg(alt))) / 1e3);
  }
  return 0;
}
