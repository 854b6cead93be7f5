// bench_city_model_load: how fast city models load — CityJSON and CityJSONSeq through
// read_mesh (io/cityjson_reader.h: parse, transform, LoD choice, triangulation with holes, the
// defect report), CityGML 2.0 (io/citygml_reader.h: libcitygml's Xerces parse, LoD choice,
// reprojection of PLATEAU's degrees to UTM, triangulation), beside an OBJ of similar size through
// the same entry point, so that a reader never dominates a run. A file the reader refuses
// (CityGML 3.0) gets a row saying so. Reports MB/s of file and triangles/s, the fastest of --repeat
// runs (the machine is shared: noise only slows), and the memory of one load: each file is loaded
// once more in a child process of its own (fork), whose peak RSS (VmHWM) less its RSS before the
// load is the load's peak; for CityJSON the reader alone (read_cityjson) is measured the same way.
// "soup MB" is the size of the resulting triangle soup (vertices, triangles, per-triangle material
// and object indices), the memory a load cannot do without.
//
//   bench_city_model_load [--repeat N] [FILE ...]   (default: the shared cityjson/ and citygml/
//                                                    files and the Delft 3dfier OBJ)
//   bench_city_model_load --generate FILE [--buildings N]
//       writes a synthetic CityJSON 2.0 model (3D BAG-like: N Buildings on a grid, each a LoD 0
//       footprint with one BuildingPart child carrying LoD 1.2, 1.3 and 2.2 Solids with semantic
//       surfaces, integer vertices with a transform; ~3 KB per building) and exits. 20,000
//       buildings give ~60 MB.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "geometry/core/input_error.h"
#include "io/cityjson_reader.h"
#include "io/mesh_reader.h"
#include "support/child_process.h"

using namespace skyband;

namespace {

double soup_mb(const TriangleSoup& s) {
  return double(s.vertices.size() * sizeof(Vec3) + s.triangles.size() * sizeof(s.triangles[0]) +
                s.triangle_material.size() * sizeof(std::uint32_t) + s.triangle_object.size() * sizeof(std::uint32_t)) /
         1e6;
}

struct LoadMemory {
  double peak_mb = -1;  // VmHWM − VmRSS before the load, MB (1e6 bytes); < 0: not measured
  double soup_mb = 0;
};

// Runs load() once in a child process; its peak RSS over the RSS it started the load with.
template <class Load>
LoadMemory load_memory(Load&& load) {
  return bench::in_child([&] {
    LoadMemory m;
    const long before = bench::status_kb("VmRSS");
    try {
      const TriangleSoup soup = load();
      m.soup_mb = soup_mb(soup);
      m.peak_mb = double(bench::status_kb("VmHWM") - before) * 1024.0 / 1e6;
    } catch (const std::exception&) {
    }
    return m;
  });
}

// ---- The synthetic model -------------------------------------------------------------------

class Generator {
 public:
  explicit Generator(std::ofstream& out) : out_(out) {}

  void write(std::size_t buildings) {
    out_
        << R"({"type":"CityJSON","version":"2.0","transform":{"scale":[0.001,0.001,0.001],"translate":[84000.0,446000.0,0.0]},)"
        << R"("metadata":{"referenceSystem":"https://www.opengis.net/def/crs/EPSG/0/7415","title":"skyband synthetic 3D BAG-like tile"},)"
        << R"("CityObjects":{)";
    const std::size_t side = static_cast<std::size_t>(std::ceil(std::sqrt(double(buildings))));
    for (std::size_t b = 0; b < buildings; ++b) {
      if (b) out_ << ",";
      building(b, (b % side) * 20000, (b / side) * 20000);  // 20 m grid, mm
    }
    out_ << R"(},"vertices":[)";
    for (std::size_t i = 0; i < vertices_.size(); ++i)
      out_ << (i ? ",[" : "[") << vertices_[i][0] << "," << vertices_[i][1] << "," << vertices_[i][2] << "]";
    out_ << "]}\n";
  }

 private:
  std::uint64_t random() {  // xorshift64*, deterministic
    state_ ^= state_ >> 12;
    state_ ^= state_ << 25;
    state_ ^= state_ >> 27;
    return state_ * 2685821657736338717ULL;
  }
  std::size_t vertex(long long x, long long y, long long z) {
    vertices_.push_back({x, y, z});
    return vertices_.size() - 1;
  }
  void ring(const std::vector<std::size_t>& r) {
    out_ << "[";
    for (std::size_t i = 0; i < r.size(); ++i) out_ << (i ? "," : "") << r[i];
    out_ << "]";
  }
  // A prism (or, with an apex, a pyramid-roofed prism) over the footprint: ground, walls, roof.
  void solid(const std::vector<std::array<long long, 2>>& fp, long long ground, long long eaves, bool apex, long long cx,
             long long cy) {
    const std::size_t k = fp.size();
    std::vector<std::size_t> lo, hi;
    for (const auto& p : fp) lo.push_back(vertex(p[0], p[1], ground));
    for (const auto& p : fp) hi.push_back(vertex(p[0], p[1], eaves));
    const std::size_t top = apex ? vertex(cx, cy, eaves + 3000 + static_cast<long long>(random() % 2000)) : 0;
    std::vector<int> values;
    out_ << R"("boundaries":[[[)";
    ring(std::vector<std::size_t>(lo.rbegin(), lo.rend()));  // ground, facing down
    out_ << "]";
    values.push_back(0);
    for (std::size_t i = 0; i < k; ++i) {
      out_ << ",[";
      ring({lo[i], lo[(i + 1) % k], hi[(i + 1) % k], hi[i]});
      out_ << "]";
      values.push_back(2);
    }
    if (apex) {
      for (std::size_t i = 0; i < k; ++i) {
        out_ << ",[";
        ring({hi[i], hi[(i + 1) % k], top});
        out_ << "]";
        values.push_back(1);
      }
    } else {
      out_ << ",[";
      ring(hi);
      out_ << "]";
      values.push_back(1);
    }
    out_ << R"(]],"semantics":{"surfaces":[{"type":"GroundSurface"},{"type":"RoofSurface","b3_azimut":)" << random() % 360
         << R"(,"b3_hellingshoek":)" << random() % 60 << R"(},{"type":"WallSurface","on_footprint_edge":true}],"values":[[)";
    for (std::size_t i = 0; i < values.size(); ++i) out_ << (i ? "," : "") << values[i];
    out_ << "]]}";
  }
  void building(std::size_t b, long long x0, long long y0) {
    const std::size_t k = 4 + random() % 7;  // 4–10 corners, a convex polygon of radius 4–8 m
    const long long cx = x0 + 10000, cy = y0 + 10000, r = 4000 + static_cast<long long>(random() % 4000);
    std::vector<std::array<long long, 2>> fp;
    for (std::size_t i = 0; i < k; ++i) {
      const double a = 2 * M_PI * double(i) / double(k);
      fp.push_back({cx + std::llround(double(r) * std::cos(a)), cy + std::llround(double(r) * std::sin(a))});
    }
    const std::string id = "NL.IMBAG.Pand.05031000" + std::to_string(10000000 + b);
    const long long ground = static_cast<long long>(random() % 3000), h = 3000 + static_cast<long long>(random() % 15000);
    out_ << "\"" << id << R"(":{"type":"Building","attributes":{"identificatie":")" << id << R"(","oorspronkelijkbouwjaar":)"
         << 1900 + random() % 124 << R"(,"b3_h_maaiveld":)" << double(ground) / 1000
         << R"(,"status":"Pand in gebruik"},"children":[")" << id << R"(-0"],"geometry":[{"type":"MultiSurface","lod":"0",)";
    std::vector<std::size_t> foot;
    for (const auto& p : fp) foot.push_back(vertex(p[0], p[1], ground));
    out_ << R"("boundaries":[[)";
    ring(foot);
    out_ << "]]}]},\"" << id << R"(-0":{"type":"BuildingPart","parents":[")" << id << R"("],"geometry":[)";
    const char* lods[] = {"1.2", "1.3", "2.2"};
    for (int l = 0; l < 3; ++l) {
      out_ << (l ? "," : "") << R"({"type":"Solid","lod":")" << lods[l] << "\",";
      solid(fp, ground, ground + h - (l == 1 ? 500 : 0), l == 2, cx, cy);
      out_ << "}";
    }
    out_ << "]}";
  }

  std::ofstream& out_;
  std::uint64_t state_ = 0x9E3779B97F4A7C15ULL;
  std::vector<std::array<long long, 3>> vertices_;
};

}  // namespace

int main(int argc, char** argv) {
  int repeat = 3;
  std::vector<std::string> files;
  std::string generate;
  std::size_t buildings = 20000;
  CLI::App app{"bench_city_model_load: load speed and memory of city models and meshes"};
  app.add_option("--repeat", repeat)->capture_default_str();
  app.add_option("--generate", generate, "write a synthetic CityJSON model to this file and exit");
  app.add_option("--buildings", buildings, "buildings of the synthetic model")->capture_default_str();
  app.add_option("files", files, "model files (default: the shared CityJSON files and the Delft OBJ)");
  CLI11_PARSE(app, argc, argv);
  if (!generate.empty()) {
    std::ofstream out(generate, std::ios::binary);
    Generator(out).write(buildings);
    out.close();
    if (!out) {
      std::fprintf(stderr, "cannot write %s\n", generate.c_str());
      return 1;
    }
    std::printf("%s: %zu buildings, %.1f MB\n", generate.c_str(), buildings, double(std::filesystem::file_size(generate)) / 1e6);
    return 0;
  }
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
  std::printf(
      "| file | MB | triangles | load s (fastest of %d) | MB/s | triangles/s | peak RSS MB (read_mesh) | peak RSS MB "
      "(reader alone) | soup MB |\n|---|---|---|---|---|---|---|---|---|\n",
      repeat);
  for (const std::string& f : files) {
    const double mb = double(std::filesystem::file_size(f)) / 1e6;
    // Memory first, each load in a fresh child, before this process has loaded anything large.
    const LoadMemory mesh_memory = load_memory([&] { return read_mesh(f); });
    LoadMemory reader_memory;
    if (is_cityjson_path(f)) reader_memory = load_memory([&] { return read_cityjson(f); });
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
      std::printf("| %s | %.2f | not read: %s | | | | | | |\n", std::filesystem::path(f).filename().c_str(), mb,
                  what.substr(what.find(": ") + 2, 60).c_str());
      continue;
    }
    const auto memory = [&](const LoadMemory& m) {
      if (m.peak_mb < 0) return std::string();
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.1f (%.1f× file)", m.peak_mb, m.peak_mb / mb);
      return std::string(buf);
    };
    std::printf("| %s | %.2f | %zu | %.4f | %.1f | %.0f | %s | %s | %.1f |\n", std::filesystem::path(f).filename().c_str(), mb,
                triangles, best, mb / best, double(triangles) / best, memory(mesh_memory).c_str(), memory(reader_memory).c_str(),
                mesh_memory.soup_mb);
    std::fflush(stdout);
  }
  return 0;
}
