#define BOOST_TEST_MODULE citygml_cli
#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/support/cli_runner.h"
#include "io/mesh_reader.h"
#include "shared_data.h"

namespace tt = boost::test_tools;
namespace fs = std::filesystem;
using skyband::test::run_skyband;
using skyband::test::slurp;

namespace {

std::string q(const fs::path& p) {
  return skyband::test::shell_quote(p);
}

// The svf column of each output row (the second-last column).
std::vector<double> svf_column(const fs::path& out) {
  std::istringstream in(slurp(out));
  std::string line;
  std::getline(in, line);
  std::vector<double> svf;
  while (std::getline(in, line)) {
    const auto last = line.rfind(','), prev = line.rfind(',', last - 1);
    svf.push_back(std::stod(line.substr(prev + 1, last - prev - 1)));
  }
  return svf;
}

// The cube of write_cube_citygml with its first ring (on line 4) as gml:pos elements, the first
// vertex's x written as `x_text` verbatim (so that bad values can be written).
void write_cube_with_pos(const fs::path& file, const std::string& x_text) {
  skyband::test::write_cube_citygml(file, 500000, 5400000);
  std::string text = slurp(file);
  const std::size_t b = text.find("<gml:posList>"), e = text.find("</gml:posList>");
  std::istringstream numbers(text.substr(b + 13, e - b - 13));
  std::string ring, x, y, z;
  for (bool first = true; numbers >> x >> y >> z; first = false)
    ring += "<gml:pos>" + (first ? x_text + " " : x + " ") + y + " " + z + "</gml:pos>";
  text.replace(b, e + 14 - b, ring);
  std::ofstream(file) << text;
}

// A CityGML 2.0 model with `members` (core:cityObjectMember contents) and the namespaces of the
// building, relief and land-use modules, plus `extra` declarations.
std::string citygml_document(const std::string& members, const std::string& extra = "") {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<core:CityModel xmlns:core=\"http://www.opengis.net/citygml/2.0\" "
         "xmlns:bldg=\"http://www.opengis.net/citygml/building/2.0\" xmlns:dem=\"http://www.opengis.net/citygml/relief/2.0\" "
         "xmlns:luse=\"http://www.opengis.net/citygml/landuse/2.0\" xmlns:gml=\"http://www.opengis.net/gml\"" +
         extra + ">\n" + members + "</core:CityModel>\n";
}

// A closed ring as a gml:posList (the first vertex repeated at the end).
std::string pos_list(const std::vector<std::array<double, 3>>& ring) {
  std::ostringstream s;
  s.precision(17);
  s << "<gml:posList>";
  for (std::size_t i = 0; i <= ring.size(); ++i) {
    const auto& p = ring[i % ring.size()];
    s << p[0] << " " << p[1] << " " << p[2] << (i < ring.size() ? " " : "");
  }
  s << "</gml:posList>";
  return s.str();
}

std::string polygon(const std::vector<std::array<double, 3>>& ring, const std::string& element = "gml:Polygon") {
  return "<" + element + "><gml:exterior><gml:LinearRing>" + pos_list(ring) + "</gml:LinearRing></gml:exterior></" + element +
         ">";
}

}  // namespace

// The cube's closed forms (as in svf_cli_test): its top face sees the whole sky (SVF 1), an open
// wall facing away from it half (0.5), at projected coordinates kept verbatim.
BOOST_AUTO_TEST_CASE(svf_on_a_citygml_cube_closed_form) {
  const fs::path d = skyband::test::test_folder("citygml_cli_cube");
  const double x0 = 500000.5, y0 = 5400000.25;
  skyband::test::write_cube_citygml(d / "cube.gml", x0, y0);
  std::ofstream(d / "pts.csv") << std::fixed << "x,y,z,nx,ny,nz\n"
                               << x0 + 5 << "," << y0 + 5 << ",10,0,0,1\n"
                               << x0 - 20 << "," << y0 + 5 << ",3,-1,0,0\n";
  const auto r = run_skyband("svf --mesh " + q(d / "cube.gml") + " --points " + q(d / "pts.csv") + " --out " + q(d / "out.csv"));
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("CityGML 2.0") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("12 triangles") != std::string::npos, r.err);
  const std::vector<double> svf = svf_column(d / "out.csv");
  BOOST_TEST_REQUIRE(svf.size() == 2u);
  BOOST_TEST(svf[0] == 1.0, tt::tolerance(1e-12));
  BOOST_TEST(svf[1] == 0.5, tt::tolerance(1e-9));
  // --lod 2: the cube has none.
  const auto lod2 =
      run_skyband("svf --mesh " + q(d / "cube.gml") + " --points " + q(d / "pts.csv") + " --out " + q(d / "o2.csv") + " --lod 2");
  BOOST_TEST(lod2.exit_code == 2, lod2.err);
  BOOST_TEST(lod2.err.find("no triangles") != std::string::npos, lod2.err);
}

// PLATEAU Tokyo (EPSG:6697, degrees) runs in JGD2011 / UTM zone 54N: a point above the roof sees
// the whole sky, one at the foot of the building less, one 2 km away nearly all of it.
BOOST_AUTO_TEST_CASE(svf_on_plateau_tokyo_in_utm, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("citygml_cli_tokyo");
  const fs::path gml = fs::path(SKYBAND_SHARED_DATA) / "citygml" / "plateau_tokyo_53394517_bldg_6697_2_op.citygml2.gml";
  const skyband::TriangleSoup s = skyband::read_mesh(gml);
  Eigen::AlignedBox3d box;
  for (const auto& v : s.vertices) box.extend(v);
  const Eigen::Vector3d c = box.center();
  // The westernmost vertex at ground level: a point 1 m west of it stands at the foot of a facade.
  Eigen::Vector3d west = c;
  for (const auto& v : s.vertices)
    if (v.z() < box.min().z() + 0.5 && v.x() < west.x()) west = v;
  std::ofstream(d / "pts.csv") << std::fixed << "x,y,z\n"
                               << c.x() << "," << c.y() << "," << box.max().z() + 1 << "\n"
                               << west.x() - 1 << "," << west.y() << "," << box.min().z() + 0.5 << "\n"
                               << c.x() + 2000 << "," << c.y() << "," << box.min().z() << "\n";
  const auto r = run_skyband("svf --mesh " + q(gml) + " --points " + q(d / "pts.csv") + " --out " + q(d / "out.csv"));
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("EPSG:6691") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("JGD2011 / UTM zone 54N") != std::string::npos, r.err);
  const std::vector<double> svf = svf_column(d / "out.csv");
  BOOST_TEST_REQUIRE(svf.size() == 3u);
  BOOST_TEST(svf[0] == 1.0, tt::tolerance(1e-12));
  BOOST_TEST(svf[1] > 0.3);  // 3 m from a ~20 m facade: much of the sky hidden, not all
  BOOST_TEST(svf[1] < 0.9);
  BOOST_TEST(svf[2] > 0.999);
}

BOOST_AUTO_TEST_CASE(citygml_3_ends_with_one_error_line, *skyband::test::needs_shared_data()) {
  const fs::path d = skyband::test::test_folder("citygml_cli_v3");
  const fs::path gml = fs::path(SKYBAND_SHARED_DATA) / "citygml" / "lyon_opera_CityGML3.0_LOD2.gml";
  std::ofstream(d / "p.csv") << "x,y,z\n0,0,0\n";
  skyband::test::check_bad_input(
      {{"svf --mesh " + q(gml) + " --points " + q(d / "p.csv") + " --out " + q(d / "o.csv"), "CityGML 3.0 is not supported"}},
      d / "o.csv");
}

// Every coordinate of a gml:pos is checked as a posList's are: a value that is not a finite
// double (overflowing, NaN, infinite, garbled) or an empty position ends the run with one line
// naming the file, the line and the value, exit code 2, and no output.
BOOST_AUTO_TEST_CASE(bad_gml_pos_values_exit_2_naming_file_line_and_value) {
  const fs::path d = skyband::test::test_folder("citygml_cli_pos");
  std::vector<skyband::test::BadInputCase> cases;
  int k = 0;
  for (const auto& [value, says] : std::vector<std::pair<std::string, std::string>>{{"1e400", "out of the range of a double"},
                                                                                    {"-1e999", "out of the range of a double"},
                                                                                    {"NaN", "non-finite"},
                                                                                    {"INF", "non-finite"},
                                                                                    {"1.0abc", "not a number"}}) {
    const fs::path f = d / ("pos" + std::to_string(k++) + ".gml");
    write_cube_with_pos(f, value);
    cases.push_back(
        {"points grid --mesh " + q(f) + " --spacing 1 --out " + q(d / "p.csv"), f.string() + ":4:", {"'" + value + "'", says}});
  }
  const fs::path empty = d / "empty.gml";
  write_cube_with_pos(empty, "");
  std::string text = slurp(empty);
  const std::size_t first = text.find("<gml:pos>");  // "<gml:pos> 5400000 0</gml:pos>" (2 numbers) made empty
  text.replace(first, text.find("</gml:pos>") - first, "<gml:pos>");
  std::ofstream(empty) << text;
  cases.push_back({"points grid --mesh " + q(empty) + " --spacing 1 --out " + q(d / "p.csv"),
                   empty.string() + ":4:",
                   {"<gml:pos> is empty"}});
  skyband::test::check_bad_input(cases, d / "p.csv");
  // The same cube with a valid value (a leading '+' is valid xs:double) reads.
  write_cube_with_pos(d / "good.gml", "+500000");
  const auto r = run_skyband("points grid --mesh " + q(d / "good.gml") + " --spacing 5 --out " + q(d / "p.csv"));
  BOOST_TEST(r.exit_code == 0, r.err);
}

// Elements of an Application Domain Extension are not read: a file that holds nothing else ends
// with one line naming it and the ADE's namespace (exit 2, no output); a building with an ADE
// property and an ADE feature beside it is read without them, and the report says so.
BOOST_AUTO_TEST_CASE(ade_elements_are_skipped_and_an_ade_only_file_is_refused) {
  const fs::path d = skyband::test::test_folder("citygml_cli_ade");
  const std::string ns = " xmlns:zone=\"https://example.org/ade/zoning/1.0\"";
  const std::string area = polygon({{{0, 0, 0}, {50, 0, 0}, {50, 50, 0}, {0, 50, 0}}});
  std::ofstream(d / "zones.gml") << citygml_document(
      "<core:cityObjectMember><zone:District gml:id=\"z\"><zone:lod1MultiSurface>"
      "<gml:MultiSurface><gml:surfaceMember>" +
          area +
          "</gml:surfaceMember></gml:MultiSurface></zone:lod1MultiSurface>"
          "</zone:District></core:cityObjectMember>\n",
      ns);
  skyband::test::check_bad_input({{"points grid --mesh " + q(d / "zones.gml") + " --spacing 5 --out " + q(d / "p.csv"),
                                   (d / "zones.gml").string(),
                                   {"Application Domain Extension", "https://example.org/ade/zoning/1.0", "zone:District"}}},
                                 d / "p.csv");
  // The cube with an ADE property inside the building and the district beside it.
  skyband::test::write_cube_citygml(d / "cube.gml", 0, 0);
  std::string cube = slurp(d / "cube.gml");
  cube.insert(cube.find("<bldg:lod1Solid>"), "<zone:floorArea>120</zone:floorArea>");
  cube.insert(cube.find("</core:CityModel>"), "<core:cityObjectMember><zone:District gml:id=\"z\"/></core:cityObjectMember>\n");
  cube.insert(cube.find(" xmlns:gml="), ns);
  std::ofstream(d / "cube_ade.gml") << cube;
  const auto r = run_skyband("points grid --mesh " + q(d / "cube_ade.gml") + " --spacing 5 --out " + q(d / "p.csv"));
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("12 triangles") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("1 x <zone:District>, 1 x <zone:floorArea>") != std::string::npos, r.err);
}

// A TINRelief (dem:ReliefFeature / dem:reliefComponent, as PLATEAU's dem files hold it) is
// terrain: `points grid` puts its points on it, and only the cube's cells are under a building.
// 10 × 10 cells of 5 m over [-20, 30]²: the 4 cells of the 10 m cube are left out.
BOOST_AUTO_TEST_CASE(tin_relief_is_the_ground_of_points_grid) {
  const fs::path d = skyband::test::test_folder("citygml_cli_relief");
  skyband::test::write_cube_citygml(d / "cube.gml", 0, 0);
  std::string text = slurp(d / "cube.gml");
  const std::string tin =
      "<core:cityObjectMember><dem:ReliefFeature gml:id=\"relief\"><dem:lod>1</dem:lod><dem:reliefComponent>"
      "<dem:TINRelief gml:id=\"tin\"><dem:lod>1</dem:lod><dem:tin><gml:TriangulatedSurface><gml:trianglePatches>" +
      polygon({{{-20, -20, 0}, {30, -20, 0}, {30, 30, 0}}}, "gml:Triangle") +
      polygon({{{-20, -20, 0}, {30, 30, 0}, {-20, 30, 0}}}, "gml:Triangle") +
      "</gml:trianglePatches></gml:TriangulatedSurface></dem:tin></dem:TINRelief></dem:reliefComponent></dem:ReliefFeature>"
      "</core:cityObjectMember>\n";
  text.insert(text.find("</core:CityModel>"), tin);
  text.insert(text.find(" xmlns:gml="), " xmlns:dem=\"http://www.opengis.net/citygml/relief/2.0\"");
  std::ofstream(d / "relief.gml") << text;
  const auto r = run_skyband("points grid --mesh " + q(d / "relief.gml") + " --spacing 5 --out " + q(d / "p.csv"));
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("10 × 10 nodes at 5 m: 96 points 0 m above the ground, 4 under or on buildings") != std::string::npos,
             r.err);
}

// Models given together must share one CRS: two cubes in ETRS89 / UTM 32N and RD New end with one
// line naming both files and both CRSs (exit 2, no output), for every command that reads meshes;
// the same CRS spelled two ways, or a mesh without a CRS, joins.
BOOST_AUTO_TEST_CASE(models_in_different_crss_are_refused) {
  const fs::path d = skyband::test::test_folder("citygml_cli_crs_mix");
  skyband::test::write_cube_citygml(d / "utm.gml", 500000, 5400000, "EPSG:25832");
  skyband::test::write_cube_citygml(d / "rd.gml", 500020, 5400000, "urn:ogc:def:crs:EPSG::28992");
  skyband::test::write_cube_citygml(d / "utm_urn.gml", 500040, 5400000, "urn:ogc:def:crs:EPSG::25832");
  skyband::test::write_cube_obj(d / "cube.obj");
  std::ofstream(d / "pts.csv") << "x,y,z\n500005,5400005,11\n";
  const std::string two = " --mesh " + q(d / "utm.gml") + " --mesh " + q(d / "rd.gml");
  const std::vector<std::string> both{(d / "rd.gml").string(), "urn:ogc:def:crs:EPSG::28992", "EPSG:25832", "different CRSs"};
  skyband::test::check_bad_input(
      {{"points grid" + two + " --spacing 5 --out " + q(d / "o.csv"), (d / "utm.gml").string(), both},
       {"svf" + two + " --points " + q(d / "pts.csv") + " --out " + q(d / "o.csv"), (d / "utm.gml").string(), both},
       {"points facades" + two + " --spacing 5 --out " + q(d / "o.csv"), (d / "utm.gml").string(), both}},
      d / "o.csv");
  skyband::test::check_bad_input({{"map" + two + " --spacing 5 --out " + q(d / "o.tif"), (d / "utm.gml").string(), both}},
                                 d / "o.tif");
  const auto r = run_skyband("svf --mesh " + q(d / "utm.gml") + " --mesh " + q(d / "utm_urn.gml") + " --mesh " +
                             q(d / "cube.obj") + " --points " + q(d / "pts.csv") + " --out " + q(d / "o.csv"));
  BOOST_TEST(r.exit_code == 0, r.err);
}

// Two geographic (JGD2011, EPSG:6668) land-use tiles on both sides of the boundary of UTM zones
// 53 and 54 (138° E) are projected to one zone, the first one's, so they join in one CRS.
BOOST_AUTO_TEST_CASE(geographic_tiles_across_a_utm_zone_boundary_share_a_zone) {
  const fs::path d = skyband::test::test_folder("citygml_cli_zones");
  auto tile = [&](const fs::path& f, double lon0) {
    const std::string area =
        polygon({{{35.0, lon0, 10}, {35.0, lon0 + 0.0005, 10}, {35.0005, lon0 + 0.0005, 10}, {35.0005, lon0, 10}}});
    std::ofstream(f) << citygml_document(
        "<core:cityObjectMember><luse:LandUse gml:id=\"l\"><luse:lod1MultiSurface>"
        "<gml:MultiSurface srsName=\"EPSG:6668\"><gml:surfaceMember>" +
        area +
        "</gml:surfaceMember></gml:MultiSurface></luse:lod1MultiSurface></luse:LandUse>"
        "</core:cityObjectMember>\n");
  };
  tile(d / "west.gml", 137.9994);
  tile(d / "east.gml", 138.0001);
  const auto r = run_skyband("points grid --mesh " + q(d / "west.gml") + " --mesh " + q(d / "east.gml") + " --spacing 10 --out " +
                             q(d / "p.csv"));
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("EPSG:6691") == std::string::npos, r.err);  // zone 54N: not used
  BOOST_TEST(r.err.find("the zone of the models read before it") != std::string::npos, r.err);
  // The other order: both in zone 54.
  const auto e = run_skyband("points grid --mesh " + q(d / "east.gml") + " --mesh " + q(d / "west.gml") + " --spacing 10 --out " +
                             q(d / "p.csv"));
  BOOST_TEST_REQUIRE(e.exit_code == 0, e.err);
  BOOST_TEST(e.err.find("EPSG:6690") == std::string::npos, e.err);  // zone 53N: not used
}

// A vertex far beyond any place on Earth (x = 1e300) is read, with a warning on stderr naming the
// file and the value, printed with --quiet too.
BOOST_AUTO_TEST_CASE(far_vertices_are_warned_about) {
  const fs::path d = skyband::test::test_folder("citygml_cli_far");
  skyband::test::write_cube_citygml(d / "cube.gml", 500000, 5400000);
  std::string text = slurp(d / "cube.gml");
  text.replace(text.find("500010 5400000 0"), 16, "1e300 5400000 0");
  std::ofstream(d / "far.gml") << text;
  std::ofstream(d / "pts.csv") << "x,y,z\n500005,5400005,11\n";
  const auto r =
      run_skyband("svf --mesh " + q(d / "far.gml") + " --points " + q(d / "pts.csv") + " --out " + q(d / "o.csv") + " --quiet");
  BOOST_TEST(r.err.find("warning: " + (d / "far.gml").string()) != std::string::npos, r.err);
  BOOST_TEST(r.err.find("1.0000000000000001e+300") != std::string::npos, r.err);
}
