// bench_city_model_load: how fast city models load — CityJSON and CityJSONSeq through
// read_mesh (io/cityjson_reader.h: parse, transform, LoD choice, triangulation with holes, the
// defect report), CityGML 2.0 (io/citygml_reader.h: libcitygml's Xerces parse, LoD choice,
// reprojection of PLATEAU's degrees to UTM, triangulation), beside an OBJ of similar size through
// the same entry point, so that a reader never dominates a run. A file the reader refuses
// (CityGML 3.0) gets a row saying so. Reports MB/s of file and triangles/s, the fastest of --repeat runs (the
// machine is shared: noise only slows).
//
//   bench_city_model_load [--repeat N] [FILE ...]   (default: the shared cityjson/ and citygml/
//                                                    files and the Delft 3dfier OBJ)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "geometry/core/input_error.h"
#include "io/mesh_reader.h"

using namespace skyband;

int main(int argc, char** argv) {
  int repeat = 3;
  std::vector<std::string> files;
  CLI::App app{"bench_city_model_load: load speed of city models and meshes"};
  app.add_option("--repeat", repeat)->capture_default_str();
  app.add_option("files", files, "model files (default: the shared CityJSON files and the Delft OBJ)");
  CLI11_PARSE(app, argc, argv);
  const std::filesystem::path data(SKYBAND_SHARED_DATA);
  if (files.empty()) {
    for (const auto& e : std::filesystem::directory_iterator(data / "cityjson"))
      if (e.path().extension() == ".json" || e.path().extension() == ".jsonl") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    std::vector<std::string> gml;
    for (const auto& e : std::filesystem::directory_iterator(data / "citygml"))
      if (e.path().extension() == ".gml") gml.push_back(e.path().string());
    std::sort(gml.begin(), gml.end());
    files.insert(files.end(), gml.begin(), gml.end());
    files.push_back((data / "buildings" / "delft_3dfier_testarea_lod1.obj").string());
  }
  std::printf("| file | MB | triangles | load s (fastest of %d) | MB/s | triangles/s |\n|---|---|---|---|---|---|\n", repeat);
  for (const std::string& f : files) {
    const double mb = double(std::filesystem::file_size(f)) / 1e6;
    double best = 1e300;
    std::size_t triangles = 0;
    try {
      for (int r = 0; r < repeat; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        MeshReadReport report;
        const TriangleSoup soup = read_mesh(f, &report);
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        triangles = soup.triangle_count();
      }
    } catch (const InputError& e) {
      const std::string what = e.what();
      std::printf("| %s | %.2f | not read: %s | | | |\n", std::filesystem::path(f).filename().c_str(), mb,
                  what.substr(what.find(": ") + 2, 60).c_str());
      continue;
    }
    std::printf("| %s | %.2f | %zu | %.4f | %.1f | %.0f |\n", std::filesystem::path(f).filename().c_str(), mb, triangles, best,
                mb / best, double(triangles) / best);
    std::fflush(stdout);
  }
  return 0;
}
