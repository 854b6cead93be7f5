#define BOOST_TEST_MODULE map_cli
#include <boost/test/unit_test.hpp>

// `skyband map` end to end: the GeoTIFF's grid and nodata from closed forms, its values against
// `skyband svf` at the same points on an independently built mesh, the CRS carried from a city
// model, the PNG's legend colours, and the errors.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/support/cli_runner.h"
#include "io/geo_raster.h"
#include "io/png_writer.h"
#include "shared_data.h"

namespace fs = std::filesystem;
using skyband::test::run_skyband;
using skyband::test::slurp;

namespace {

std::string q(const fs::path& p) {
  return skyband::test::shell_quote(p);
}

// The last two comma-separated values of each data row of a CSV: (svf, sky_exposure).
std::vector<std::pair<double, double>> last_two_columns(const fs::path& csv) {
  std::istringstream in(slurp(csv));
  std::string line;
  std::getline(in, line);
  std::vector<std::pair<double, double>> out;
  while (std::getline(in, line)) {
    const auto last = line.rfind(','), prev = line.rfind(',', last - 1);
    out.emplace_back(std::stod(line.substr(prev + 1, last - prev - 1)), std::stod(line.substr(last + 1)));
  }
  return out;
}

// GeoTIFF values are Float32: a double in [0, 1] is stored within 2⁻²⁴ (relative rounding).
constexpr double kFloat32 = 1e-7;

}  // namespace

BOOST_AUTO_TEST_CASE(dsm_block_matches_svf_on_a_box_mesh) {
  // A 20 × 20 ESRI ASCII grid of 1 m pixels (lower-left corner (0, 0)), 0 m everywhere but a
  // 4 × 4 block of 6 m in rows 8–11 and columns 8–11 — the box [8, 12]² × [0, 6]. Each pixel is
  // a flat column: the map's value at a pixel is the SVF of the pixel's centre on its top, which
  // `skyband svf` computes on an OBJ of that box alone (the raster's edge skirt and the flat
  // pixels lie at or below every point's horizontal plane).
  const fs::path d = skyband::test::test_folder("map_cli_dsm");
  {
    std::ofstream f(d / "dsm.asc");
    f << "ncols 20\nnrows 20\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n";
    for (int r = 0; r < 20; ++r)
      for (int c = 0; c < 20; ++c) f << (r >= 8 && r < 12 && c >= 8 && c < 12 ? 6 : 0) << (c == 19 ? '\n' : ' ');
    std::ofstream box(d / "box.obj");
    for (int i = 0; i < 8; ++i) box << "v " << (i & 1 ? 12 : 8) << ' ' << (i & 2 ? 12 : 8) << ' ' << (i & 4 ? 6 : 0) << '\n';
    box << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    std::ofstream pts(d / "pts.csv");
    pts << "x,y,z\n";
    for (int r = 0; r < 20; ++r)
      for (int c = 0; c < 20; ++c)
        pts << c + 0.5 << ',' << 19.5 - r << ',' << (r >= 8 && r < 12 && c >= 8 && c < 12 ? 6 : 0) << '\n';
  }
  auto r =
      run_skyband("map --dsm " + q(d / "dsm.asc") + " --crs EPSG:28992 --out " + q(d / "m.tif") + " --png " + q(d / "m.png"));
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("400 points exact by the horizon") != std::string::npos, r.err);
  r = run_skyband("svf --mesh " + q(d / "box.obj") + " --points " + q(d / "pts.csv") + " --out " + q(d / "s.csv") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  const skyband::GeoRaster m = skyband::read_geo_raster(d / "m.tif");
  BOOST_TEST(m.columns == 20u);
  BOOST_TEST(m.rows == 20u);
  BOOST_TEST((m.geotransform == std::array<double, 6>{0, 1, 0, 20, 0, -1}));
  BOOST_TEST(m.crs_name == "EPSG:28992");
  const auto svf = last_two_columns(d / "s.csv");
  BOOST_TEST_REQUIRE(svf.size() == 400u);
  double lowest = 1;
  for (std::size_t i = 0; i < 400; ++i) {
    BOOST_TEST(std::abs(m.values[i] - svf[i].first) < kFloat32,
               "pixel " << i << ": map " << m.values[i] << " svf " << svf[i].first);
    lowest = std::min(lowest, m.values[i]);
  }
  BOOST_TEST(lowest < 0.7);                 // the pixels at the block's foot see it
  BOOST_TEST(m.values[9 * 20 + 9] == 1.0);  // on the block's top: the open sky
  // --quantity sky_exposure on the same raster.
  r = run_skyband("map --dsm " + q(d / "dsm.asc") + " --quantity sky_exposure --out " + q(d / "e.tif") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("names no CRS") != std::string::npos, r.err);  // a warning, not an error
  const skyband::GeoRaster e = skyband::read_geo_raster(d / "e.tif");
  for (std::size_t i = 0; i < 400; ++i) BOOST_TEST(std::abs(e.values[i] - svf[i].second) < kFloat32, "pixel " << i);

  // The PNG: map and legend; the block's top (open sky, the top of the range) in viridis' last
  // colour (253, 231, 37), drawn at 20 picture pixels per raster pixel from (16, 16).
  const skyband::PngImage png = skyband::read_png_rgb8(d / "m.png");
  BOOST_TEST(png.width > 400);
  const auto at = [&](int x, int y) {
    const std::size_t k = (std::size_t(y) * std::size_t(png.width) + std::size_t(x)) * 3;
    return std::array<int, 3>{png.rgb[k], png.rgb[k + 1], png.rgb[k + 2]};
  };
  BOOST_TEST((at(16 + 20 * 9 + 10, 16 + 20 * 9 + 10) == std::array<int, 3>{253, 231, 37}));
  BOOST_TEST(fs::exists(d / "m.tif.provenance.json"));
  BOOST_TEST(fs::exists(d / "m.png.provenance.json"));
}

BOOST_AUTO_TEST_CASE(city_model_map_is_the_ground_grid_with_nodata_under_buildings) {
  // The 10 m cube on a 2 m grid over [−4, 14]²: 9 × 9 pixels, north-up from (−4, 14); the 25
  // cells under the cube are nodata; every other value equals `svf` at `points grid`'s points.
  const fs::path d = skyband::test::test_folder("map_cli_mesh");
  skyband::test::write_cube_obj(d / "cube.obj");
  const std::string common = " --mesh " + q(d / "cube.obj") + " --spacing 2 --height 1.5 --bounds -4,-4,14,14 ";
  auto r = run_skyband("map" + common + "--out " + q(d / "m.tif") + " --png " + q(d / "m.png") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  r = run_skyband("points grid" + common + "--out " + q(d / "g.csv") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  r = run_skyband("svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "g.csv") + " --out " + q(d / "s.csv") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  const skyband::GeoRaster m = skyband::read_geo_raster(d / "m.tif");
  BOOST_TEST(m.columns == 9u);
  BOOST_TEST(m.rows == 9u);
  BOOST_TEST((m.geotransform == std::array<double, 6>{-4, 2, 0, 14, 0, -2}));
  BOOST_TEST(m.nodata_pixels == 25u);
  // The grid CSV's rows: x,y,z,nx,ny,nz,ix,iy,ground (+ svf, sky_exposure): pixel (ix, iy) is
  // column ix + 2, row 6 − iy (x = (ix + ½)·2, rows from the north).
  std::istringstream in(slurp(d / "s.csv"));
  std::string line;
  std::getline(in, line);
  std::size_t checked = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string v; std::getline(ss, v, ',');) f.push_back(v);
    const int ix = std::stoi(f[6]), iy = std::stoi(f[7]);
    const std::size_t pixel = std::size_t(6 - iy) * 9 + std::size_t(ix + 2);
    BOOST_TEST(std::abs(m.values[pixel] - std::stod(f[9])) < kFloat32, line);
    ++checked;
  }
  BOOST_TEST(checked == 56u);
  const skyband::PngImage png = skyband::read_png_rgb8(d / "m.png");
  // The centre cell (under the cube) in the no-data grey; 400/9 picture pixels per cell.
  const std::size_t k = (std::size_t(16 + 200) * std::size_t(png.width) + std::size_t(16 + 200)) * 3;
  BOOST_TEST((std::array<int, 3>{png.rgb[k], png.rgb[k + 1], png.rgb[k + 2]} == std::array<int, 3>{200, 200, 200}));
}

BOOST_AUTO_TEST_CASE(city_model_crs_goes_into_the_geotiff, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("map_cli_crs");
  const fs::path delft = fs::path(SKYBAND_SHARED_DATA) / "cityjson" / "delft.city.json";
  auto r = run_skyband("map --mesh " + q(delft) + " --spacing 100 --out " + q(d / "m.tif") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  // The file's referenceSystem is EPSG:7415 (Amersfoort / RD New + NAP height, a compound CRS):
  // A raster is 2D: the GeoTIFF carries its horizontal part, EPSG:28992 (RD New).
  BOOST_TEST(skyband::read_geo_raster(d / "m.tif").crs_name == "EPSG:28992");
}

BOOST_AUTO_TEST_CASE(bad_input_exits_2_and_writes_nothing) {
  const fs::path d = skyband::test::test_folder("map_cli_bad");
  skyband::test::write_cube_obj(d / "cube.obj");
  {
    std::ofstream(d / "dsm.asc") << "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n";
    std::ofstream(d / "garbage.tif") << "not a raster";
  }
  const std::string out = " --out " + q(d / "out.tif");
  const std::string cube = " --mesh " + q(d / "cube.obj");
  skyband::test::check_bad_input(
      {
          {"map" + out, "either --mesh"},
          {"map" + cube + " --dsm " + q(d / "dsm.asc") + out, "not both"},
          {"map" + cube + out, "--spacing"},
          {"map" + cube + " --spacing -1" + out, "--spacing"},
          {"map" + cube + " --spacing 2 --quantity daylight" + out, "daylight"},
          {"map --dsm " + q(d / "dsm.asc") + " --spacing 2" + out, "apply to --mesh"},
          {"map --dsm " + q(d / "missing.tif") + out, "missing.tif"},
          {"map --dsm " + q(d / "garbage.tif") + out, "garbage.tif"},
          {"map --dsm " + q(d / "dsm.asc") + " --crs EPSG:4326" + out, "geographic"},
          {"map --dsm " + q(d / "dsm.asc") + " --crs EPSG:nonsense" + out, "nonsense"},
          {"map --dsm " + q(d / "dsm.asc") + " --out " + q(d / "no_folder" / "m.tif"), "no_folder"},
          {"map --dsm " + q(d / "dsm.asc") + " --out " + q(d / "dsm.asc"), "dsm.asc"},
          {"map --dsm " + q(d / "dsm.asc") + out + " --png " + q(d / "out.tif"), "same file"},
      },
      d / "out.tif");
  BOOST_TEST(!fs::exists(d / "no_folder"));
}

// --crs labels the map, it does not reproject: with an input that names a CRS it must be that
// CRS (however spelled; a compound CRS matches its horizontal part), else the command ends with
// one line naming the input, its CRS and --crs (exit 2, no map); an input without a CRS takes it.
BOOST_AUTO_TEST_CASE(crs_option_must_be_the_inputs_own_crs) {
  const fs::path d = skyband::test::test_folder("map_cli_crs_option");
  {
    // A flat 3 × 3 DSM of 1 m pixels in RD New, and the same without a CRS.
    skyband::GeoTiffOutput dsm;
    dsm.columns = dsm.rows = 3;
    dsm.geotransform = {155000, 1, 0, 463003, 0, -1};
    const std::vector<float> zeros(9, 0.0f);
    dsm.values = zeros;
    dsm.crs_wkt = skyband::crs_wkt_of("EPSG:28992", "test");
    skyband::write_geotiff(d / "rd.tif", dsm);
    std::ofstream(d / "plain.asc") << "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n0 0 0\n0 0 0\n0 0 0\n";
  }
  const double x0 = 500000, y0 = 5400000;
  skyband::test::write_cube_citygml(d / "cube.gml", x0, y0, "EPSG:25832");
  const std::string model =
      " --mesh " + q(d / "cube.gml") + " --spacing 5 --bounds 499990,5399990,500020,5400020 --out " + q(d / "m.tif");
  skyband::test::check_bad_input({{"map --dsm " + q(d / "rd.tif") + " --crs EPSG:2056 --out " + q(d / "m.tif"),
                                   (d / "rd.tif").string(),
                                   {"EPSG:28992", "--crs EPSG:2056", "does not reproject", "gdalwarp"}},
                                  {"map" + model + " --crs EPSG:28992",
                                   (d / "cube.gml").string(),
                                   {"EPSG:25832", "--crs EPSG:28992", "does not reproject"}}},
                                 d / "m.tif");
  for (const auto& [args, crs] : std::vector<std::pair<std::string, std::string>>{
           {"map --dsm " + q(d / "rd.tif") + " --crs EPSG:7415 --out " + q(d / "m.tif"), "EPSG:28992"},
           {"map --dsm " + q(d / "rd.tif") + " --crs urn:ogc:def:crs:EPSG::28992 --out " + q(d / "m.tif"), "EPSG:28992"},
           {"map --dsm " + q(d / "plain.asc") + " --crs EPSG:28992 --out " + q(d / "m.tif"), "EPSG:28992"},
           {"map" + model + " --crs urn:ogc:def:crs:EPSG::25832", "EPSG:25832"},
           {"map" + model, "EPSG:25832"}}) {
    fs::remove(d / "m.tif");
    const auto r = run_skyband(args + " --quiet");
    BOOST_TEST_INFO(args);
    BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
    BOOST_TEST(skyband::read_geo_raster(d / "m.tif").crs_name == crs);
  }
}
