#define BOOST_TEST_MODULE points_cli
#include <boost/test/unit_test.hpp>

// `skyband points grid` and `skyband points facades` end to end: the CSVs' columns and counts on
// closed-form cases, the points fed to `skyband svf`, facade points on real city models checked
// independently (on their face, none inside a building), and the errors.

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "cli/support/cli_runner.h"
#include "geometry/mesh/scene.h"
#include "io/mesh_reader.h"
#include "shared_data.h"

namespace fs = std::filesystem;
using skyband::test::run_skyband;
using skyband::test::slurp;

namespace {
std::string q(const fs::path& p) {
  return skyband::test::shell_quote(p);
}
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

// A terrain given as its own OBJ without usemtl is named by its file: the flat square dtm.obj
// (z = 0.5 over [−5, 15]²) around the cube, --ground-materials dtm: the same 56 nodes beside the
// cube, 1.5 m above the square (z = 2), the ground column naming it.
BOOST_AUTO_TEST_CASE(grid_on_a_terrain_file_without_materials) {
  const fs::path d = skyband::test::test_folder("points_cli_grid_dtm");
  skyband::test::write_cube_obj(d / "cube.obj");
  std::ofstream(d / "dtm.obj") << "v -5 -5 0.5\nv 15 -5 0.5\nv 15 15 0.5\nv -5 15 0.5\nf 1 2 3\nf 1 3 4\n";
  const auto r =
      run_skyband("points grid --mesh " + q(d / "cube.obj") + " --mesh " + q(d / "dtm.obj") +
                  " --ground-materials dtm --spacing 2 --height 1.5 --bounds -4,-4,14,14 --out " + q(d / "g.csv") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("56 points 1.5 m above the ground") != std::string::npos, r.err);
  std::istringstream in(slurp(d / "g.csv"));
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  BOOST_TEST(line == "-3,-3,2,0,0,1,-2,-2,dtm");
}

BOOST_AUTO_TEST_CASE(grid_errors) {
  const fs::path d = skyband::test::test_folder("points_cli_errors");
  skyband::test::write_cube_obj(d / "cube.obj");
  const std::string mesh = "points grid --mesh " + q(d / "cube.obj");
  skyband::test::check_bad_input(
      {
          {mesh + " --out " + q(d / "g.csv"), "--spacing"},
          {mesh + " --spacing 1", "--out"},
          {mesh + " --spacing -2 --out " + q(d / "g.csv"), "--spacing"},
          {mesh + " --spacing 1 --height -3 --out " + q(d / "g.csv"), "--height -3"},
          {mesh + " --spacing 1 --bounds 1,2,3 --out " + q(d / "g.csv"), "--bounds"},
          {mesh + " --spacing 0.0001 --out " + q(d / "g.csv"), "grid nodes over the area"},
          {mesh + " --spacing 1 --out " + q(d / "missing" / "g.csv"), "missing"},
          {"points grid --mesh " + q(d / "absent.obj") + " --spacing 1 --out " + q(d / "g.csv"), "absent.obj"},
      },
      d / "g.csv");
}

// ---- skyband points facades ---------------------------------------------------------------

namespace {

struct FacadeRow {
  skyband::Vec3 x, n;
  std::string object, surface;
  std::size_t face = 0;
};

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// The rows of a facades CSV (its object names have no commas in these files: checked).
std::vector<FacadeRow> read_facade_rows(const fs::path& file, std::string& header) {
  std::istringstream in(slurp(file));
  std::getline(in, header);
  std::vector<FacadeRow> rows;
  std::string line;
  while (std::getline(in, line)) {
    const std::vector<std::string> c = split_csv_line(line);
    BOOST_TEST_REQUIRE(c.size() == 12u, line);
    FacadeRow r;
    r.x = {std::stod(c[0]), std::stod(c[1]), std::stod(c[2])};
    r.n = {std::stod(c[3]), std::stod(c[4]), std::stod(c[5])};
    r.object = c[6], r.surface = c[7], r.face = std::stoul(c[9]);
    rows.push_back(r);
  }
  return rows;
}

// An independent check that no point lies inside a building: the model read by the library's
// reader, its buildings (the CityObjects, or the OBJ's `g` groups, which skyband does not
// read), and a point counted inside a solid whose box holds it when five Möller–Trumbore rays
// in fixed, irregular directions (three tilted, two horizontal) each cross it an odd number of
// times (doubles: the points
// are 0.1 m from any face, far beyond its rounding). Agreement of the five is what makes a
// shell closed for this test — combinatorially closed or with T-junctions — and an open one
// (a lone wall in front) not count.
struct Solids {
  std::vector<std::vector<std::array<skyband::Vec3, 3>>> triangles;
  std::vector<skyband::Aabb> box;
};

// The OBJ's buildings: the `g <CityObject id>` line before each face (the shared Rotterdam OBJ
// has one per building and only triangles, so face k is triangle k of the soup).
std::vector<std::uint32_t> obj_groups(const fs::path& file) {
  std::istringstream in(slurp(file));
  std::vector<std::uint32_t> group;
  std::uint32_t current = 0, count = 0;
  std::string line;
  while (std::getline(in, line)) {
    if (line.starts_with("g ")) current = ++count;
    if (line.starts_with("f ")) group.push_back(current);
  }
  return group;
}

// The solids: per CityObject, else per entry of `group` (one per triangle).
Solids solids_of(const skyband::TriangleSoup& soup, std::vector<std::uint32_t> group) {
  if (soup.triangle_object.size() == soup.triangles.size()) group = soup.triangle_object;
  BOOST_TEST_REQUIRE(group.size() == soup.triangles.size());
  std::map<std::uint32_t, std::vector<std::size_t>> members;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) members[group[t]].push_back(t);
  Solids s;
  for (const auto& [g, tris] : members) {
    s.triangles.emplace_back();
    s.box.emplace_back();
    for (const std::size_t t : tris) {
      std::array<skyband::Vec3, 3> c;
      for (int k = 0; k < 3; ++k) c[k] = soup.vertices[soup.triangles[t][k]], s.box.back().extend(c[k]);
      s.triangles.back().push_back(c);
    }
  }
  return s;
}

bool ray_hits(const skyband::Vec3& o, const skyband::Vec3& d, const std::array<skyband::Vec3, 3>& t) {
  const skyband::Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0], p = d.cross(e2);
  const double det = e1.dot(p);
  if (det == 0) return false;
  const skyband::Vec3 s = o - t[0];
  const double u = s.dot(p) / det;
  if (u < 0 || u > 1) return false;
  const skyband::Vec3 q = s.cross(e1);
  const double v = d.dot(q) / det;
  return v >= 0 && u + v <= 1 && e2.dot(q) / det > 0;
}

std::size_t points_inside_solids(const std::vector<FacadeRow>& rows, const Solids& s) {
  const std::array<skyband::Vec3, 5> dirs = {
      skyband::Vec3(0.5377, 0.8271, 0.1637).normalized(), skyband::Vec3(-0.7193, 0.2417, -0.3119).normalized(),
      skyband::Vec3(0.1291, -0.6733, 0.4422).normalized(), skyband::Vec3(-0.9811, -0.1932, 0).normalized(),
      skyband::Vec3(0.2213, -0.9752, 0).normalized()};
  std::size_t inside = 0;
  for (const FacadeRow& r : rows)
    for (std::size_t g = 0; g < s.triangles.size(); ++g) {
      const skyband::Aabb& b = s.box[g];
      if ((r.x.array() < b.lo.array()).any() || (r.x.array() > b.hi.array()).any()) continue;
      bool all_odd = true;
      for (const skyband::Vec3& d : dirs) {
        std::size_t crossings = 0;
        for (const auto& t : s.triangles[g]) crossings += ray_hits(r.x, d, t);
        all_odd = all_odd && crossings % 2 == 1;
      }
      inside += all_odd;
    }
  return inside;
}

// Each point is `offset` in front of its face's plane along its normal, and its foot lies in
// the face (to 1e-6 m: the rounding of coordinates of 4·10⁵ m is ~10⁻¹⁰).
std::size_t points_off_their_face(const std::vector<FacadeRow>& rows, const skyband::TriangleSoup& soup, double offset) {
  std::size_t bad = 0;
  for (const FacadeRow& r : rows) {
    const auto& t = soup.triangles.at(r.face);
    const skyband::Vec3 &a = soup.vertices[t[0]], &b = soup.vertices[t[1]], &c = soup.vertices[t[2]];
    const skyband::Vec3 n = (b - a).cross(c - a).normalized();
    const double dist = std::abs(n.dot(r.x - a));
    const skyband::Vec3 foot = r.x - offset * r.n;
    const double area2 = (b - a).cross(c - a).norm();
    const double sum = (b - foot).cross(c - foot).norm() + (c - foot).cross(a - foot).norm() + (a - foot).cross(b - foot).norm();
    const bool in_face = sum <= area2 + 1e-6 * ((b - a).norm() + (c - b).norm() + (a - c).norm());
    const bool along_normal = std::abs(std::abs(n.dot(r.n)) - 1) < 1e-9;
    if (!(std::abs(dist - offset) < 1e-6 && in_face && along_normal && std::abs(r.n.norm() - 1) < 1e-12)) ++bad;
  }
  return bad;
}

}  // namespace

// The 10 m cube at spacing 2: 4 walls × 5 × 5 = 100 centres, each 0.1 m out; the roof's 25
// with --surfaces wall,roof. On the cube alone a wall point sees exactly half the sky (svf 0.5:
// nothing in front of the wall, the cube behind its plane).
BOOST_AUTO_TEST_CASE(facades_of_a_cube) {
  const fs::path d = skyband::test::test_folder("points_cli_facades");
  skyband::test::write_cube_obj(d / "cube.obj");
  auto r = run_skyband("points facades --mesh " + q(d / "cube.obj") + " --spacing 2 --out " + q(d / "f.csv") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("100 cell centres at 2 m on 8 faces: 100 points 0.1 m out") != std::string::npos, r.err);
  std::string header;
  const std::vector<FacadeRow> rows = read_facade_rows(d / "f.csv", header);
  BOOST_TEST(header == "x,y,z,nx,ny,nz,object,surface,material,face,iu,iv");
  BOOST_TEST(rows.size() == 100u);
  for (const FacadeRow& p : rows) {
    BOOST_TEST(p.n.z() == 0.0);
    BOOST_TEST(p.surface == "wall");
    BOOST_TEST(p.object == "component 0");
    // Outward: the point is 0.1 m outside the cube along its normal.
    BOOST_TEST(std::max({-p.x.x(), p.x.x() - 10, -p.x.y(), p.x.y() - 10}) == 0.1, boost::test_tools::tolerance(1e-12));
  }
  BOOST_TEST(fs::exists(d / "f.csv.provenance.json"));
  r = run_skyband("svf --mesh " + q(d / "cube.obj") + " --points " + q(d / "f.csv") + " --out " + q(d / "s.csv") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  std::istringstream out(slurp(d / "s.csv"));
  std::string line;
  std::getline(out, line);
  while (std::getline(out, line)) {
    const auto last = line.rfind(','), prev = line.rfind(',', last - 1);
    BOOST_TEST(std::stod(line.substr(prev + 1, last - prev - 1)) == 0.5, boost::test_tools::tolerance(1e-9));
  }
  r = run_skyband("points facades --mesh " + q(d / "cube.obj") + " --spacing 2 --surfaces wall,roof --out " + q(d / "r.csv") +
                  " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(read_facade_rows(d / "r.csv", header).size() == 125u);
}

// The shared Rotterdam block (OBJ, its `g` groups the objects: outward per building; party walls
// modelled once per building), the Delft tile (CityJSON LoD1 solids, no semantics: walls by
// the normal) and the Rotterdam CityJSON subset (objects, semantic walls):
// every point 0.1 m in front of its own face with its foot in it, no point inside any
// building (independent parity, per building even where skyband only sees components), walls' normals within 30° of horizontal
// (by the normal, OBJ) or exactly horizontal (the CityJSON walls are vertical), and the CSV's row count the one printed.
BOOST_AUTO_TEST_CASE(facades_of_real_city_models, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("points_cli_facades_real");
  const fs::path shared(SKYBAND_SHARED_DATA);
  for (const fs::path& model : {shared / "buildings" / "rotterdam_delfshaven_blockA_lod2.obj",
                                shared / "cityjson" / "delft.city.json", shared / "cityjson" / "rotterdam_subset.city.json"}) {
    const fs::path out = d / (model.stem().string() + ".csv");
    const auto r = run_skyband("points facades --mesh " + q(model) + " --spacing 1 --out " + q(out) + " --quiet");
    BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
    std::string header;
    const std::vector<FacadeRow> rows = read_facade_rows(out, header);
    BOOST_TEST(r.err.find(": " + std::to_string(rows.size()) + " points 0.1 m out") != std::string::npos, r.err);
    BOOST_TEST(rows.size() > 1000u, model);  // a block of facades at 1 m: thousands of points
    const skyband::TriangleSoup soup = skyband::read_mesh(model);
    const bool vertical_walls = model.extension() == ".json";  // the CityJSON walls are vertical
    std::size_t steep = 0;
    for (const FacadeRow& p : rows) {
      BOOST_TEST(p.surface == "wall");
      steep += std::abs(p.n.z()) > 0.5 || (vertical_walls && p.n.z() != 0);
    }
    BOOST_TEST(steep == 0u, model);
    BOOST_TEST(points_off_their_face(rows, soup, 0.1) == 0u, model);
    const std::vector<std::uint32_t> groups = model.extension() == ".obj" ? obj_groups(model) : std::vector<std::uint32_t>{};
    const std::size_t inside = points_inside_solids(rows, solids_of(soup, groups));
    // The OBJ's buildings that overlap a neighbour (the data README counts 89 crossing triangle
    // pairs) are caught by the inside tests of geometry/points/facade_points.h.
    BOOST_TEST(inside == 0u, model << ": " << inside << " of " << rows.size() << " points inside a building");
  }
}

BOOST_AUTO_TEST_CASE(facades_errors) {
  const fs::path d = skyband::test::test_folder("points_cli_facades_errors");
  skyband::test::write_cube_obj(d / "cube.obj");
  const std::string mesh = "points facades --mesh " + q(d / "cube.obj");
  const std::string out = " --out " + q(d / "f.csv");
  skyband::test::check_bad_input(
      {
          {mesh + out, "--spacing"},
          {mesh + " --spacing 1", "--out"},
          {mesh + " --spacing -2" + out, "--spacing -2"},
          {mesh + " --spacing 0" + out, "--spacing"},
          {mesh + " --spacing nan" + out, "--spacing nan"},
          {mesh + " --spacing 1 --offset 0" + out, "--offset 0"},
          {mesh + " --spacing 1 --offset -0.1" + out, "--offset -0.1"},
          {mesh + " --spacing 1 --offset inf" + out, "--offset"},
          {mesh + " --spacing 1 --surfaces wall,door" + out, "--surfaces door"},
          {mesh + " --spacing 1 --threads -1" + out, "--threads -1"},
          {mesh + " --spacing 0.0001" + out, "grid cells over the model's faces"},
          {mesh + " --spacing 1 --out " + q(d / "missing" / "f.csv"), "missing"},
          {"points facades --mesh " + q(d / "absent.obj") + " --spacing 1" + out, "absent.obj"},
      },
      d / "f.csv");
}

// The same CSV whatever the thread count (faces in chunks, joined in order), on the shared
// Rotterdam CityJSON subset with its roofs: every roof point (a RoofSurface) faces up, every
// wall point (a WallSurface) is horizontal.
BOOST_AUTO_TEST_CASE(facades_do_not_depend_on_threads, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("points_cli_facades_threads");
  const fs::path model = fs::path(SKYBAND_SHARED_DATA) / "cityjson" / "rotterdam_subset.city.json";
  for (const char* t : {"1", "2"}) {
    const auto r = run_skyband("points facades --mesh " + q(model) + " --spacing 0.5 --surfaces wall,roof --threads " + t +
                               " --out " + q(d / (std::string("t") + t + ".csv")) + " --quiet");
    BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  }
  BOOST_TEST(slurp(d / "t1.csv") == slurp(d / "t2.csv"));
  std::istringstream in(slurp(d / "t1.csv"));
  std::string line;
  std::getline(in, line);
  std::size_t roofs = 0, walls = 0;
  while (std::getline(in, line)) {
    const std::vector<std::string> c = split_csv_line(line);
    BOOST_TEST_REQUIRE(c.size() == 12u, line);
    const double nz = std::stod(c[5]);
    if (c[7] == "roof") {
      ++roofs;
      BOOST_TEST((c[8] == "RoofSurface" && nz > 0), line);
    } else {
      ++walls;
      BOOST_TEST((c[7] == "wall" && c[8] == "WallSurface" && nz == 0), line);
    }
  }
  BOOST_TEST(roofs > 0u);
  BOOST_TEST(walls > 0u);
}
