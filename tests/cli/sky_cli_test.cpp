#define BOOST_TEST_MODULE sky_cli
#include <boost/test/unit_test.hpp>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/support/cli_runner.h"
#include "io/exr_writer.h"
#include "io/png_writer.h"

namespace tt = boost::test_tools;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {
using skyband::test::CliResult;
using RunResult = CliResult;

fs::path work_dir() {
  static const fs::path d = skyband::test::test_folder("sky_cli");
  return d;
}

CliResult run(const std::string& args) {
  return skyband::test::run_skyband("sky " + args);
}

json run_json(const std::string& args) {
  const RunResult r = run(args + " --json");
  BOOST_REQUIRE_MESSAGE(r.exit_code == 0, "exit " << r.exit_code << ": " << r.err);
  return json::parse(r.out);
}

double trapezoid(const json& x, const json& y) {
  double s = 0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i)
    s += 0.5 * (y[i].get<double>() + y[i + 1].get<double>()) * (x[i + 1].get<double>() - x[i].get<double>());
  return s;
}
}  // namespace

BOOST_AUTO_TEST_CASE(json_has_the_required_keys) {
  const json j = run_json("--sun-altitude 30 --sun-azimuth 135 --model single");
  for (const char* k : {"altitude_deg", "azimuth_deg", "direct_normal_irradiance_W_m2", "direct_normal_illuminance_lx",
                        "chromaticity_xy", "cct_K", "spectrum"})
    BOOST_TEST(j.at("sun").contains(k), k);
  BOOST_TEST(j["sun"]["spectrum"]["wavelength_nm"].size() == 41u);
  BOOST_TEST(j["sun"]["spectrum"]["direct_normal_W_m2_nm"].size() == 41u);
  BOOST_TEST(j["sun"]["chromaticity_xy"].size() == 2u);
  for (const char* k : {"horizontal_diffuse_irradiance_W_m2", "horizontal_diffuse_illuminance_lx", "zenith"})
    BOOST_TEST(j.at("sky").contains(k), k);
  BOOST_TEST(j["sky"]["zenith"].contains("luminance_cd_m2"));
  BOOST_TEST(j["sky"]["zenith"]["chromaticity_xy"].size() == 2u);
  for (const char* k : {"400", "550", "700"}) BOOST_TEST(j["atmosphere"]["rayleigh_optical_depth"].contains(k), k);
  BOOST_TEST(j["atmosphere"]["aerosol_optical_depth_550"].get<double>() == 0.1);
  BOOST_TEST(j["atmosphere"]["ozone_DU"].get<double>() == 300.0);
  BOOST_TEST(j["sun"]["altitude_deg"].get<double>() == 30.0);
  BOOST_TEST(j["sun"]["azimuth_deg"].get<double>() == 135.0);
}

BOOST_AUTO_TEST_CASE(json_values_are_consistent) {
  const json j = run_json("--sun-altitude 45 --model single --aod550 0.05 --ozone-du 250");
  // The broadband value is the trapezoid of the printed spectrum (independent recomputation;
  // the JSON prints doubles with round-trip precision → 1e-12).
  const json& sp = j["sun"]["spectrum"];
  BOOST_TEST(
      j["sun"]["direct_normal_irradiance_W_m2"].get<double>() == trapezoid(sp["wavelength_nm"], sp["direct_normal_W_m2_nm"]),
      tt::tolerance(1e-12));
  // Rayleigh optical depth at sea level, 550 nm: 0.0968 (Bucholtz 1995, reference-notes §2.3
  // table, 4 digits) → 0.1% plus the atmosphere's own fitting (1%).
  BOOST_TEST(j["atmosphere"]["rayleigh_optical_depth"]["550"].get<double>() == 0.0968, tt::tolerance(0.01));
  BOOST_TEST(j["atmosphere"]["ozone_DU"].get<double>() == 250.0);
  // Plausibility band (reference-notes §3.2): direct sun at 45° with light aerosol is within
  // 60–120 klx, a sunlight CCT within 4500–6000 K; the sky is bluer (higher CCT) than the sun.
  const double lx = j["sun"]["direct_normal_illuminance_lx"].get<double>();
  BOOST_TEST(lx > 60e3);
  BOOST_TEST(lx < 120e3);
  const double cct = j["sun"]["cct_K"].get<double>();
  BOOST_TEST(cct > 4500.0);
  BOOST_TEST(cct < 6000.0);
  BOOST_TEST(j["sky"]["horizontal_diffuse_cct_K"].get<double>() > cct);
}

BOOST_AUTO_TEST_CASE(spa_worked_example_through_the_cli) {
  // NREL SPA worked example (Reda & Andreas 2008, Table A5.2): zenith 50.11162°, azimuth
  // 194.34024° (5 decimals → 1e-5).
  const json j = run_json(
      "--lat 39.742476 --lon -105.1786 --elevation 1830.14 --time 2003-10-17T12:30:30 --tz -7 "
      "--pressure-mbar 820 --temperature-c 11 --delta-t 67 --model single");
  BOOST_TEST(std::abs(j["sun"]["altitude_deg"].get<double>() - (90.0 - 50.11162)) < 1e-5);
  BOOST_TEST(std::abs(j["sun"]["azimuth_deg"].get<double>() - 194.34024) < 1e-5);
}

BOOST_AUTO_TEST_CASE(cie_overcast_closed_form_and_no_sun) {
  // E_h = 7πL_z/9 for the CIE overcast sky (reference-notes §3.3); the CLI integrates on 0.5°
  // cells (midpoint error ~1e-5) → 1e-4.
  const json j = run_json("--sun-altitude 35 --model cie-overcast --zenith-luminance 10000");
  BOOST_TEST(j["sky"]["horizontal_diffuse_illuminance_lx"].get<double>() == 7.0 * M_PI / 9.0 * 10000.0, tt::tolerance(1e-4));
  BOOST_TEST(j["sky"]["zenith"]["luminance_cd_m2"].get<double>() == 10000.0, tt::tolerance(1e-9));
  BOOST_TEST(j["sun"]["direct_normal_irradiance_W_m2"].get<double>() == 0.0);
  BOOST_TEST(j["sun"]["cct_K"].is_null());
  BOOST_TEST(j["sky"]["model"].get<std::string>() == "cie-overcast");
}

BOOST_AUTO_TEST_CASE(sun_below_horizon) {
  const json j = run_json("--sun-altitude -5 --model single");
  BOOST_TEST(j["sun"]["above_horizon"].get<bool>() == false);
  BOOST_TEST(j["sun"]["direct_normal_irradiance_W_m2"].get<double>() == 0.0);
  BOOST_TEST(j["sun"]["chromaticity_xy"].is_null());
  const double d = j["sky"]["horizontal_diffuse_irradiance_W_m2"].get<double>();
  BOOST_TEST((std::isfinite(d) && d >= 0.0));
}

BOOST_AUTO_TEST_CASE(impossible_parameters_exit_2_naming_flag_and_value) {
  struct Case {
    const char* args;
    const char* flag;
    const char* value;
  };
  const Case cases[] = {
      {"--sun-altitude 95", "--sun-altitude", "95"},
      {"--sun-altitude -91", "--sun-altitude", "-91"},
      {"--sun-altitude 30 --aod550 -0.5", "--aod550", "-0.5"},
      {"--sun-altitude 30 --ozone-du -3", "--ozone-du", "-3"},
      {"--sun-altitude 30 --model cie-16", "--model", "cie-16"},
      {"--sun-altitude 30 --model clear", "--model", "clear"},
      {"--lat 40 --lon 10 --time 2026-02-30T10:00Z", "--time", "2026-02-30T10:00Z"},
      {"--lat 40 --lon 10 --time tomorrow", "--time", "tomorrow"},
      {"--lat 40 --lon 10 --time 2026-06-21T12:00", "--time", "2026-06-21T12:00"},
      {"--lat 95 --lon 10 --time 2026-06-21T12:00Z", "--lat", "95"},
      {"--sun-altitude 30 --out sky.txt", "--out", "sky.txt"},
      {"--sun-altitude 30 --out /nonexistent_skyband_dir/a.exr", "--out", "/nonexistent_skyband_dir"},
  };
  for (const Case& c : cases) {
    const RunResult r = run(c.args);
    BOOST_TEST(r.exit_code == 2, c.args << " → exit " << r.exit_code);
    BOOST_TEST(r.err.find(c.flag) != std::string::npos, c.args << " → " << r.err);
    BOOST_TEST(r.err.find(c.value) != std::string::npos, c.args << " → " << r.err);
    BOOST_TEST(r.out.empty());
  }
  // No sun at all, or both ways of giving it.
  BOOST_TEST(run("").exit_code == 2);
  BOOST_TEST(run("--sun-altitude 30 --lat 40 --lon 10 --time 2026-06-21T12:00Z").exit_code == 2);
  // Not a number at all: CLI11's own parse error, non-zero.
  BOOST_TEST(run("--sun-altitude abc").exit_code != 0);
}

BOOST_AUTO_TEST_CASE(fisheye_exr_and_png_appear) {
  const fs::path exr = work_dir() / "east_sun.exr", png = work_dir() / "east_sun.png";
  fs::remove(exr);
  fs::remove(png);
  // Sun low in the east: with north up and east LEFT the left half must be brighter.
  const json j = run_json("--sun-altitude 10 --sun-azimuth 90 --model single --size 64 --out '" + exr.string() + "'");
  BOOST_REQUIRE(fs::exists(exr));
  BOOST_REQUIRE(fs::exists(png));
  BOOST_TEST(j["image"]["exr"].get<std::string>() == exr.string());
  const skyband::ExrImage img = skyband::read_exr_layers(exr);
  BOOST_TEST(img.width == 64);
  BOOST_TEST(img.height == 64);
  BOOST_REQUIRE_EQUAL(img.layers.size(), 1u);
  BOOST_TEST(img.layers[0].name == "sky");
  BOOST_TEST(img.attributes.count("skyband_units") == 1u);
  BOOST_TEST(img.attributes.at("skyband_sky").find("model=single") != std::string::npos);
  BOOST_TEST(img.attributes.at("skyband_projection").find("east left") != std::string::npos);
  const auto& px = img.layers[0].rgb;
  const auto at = [&](int row, int col, int c) { return px[static_cast<std::size_t>((row * 64 + col) * 3 + c)]; };
  BOOST_TEST(at(0, 0, 1) == 0.0f);   // outside the circle
  BOOST_TEST(at(32, 32, 1) > 0.0f);  // zenith
  double left = 0, right = 0;
  for (int r = 0; r < 64; ++r)
    for (int c = 0; c < 64; ++c) (c < 32 ? left : right) += at(r, c, 1);
  BOOST_TEST(left > right);
  const skyband::PngImage p = skyband::read_png_rgb8(png);
  BOOST_TEST(p.width == 64);
  BOOST_TEST(p.height == 64);
}

// A folder name the system refuses (a component over 255 bytes: ENAMETOOLONG) is the user's
// input: exit 2 naming --out and the reason, not exit 3 "internal error" (a filesystem_error, the
// same finding as a scene's mesh path, ../shared/data/fuzz-found/README.md).
BOOST_AUTO_TEST_CASE(out_folder_name_too_long_exits_2) {
  const std::string folder = skyband::test::test_folder("sky_cli_long_out").string();
  const std::string out = folder + "/" + std::string(300, 'a') + "/sky.exr";
  const RunResult r = run("--sun-altitude 30 --out '" + out + "'");
  BOOST_TEST(r.exit_code == 2, r.err);
  BOOST_TEST(r.err.starts_with("skyband: error: --out '" + folder + "/aaaa"), r.err);
  BOOST_TEST(r.err.find("cannot be used: File name too long") != std::string::npos, r.err);
}

// --at X,Y,Z --mesh: the fisheye of what one point sees. On the cube's roof every pixel of the
// circle is sky (visible fraction 1, SVF 1); on its east wall, facing east, exactly the western
// half of the pixels lies behind the face (the pixel grid is symmetric about the meridian) and
// nothing in front is hidden: fraction 0.5, SVF 0.5 (an open vertical face). A point on the
// ground 5 m east of the cube sees its 10 m wall up to atan(10/5) = 63.4° in the west: red
// horizon pixels appear, and the picture is written beside the EXR.
BOOST_AUTO_TEST_CASE(fisheye_of_a_point_in_a_model) {
  const fs::path d = work_dir();
  skyband::test::write_cube_obj(d / "cube.obj");
  const std::string mesh = " --mesh '" + (d / "cube.obj").string() + "' --size 128 --sun-altitude 30 --sun-azimuth 180";
  json j = run_json("--at 5,5,10 --out '" + (d / "roof.exr").string() + "'" + mesh);
  BOOST_TEST(j["point"]["svf"].get<double>() == 1.0, tt::tolerance(1e-12));
  BOOST_TEST(j["point"]["visible_fraction_of_fisheye_pixels"].get<double>() == 1.0);
  j = run_json("--at 10,5,5 --normal 1,0,0 --out '" + (d / "wall.exr").string() + "'" + mesh);
  BOOST_TEST(j["point"]["svf"].get<double>() == 0.5, tt::tolerance(1e-9));
  BOOST_TEST(j["point"]["visible_fraction_of_fisheye_pixels"].get<double>() == 0.5);
  j = run_json("--at 15,5,0 --out '" + (d / "ground.exr").string() + "'" + mesh);
  BOOST_TEST(j["point"]["svf"].get<double>() < 0.95);
  const skyband::PngImage png = skyband::read_png_rgb8(d / "ground.png");
  BOOST_TEST_REQUIRE(png.width == 128);
  std::size_t red = 0;
  for (std::size_t i = 0; i + 2 < png.rgb.size(); i += 3)
    red += png.rgb[i] == 230 && png.rgb[i + 1] == 30 && png.rgb[i + 2] == 30;
  BOOST_TEST(red > 20u);
  BOOST_TEST(fs::exists(d / "ground.exr"));
  // Errors name the option.
  for (const auto& [args, what] : std::vector<std::pair<std::string, std::string>>{
           {"--at 5,5 --out '" + (d / "x.exr").string() + "'" + mesh, "--at"},
           {"--at 5,5,10 --out '" + (d / "x.exr").string() + "' --sun-altitude 30", "--mesh"},
           {"--at 5,5,10 --normal 0,0,0 --out '" + (d / "x.exr").string() + "'" + mesh, "--normal"},
           {"--at 5,5,10" + mesh, "--out"}}) {
    const RunResult r = run(args);
    BOOST_TEST(r.exit_code == 2, r.err);
    BOOST_TEST(r.err.find(what) != std::string::npos, r.err);
  }
}

// --sun-path on the fisheye of a point: at the equator on the March equinox the sun is above the
// horizon for 12 h plus the few minutes refraction and its disc's radius add (the SPA's
// sunrise-sunset convention, ~4 min at each end): 72–74 of the day's ten-minute marks. On the
// cube's roof all of them are seen; on the ground 5 m west of the cube (its 10 m wall hides the
// east up to atan(10/5) = 63.4°: the morning sun) fewer, and the hidden marks are drawn dark
// orange.
BOOST_AUTO_TEST_CASE(sun_path_on_a_point_fisheye) {
  const fs::path d = work_dir();
  skyband::test::write_cube_obj(d / "cube.obj");
  const std::string common =
      " --mesh '" + (d / "cube.obj").string() + "' --size 256 --lat 0 --lon 0 --time 2026-03-20T12:00Z --sun-path";
  json j = run_json("--at 5,5,10 --out '" + (d / "path_roof.exr").string() + "'" + common);
  const std::size_t up = j["point"]["sun_path"]["marks_above_horizon"].get<std::size_t>();
  BOOST_TEST(up >= 72u);
  BOOST_TEST(up <= 74u);
  BOOST_TEST(j["point"]["sun_path"]["marks_seen"].get<std::size_t>() == up);
  j = run_json("--at -5,5,0 --out '" + (d / "path_west.exr").string() + "'" + common);
  const std::size_t seen = j["point"]["sun_path"]["marks_seen"].get<std::size_t>();
  // The wall hides the sun from sunrise until it stands 63.4° high in the east (at the equator
  // on the equinox the sun climbs 15° an hour through the zenith: ~4.2 h): ~25 marks hidden.
  BOOST_TEST(seen + 20 < up);
  BOOST_TEST(seen + 30 > up);
  const skyband::PngImage png = skyband::read_png_rgb8(d / "path_west.png");
  std::size_t hidden = 0;
  for (std::size_t i = 0; i + 2 < png.rgb.size(); i += 3)
    hidden += png.rgb[i] == 150 && png.rgb[i + 1] == 80 && png.rgb[i + 2] == 0;
  BOOST_TEST(hidden > 20u);
  const RunResult r = run("--sun-path --lat 0 --lon 0 --time 2026-03-20T12:00Z --out '" + (d / "x.exr").string() + "'");
  BOOST_TEST(r.exit_code == 2, r.err);
  BOOST_TEST(r.err.find("--sun-path") != std::string::npos, r.err);
}
