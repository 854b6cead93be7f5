#define BOOST_TEST_MODULE scene_file
#include <boost/test/unit_test.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "geometry/core/input_error.h"
#include "input_error_of.h"
#include "io/scene_file.h"
#include "io/toml_ascii.h"
#include "shared_data.h"

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

using skyband::test::error_of;

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

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
  BOOST_TEST(s.bands == 64);  // documented defaults (scene_file.h)
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
  const SceneDescription s =
      parse(kBase, {"sun.altitude_deg=17", "image.width=320", "sky.model=cie-12", "materials.assign.facade=painted-wall",
                    "quality.samples=4", "camera.position=[1, -20, 3]", "image.exposure=0.5", "quality.visibility=bands"});
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
  text.replace(
      text.find("altitude_deg = 30\nazimuth_deg = 200\n"), 36,
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

namespace {

const fs::path kFuzzFound = fs::path(SKYBAND_SHARED_DATA) / "fuzz-found";

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

// The scene files fuzzing found (../shared/data/fuzz-found/README.md): an InputError naming the
// file, position and key, quickly (10 s asserted loosely against a hang), never toml++'s
// undefined behaviour (it never sees a non-ASCII byte: io/toml_ascii.h) nor a filesystem_error.
BOOST_AUTO_TEST_CASE(fuzz_found_scene_files_fail_cleanly, *skyband::test::needs_shared_data()) {
  struct Case {
    std::string file;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases{
      // the two bytes D2 96: U+0496 'Җ' where a key must start (line 1, column 1).
      {"scene_unicode_2bytes.toml", {":1:1:", "U+0496", "outside a string or comment"}},
      // `meshes = [0.01]`: printed by our formatter (shortest round-trip form of 0.01).
      {"scene_array_small_float_in_error_message.toml", {":1:10:", "meshes = [0.01]", "non-empty path string"}},
      // a 300-byte file name: ENAMETOOLONG from the system, the key is named.
      {"scene_mesh_name_too_long.toml", {":1:11:", "meshes = \"aaaa", "cannot use the mesh path", "File name too long"}},
  };
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT(c.file) {
      const auto t0 = std::chrono::steady_clock::now();
      const std::string msg = error_of([&] { load_scene_file(kFuzzFound / c.file); });
      BOOST_TEST(seconds_since(t0) < 10.0);
      BOOST_TEST(contains(msg, (kFuzzFound / c.file).string()), msg);
      for (const std::string& p : c.parts) BOOST_TEST(contains(msg, p), msg);
    }
  }
  // scene_override_unicode.txt holds the arguments "--set" "sky.model=Җ", one a line (after an
  // empty one): the value is no TOML value, so a plain string, so an unknown sky model.
  const std::string args = slurp(kFuzzFound / "scene_override_unicode.txt");
  const std::string value = args.substr(args.find("sky.model="), args.rfind('\n') - args.find("sky.model="));
  BOOST_TEST(value == "sky.model=\xD2\x96");
  const std::string msg = error_of([&] { parse(kBase, {value}); });
  BOOST_TEST(contains(msg, "--set sky.model=\xD2\x96"), msg);
  BOOST_TEST(contains(msg, "unknown sky model"), msg);
  // The whole file as one override (as the fuzz harness passed it): its key holds line breaks.
  const std::string whole = error_of([&] { parse(kBase, {args}); });
  BOOST_TEST(contains(whole, "may hold only letters"), whole);
  BOOST_TEST(whole.find('\n') == std::string::npos, whole);  // escaped: one line
}

// Non-ASCII text where TOML allows it reads as written: quoted keys, basic and literal strings
// (one and several lines), the #190 case (a line-ending backslash followed by U+00A7 '§' on the
// next line), comments. The expected values are the file names created here: the scene loads
// only if each path string is exactly right.
BOOST_AUTO_TEST_CASE(non_ascii_strings_keys_and_comments_read_as_written) {
  const fs::path d = scene_dir();
  const std::vector<std::string> names{"Gebäude ü.obj", "§ü.obj", "back\\slash \"ç\".obj", "ü''.obj"};
  for (const std::string& n : names) fs::copy_file(d / "tri.obj", d / n, fs::copy_options::overwrite_existing);
  std::string text = kBase;
  text.replace(0, text.find('\n'),
               "# Gebäude — façade\n"
               "meshes = [\"Gebäude ü.obj\", \"\"\"\\\n\xC2\xA7\xC3\xBC.obj\"\"\", 'back\\slash \"ç\".obj', '''ü''.obj''']");
  text.replace(text.find("facade = "), 9, "\"façade\" = ");
  const SceneDescription s = parse(text);
  BOOST_REQUIRE_EQUAL(s.meshes.size(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) BOOST_TEST(s.meshes[i] == d / names[i]);
  BOOST_TEST(s.material_assignment.at("façade") == "aluminium-panel");
  // A column after an escape on the same line is the user's: `wall` = "marble" starts at column
  // 46 of the line (counted in characters: 'ç' is one), although toml++ sees "\u00E7" there.
  const std::string inline_table = kBase.substr(0, kBase.find("[materials]")) +
                                   "[materials]\nassign = { \"façade\" = \"ceramic-tile\", wall = \"marble\" }\n" +
                                   kBase.substr(kBase.find("[camera]"));
  const std::string msg = error_of([&] { parse(inline_table); });
  BOOST_TEST(contains(msg, "scene.toml:3:46: materials.assign.wall = \"marble\""), msg);
}

// What toml_ascii.h rejects, with file:line:column; what the string readers reject.
BOOST_AUTO_TEST_CASE(bytes_toml_must_not_see_are_errors) {
  const std::string f = (scene_dir() / "scene.toml").string();
  using namespace std::string_literals;
  // kBase has 14 lines: what is appended starts on line 15.
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases{
      {kBase + "# \xFF\n", {f + ":15:3:", "not valid UTF-8", "0xFF"}},
      {kBase + "# \xED\xA0\x80\n", {f + ":15:3:", "not valid UTF-8"}},  // a surrogate, U+D800
      {kBase + "\x01\n"s, {f + ":15:1:", "control character U+0001"}},
      {kBase + "[quality]\nvisibility = \"\\u0000auto\"\n",
       {f + ":16:14:", "quality.visibility", "\\x00auto", "control character"}},
      {kBase + "[sky]\nmodel = \"multiple\\\xC3\xA9\"\n", {f + ":16:18:", "not a TOML escape sequence"}},
      {kBase + "[sky]\nmodel = '''multiple''''''\n", {f + ":16:20:", "6 quotes"}},
  };
  for (const auto& [text, parts] : cases) {
    const std::string& t = text;  // a lambda cannot capture a structured binding in clang 14
    const std::string msg = error_of([&] { parse(t); });
    BOOST_TEST_INFO("message: " << msg);
    BOOST_TEST(!msg.empty());
    for (const std::string& p : parts) BOOST_TEST(contains(msg, p));
  }
  // A --set value: not UTF-8, or holding a control character (a line break would add keys).
  BOOST_TEST(contains(error_of([] { parse(kBase, {"sky.model=\xC3"}); }), "not valid UTF-8"));
  // Shapes toml++ 3.3.0 reaches an assertion on (found by fuzz/scene_file_fuzz.cpp and
  // fuzz/scene_override_fuzz.cpp): a header without a key, '}' where an array expects a value
  // (both rejected in io/toml_ascii.cpp), a date-time without its time (toml++'s own error).
  const std::vector<std::pair<std::string, std::vector<std::string>>> shapes{
      {kBase + "[}\n", {f + ":15:2:", "a table header holds a key", "'}'"}},
      {kBase + "[[ #\n", {f + ":15:4:", "a table header holds a key", "'#'"}},
      {kBase + "[sky]\nv = [}\n", {f + ":16:6:", "expected a value or ']' in the array, saw '}'"}},
      {kBase + "[sky]\nv = [1,\n  # note\n  }\n", {f + ":18:3:", "saw '}'"}},
      // A date-time whose 'T' is followed by no time: toml++ asserts a digit, then checks it.
      {kBase + "[sky]\nv = 2024-06-21T'10:00:00+02:00\n", {f + ":16:", "hour"}},
  };
  for (const auto& [text, parts] : shapes) {
    const std::string& t = text;  // a lambda cannot capture a structured binding in clang 14
    const std::string msg = error_of([&] { parse(t); });
    BOOST_TEST_INFO("message: " << msg);
    for (const std::string& p : parts) BOOST_TEST(contains(msg, p));
  }
  const std::string set_msg = error_of([] { parse(kBase, {"sky.model=[}"}); });
  BOOST_TEST(contains(set_msg, "sky.model '[}': unknown sky model"), set_msg);  // not TOML: a plain string
  // The same brackets where TOML allows them still parse: arrays of tables, nested and
  // multi-line arrays, a '[' inside a string, '}' closing an inline table inside an array.
  const std::string ok =
      error_of([] { AsciiToml("v = [[1, 2], [\n 3, # c\n ], {a = 1}]\ns = \"[}\"\n[[list]]\nx = [ ]\n", "t"); });
  BOOST_TEST(ok.empty(), ok);
  BOOST_TEST(contains(error_of([] { parse(kBase, {"quality.samples=2\nquality.bands=3"}); }), "control character"));
}

// Values in messages come from our formatter (toml++ 3.3.0's has a float-cast overflow on small
// floats in arrays); dates and times in TOML's form, which parse_iso8601 reads back for sun.time.
BOOST_AUTO_TEST_CASE(values_in_messages_and_toml_date_times) {
  const auto with = [](const std::string& from, const std::string& to) {
    std::string t = kBase;
    return t.replace(t.find(from), from.size(), to);
  };
  const std::string up = error_of([&] { parse(with("[camera]\n", "[camera]\nup = [[0.001, 1e-300], 0, 1]\n")); });
  BOOST_TEST(contains(up, "camera.up = [[0.001, 1e-300], 0, 1]"), up);
  BOOST_TEST(contains(error_of([&] { parse(with("width = 64", "width = 0.5")); }), "image.width = 0.5: expected an integer"));
  BOOST_TEST(contains(error_of([&] { parse(with("width = 64", "width = 1979-05-27T07:32:00.5-07:30")); }),
                      "image.width = 1979-05-27T07:32:00.5-07:30"));
  BOOST_TEST(contains(error_of([&] { parse(with("width = 64", "width = {a = 'x', b = [true, -inf]}")); }),
                      "image.width = {a = \"x\", b = [true, -inf]}"));
  // The SPA worked example (as sun_from_place_and_time above) with a TOML date-time value
  // instead of a string: the same sun.
  std::string text = kBase;
  text.replace(text.find("altitude_deg = 30\nazimuth_deg = 200\n"), 36,
               "latitude_deg = 39.742476\nlongitude_deg = -105.1786\nelevation_m = 1830.14\ntime = 2003-10-17T12:30:30-07:00\n");
  const SceneDescription s = parse(text);
  BOOST_TEST(std::abs(s.sun_altitude_deg - (90.0 - 50.11162)) < 0.01);
  BOOST_TEST(std::abs(s.sun_azimuth_deg - 194.34024) < 0.01);
  // The SPA's own range check (year in [-2000, 6000]) names the file and the key.
  text.replace(text.find("2003-10-17"), 10, "9999-10-17");
  const std::string msg = error_of([&] { parse(text); });
  BOOST_TEST(contains(msg, (scene_dir() / "scene.toml").string() + ":13:"), msg);
  BOOST_TEST(contains(msg, "sun.time = 9999-10-17T12:30:30-07:00"), msg);
  BOOST_TEST(contains(msg, "year = 9999"), msg);
}
