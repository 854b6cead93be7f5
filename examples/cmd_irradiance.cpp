// skyband irradiance — sky and sun irradiance and illuminance on calculation points.
//
//   skyband irradiance --mesh FILE [--mesh FILE ...] --points FILE.csv --out FILE.csv
//                      (--sun-altitude DEG [--sun-azimuth DEG] | --lat DEG --lon DEG --time ISO8601)
//                      [--model multiple|single|cie-N|cie-overcast] [--aod550 ...] [--bands N | --tolerance T]
//                      [--threads K] [--quiet]
//   skyband irradiance --demo --sun-altitude DEG [--sun-azimuth DEG]
//   skyband irradiance --mesh ... --points ... --out ... --times TIMES.csv [--lat DEG --lon DEG] [sky options]
//
// Points as for `skyband svf` (metres, z up; normals default to +z). Per point, on the plane of
// its normal (lighting/point_irradiance.h): the sky through the exact visible α-intervals of the
// point's bands, the sun with the exact shadow test of the sun's centre. The output holds the input
// rows in input order plus
//   svf, sky_exposure     as `skyband svf`
//   cos_incidence         cosine of the sun's angle of incidence on the face (< 0: sun behind it)
//   sun_visible           1 if the sun is above the horizon, in front of the face and not hidden
//   sky_W_m2, sun_W_m2, global_W_m2   irradiance, W·m⁻², integrated over 380–780 nm
//   sky_lx, sun_lx, global_lx         illuminance, lux
//   sky_ratio             sky_lx / that of an unobstructed horizontal face under the same sky
//                         (with --model cie-overcast: the vertical sky component of a window)
// written atomically. With --times, sums over the file's moments (each weighted by its `hours`):
//   svf, sky_exposure, sun_hours, sky_Wh_m2, sun_Wh_m2, global_Wh_m2 (W·h·m⁻², 380–780 nm),
//   sky_lxh, sun_lxh, global_lxh (lx·h): one geometry pass, one quadrature of the time-summed sky
//   per point, one exact shadow test per moment and point.
// Not included: light reflected by the ground and the buildings.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>

#include "examples/command_registry.h"
#include "examples/demo_scene.h"
#include "examples/point_job_args.h"
#include "examples/sun_sky_options.h"
#include "geometry/input_error.h"
#include "io/csv_table.h"
#include "io/points_csv.h"
#include "lighting/colour.h"
#include "lighting/point_irradiance.h"

namespace skyband::cli {

namespace {

// How the points were computed (by method), in plain words.
template <class Result>
std::string summary(const std::vector<Result>& r) {
  std::size_t n[3] = {0, 0, 0};
  for (const Result& x : r) ++n[int(x.method)];
  return method_summary(n[int(SkyMethod::exact_horizon)], n[int(SkyMethod::exact_union)], n[int(SkyMethod::bands)]);
}

struct IrradianceArgs {
  PointJobArgs job;
  SunSkyOptions sun_sky;
  std::string times;
  bool demo = false;
};

// Accuracy and threads from the shared per-point options (validated there).
PointIrradianceOptions irradiance_options(const PointJobArgs& job) {
  PointIrradianceOptions opt;
  opt.visibility = job.visibility_options();
  opt.method = job.method();
  opt.threads = job.threads;
  return opt;
}

// The moments of a times file: a header with either `time` (ISO 8601 local time; needs --lat and
// --lon) or `sun_altitude` and `sun_azimuth` (degrees), and optionally `hours` (the duration each
// row stands for, ≥ 0; default 1). Errors name the file, line, column and value.
std::vector<SunMoment> read_moments(const IrradianceArgs& a) {
  const CsvTable csv = read_csv_table(a.times, "times file");
  const std::string header_at = a.times + ":" + std::to_string(csv.header_line);
  const int ct = csv.column("time"), calt = csv.column("sun_altitude"), caz = csv.column("sun_azimuth"),
            ch = csv.column("hours");
  const bool by_time = ct >= 0, by_angle = calt >= 0 || caz >= 0;
  if (by_time == by_angle)
    throw InputError(header_at + ": give either a 'time' column or 'sun_altitude' and 'sun_azimuth' columns");
  if (by_angle && (calt < 0 || caz < 0)) throw InputError(header_at + ": 'sun_altitude' and 'sun_azimuth' come together");
  std::vector<SunMoment> moments;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    SunMoment m;
    if (by_time) {
      m.sun_dir = a.sun_sky.sun_at(trim_csv_cell(csv.rows[r][static_cast<std::size_t>(ct)]), csv.where(r)).direction();
    } else {
      const double alt = csv.number(r, calt), az = csv.number(r, caz);
      if (alt < -90 || alt > 90) throw InputError(csv.where(r) + ": sun_altitude " + fmt(alt) + " must be in [-90, 90] degrees");
      m.sun_dir = SunPlacement{alt, az, {}}.direction();
    }
    if (ch >= 0) {
      m.hours = csv.number(r, ch);
      if (m.hours < 0) throw InputError(csv.where(r) + ": hours " + fmt(m.hours) + " must be >= 0");
    }
    moments.push_back(m);
  }
  if (moments.empty()) throw InputError(a.times + ": no moments (the file has a header only)");
  return moments;
}

// --times: irradiation summed over the file's moments.
void run_times(const IrradianceArgs& a) {
  if (a.sun_sky.moment_given())
    throw InputError("--times: the suns come from the times file; --sun-altitude, --sun-azimuth and --time do not "
                     "apply (--tz gives the UTC offset of times written without one)");
  const PointIrradianceOptions opt = irradiance_options(a.job);
  const AtmosphereParams atm = a.sun_sky.atmosphere();
  const SkyModelSpec spec = a.sun_sky.sky_spec();
  const std::vector<SunMoment> moments = read_moments(a);

  TriangleSoup soup = a.job.load_meshes();
  const PointsTable table = read_points_csv(a.job.points);
  const auto t0 = std::chrono::steady_clock::now();
  const Scene scene(std::move(soup));
  Progress progress("irradiance", !a.job.quiet), sky_progress("irradiance: skies", !a.job.quiet, "moments");
  const std::vector<PointIrradiation> r = compute_point_irradiation(
      scene, table.points, atm, spec, moments, opt, [&](std::size_t d, std::size_t t) { progress(d, t); },
      [&](std::size_t d, std::size_t t) { sky_progress(d, t); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const std::vector<std::string> columns = {"svf",        "sky_exposure", "sun_hours", "sky_Wh_m2", "sun_Wh_m2",
                                            "global_Wh_m2", "sky_lxh",    "sun_lxh",   "global_lxh"};
  std::vector<std::vector<double>> values(columns.size(), std::vector<double>(r.size()));
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double v[] = {r[i].svf,       r[i].sky_exposure, r[i].sun_hours, r[i].sky_Wh_m2, r[i].sun_Wh_m2,
                        r[i].sky_Wh_m2 + r[i].sun_Wh_m2,   r[i].sky_lxh,   r[i].sun_lxh,   r[i].sky_lxh + r[i].sun_lxh};
    for (std::size_t c = 0; c < columns.size(); ++c) values[c][i] = v[c];
  }
  write_points_csv(a.job.out, table, columns, values);
  if (!a.job.quiet) {
    double hours = 0;
    for (const SunMoment& m : moments) hours += m.hours;
    std::fprintf(stderr, "irradiance: %zu points x %zu moments (%.2f h) in %.2f s; %s; wrote %s\n", r.size(), moments.size(),
                 hours, seconds, summary(r).c_str(), a.job.out.c_str());
  }
}

// The built-in street block of `svf --demo` under the given sun and sky: a table on stdout.
void run_demo(const IrradianceArgs& a) {
  const PointIrradianceOptions opt = irradiance_options(a.job);
  const SunPlacement sun = a.sun_sky.place_sun();
  const SkyModel sky = a.sun_sky.make_sky(sun);
  const DemoScene demo = make_demo_scene();
  const Scene scene(demo.soup);
  std::vector<QueryPoint> pts;
  for (const auto& p : demo.points) pts.push_back(p.point);
  const std::vector<PointIrradiance> r = compute_point_irradiance(scene, pts, sky, opt);
  std::printf("skyband irradiance --demo: built-in street block, sun altitude %.1f deg, azimuth %.1f deg, sky %s\n",
              sun.altitude_deg, sun.azimuth_deg, sky.model_name().c_str());
  std::printf("%-36s %6s %4s %9s %9s %9s %9s\n", "point", "svf", "sun", "sky W/m2", "sun W/m2", "global lx", "sky ratio");
  for (std::size_t i = 0; i < pts.size(); ++i)
    std::printf("%-36s %6.4f %4s %9.1f %9.1f %9.0f %9.4f\n", demo.points[i].name.c_str(), r[i].svf,
                r[i].sun_visible ? "yes" : "no", r[i].sky_W_m2, r[i].sun_W_m2, r[i].sky_lx + r[i].sun_lx, r[i].sky_ratio);
  std::printf("W/m2 over 380-780 nm; no ground or inter-reflected light\n");
}

void run(const IrradianceArgs& a) {
  if (a.demo) {
    if (!a.times.empty()) throw InputError("--demo takes one sun (--sun-altitude or --lat/--lon/--time), not --times");
    return run_demo(a);
  }
  if (!a.times.empty()) {
    a.job.require_files("irradiance");
    return run_times(a);
  }
  // Everything the user typed is validated before any file is read or written.
  a.job.require_files("irradiance", " (or --demo)");
  const PointIrradianceOptions opt = irradiance_options(a.job);
  const SunPlacement sun = a.sun_sky.place_sun();
  const SkyModel sky = a.sun_sky.make_sky(sun);

  TriangleSoup soup = a.job.load_meshes();
  const PointsTable table = read_points_csv(a.job.points);
  const auto t0 = std::chrono::steady_clock::now();
  const Scene scene(std::move(soup));
  Progress progress("irradiance", !a.job.quiet);
  const std::vector<PointIrradiance> r =
      compute_point_irradiance(scene, table.points, sky, opt, [&](std::size_t d, std::size_t t) { progress(d, t); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const std::vector<std::string> columns = {"svf",      "sky_exposure", "cos_incidence", "sun_visible",
                                            "sky_W_m2", "sun_W_m2",     "global_W_m2",   "sky_lx",
                                            "sun_lx",   "global_lx",    "sky_ratio"};
  std::vector<std::vector<double>> values(columns.size(), std::vector<double>(r.size()));
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double v[] = {r[i].svf,      r[i].sky_exposure,           r[i].cos_incidence, r[i].sun_visible ? 1.0 : 0.0,
                        r[i].sky_W_m2, r[i].sun_W_m2,               r[i].sky_W_m2 + r[i].sun_W_m2,
                        r[i].sky_lx,   r[i].sun_lx,                 r[i].sky_lx + r[i].sun_lx,
                        r[i].sky_ratio};
    for (std::size_t c = 0; c < columns.size(); ++c) values[c][i] = v[c];
  }
  write_points_csv(a.job.out, table, columns, values);
  if (!a.job.quiet) {
    const Spectrum& dn = sky.sun_direct_normal();
    const std::size_t n = r.size();
    const double mean_global = n ? std::accumulate(values[6].begin(), values[6].end(), 0.0) / double(n) : 0.0;
    std::fprintf(stderr,
                 "irradiance: sun altitude %.3f deg, azimuth %.3f deg, direct normal %.1f W/m2 (%.0f lx); sky %s\n",
                 sun.altitude_deg, sun.azimuth_deg, dn.integral_nm(), luminous(dn), sky.model_name().c_str());
    std::fprintf(stderr,
                 "irradiance: %zu points in %.2f s (%.0f points/s), mean global %.1f W/m2 (380-780 nm); %s; wrote %s\n",
                 n, seconds, seconds > 0 ? double(n) / seconds : 0.0, mean_global, summary(r).c_str(),
                 a.job.out.c_str());
  }
}

CommandRegistration registration{"irradiance", [](CLI::App& app) {
  auto args = std::make_shared<IrradianceArgs>();
  CLI::App* cmd = app.add_subcommand(
      "irradiance",
      "Sky and sun irradiance (W/m2, 380-780 nm) and illuminance (lux) on calculation points: the sky through the\n"
      "exact visible sky of each point, the sun with an exact shadow test. Points and accuracy options as for svf.\n"
      "Coordinates: metres, z up (x east, y north); azimuth clockwise from north. Output columns: svf, sky_exposure,\n"
      "cos_incidence, sun_visible, sky_W_m2, sun_W_m2, global_W_m2, sky_lx, sun_lx, global_lx, sky_ratio (sky_lx over\n"
      "that of an open horizontal face; with --model cie-overcast the vertical sky component of a window).\n"
      "With --times FILE: sums over the file's moments instead: sun_hours, sky_Wh_m2, sun_Wh_m2, global_Wh_m2, sky_lxh,\n"
      "sun_lxh, global_lxh (each moment weighted by its 'hours').\n"
      "Not included: light reflected by the ground and the buildings.");
  args->job.add_to(cmd, "Output CSV (input rows + the columns above), written atomically");
  args->sun_sky.add_to(cmd);
  cmd->add_option("--times", args->times,
                  "CSV of moments: 'time' (ISO 8601, with --lat --lon) or 'sun_altitude','sun_azimuth' (degrees), "
                  "optional 'hours' (default 1); outputs sums over them instead of one moment (see --help above)");
  cmd->add_flag("--demo", args->demo, "Run on the built-in demo street block and print a table (needs a sun)");
  cmd->callback([args] { run(*args); });
  return cmd;
}};

}  // namespace

}  // namespace skyband::cli
