#pragma once
// The options every per-point job shares (`skyband svf`, `skyband irradiance`): meshes, the
// points CSV, the output CSV, the band/tolerance accuracy choice, threads, quiet; mesh loading
// with its report; and the progress line on stderr.
#include <chrono>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "geometry/band_visibility.h"
#include "geometry/sky_factors.h"
#include "geometry/triangle_soup.h"

namespace skyband::cli {

class PointJobArgs {
 public:
  std::vector<std::string> meshes;
  std::string points, out;
  int threads = 0;
  bool quiet = false;

  // Adds --mesh, --points, --out (`out_help` says which columns are appended), --method, --bands,
  // --tolerance, --threads, --quiet. The object must outlive the command's callback.
  void add_to(CLI::App* cmd, const std::string& out_help);
  // The accuracy options (validated: InputError naming the flag and value).
  VisibilityOptions visibility_options() const;
  // --method: auto (the exact horizon where the scene allows it, bands elsewhere) or bands.
  SkyFactorsMethod method() const { return method_ == "bands" ? SkyFactorsMethod::bands : SkyFactorsMethod::automatic; }
  // Requires --mesh, --points and --out (InputError "<command>: ..." naming what is missing;
  // `alternative` is appended to the --mesh message, e.g. " (or --demo)").
  void require_files(const std::string& command, const std::string& alternative = "") const;
  // All meshes appended in order; each file's read report on stderr unless quiet.
  TriangleSoup load_meshes() const;

 private:
  std::string method_ = "auto";
  int bands_ = 0;
  double tolerance_ = 0;
  CLI::Option *o_bands_ = nullptr, *o_tolerance_ = nullptr;
};

// "\r<label>: done / total <unit> (p%), t s" on stderr at most twice a second, silent for runs
// under a second; the final line once.
class Progress {
 public:
  // `unit`: what is counted ("points", "moments").
  Progress(std::string label, bool enabled, std::string unit = "points")
      : label_(std::move(label)), unit_(std::move(unit)), enabled_(enabled), start_(std::chrono::steady_clock::now()) {}
  void operator()(std::size_t done, std::size_t total);

 private:
  std::string label_, unit_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  double last_ = 0;
  bool finished_ = false;
};

}  // namespace skyband::cli
