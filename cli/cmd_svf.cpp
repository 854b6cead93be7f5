// skyband svf — exact sky view factors and sky exposure at calculation points.
//
//   skyband svf --mesh FILE [--mesh FILE ...] --points FILE.csv --out FILE.csv
//               [--method auto|bands] [--bands N | --tolerance T] [--threads K] [--quiet]
//   skyband svf --demo
//
// Coordinates are metres with z up (x east, y north), as in the mesh files. The points CSV has a
// header; x,y,z are required, nx,ny,nz optional (default 0,0,1, normalised on read); every other
// column passes through. The output holds the input rows in input order plus
//   svf           cosine-weighted sky view factor (1 open horizontal face, 0.5 open wall),
//   sky_exposure  visible sky solid angle in front of the face / 2π,
// and is written atomically. Method (docs/geometry.md, geometry/visibility/sky_visibility.h): by default
// ("auto") exact at every point, for any mesh — the exact horizon where the scene is a column scene
// from the point (closed extruded buildings on a ground at or below it), the exact union of the
// occluders' projections elsewhere; "bands" (or --bands / --tolerance alone) the paper's band
// method, with adaptive refinement to an estimated absolute error of 5e-4 or N fixed bands.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numeric>

#include "cli/command_registry.h"
#include "cli/demo_scene.h"
#include "cli/number_text.h"
#include "cli/point_checks.h"
#include "cli/point_job_args.h"
#include "cli/provenance.h"
#include "geometry/bands/band_visibility.h"
#include "geometry/bands/sky_integral.h"
#include "geometry/core/input_error.h"
#include "geometry/horizon/column_scene.h"
#include "geometry/horizon/horizon_profile.h"
#include "geometry/visibility/sky_factors.h"
#include "io/atomic_file.h"
#include "io/points_csv.h"

namespace skyband::cli {

namespace {

struct SvfArgs {
  PointJobArgs job;
  bool demo = false;
  std::string horizon;        // --horizon FILE.csv
  double horizon_step = 1.0;  // --horizon-step DEG
};

// --horizon: rows point,azimuth_deg,elevation_deg (geometry/horizon/horizon_profile.h), written atomically.
void write_horizon(const SvfArgs& a, const Scene& scene, const PointsTable& table, const VisibilityOptions& opt) {
  const std::size_t m = horizon_azimuth_count(a.horizon_step);
  Progress progress("horizon", !a.job.quiet);
  write_atomically(a.horizon, [&](const std::filesystem::path& tmp) {
    std::FILE* f = std::fopen(tmp.c_str(), "w");
    if (!f) throw InputError("--horizon " + a.horizon + ": cannot write");
    std::fprintf(f, "point,azimuth_deg,elevation_deg\n");
    bool ok = true;
    try {
      for_each_horizon_profile(
          scene, table.points, opt, a.horizon_step, a.job.threads, [&](std::size_t d, std::size_t t) { progress(d, t); },
          [&](std::size_t first, std::size_t count, std::span<const double> e) {
            for (std::size_t i = 0; i < count; ++i)
              for (std::size_t k = 0; k < m; ++k)
                ok = std::fprintf(f, "%zu,%.10g,%.6f\n", first + i, double(k) * a.horizon_step, e[i * m + k]) > 0 && ok;
          });
    } catch (...) {
      std::fclose(f);
      throw;
    }
    ok = std::fclose(f) == 0 && ok;
    if (!ok) throw InputError("--horizon " + a.horizon + ": write failed (disk full?)");
  });
}

std::string method_summary(const SkyFactorsRun& run) {
  return cli::method_summary(run.by_horizon, run.by_exact, run.by_bands);
}

void run_demo(const SvfArgs& a) {
  const DemoScene demo = make_demo_scene();
  const Scene scene(demo.soup);
  std::vector<QueryPoint> pts;
  for (const auto& p : demo.points) pts.push_back(p.point);
  const VisibilityOptions opt = a.job.visibility_options();
  const auto t0 = std::chrono::steady_clock::now();
  const SkyFactorsRun run = compute_sky_factors(scene, pts, opt, a.job.method(), a.job.threads);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string bands = run.by_bands == 0   ? ""
                            : opt.tolerance > 0 ? " (bands: adaptive, tolerance " + shortest_text(opt.tolerance) + ")"
                                                : " (bands: " + std::to_string(opt.bands) + " fixed)";
  std::printf("skyband svf --demo: built-in street block (%zu triangles), %zu points; %s%s\n", demo.soup.triangle_count(),
              pts.size(), method_summary(run).c_str(), bands.c_str());
  std::printf("%-36s %8s %8s %8s %6s %6s\n", "point", "x [m]", "y [m]", "z [m]", "svf", "sky_exp");
  for (std::size_t i = 0; i < pts.size(); ++i)
    std::printf("%-36s %8.1f %8.1f %8.1f %6.4f %6.4f\n", demo.points[i].name.c_str(), pts[i].position.x(), pts[i].position.y(),
                pts[i].position.z(), run.factors[i].svf, run.factors[i].sky_exposure);
  std::printf("%.3f ms\n", seconds * 1e3);
}

void run(const SvfArgs& a) {
  if (a.demo) return run_demo(a);
  a.job.require_files("svf", " (or --demo)");
  if (!a.horizon.empty()) {  // a bad step or file fails before the work
    (void)horizon_azimuth_count(a.horizon_step);
    std::vector<std::pair<std::string, std::string>> inputs{{"--points", a.job.points}, {"--out", a.job.out}};
    for (const std::string& m : a.job.meshes) inputs.emplace_back("--mesh", m);
    check_output_file("--horizon", a.horizon, inputs);
  }
  const VisibilityOptions opt = a.job.visibility_options();
  const PointsTable table = a.job.read_points({"svf", "sky_exposure"});
  TriangleSoup soup = a.job.load_meshes();
  const auto t0 = std::chrono::steady_clock::now();
  const Scene scene(std::move(soup));
  a.job.warn_about_points("svf", scene, table);
  Progress progress("svf", !a.job.quiet);
  // Only the two numbers per point are kept (not the visibility cache): memory stays O(points).
  const SkyFactorsRun run = compute_sky_factors(scene, table.points, opt, a.job.method(), a.job.threads,
                                                [&](std::size_t d, std::size_t t) { progress(d, t); });
  const std::vector<SkyFactors>& factors = run.factors;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::vector<std::vector<double>> values(2, std::vector<double>(table.points.size()));
  for (std::size_t i = 0; i < table.points.size(); ++i) {
    values[0][i] = factors[i].svf;
    values[1][i] = factors[i].sky_exposure;
  }
  write_points_csv(a.job.out, table, {"svf", "sky_exposure"}, values);
  write_provenance(a.job.out, a.job.input_files());
  if (!a.horizon.empty()) {
    write_horizon(a, scene, table, opt);
    write_provenance(a.horizon, a.job.input_files());
  }
  if (!a.job.quiet) {
    const std::size_t n = table.points.size();
    const double mean = n ? std::accumulate(values[0].begin(), values[0].end(), 0.0) / double(n) : 0.0;
    std::fprintf(stderr, "svf: %zu points in %.2f s (%.0f points/s), mean svf %.4f; %s; wrote %s\n", n, seconds,
                 seconds > 0 ? double(n) / seconds : 0.0, mean, method_summary(run).c_str(), a.job.out.c_str());
  }
}

CommandRegistration registration{
    "svf", [](CLI::App& app) {
      auto args = std::make_shared<SvfArgs>();
      CLI::App* cmd =
          app.add_subcommand("svf",
                             "Sky view factor and sky exposure at calculation points, exact for any mesh (open, broken,\n"
                             "overhanging; the horizon of closed extruded buildings where it applies, the exact union of the\n"
                             "occluders' projections elsewhere).\n"
                             "Coordinates: metres, z up (x east, y north). Output columns: svf (cosine-weighted, 1 for an open\n"
                             "horizontal face, 0.5 for an open wall) and sky_exposure (visible sky solid angle / 2π).");
      args->job.add_to(cmd, "Output CSV (input rows + svf, sky_exposure), written atomically");
      cmd->add_flag("--demo", args->demo, "Run on the built-in demo street block and print a table");
      cmd->add_option("--horizon", args->horizon,
                      "Also write every point's horizon profile: CSV rows point,azimuth_deg,elevation_deg (point: 0-based\n"
                      "row of the points file; azimuth clockwise from north; the highest occluded elevation, sky below an\n"
                      "overhang not counted), written atomically");
      cmd->add_option("--horizon-step", args->horizon_step, "Azimuth step of --horizon in degrees (default 1)");
      cmd->callback([args] { run(*args); });
      return cmd;
    }};

}  // namespace

}  // namespace skyband::cli
