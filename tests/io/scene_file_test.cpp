#define BOOST_TEST_MODULE scene_file
#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geometry/input_error.h"
#include "io/scene_file.h"

using namespace skyband;
namespace fs = std::filesystem;

namespace {

// A scene folder with one tiny OBJ (two materials) in the build tree.
fs::path scene_dir() {
  const fs::path d = fs::path(SKYBAND_BINARY_DIR) / "scene_file_test";
  fs::create_directories(d);
  std::ofstream(d / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl facade\nf 1 2 3\nusemtl ceramic-tile\nf 1 2 4\n";
  return d;
}

const std::string kBase = R"(meshes = ["tri.obj"]
[materials]
default = "diffuse-wall"
[materials.assign]
facade = "aluminium-panel"
[camera]
position = [0, -10, 2]
look_at = [0, 0, 2]
[sun]
altitude_deg = 30
azimuth_deg = 200
[image]
width = 64
height = 48
)";

SceneDescription parse(const std::string& text, std::vector<std::string> sets = {}) {
  return parse_scene(text, scene_dir() / "scene.toml", sets);
}

// The message of the InputError thrown by f (empty if none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

BOOST_AUTO_TEST_CASE(parses_keys_and_defaults) {
  const SceneDescription s = parse(kBase);
  BOOST_TEST(s.meshes.size() == 1u);
  BOOST_TEST(s.meshes[0] == scene_dir() / "tri.obj");
  BOOST_TEST(s.camera.width == 64);
  BOOST_TEST(s.camera.height == 48);
  BOOST_TEST(s.camera.position.y() == -10.0);
  BOOST_TEST(s.sun_altitude_deg == 30.0);
  BOOST_TEST(s.sun_azimuth_deg == 200.0);
  BOOST_TEST(s.bands == 64);       // documented defaults (scene_file.h)
  BOOST_TEST(s.reuse_block == 32);
  BOOST_TEST(s.reuse_tolerance == 0.01);
  BOOST_TEST(s.samples == 1);
  BOOST_TEST(s.tolerance == 0.0);
  BOOST_TEST((s.visibility == SkyFactorsMethod::automatic));
  BOOST_TEST(s.sky_model == "multiple");
  BOOST_TEST(!s.exposure.has_value());
  BOOST_TEST(s.material_assignment.at("facade") == "aluminium-panel");
}

BOOST_AUTO_TEST_CASE(geometry_maps_usemtl_names) {
  const SceneDescription s = parse(kBase);
  const TriangleSoup soup = load_scene_geometry(s);
  BOOST_TEST(soup.triangle_count() == 2u);
  // usemtl facade → assigned aluminium-panel; usemtl ceramic-tile is built-in → itself.
  BOOST_TEST(soup.material_names[soup.triangle_material[0]] == "aluminium-panel");
  BOOST_TEST(soup.material_names[soup.triangle_material[1]] == "ceramic-tile");
}

BOOST_AUTO_TEST_CASE(overrides_with_dotted_keys) {
  const SceneDescription s = parse(kBase, {"sun.altitude_deg=17", "image.width=320", "sky.model=cie-12",
                                           "materials.assign.facade=painted-wall", "quality.samples=4",
                                           "camera.position=[1, -20, 3]", "image.exposure=0.5", "quality.visibility=bands"});
  BOOST_TEST((s.visibility == SkyFactorsMethod::bands));
  BOOST_TEST((parse(kBase, {"quality.visibility=exact"}).visibility == SkyFactorsMethod::exact));
  BOOST_TEST(s.sun_altitude_deg == 17.0);
  BOOST_TEST(s.camera.width == 320);
  BOOST_TEST(s.sky_model == "cie-12");
  BOOST_TEST(!s.sky_spec.physical);
  BOOST_TEST(s.material_assignment.at("facade") == "painted-wall");
  BOOST_TEST(s.samples == 4);
  BOOST_TEST(s.camera.position.x() == 1.0);
  BOOST_TEST(s.exposure.value() == 0.5);
}

BOOST_AUTO_TEST_CASE(sun_from_place_and_time) {
  // SPA worked example of Reda & Andreas (2004), Table A5.2 inputs: 2003-10-17 12:30:30 at
  // UTC−7, 39.742476 N, 105.1786 W, 1830.14 m → zenith 50.11162°, azimuth 194.34024°. The
  // pressure/temperature of the example (820 mbar, 11 °C) are not scene keys, so refraction
  // differs by < 0.01°; ΔT is the scene default 69 s instead of 67 s (< 0.001°).
  std::string text = kBase;
  text.replace(text.find("altitude_deg = 30\nazimuth_deg = 200\n"), 36,
               "latitude_deg = 39.742476\nlongitude_deg = -105.1786\nelevation_m = 1830.14\ntime = \"2003-10-17T12:30:30-07:00\"\n");
  const SceneDescription s = parse(text);
  BOOST_TEST(std::abs(s.sun_altitude_deg - (90.0 - 50.11162)) < 0.01);
  BOOST_TEST(std::abs(s.sun_azimuth_deg - 194.34024) < 0.01);
}

BOOST_AUTO_TEST_CASE(every_error_names_where_the_key_and_the_value) {
  struct Case {
    std::string text;
    std::vector<std::string> sets;
    std::vector<std::string> parts;  // all must appear in the message
  };
  const std::string f = (scene_dir() / "scene.toml").string();
  const std::vector<Case> cases = {
      {kBase + "[bogus]\nx = 1\n", {}, {f, "bogus.x", "unknown key"}},
      {kBase, {"sun.altitude=20"}, {"--set sun.altitude=20", "unknown key"}},
      {kBase, {"sun.altitude_deg=95"}, {"--set sun.altitude_deg=95", "[-90, 90]"}},
      {kBase, {"image.width=0"}, {"--set image.width=0", "[1, 16384]"}},
      {kBase, {"image.width=abc"}, {"image.width", "expected an integer"}},
      {kBase, {"quality.bands=0"}, {"quality.bands", "[1, 4096]"}},
      {kBase, {"quality.visibility=fast"}, {"quality.visibility", "fast", "\"auto\", \"exact\" or \"bands\""}},
      {kBase, {"quality.epsilon=0"}, {"quality.epsilon", "(0, 1)"}},
      {kBase, {"quality.paper_scale=3"}, {"quality.paper_scale", "true or false"}},
      {kBase, {"quality.reuse_tolerance=0.9"}, {"quality.reuse_tolerance", "[0, 0.5]"}},
      {kBase, {"quality.reuse_block=0"}, {"quality.reuse_block", "[1, 1024]"}},
      {kBase, {"sky.model=rainbow"}, {"sky.model", "rainbow"}},
      {kBase, {"sky.aod550=-1"}, {"sky.aod550", "[0, 10]"}},
      {kBase, {"sky.zenith_luminance_cd_m2=5000"}, {"sky.zenith_luminance_cd_m2", "CIE"}},
      {kBase, {"materials.default=marble"}, {"materials.default", "marble"}},
      {kBase, {"materials.assign.facade=marble"}, {"materials.assign.facade", "marble"}},
      {kBase, {"camera.position=[0, 0]"}, {"camera.position", "3 numbers"}},
      {kBase, {"camera.look_at=[0, -10, 2]"}, {"camera.look_at", "equals camera.position"}},
      {kBase, {"camera.up=[0, 1, 0]"}, {"camera.up", "parallel"}},
      {kBase, {"camera.fov_deg=180"}, {"camera.fov_deg", "179"}},
      {kBase, {"image.exposure=-1"}, {"image.exposure", "> 0"}},
      {kBase, {"meshes=[\"missing.obj\"]"}, {"meshes", "missing.obj", "not found"}},
      {kBase, {"sun.latitude_deg=10"}, {"either altitude_deg"}},
      {kBase, {"noequals"}, {"--set 'noequals'", "key=value"}},
      {kBase, {"image.width.x=3"}, {"image.width", "not a table"}},
      {"meshes = [\"tri.obj\"\n", {}, {f + ":"}},  // TOML syntax error with a position
      {"[camera]\nposition = [0,0,0]\nlook_at = [1,0,0]\n", {}, {"missing key 'meshes'"}},
      {kBase + "[quality]\nbands = \"many\"\n", {}, {f + ":", "quality.bands", "\"many\"", "expected an integer"}},
  };
  for (const Case& c : cases) {
    const std::string msg = error_of([&] { parse(c.text, c.sets); });
    BOOST_TEST_INFO("sets: " << (c.sets.empty() ? std::string("-") : c.sets[0]) << " message: " << msg);
    BOOST_TEST(!msg.empty());
    for (const std::string& p : c.parts) BOOST_TEST(contains(msg, p));
  }
  // A file error carries line:column of the offending value.
  const std::string msg = error_of([&] { parse(kBase + "[quality]\nbands = 0\n"); });
  BOOST_TEST(contains(msg, f + ":16:9"));
  BOOST_TEST(contains(error_of([] { load_scene_file("/nonexistent/scene.toml"); }), "/nonexistent/scene.toml"));
}
