#pragma once
// The options every per-point job shares (`skyband svf`, `skyband irradiance`): meshes, the
// points CSV, the output CSV, the band/tolerance accuracy choice, threads, quiet; mesh loading
// with its report; and the progress line on stderr.
#include <chrono>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "geometry/bands/band_visibility.h"
#include "geometry/mesh/scene.h"
#include "geometry/mesh/triangle_soup.h"
#include "geometry/visibility/sky_factors.h"
#include "io/mesh_reader.h"
#include "io/points_csv.h"

namespace skyband::cli {

class PointJobArgs {
 public:
  std::vector<std::string> meshes;
  std::string points, out;
  int threads = 0;
  bool quiet = false;
  double offset = 0;  // --offset D: metres along each point's normal
  std::string lod;    // --lod: city models read at this LoD ("" = each object's highest)

  // Adds --mesh, --points, --out (`out_help` says which columns are appended), --offset, --method,
  // --bands, --tolerance, --threads, --quiet. The object must outlive the command's callback.
  void add_to(CLI::App* cmd, const std::string& out_help);
  // The accuracy options (validated: InputError naming the flag and value).
  VisibilityOptions visibility_options() const;
  // --method: auto (exact everywhere: the exact horizon where the scene allows it, the exact union
  // elsewhere), exact (the exact union everywhere) or bands; --bands or --tolerance without
  // --method select bands.
  SkyFactorsMethod method() const {
    if (method_ == "bands" || (o_method_->count() == 0 && (o_bands_->count() > 0 || o_tolerance_->count() > 0)))
      return SkyFactorsMethod::bands;
    return method_ == "exact" ? SkyFactorsMethod::exact : SkyFactorsMethod::automatic;
  }
  // Requires --mesh, --points and --out (InputError "<command>: ..." naming what is missing;
  // `alternative` is appended to the --mesh message, e.g. " (or --demo)"), and checks --out
  // before any work (cli/point_checks.h: its folder, not an input file).
  void require_files(const std::string& command, const std::string& alternative = "") const;
  // The input files: --points and every --mesh, as (flag, path) pairs.
  std::vector<std::pair<std::string, std::string>> input_files() const;
  // Reads --points, checks that none of `out_columns` is already an input column, and applies
  // --offset (cli/point_checks.h).
  PointsTable read_points(const std::vector<std::string>& out_columns) const;
  // The point sanity warnings against the scene on stderr (printed even with --quiet).
  void warn_about_points(const std::string& command, const Scene& scene, const PointsTable& table) const;
  // All meshes appended in order; each file's read report on stderr unless quiet.
  TriangleSoup load_meshes() const;

 private:
  std::string method_ = "auto";
  int bands_ = 0;
  double tolerance_ = 0;
  CLI::Option *o_bands_ = nullptr, *o_tolerance_ = nullptr, *o_method_ = nullptr;
};

// Mesh and city-model files appended in order into one soup, each read at `lod` ("" = each
// object's highest), each file's read report on stderr unless `quiet` (its warnings always), and
// kept in `reports` when given (the CRS of a city model is in its report). The files must share
// one CRS (io/scene_crs.h): InputError naming two files in different CRSs. A file without
// materials (an OBJ without usemtl, OFF, PLY, STL) has its triangles named after the file's stem
// ("dtm" for dtm.obj), so that --ground-materials can name a terrain given as a file of its own.
TriangleSoup load_meshes(const std::vector<std::string>& files, const std::string& lod, bool quiet,
                         std::vector<MeshReadReport>* reports = nullptr);

// How the points were computed, in plain words: "9,800 points exact by the horizon of closed
// buildings, 200 exact by the union of the occluders' projections, 0 by the band method".
std::string method_summary(std::size_t by_horizon, std::size_t by_exact, std::size_t by_bands);

// "<label>: done / total <unit> (p%), t s" on stderr: on a terminal one line redrawn at most
// twice a second (silent for runs under a second), in a log a line every 10 s (silent for runs
// under 10 s); the final line once.
class Progress {
 public:
  // `unit`: what is counted ("points", "moments").
  Progress(std::string label, bool enabled, std::string unit = "points");
  void operator()(std::size_t done, std::size_t total);

 private:
  std::string label_, unit_;
  bool enabled_;
  bool terminal_;  // stderr is a terminal
  std::chrono::steady_clock::time_point start_;
  double last_ = 0;
  bool finished_ = false;
};

}  // namespace skyband::cli
