#define BOOST_TEST_MODULE render_cli
#include <boost/test/unit_test.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "cli/support/cli_runner.h"
#include "io/exr_writer.h"
#include "io/png_writer.h"
#include "shared_data.h"

namespace fs = std::filesystem;
using namespace skyband;

namespace {

using test::CliResult;

fs::path work_dir() {
  static const fs::path d = test::test_folder("render_cli");
  return d;
}

CliResult run(const std::string& args) {
  return test::run_skyband(args);
}

// The committed default scene.
const std::string kScene = std::string(SKYBAND_EXAMPLES_DIR) + "/scenes/default.toml";
const std::string kTiny = " --set image.width=48 --set image.height=36 --set quality.bands=8";

}  // namespace

BOOST_AUTO_TEST_CASE(renders_default_scene_to_exr_and_png) {
  const fs::path exr = work_dir() / "tiny.exr", png = work_dir() / "tiny.png";
  fs::remove(exr);
  fs::remove(png);
  const CliResult r = run("render --quiet --scene '" + kScene + "' --out '" + exr.string() + "'" + kTiny);
  BOOST_REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  BOOST_REQUIRE(fs::exists(exr));
  BOOST_REQUIRE(fs::exists(png));
  const ExrImage img = read_exr_layers(exr);
  BOOST_TEST(img.width == 48);
  BOOST_TEST(img.height == 36);
  std::set<std::string> names;
  for (const auto& l : img.layers) names.insert(l.name);
  for (const char* n : {"sun_diffuse", "sun_specular", "sky_diffuse", "sky_specular", "total"}) BOOST_TEST(names.count(n) == 1u);
  for (const char* a : {"skyband_version", "skyband_command", "skyband_sun", "skyband_sky", "skyband_units"})
    BOOST_TEST(img.attributes.count(a) == 1u);
  BOOST_TEST(img.attributes.at("skyband_sun").find("altitude 50.0000") != std::string::npos);  // default.toml sun
  for (const auto& l : img.layers)
    for (float v : l.rgb) BOOST_TEST(std::isfinite(v));
  const PngImage p = read_png_rgb8(png);
  BOOST_TEST(p.width == 48);
  BOOST_TEST(p.height == 36);
}

BOOST_AUTO_TEST_CASE(overrides_change_the_image) {
  const fs::path a = work_dir() / "sun50.exr", b = work_dir() / "sun8.exr";
  BOOST_REQUIRE(run("render --quiet --scene '" + kScene + "' --out '" + a.string() + "'" + kTiny).exit_code == 0);
  BOOST_REQUIRE(
      run("render --quiet --scene '" + kScene + "' --out '" + b.string() + "'" + kTiny + " --set sun.altitude_deg=8").exit_code ==
      0);
  const ExrImage ia = read_exr_layers(a), ib = read_exr_layers(b);
  BOOST_TEST(ib.attributes.at("skyband_sun").find("altitude 8.0000") != std::string::npos);
  BOOST_TEST((ia.layers.back().rgb != ib.layers.back().rgb));
}

BOOST_AUTO_TEST_CASE(bad_input_exits_2_naming_the_key) {
  struct Case {
    std::string args, expect;
  };
  const std::string base = "render --quiet --scene '" + kScene + "' --out '" + (work_dir() / "bad.exr").string() + "'";
  const Case cases[] = {
      {base + " --set sun.altitude_deg=95", "sun.altitude_deg"},
      {base + " --set image.width=-3", "image.width"},
      {base + " --set sky.model=purple", "sky.model"},
      {base + " --set materials.assign.facade=marble", "materials.assign.facade"},
      {base + " --set camera.fov=40", "camera.fov"},
      {base + " --exposure -1", "--exposure"},
      {"render --scene /nonexistent.toml", "/nonexistent.toml"},
      {"render --scene '" + kScene + "' --out x.png", "--out"},
  };
  for (const Case& c : cases) {
    const CliResult r = run(c.args);
    BOOST_TEST(r.exit_code == 2, c.args << " → exit " << r.exit_code);
    BOOST_TEST(r.err.find(c.expect) != std::string::npos, c.args << " → " << r.err);
  }
  BOOST_TEST(!fs::exists(work_dir() / "bad.exr"));  // nothing half-written
}

// The scene inputs fuzzing found (../shared/data/fuzz-found/README.md): exit 2 with one line
// naming the file and what is wrong — not exit 3 "internal error" (a filesystem_error on a
// 300-byte file name), not toml++'s undefined behaviour on 'Җ' (U+0496) or on printing
// `[0.01]` — at once (10 s asserted against a hang), and no image written.
BOOST_AUTO_TEST_CASE(fuzz_found_scene_inputs_exit_2_naming_file_and_key, *skyband::test::needs_shared_data()) {
  const fs::path found = fs::path(SKYBAND_SHARED_DATA) / "fuzz-found";
  const fs::path out = work_dir() / "fuzz_found.exr";
  const std::string to = " --quiet --out " + test::shell_quote(out);
  // scene_override_unicode.txt: the arguments, one a line after an empty one ("--set", "sky.model=Җ").
  std::string args;
  {
    std::istringstream lines(test::slurp(found / "scene_override_unicode.txt"));
    for (std::string line; std::getline(lines, line);)
      if (!line.empty()) {
        args += ' ';  // built with += : GCC 12 warns falsely (-Wrestrict) on " " + string&&
        args += test::shell_quote(line);
      }
  }
  BOOST_TEST(args == " '--set' 'sky.model=\xD2\x96'");
  struct Case {
    std::string args, expect;
  };
  const Case cases[] = {
      {"render --scene " + test::shell_quote(found / "scene_unicode_2bytes.toml") + to,
       "scene_unicode_2bytes.toml:1:1: character"},
      {"render --scene " + test::shell_quote(found / "scene_array_small_float_in_error_message.toml") + to,
       "scene_array_small_float_in_error_message.toml:1:10: meshes = [0.01]: every entry must be a non-empty path string"},
      {"render --scene " + test::shell_quote(found / "scene_mesh_name_too_long.toml") + to, "File name too long"},
      {"render --scene '" + kScene + "'" + to + args, "--set sky.model=\xD2\x96: sky.model '\xD2\x96': unknown sky model"},
  };
  for (const Case& c : cases) {
    const auto t0 = std::chrono::steady_clock::now();
    const CliResult r = run(c.args);
    BOOST_TEST(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 10.0);
    BOOST_TEST(r.exit_code == 2, c.args << " → exit " << r.exit_code << ": " << r.err);
    BOOST_TEST(r.err.starts_with("skyband: error: "), r.err);
    BOOST_TEST(r.err.find(c.expect) != std::string::npos, c.args << " → " << r.err);
    BOOST_TEST(std::count(r.err.begin(), r.err.end(), '\n') == 1, r.err);
  }
  BOOST_TEST(!fs::exists(out));
}
