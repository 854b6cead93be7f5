// Options and progress shared by the per-point jobs (point_job_args.h).
#include "cli/point_job_args.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/number_text.h"
#include "cli/point_checks.h"
#include "geometry/core/input_error.h"
#include "io/mesh_reader.h"
#include "io/scene_crs.h"

namespace skyband::cli {

void PointJobArgs::add_to(CLI::App* cmd, const std::string& out_help) {
  cmd->add_option("--mesh", meshes,
                  "Mesh or city model file (OBJ, OFF, PLY, STL, CityJSON .json, CityJSONSeq .jsonl); repeat\nfor several")
      ->check(CLI::ExistingFile);
  cmd->add_option("--lod", lod,
                  "City models (CityJSON): read every object at this LoD, e.g. 1.2, 1.3 or 2.2 for 3D BAG (default:\n"
                  "each object at the highest LoD it has; objects without the given LoD are skipped and counted)");
  cmd->add_option("--points", points, "CSV with header: x,y,z[,nx,ny,nz] (metres), other columns pass through");
  cmd->add_option("--out", out, out_help);
  cmd->add_option("--offset", offset,
                  "Move every point this many metres along its normal before computing (e.g. 0.1 for points on a\n"
                  "facade, as Ladybug and Honeybee do; default 0); the output keeps the input's coordinates");
  o_method_ = cmd->add_option("--method", method_,
                              "auto (default): exact at every point, for any mesh — the exact horizon where the scene is\n"
                              "closed buildings extruded from floors at or below the point (fastest), the exact\n"
                              "union of the occluders' projections elsewhere; exact: the exact union everywhere; bands:\n"
                              "the paper's band method (--bands N or --tolerance T; either alone selects it)")
                  ->check(CLI::IsMember({"auto", "exact", "bands"}));
  o_bands_ = cmd->add_option("--bands", bands_, "Fixed number of equal-weight bands (the paper's method, no refinement)");
  o_tolerance_ =
      cmd->add_option("--tolerance", tolerance_,
                      "Band method: adaptive refinement to this absolute error of svf and sky_exposure (default 5e-4)");
  o_bands_->excludes(o_tolerance_);
  cmd->add_option("--threads", threads, "Worker threads (0 = all cores; results do not depend on it)");
  cmd->add_flag("--quiet", quiet, "No progress or summary on stderr");
}

VisibilityOptions PointJobArgs::visibility_options() const {
  VisibilityOptions opt;
  if (o_bands_ && o_bands_->count() > 0) {
    if (bands_ < 1 || bands_ > 1000000) throw InputError("--bands " + std::to_string(bands_) + ": must be between 1 and 1000000");
    opt.bands = bands_;
    opt.tolerance = 0;  // a fixed band count: the paper's method, no refinement
  }
  if (o_tolerance_ && o_tolerance_->count() > 0) {
    if (!(tolerance_ > 0) || !std::isfinite(tolerance_) || tolerance_ >= 1)
      throw InputError("--tolerance " + shortest_text(tolerance_) + ": must be a number in (0, 1) (absolute SVF error)");
    opt.tolerance = tolerance_;
  }
  if (threads < 0) throw InputError("--threads " + std::to_string(threads) + ": must be ≥ 0 (0 = all cores)");
  return opt;
}

void PointJobArgs::require_files(const std::string& command, const std::string& alternative) const {
  if (meshes.empty()) throw InputError(command + ": at least one --mesh FILE is required" + alternative);
  if (points.empty()) throw InputError(command + ": --points FILE.csv is required");
  if (out.empty()) throw InputError(command + ": --out FILE.csv is required");
  check_output_file("--out", out, input_files());
  if (!std::isfinite(offset) || std::abs(offset) > 1000)
    throw InputError("--offset " + shortest_text(offset) + ": must be a distance in metres within [-1000, 1000]");
}

std::vector<std::pair<std::string, std::string>> PointJobArgs::input_files() const {
  std::vector<std::pair<std::string, std::string>> inputs{{"--points", points}};
  for (const std::string& m : meshes) inputs.emplace_back("--mesh", m);
  return inputs;
}

PointsTable PointJobArgs::read_points(const std::vector<std::string>& out_columns) const {
  PointsTable table = read_points_csv(points);
  check_output_columns(out, table, out_columns);
  offset_points(table, offset);
  return table;
}

void PointJobArgs::warn_about_points(const std::string& command, const Scene& scene, const PointsTable& table) const {
  print_point_warnings(command, find_point_warnings(scene, table), points);
}

TriangleSoup PointJobArgs::load_meshes() const {
  return cli::load_meshes(meshes, lod, quiet);
}

namespace {

// A file without materials (an OBJ without usemtl, an OFF, PLY or STL) gets one named after the
// file, so that --ground-materials can name a terrain given as its own file: --mesh dtm.obj
// --ground-materials dtm (and a file named ground.obj or terrain.obj is ground by default).
void name_by_file_if_unnamed(TriangleSoup& part, const std::string& file) {
  if (!part.material_names.empty() || part.triangles.empty()) return;
  part.material_names = {std::filesystem::path(file).stem().string()};
  part.triangle_material.assign(part.triangles.size(), 0);
}

}  // namespace

TriangleSoup load_meshes(const std::vector<std::string>& files, const std::string& lod, bool quiet,
                         std::vector<MeshReadReport>* reports) {
  TriangleSoup soup;
  MeshReadOptions options;
  if (!lod.empty()) options.lod = lod;
  SceneCrs crs;
  for (const std::string& file : files) {
    MeshReadReport report;
    TriangleSoup part = read_mesh(file, &report, crs.next(options));
    crs.add(report);
    name_by_file_if_unnamed(part, file);
    soup.append(part);
    if (!quiet)
      std::fprintf(stderr, "%s\n", report.summary().c_str());  // warnings included
    else
      for (const std::string& w : report.warnings) std::fprintf(stderr, "skyband: warning: %s\n", w.c_str());
    if (reports) reports->push_back(std::move(report));
  }
  return soup;
}

std::string method_summary(std::size_t by_horizon, std::size_t by_exact, std::size_t by_bands) {
  const auto count = [](std::size_t n) { return std::to_string(n) + (n == 1 ? " point" : " points"); };
  std::string s;
  const auto add = [&](std::size_t n, const char* how) {
    if (n == 0) return;
    if (!s.empty()) s += ", ";
    s += count(n) + " " + how;
  };
  add(by_horizon, "exact by the horizon of closed buildings");
  add(by_exact, "exact by the union of the occluders' projections");
  add(by_bands, "by the band method");
  return s.empty() ? "no points" : s;
}

Progress::Progress(std::string label, bool enabled, std::string unit)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      enabled_(enabled),
      terminal_(isatty(fileno(stderr)) == 1),
      start_(std::chrono::steady_clock::now()) {}

void Progress::operator()(std::size_t done, std::size_t total) {
  if (!enabled_ || finished_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  // On a terminal the line is redrawn twice a second; in a log (stderr a file or a pipe) a line
  // is added every 10 s, so the log stays readable, and runs under 10 s add none.
  const double every_s = terminal_ ? 0.5 : 10.0, quiet_below_s = terminal_ ? 1.0 : 10.0;
  if (done < total && elapsed - last_ < every_s) return;
  if (elapsed < quiet_below_s) {
    if (done == total) finished_ = true;
    return;
  }
  last_ = elapsed;
  std::fprintf(stderr, "%s%s: %zu / %zu %s (%.0f%%), %.1f s%s", terminal_ ? "\r" : "", label_.c_str(), done, total, unit_.c_str(),
               100.0 * double(done) / double(total ? total : 1), elapsed, terminal_ ? "" : "\n");
  if (done == total) {
    if (terminal_) std::fprintf(stderr, "\n");
    finished_ = true;
  }
}

}  // namespace skyband::cli
