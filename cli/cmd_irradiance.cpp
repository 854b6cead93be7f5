// skyband irradiance — sky and sun irradiance and illuminance on calculation points.
//
//   skyband irradiance --mesh FILE [--mesh FILE ...] --points FILE.csv --out FILE.csv
//                      (--sun-altitude DEG [--sun-azimuth DEG] | --lat DEG --lon DEG --time ISO8601)
//                      [--model multiple|single|cie-N|cie-overcast] [--aod550 ...] [--bands N | --tolerance T]
//                      [--threads K] [--quiet]
//   skyband irradiance --demo --sun-altitude DEG [--sun-azimuth DEG]
//   skyband irradiance --mesh ... --points ... --out ... --times TIMES.csv [--lat DEG --lon DEG] [sky options]
//   skyband irradiance --mesh ... --points ... --out ... --weather FILE.epw|FILE.csv (EPW or TMY3) [--from MM-DD --to MM-DD]
//                      [--albedo R] [--ground-materials NAME,...] [--sun-at start|middle|end]
//
// Points as for `skyband svf` (metres, z up; normals default to +z). Per point, on the plane of
// its normal (lighting/integrals/point_irradiance.h): the sky through the exact visible α-intervals of the
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
// Not included in these: light reflected by the ground and the buildings.
// With --weather, sums over the weather file's period (lighting/climate/climate_irradiation.h: the Perez
// all-weather sky of each hour, the sun from its DNI, the ground seen below the horizon), in
// broadband shortwave kWh·m⁻² as the file measures: svf, sky_exposure, ground_view,
// global_kWh_m2, sky_kWh_m2, sun_kWh_m2, ground_kWh_m2, global_klxh (kilolux-hours), sun_hours.
// The file's warnings, its timing check (radiation against the sun, weather_timing.h) and its
// closure check (GHI against DHI + DNI·cos z, weather_closure.h) go to stderr.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numeric>
#include <optional>
#include <tuple>

#include "cli/command_registry.h"
#include "cli/demo_scene.h"
#include "cli/point_job_args.h"
#include "cli/provenance.h"
#include "cli/sun_sky_options.h"
#include "geometry/core/input_error.h"
#include "io/csv_table.h"
#include "io/epw_reader.h"
#include "io/hourly_netcdf.h"
#include "io/points_csv.h"
#include "io/tmy3_reader.h"
#include "lighting/climate/climate_irradiation.h"
#include "lighting/climate/moment_series.h"
#include "lighting/climate/weather_closure.h"
#include "lighting/climate/weather_hours.h"
#include "lighting/climate/weather_timing.h"
#include "lighting/integrals/point_irradiance.h"
#include "lighting/spectrum/colour.h"

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
  std::string weather, from, to, hourly;
  std::optional<double> albedo;
  std::string sun_at;  // --sun-at start|middle|end
  std::vector<std::string> ground_materials;
  CLI::Option* o_ground = nullptr;
  std::string dates, zone;  // --date FIRST[:LAST], --zone NAME
  double step_minutes = 10;
  CLI::Option* o_step = nullptr;
  bool sun_only = false;
};

// The moments of --date/--step/--zone (lighting/climate/moment_series.h): every step through the days,
// at the middle of each step, with the sun by the SPA at --lat/--lon.
// The files an irradiance run reads (for the provenance record).
std::vector<std::pair<std::string, std::string>> input_files(const IrradianceArgs& a) {
  auto inputs = a.job.input_files();
  inputs.emplace_back("--times", a.times);
  inputs.emplace_back("--weather", a.weather);
  return inputs;
}

std::vector<SunMoment> generated_moments(const IrradianceArgs& a) {
  MomentSeriesSpec spec;
  std::tie(spec.first_date, spec.last_date) = parse_date_range(a.dates, "--date");
  spec.step_minutes = a.step_minutes;
  spec.zone = a.zone;
  spec.utc_offset_hours = a.sun_sky.utc_offset_given();
  const std::vector<TimedMoment> times = moment_series(spec);
  std::vector<SunMoment> moments;
  moments.reserve(times.size());
  for (const TimedMoment& t : times) moments.push_back({a.sun_sky.sun_at(t.time, "--date").direction(), t.hours});
  return moments;
}

// Accuracy and threads from the shared per-point options (validated there).
PointIrradianceOptions irradiance_options(const PointJobArgs& job) {
  PointIrradianceOptions opt;
  opt.visibility = job.visibility_options();
  opt.method = job.method();
  opt.threads = job.threads;
  return opt;
}

// The longest a times-file row may stand for: a leap year, 366 · 24 h. It keeps every sum over the
// moments finite (two rows of 1e308 h summed to inf).
constexpr double kMaxHoursPerMoment = 8784;

// The sun of a times-file row's `time`: errors name the file and line, also the range checks of
// the SPA (lighting/sun/sun_position.cpp), which know no file.
Vec3 sun_of_time_cell(const IrradianceArgs& a, const CsvTable& csv, std::size_t r, int column) {
  const std::string where = csv.where(r);
  const std::string time = csv.text(r, column);  // no control characters: a NUL would cut messages short
  try {
    return a.sun_sky.sun_at(time, where).direction();
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.starts_with(where + " ") || what.starts_with(where + ":")) throw;  // parse_iso8601 names it
    throw InputError(where + ": column 'time': value '" + time + "': " + what);
  }
}

// The moments of a times file: a header with either `time` (ISO 8601 local time; needs --lat and
// --lon) or `sun_altitude` and `sun_azimuth` (degrees: altitude in [-90, 90], azimuth in
// [-360, 360] clockwise from north, as in a scene file), and optionally `hours` (the duration each
// row stands for, in [0, 8784] h; default 1). Errors name the file, line, column and value.
std::vector<SunMoment> read_moments(const IrradianceArgs& a) {
  const CsvTable csv = read_csv_table(a.times, "times file");
  const std::string header_at = a.times + ":" + std::to_string(csv.header_line);
  const int ct = csv.column("time"), calt = csv.column("sun_altitude"), caz = csv.column("sun_azimuth"), ch = csv.column("hours");
  const bool by_time = ct >= 0, by_angle = calt >= 0 || caz >= 0;
  if (by_time == by_angle)
    throw InputError(header_at + ": give either a 'time' column or 'sun_altitude' and 'sun_azimuth' columns");
  if (by_angle && (calt < 0 || caz < 0)) throw InputError(header_at + ": 'sun_altitude' and 'sun_azimuth' come together");
  std::vector<SunMoment> moments;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    SunMoment m;
    if (by_time) {
      m.sun_dir = sun_of_time_cell(a, csv, r, ct);
    } else {
      const double alt = csv.number(r, calt), az = csv.number(r, caz);
      if (alt < -90 || alt > 90) throw InputError(csv.where(r) + ": sun_altitude " + fmt(alt) + " must be in [-90, 90] degrees");
      if (az < -360 || az > 360)
        throw InputError(csv.where(r) + ": sun_azimuth " + fmt(az) + " must be in [-360, 360] degrees (clockwise from north)");
      const double az360 = std::fmod(az, 360.0);
      m.sun_dir = SunPlacement{alt, az360 < 0 ? az360 + 360.0 : az360, {}}.direction();
    }
    if (ch >= 0) {
      m.hours = csv.number(r, ch);
      if (m.hours < 0 || m.hours > kMaxHoursPerMoment)
        throw InputError(csv.where(r) + ": hours " + fmt(m.hours) +
                         " must be in [0, 8784] (a row stands for at most a leap year)");
    }
    moments.push_back(m);
  }
  if (moments.empty()) throw InputError(a.times + ": no moments (the file has a header only)");
  return moments;
}

// --sun-only: sun hours over the moments, no sky model.
void run_sun_hours(const IrradianceArgs& a, const std::vector<SunMoment>& moments) {
  const PointIrradianceOptions opt = irradiance_options(a.job);
  const std::vector<std::string> columns = {"svf", "sky_exposure", "sun_hours"};
  const PointsTable table = a.job.read_points(columns);
  TriangleSoup soup = a.job.load_meshes();
  const auto t0 = std::chrono::steady_clock::now();
  const Scene scene(std::move(soup));
  a.job.warn_about_points("irradiance", scene, table);
  Progress progress("irradiance", !a.job.quiet);
  const std::vector<PointIrradiation> r =
      compute_point_sun_hours(scene, table.points, moments, opt, [&](std::size_t d, std::size_t t) { progress(d, t); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::vector<std::vector<double>> values(columns.size(), std::vector<double>(r.size()));
  for (std::size_t i = 0; i < r.size(); ++i) {
    values[0][i] = r[i].svf;
    values[1][i] = r[i].sky_exposure;
    values[2][i] = r[i].sun_hours;
  }
  write_points_csv(a.job.out, table, columns, values);
  write_provenance(a.job.out, input_files(a));
  if (!a.job.quiet) {
    double hours = 0;
    for (const SunMoment& m : moments) hours += m.hours;
    std::fprintf(stderr, "irradiance: sun hours of %zu points over %zu moments (%.2f h) in %.2f s; %s; wrote %s\n", r.size(),
                 moments.size(), hours, seconds, summary(r).c_str(), a.job.out.c_str());
  }
}

// --times / --date: irradiation summed over the moments.
void run_times(const IrradianceArgs& a) {
  const char* source = a.times.empty() ? "--date" : "--times";
  if (a.sun_sky.moment_given())
    throw InputError(std::string(source) + ": the suns come from " + (a.times.empty() ? "the dates" : "the times file") +
                     "; --sun-altitude, --sun-azimuth and --time do not apply (--tz gives the UTC offset of times "
                     "written without one)");
  const PointIrradianceOptions opt = irradiance_options(a.job);
  const AtmosphereParams atm = a.sun_sky.atmosphere();
  const SkyModelSpec spec = a.sun_sky.sky_spec();
  const std::vector<SunMoment> moments = a.times.empty() ? generated_moments(a) : read_moments(a);
  if (a.sun_only) return run_sun_hours(a, moments);

  const std::vector<std::string> columns = {"svf",          "sky_exposure", "sun_hours", "sky_Wh_m2", "sun_Wh_m2",
                                            "global_Wh_m2", "sky_lxh",      "sun_lxh",   "global_lxh"};
  const PointsTable table = a.job.read_points(columns);
  TriangleSoup soup = a.job.load_meshes();
  const auto t0 = std::chrono::steady_clock::now();
  const Scene scene(std::move(soup));
  a.job.warn_about_points("irradiance", scene, table);
  Progress progress("irradiance", !a.job.quiet), sky_progress("irradiance: skies", !a.job.quiet, "moments");
  const std::vector<PointIrradiation> r = compute_point_irradiation(
      scene, table.points, atm, spec, moments, opt, [&](std::size_t d, std::size_t t) { progress(d, t); },
      [&](std::size_t d, std::size_t t) { sky_progress(d, t); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::vector<std::vector<double>> values(columns.size(), std::vector<double>(r.size()));
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double v[] = {r[i].svf,       r[i].sky_exposure, r[i].sun_hours,
                        r[i].sky_Wh_m2, r[i].sun_Wh_m2,    r[i].sky_Wh_m2 + r[i].sun_Wh_m2,
                        r[i].sky_lxh,   r[i].sun_lxh,      r[i].sky_lxh + r[i].sun_lxh};
    for (std::size_t c = 0; c < columns.size(); ++c) values[c][i] = v[c];
  }
  write_points_csv(a.job.out, table, columns, values);
  write_provenance(a.job.out, input_files(a));
  if (!a.job.quiet) {
    double hours = 0;
    for (const SunMoment& m : moments) hours += m.hours;
    std::fprintf(stderr, "irradiance: %zu points x %zu moments (%.2f h) in %.2f s; %s; wrote %s\n", r.size(), moments.size(),
                 hours, seconds, summary(r).c_str(), a.job.out.c_str());
  }
}

// The hourly file's layout: the intervals in UTC (a typical year's records, which take each month
// from another year, are placed in the year of its first record, so that time runs forward), the
// points and their ids.
HourlyNetcdfSpec hourly_spec(const IrradianceArgs& a, const WeatherSeries& series, const PointsTable& table) {
  using namespace std::chrono;
  HourlyNetcdfSpec spec;
  spec.file = a.hourly;
  const int year = series.records.empty() ? 2000 : series.records.front().year;
  int last_month = 0, shift = 0;
  for (const WeatherRecord& r : series.records) {
    if (r.month < last_month) ++shift;  // a period wrapping over the new year
    last_month = r.month;
    const sys_days day{std::chrono::year{year + shift} / r.month / r.day};
    const double midnight_h = duration<double, std::ratio<3600>>(day.time_since_epoch()).count();
    const double end = midnight_h + r.hour - series.location.time_zone_hours;
    spec.time_begin_h.push_back(end - r.interval_hours);
    spec.time_end_h.push_back(end);
  }
  spec.points = table.points;
  const auto id = std::find(table.header.begin(), table.header.end(), "id");
  if (id != table.header.end())
    for (const auto& row : table.rows) spec.point_ids.push_back(row[static_cast<std::size_t>(id - table.header.begin())]);
  spec.title = "skyband irradiance --weather: hourly irradiance and illuminance on calculation points";
  spec.source = series.file.string() + " (" + series.location.name + ", " + fmt(series.location.latitude_deg) + " N, " +
                fmt(series.location.longitude_deg) + " E, UTC" + (series.location.time_zone_hours >= 0 ? "+" : "") +
                fmt(series.location.time_zone_hours) + ")";
  spec.history = "skyband irradiance --weather " + a.weather + " --points " + a.job.points + " --out " + a.job.out;
  return spec;
}

// --weather: irradiation over a weather file's period (lighting/climate/climate_irradiation.h).
void run_weather(const IrradianceArgs& a) {
  // Everything the user typed is checked before the work starts.
  if (const std::string f = a.sun_sky.first_given(); !f.empty())
    throw InputError("--weather: the site, the sun and the sky come from the weather file; " + f + " does not apply");
  if (a.albedo && !(*a.albedo >= 0 && *a.albedo <= 1)) throw InputError("--albedo " + fmt(*a.albedo) + ": must be in [0, 1]");
  if (a.from.empty() != a.to.empty()) throw InputError(a.from.empty() ? "--to needs --from" : "--from needs --to");
  if (!a.hourly.empty()) {
    const std::filesystem::path h(a.hourly);
    if (h.extension() != ".nc") throw InputError("--hourly '" + a.hourly + "': the file name must end in .nc (NetCDF-4)");
    const std::filesystem::path dir = h.has_parent_path() ? h.parent_path() : std::filesystem::path(".");
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) throw InputError("--hourly '" + a.hourly + "': no folder " + dir.string());
    const auto same = std::filesystem::weakly_canonical(h, ec);
    if (!ec && same == std::filesystem::weakly_canonical(a.job.out, ec) && !ec)
      throw InputError("--hourly '" + a.hourly + "': the same file as --out");
  }
  std::optional<MonthDay> from, to;
  if (!a.from.empty()) from = parse_month_day(a.from, "--from"), to = parse_month_day(a.to, "--to");
  ClimateIrradiationOptions opt;
  opt.visibility = a.job.visibility_options();
  opt.method = a.job.method();
  opt.threads = a.job.threads;
  if (a.o_ground->count()) opt.ground_materials = a.ground_materials;

  WeatherSeries series = read_weather_file(a.weather);
  if (from) {
    series = select_period(series, *from, *to);
    if (series.records.empty()) throw InputError(a.weather + ": no records from " + a.from + " to " + a.to);
  }
  for (const std::string& w : series.warnings) std::fprintf(stderr, "skyband: warning: %s\n", w.c_str());
  if (const auto w = weather_timing_warning(series, weather_timing(series)))
    std::fprintf(stderr, "skyband: warning: %s\n", w->c_str());
  WeatherHoursOptions hopt;
  hopt.albedo = a.albedo;
  if (a.sun_at == "start")
    hopt.sun_fraction = 0.0;
  else if (a.sun_at == "end")
    hopt.sun_fraction = 1.0;
  WeatherHoursReport hrep;
  const std::vector<WeatherHour> hours = weather_hours(series, hopt, &hrep);
  if (const auto w = weather_closure_warning(series, weather_closure(series, hours)))
    std::fprintf(stderr, "skyband: warning: %s\n", w->c_str());

  const std::vector<std::string> columns = {"svf",        "sky_exposure",  "ground_view", "global_kWh_m2", "sky_kWh_m2",
                                            "sun_kWh_m2", "ground_kWh_m2", "global_klxh", "sun_hours"};
  const PointsTable table = a.job.read_points(columns);
  TriangleSoup soup = a.job.load_meshes();
  const auto t0 = std::chrono::steady_clock::now();
  const Scene scene(std::move(soup));
  a.job.warn_about_points("irradiance", scene, table);
  Progress progress("irradiance", !a.job.quiet);
  std::unique_ptr<HourlyNetcdfWriter> hourly;
  if (!a.hourly.empty()) hourly = std::make_unique<HourlyNetcdfWriter>(hourly_spec(a, series, table));
  ClimateHourlySink sink;
  if (hourly)
    sink = [&](std::size_t i, std::span<const float> sky, std::span<const float> sun, std::span<const float> ground,
               std::span<const float> global_lx) { hourly->write(i, sky, sun, ground, global_lx); };
  const ClimateRun run = compute_point_climate(
      scene, table.points, hours, opt, [&](std::size_t d, std::size_t t) { progress(d, t); }, sink);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::vector<std::vector<double>> values(columns.size(), std::vector<double>(run.points.size()));
  for (std::size_t i = 0; i < run.points.size(); ++i) {
    const PointClimate& r = run.points[i];
    const double v[] = {r.svf,
                        r.sky_exposure,
                        r.ground_view,
                        1e-3 * (r.sky_Wh_m2 + r.sun_Wh_m2 + r.ground_Wh_m2),
                        1e-3 * r.sky_Wh_m2,
                        1e-3 * r.sun_Wh_m2,
                        1e-3 * r.ground_Wh_m2,
                        1e-3 * (r.sky_lxh + r.sun_lxh + r.ground_lxh),
                        r.sun_hours};
    for (std::size_t c = 0; c < columns.size(); ++c) values[c][i] = v[c];
  }
  write_points_csv(a.job.out, table, columns, values);
  write_provenance(a.job.out, input_files(a));
  if (hourly) hourly->commit();
  // A terrain sheet without a ground material hides the ground from every point: say so when most
  // points that face the ground see none of it.
  if (run.ground_triangles == 0) {
    std::size_t facing = 0, blind = 0;
    for (std::size_t i = 0; i < run.points.size(); ++i) {
      const double open = 0.5 * (1 - table.points[i].normal.normalized().z());
      if (open < 0.05) continue;
      ++facing;
      blind += run.points[i].ground_view < 0.05 * open;
    }
    if (facing > 0 && 4 * blind > facing) {
      std::string names;
      for (const std::string& g : opt.ground_materials) names += (names.empty() ? "" : ",") + g;
      std::fprintf(stderr,
                   "skyband: warning: %zu of the %zu points that face the ground see less than 5 %% of it, and no triangle "
                   "has a ground material (%s): if the model holds its terrain, name its material with --ground-materials\n",
                   blind, facing, names.c_str());
    }
  }
  if (!a.job.quiet) {
    const WeatherRecord& first = series.records.front();
    const WeatherRecord& last = series.records.back();
    std::fprintf(stderr,
                 "irradiance: %s (%.2f N, %.2f E, UTC%+g), %zu intervals %02d-%02d to %02d-%02d: %zu with diffuse light, "
                 "%zu with the sun up; illuminance %s; albedo %s\n",
                 series.location.name.c_str(), series.location.latitude_deg, series.location.longitude_deg,
                 series.location.time_zone_hours, hours.size(), first.month, first.day, last.month, last.day, run.sky_intervals,
                 run.sun_intervals,
                 hrep.illuminance_modelled == 0    ? "from the file"
                 : hrep.illuminance_from_file == 0 ? "by the Perez 1990 efficacy model"
                                                   : "from the file where given, else Perez 1990",
                 a.albedo                    ? fmt(*a.albedo).c_str()
                 : hrep.albedo_from_file > 0 ? "from the file (0.2 where missing)"
                                             : "0.2");
    std::fprintf(stderr,
                 "irradiance: %zu points in %.2f s; %s; sky quadrature calibrated by %.6f (W) and %.6f (lx); %zu ground "
                 "triangles; wrote %s\n",
                 run.points.size(), seconds,
                 method_summary(run.counts.by_horizon, run.counts.by_exact, run.counts.by_bands).c_str(), run.sky_calibration[0],
                 run.sky_calibration[1], run.ground_triangles, a.job.out.c_str());
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
  if (!a.weather.empty()) {
    if (!a.times.empty() || !a.dates.empty())
      throw InputError(std::string("--weather and ") + (a.times.empty() ? "--date" : "--times") + ": give one of them");
    if (a.sun_only) throw InputError("--sun-only applies to --times and --date (--weather gives sun_hours with the rest)");
    a.job.require_files("irradiance");
    return run_weather(a);
  }
  if (!a.from.empty() || !a.to.empty() || a.albedo || a.o_ground->count() || !a.hourly.empty() || !a.sun_at.empty())
    throw InputError("--from, --to, --albedo, --ground-materials, --hourly and --sun-at need --weather");
  if (!a.times.empty() && !a.dates.empty()) throw InputError("--times and --date: give one of them");
  if (a.dates.empty() && (a.o_step->count() || !a.zone.empty()))
    throw InputError(a.zone.empty() ? "--step needs --date" : "--zone needs --date");
  if (a.sun_only && a.times.empty() && a.dates.empty()) throw InputError("--sun-only needs --times or --date");
  if (!a.times.empty() || !a.dates.empty()) {
    a.job.require_files("irradiance");
    return run_times(a);
  }
  // Everything the user typed is validated before any file is read or written.
  a.job.require_files("irradiance", " (or --demo)");
  const PointIrradianceOptions opt = irradiance_options(a.job);
  const SunPlacement sun = a.sun_sky.place_sun();
  const SkyModel sky = a.sun_sky.make_sky(sun);

  const std::vector<std::string> columns = {"svf",         "sky_exposure", "cos_incidence", "sun_visible", "sky_W_m2", "sun_W_m2",
                                            "global_W_m2", "sky_lx",       "sun_lx",        "global_lx",   "sky_ratio"};
  const PointsTable table = a.job.read_points(columns);
  TriangleSoup soup = a.job.load_meshes();
  const auto t0 = std::chrono::steady_clock::now();
  const Scene scene(std::move(soup));
  a.job.warn_about_points("irradiance", scene, table);
  Progress progress("irradiance", !a.job.quiet);
  const std::vector<PointIrradiance> r =
      compute_point_irradiance(scene, table.points, sky, opt, [&](std::size_t d, std::size_t t) { progress(d, t); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::vector<std::vector<double>> values(columns.size(), std::vector<double>(r.size()));
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double v[] = {r[i].svf,
                        r[i].sky_exposure,
                        r[i].cos_incidence,
                        r[i].sun_visible ? 1.0 : 0.0,
                        r[i].sky_W_m2,
                        r[i].sun_W_m2,
                        r[i].sky_W_m2 + r[i].sun_W_m2,
                        r[i].sky_lx,
                        r[i].sun_lx,
                        r[i].sky_lx + r[i].sun_lx,
                        r[i].sky_ratio};
    for (std::size_t c = 0; c < columns.size(); ++c) values[c][i] = v[c];
  }
  write_points_csv(a.job.out, table, columns, values);
  write_provenance(a.job.out, input_files(a));
  if (!a.job.quiet) {
    const Spectrum& dn = sky.sun_direct_normal();
    const std::size_t n = r.size();
    const double mean_global = n ? std::accumulate(values[6].begin(), values[6].end(), 0.0) / double(n) : 0.0;
    std::fprintf(stderr, "irradiance: sun altitude %.3f deg, azimuth %.3f deg, direct normal %.1f W/m2 (%.0f lx); sky %s\n",
                 sun.altitude_deg, sun.azimuth_deg, dn.integral_nm(), luminous(dn), sky.model_name().c_str());
    std::fprintf(stderr, "irradiance: %zu points in %.2f s (%.0f points/s), mean global %.1f W/m2 (380-780 nm); %s; wrote %s\n",
                 n, seconds, seconds > 0 ? double(n) / seconds : 0.0, mean_global, summary(r).c_str(), a.job.out.c_str());
  }
}

CommandRegistration registration{
    "irradiance", [](CLI::App& app) {
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
          "With --weather FILE.epw: sums over the file's period under the Perez all-weather sky, with the ground\n"
          "reflecting albedo x GHI where the point sees it: broadband kWh/m2 (see --weather).\n"
          "Not included: light reflected by the buildings (and, without --weather, by the ground).");
      args->job.add_to(cmd, "Output CSV (input rows + the columns above), written atomically");
      args->sun_sky.add_to(cmd);
      cmd->add_option("--times", args->times,
                      "CSV of moments: 'time' (ISO 8601, with --lat --lon) or 'sun_altitude','sun_azimuth' (degrees), "
                      "optional 'hours' (default 1); outputs sums over them instead of one moment (see --help above)");
      cmd->add_option("--weather", args->weather,
                      "Weather file, EnergyPlus EPW or NREL TMY3 CSV (told by content): sums over its period under the Perez "
                      "all-weather sky, the sun and the "
                      "ground: svf, sky_exposure, ground_view, global_kWh_m2, sky_kWh_m2, sun_kWh_m2, ground_kWh_m2 "
                      "(broadband shortwave), global_klxh, sun_hours");
      cmd->add_option("--hourly", args->hourly,
                      "With --weather: also the hourly irradiance of every point (sky, sun, ground, global; W/m2) and "
                      "its global illuminance (lx) as NetCDF-4/CF, written as computed (xarray.open_dataset reads it)");
      cmd->add_option("--from", args->from, "With --weather: first day of the period, MM-DD (with --to; may wrap over new year)");
      cmd->add_option("--to", args->to, "With --weather: last day of the period, MM-DD (inclusive)");
      cmd->add_option("--sun-at", args->sun_at,
                      "With --weather: where in each record's interval the sun is placed: middle (default, for values\n"
                      "that are means over the interval, as EPW's), end or start (for instantaneous values)")
          ->check(CLI::IsMember({"start", "middle", "end"}));
      cmd->add_option("--albedo", args->albedo, "With --weather: ground reflectance [0, 1] (default: the file's, else 0.2)");
      args->o_ground = cmd->add_option("--ground-materials", args->ground_materials,
                                       "With --weather: material names (any case) of the triangles that are ground and hide no "
                                       "ground (default: ground, terrain, road, water, forest, grass, landuse, ...)")
                           ->delimiter(',');
      cmd->add_option("--date", args->dates,
                      "Moments instead of a times file: every --step minutes through the local day(s) YYYY-MM-DD or "
                      "FIRST:LAST, at the middle of each step, in --zone (or --tz); needs --lat --lon");
      args->o_step = cmd->add_option("--step", args->step_minutes, "With --date: minutes per moment (default 10)");
      cmd->add_option("--zone", args->zone, "With --date: IANA time zone, e.g. Europe/Amsterdam (daylight saving applied)");
      cmd->add_flag("--sun-only", args->sun_only,
                    "With --times or --date: sun hours only (columns svf, sky_exposure, sun_hours), no sky model per moment");
      cmd->add_flag("--demo", args->demo, "Run on the built-in demo street block and print a table (needs a sun)");
      cmd->callback([args] { run(*args); });
      return cmd;
    }};

}  // namespace

}  // namespace skyband::cli
