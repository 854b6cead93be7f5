// Where the geometry core spends its time: per configuration, points/s, planes per point, bands
// per point (after refinement), triangle tests per point and cache bytes per point. Single
// thread, CPU time (steadier than wall time on a shared machine).
//   bench_visibility_profile [--scene city|paper] [--triangles N] [--points K] [--width W --height H]
//                            [--only TEXT] [--no-reference]
// --scene city: street and facade points of the procedural city of tests/geometry/support, error
//   columns against 4096 fixed bands (not independent of the method; the exact-oracle comparison
//   is bench_svf).
// --scene paper: the renderer's surface points — primary-ray hits of the paper building seen by
//   its camera at W×H (as render/renderer.cpp's trace_geometry makes them: barycentric
//   position, normal facing the camera) — the geometry pass of bench_render without shading.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/paper_building.h"
#include "geometry/bands/band_visibility.h"
#include "geometry/bands/sky_integral.h"
#include "geometry/mesh/camera.h"
#include "geometry/support/scene_generators.h"

using namespace skyband;

namespace {

// Surface points of the renderer's first pass: one primary ray per pixel centre.
std::vector<QueryPoint> camera_hits(const Scene& scene, const PinholeCamera& camera) {
  std::vector<QueryPoint> out;
  for (int row = 0; row < camera.height(); ++row) {
    for (int col = 0; col < camera.width(); ++col) {
      const Ray ray = camera.primary_ray(col + 0.5, row + 0.5);
      if (const std::optional<SurfaceHit> h = scene.surface_hit(ray)) out.push_back({h->position, h->normal});
    }
  }
  return out;
}

struct Set {
  const char* name;
  std::vector<QueryPoint> pts;
};

struct Config {
  std::string name;
  int bands;
  double tol;
};

void profile(const Scene& scene, const std::vector<Set>& sets, const std::vector<Config>& configs, bool reference,
             const std::string& only) {
  std::printf("%-8s %-28s %10s %8s %8s %10s %9s %8s %9s %9s %8s\n", "points", "options", "points/s", "planes", "bands",
              "tri tests", "bytes/pt", "mean svf", "max|err|", "mean|err|", "svf hash");
  for (const Set& set : sets) {
    std::vector<double> ref;
    if (reference) {
      VisibilityOptions opt;
      opt.bands = 4096;
      opt.tolerance = 0;
      const VisibilityCache c = compute_visibility(scene, set.pts, opt, 0);
      for (std::size_t i = 0; i < c.size(); ++i) ref.push_back(sky_view_factor(c.view(i)));
    }
    for (const Config& c : configs) {
      if (!only.empty() && c.name.find(only) == std::string::npos) continue;
      VisibilityOptions opt;
      opt.bands = c.bands;
      opt.tolerance = c.tol;
      BandVisibility bv(scene, opt);
      VisibilityCache cache;
      VisibilityCache::PointResult r;
      double planes = 0, tests = 0;
      const std::clock_t t0 = std::clock();
      for (const QueryPoint& q : set.pts) {
        bv.compute(q, r);
        planes += double(bv.last_plane_count());
        tests += double(bv.last_triangle_tests());
        cache.append(r);
      }
      const double s = double(std::clock() - t0) / CLOCKS_PER_SEC;
      double svf = 0, max_err = 0, sum_err = 0;
      std::uint64_t hash = 1469598103934665603ull;  // FNV-1a of the SVF bits: bit-identity between builds
      for (std::size_t i = 0; i < cache.size(); ++i) {
        const double v = sky_view_factor(cache.view(i));
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        hash = (hash ^ bits) * 1099511628211ull;
        svf += v;
        if (reference) {
          max_err = std::max(max_err, std::abs(v - ref[i]));
          sum_err += std::abs(v - ref[i]);
        }
      }
      const double n = double(set.pts.size());
      std::printf("%-8s %-28s %10.0f %8.1f %8.1f %10.1f %9.0f %8.4f %9.2e %9.2e %08x\n", set.name, c.name.c_str(), n / s,
                  planes / n, double(cache.bands().size()) / n, tests / n, cache.bytes_per_point(), svf / n, max_err, sum_err / n,
                  static_cast<unsigned>(hash >> 32));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  CLI::App app{"geometry core profile"};
  std::string scene_name = "city", only;
  std::size_t triangles = 10000, count = 2000;
  int width = 256, height = 192;
  bool no_reference = false;
  app.add_option("--scene", scene_name, "city or paper")->check(CLI::IsMember({"city", "paper"}));
  app.add_option("--triangles", triangles, "city size");
  app.add_option("--points", count, "city points per set");
  app.add_option("--width", width, "paper: image width (pixels)")->check(CLI::Range(1, 16384));
  app.add_option("--height", height, "paper: image height (pixels)")->check(CLI::Range(1, 16384));
  app.add_option("--only", only, "run only the configurations whose name contains this text");
  app.add_flag("--no-reference", no_reference, "skip the 4096-band reference (no error columns)");
  std::vector<std::string> extra;
  app.add_option("--config", extra, "extra configuration BANDS,TOLERANCE (e.g. 64,1e-3; tolerance 0 = fixed bands); repeatable");
  CLI11_PARSE(app, argc, argv);
  std::vector<Config> configs = {{"N=32 fixed", 32, 0},
                                 {"N=64 fixed", 64, 0},
                                 {"N=256 fixed", 256, 0},
                                 {"default (N=32, tol 5e-4)", 32, 5e-4},
                                 {"N=32, tol 2.5e-4", 32, 2.5e-4},
                                 {"N=32, tol 1e-3", 32, 1e-3},
                                 {"N=16, tol 2.5e-4", 16, 2.5e-4},
                                 {"N=32, tol 1e-4", 32, 1e-4},
                                 {"N=16, tol 1e-3", 16, 1e-3},
                                 {"N=16, tol 2e-3", 16, 2e-3}};
  for (const std::string& e : extra) {
    const std::size_t comma = e.find(',');
    int bands = 0;
    double tol = -1;
    try {
      bands = std::stoi(e.substr(0, comma));
      tol = comma == std::string::npos ? 0.0 : std::stod(e.substr(comma + 1));
    } catch (const std::exception&) {
    }
    if (bands < 1 || !(tol >= 0)) {
      std::fprintf(stderr, "--config %s: expected BANDS,TOLERANCE with BANDS >= 1 and TOLERANCE >= 0\n", e.c_str());
      return 2;
    }
    configs.push_back({"custom N=" + std::to_string(bands) + (tol > 0 ? ", tol " + e.substr(comma + 1) : " fixed"), bands, tol});
  }
  if (scene_name == "paper") {
    cli::PaperBuilding pb = cli::make_paper_building();
    pb.camera.width = width;
    pb.camera.height = height;
    const PinholeCamera camera(pb.camera);
    const Scene scene(std::move(pb.soup));
    std::vector<Set> sets{{"paper", camera_hits(scene, camera)}};
    std::printf("paper building: %zu triangles, %dx%d, %zu surface points\n", scene.soup().triangle_count(), width, height,
                sets[0].pts.size());
    profile(scene, sets, configs, !no_reference, only);
    return 0;
  }
  const gen::City city = gen::make_city(gen::city_params_for_triangles(triangles, 1));
  const Scene scene(city.soup);
  std::printf("city: %zu triangles, %zu buildings\n", city.soup.triangle_count(), city.buildings.size());
  std::vector<Set> sets{{"street", gen::street_points(city, count, 2)},
                        {"facade", gen::facade_points(city.buildings, count, 0.0, 3)}};
  profile(scene, sets, configs, !no_reference, only);
}
