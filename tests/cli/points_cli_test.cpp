#define BOOST_TEST_MODULE points_cli
#include <boost/test/unit_test.hpp>

// `skyband points grid` end to end: the CSV's columns and counts on a closed-form case, the
// points fed to `skyband svf` (none inside a building: no SVF of 0), and its errors.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/support/cli_runner.h"

namespace fs = std::filesystem;
using skyband::test::run_skyband;
using skyband::test::slurp;

namespace {
std::string q(const fs::path& p) { return skyband::test::shell_quote(p); }
}  // namespace

// The 10 m cube (no ground material: it stands on the plane z = 0) on a 2 m grid over
// [−4, 14]²: 81 nodes, 25 under the cube, 56 points at the odd coordinates, 1.5 m up; svf on them
// runs and no point has SVF 0 (none is inside the cube).
BOOST_AUTO_TEST_CASE(grid_around_a_cube) {
  const fs::path d = skyband::test::test_folder("points_cli_grid");
  skyband::test::write_cube_obj(d / "cube.obj");
  auto r = run_skyband("points grid --mesh " + q(d / "cube.obj") + " --spacing 2 --height 1.5 --bounds -4,-4,14,14 --out " +
                       q(d / "g.csv") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("9 × 9 nodes at 2 m: 56 points 1.5 m above the model's lowest z") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("25 under or on buildings") != std::string::npos, r.err);
  std::istringstream in(slurp(d / "g.csv"));
  std::string line;
  std::getline(in, line);
  BOOST_TEST(line == "x,y,z,nx,ny,nz,ix,iy,ground");
  std::getline(in, line);
  BOOST_TEST(line == "-3,-3,1.5,0,0,1,-2,-2,floor");
  std::size_t rows = 1;
  while (std::getline(in, line)) ++rows;
  BOOST_TEST(rows == 56u);
  BOOST_TEST(fs::exists(d / "g.csv.provenance.json"));
  r = run_skyband("svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "g.csv") + " --out " + q(d / "s.csv") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  std::istringstream out(slurp(d / "s.csv"));
  std::getline(out, line);
  BOOST_TEST(line == "x,y,z,nx,ny,nz,ix,iy,ground,svf,sky_exposure");
  while (std::getline(out, line)) {
    const auto last = line.rfind(','), prev = line.rfind(',', last - 1);
    BOOST_TEST(std::stod(line.substr(prev + 1, last - prev - 1)) > 0.3, line);
  }
}

BOOST_AUTO_TEST_CASE(grid_errors) {
  const fs::path d = skyband::test::test_folder("points_cli_errors");
  skyband::test::write_cube_obj(d / "cube.obj");
  const std::string mesh = "points grid --mesh " + q(d / "cube.obj");
  skyband::test::check_bad_input({
      {mesh + " --out " + q(d / "g.csv"), "--spacing"},
      {mesh + " --spacing 1", "--out"},
      {mesh + " --spacing -2 --out " + q(d / "g.csv"), "--spacing"},
      {mesh + " --spacing 1 --height -3 --out " + q(d / "g.csv"), "--height -3"},
      {mesh + " --spacing 1 --bounds 1,2,3 --out " + q(d / "g.csv"), "--bounds"},
      {mesh + " --spacing 0.0001 --out " + q(d / "g.csv"), "grid nodes over the area"},
      {mesh + " --spacing 1 --out " + q(d / "missing" / "g.csv"), "missing"},
      {"points grid --mesh " + q(d / "absent.obj") + " --spacing 1 --out " + q(d / "g.csv"), "absent.obj"},
  }, d / "g.csv");
}
