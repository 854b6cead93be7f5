#define BOOST_TEST_MODULE paint_cli
#include <boost/test/unit_test.hpp>

// `skyband paint` end to end: facade points of the 10 m cube, their SVF, painted back onto the
// cube as PLY; the PLY read back (our reader: same triangles) and its face values against the
// mean of each face's points computed here from the CSV; the errors.

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/support/cli_runner.h"
#include "io/mesh_reader.h"

namespace fs = std::filesystem;
using skyband::test::run_skyband;
using skyband::test::slurp;

namespace {

std::string q(const fs::path& p) {
  return skyband::test::shell_quote(p);
}

struct PlyFaces {
  std::size_t vertices = 0;
  std::vector<float> values;
  std::vector<std::array<int, 3>> rgb;
};

// The face values and colours of a PLY written by skyband paint (binary little endian: vertices
// of 3 doubles, faces of a uchar count 3, three uint indices, a float and three uchars).
PlyFaces read_ply_faces(const fs::path& file) {
  const std::string bytes = slurp(file);
  const auto end = bytes.find("end_header\n");
  BOOST_REQUIRE(end != std::string::npos);
  std::istringstream header(bytes.substr(0, end));
  PlyFaces out;
  std::size_t faces = 0;
  for (std::string line; std::getline(header, line);) {
    if (line.rfind("element vertex ", 0) == 0) out.vertices = std::stoul(line.substr(15));
    if (line.rfind("element face ", 0) == 0) faces = std::stoul(line.substr(13));
  }
  std::size_t at = end + 11 + out.vertices * 24;
  BOOST_REQUIRE(bytes.size() == at + faces * 20);
  for (std::size_t f = 0; f < faces; ++f, at += 20) {
    BOOST_REQUIRE(bytes[at] == 3);
    float v = 0;
    std::memcpy(&v, bytes.data() + at + 13, 4);
    out.values.push_back(v);
    out.rgb.push_back({std::uint8_t(bytes[at + 17]), std::uint8_t(bytes[at + 18]), std::uint8_t(bytes[at + 19])});
  }
  return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(facade_svf_painted_onto_the_cube) {
  const fs::path d = skyband::test::test_folder("paint_cli_cube");
  skyband::test::write_cube_obj(d / "cube.obj");
  const std::string mesh = " --mesh " + q(d / "cube.obj");
  auto r = run_skyband("points facades" + mesh + " --spacing 2.5 --out " + q(d / "f.csv") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  r = run_skyband("svf" + mesh + " --points " + q(d / "f.csv") + " --out " + q(d / "s.csv") + " --quiet");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  r = run_skyband("paint" + mesh + " --values " + q(d / "s.csv") + " --out " + q(d / "cube.ply"));
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  // The mean SVF of each face's points, from the CSV (columns ..., face, iu, iv, svf, sky_exposure).
  std::istringstream in(slurp(d / "s.csv"));
  std::string line;
  std::getline(in, line);
  std::map<int, std::pair<double, int>> per_face;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string v; std::getline(ss, v, ',');) f.push_back(v);
    auto& [sum, n] = per_face[std::stoi(f[9])];
    sum += std::stod(f[12]);
    ++n;
  }
  // The cube's 8 wall triangles carry points, its roof and floor none.
  BOOST_TEST(per_face.size() == 8u);
  const skyband::TriangleSoup back = skyband::read_mesh(d / "cube.ply");
  const skyband::TriangleSoup cube = skyband::read_mesh(d / "cube.obj");
  BOOST_TEST(back.triangle_count() == cube.triangle_count());
  BOOST_TEST((back.vertices == cube.vertices));
  const PlyFaces ply = read_ply_faces(d / "cube.ply");
  BOOST_TEST_REQUIRE(ply.values.size() == cube.triangle_count());
  std::size_t nodata = 0;
  for (std::size_t t = 0; t < ply.values.size(); ++t) {
    if (const auto it = per_face.find(int(t)); it != per_face.end()) {
      // Float32: within 2⁻²⁴ relative of the mean.
      BOOST_TEST(std::abs(ply.values[t] - it->second.first / it->second.second) < 1e-7, "face " << t);
    } else {
      BOOST_TEST(ply.values[t] == -9999.0f);
      BOOST_TEST((ply.rgb[t] == std::array<int, 3>{200, 200, 200}));
      ++nodata;
    }
  }
  BOOST_TEST(nodata == 4u);
  BOOST_TEST(r.err.find("8 of 12 faces painted") != std::string::npos, r.err);
  BOOST_TEST(fs::exists(d / "cube.ply.provenance.json"));
}

BOOST_AUTO_TEST_CASE(bad_input_exits_2_and_writes_nothing) {
  const fs::path d = skyband::test::test_folder("paint_cli_bad");
  skyband::test::write_cube_obj(d / "cube.obj");
  std::ofstream(d / "noface.csv") << "x,y,z,svf\n1,2,3,0.5\n";
  std::ofstream(d / "far.csv") << "x,y,z,face,svf\n1,2,3,12,0.5\n";
  std::ofstream(d / "frac.csv") << "x,y,z,face,svf\n1,2,3,1.5,0.5\n";
  std::ofstream(d / "novalue.csv") << "x,y,z,face,svf\n1,2,3,1,abc\n";
  const std::string mesh = " --mesh " + q(d / "cube.obj"), out = " --out " + q(d / "out.ply");
  skyband::test::check_bad_input(
      {
          {"paint --values " + q(d / "far.csv") + out, "--mesh"},
          {"paint" + mesh + out, "--values"},
          {"paint" + mesh + " --values " + q(d / "noface.csv") + out, "face"},
          {"paint" + mesh + " --values " + q(d / "far.csv") + out, "far.csv:2"},
          {"paint" + mesh + " --values " + q(d / "frac.csv") + out, "1.5"},
          {"paint" + mesh + " --values " + q(d / "novalue.csv") + out, "abc"},
          {"paint" + mesh + " --values " + q(d / "far.csv") + " --column sky_exposure" + out, "sky_exposure"},
          {"paint" + mesh + " --values " + q(d / "far.csv") + " --out " + q(d / "out.obj"), ".ply"},
          {"paint" + mesh + " --values " + q(d / "missing.csv") + out, "missing.csv"},
      },
      d / "out.ply");
}
