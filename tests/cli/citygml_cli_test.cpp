#define BOOST_TEST_MODULE citygml_cli
#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>
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

// A CityGML 2.0 cube [x0, x0 + 10] × [y0, y0 + 10] × [0, 10] as an LoD 1 solid, in ETRS89 / UTM 32N.
void write_cube_gml(const fs::path& file, double x0, double y0) {
  auto p = [&](double x, double y, double z) {
    std::ostringstream s;
    s.precision(17);
    s << x0 + x << " " << y0 + y << " " << z << " ";
    return s.str();
  };
  const std::vector<std::string> faces{p(0, 0, 0) + p(0, 10, 0) + p(10, 10, 0) + p(10, 0, 0) + p(0, 0, 0),
                                       p(0, 0, 10) + p(10, 0, 10) + p(10, 10, 10) + p(0, 10, 10) + p(0, 0, 10),
                                       p(0, 0, 0) + p(10, 0, 0) + p(10, 0, 10) + p(0, 0, 10) + p(0, 0, 0),
                                       p(10, 0, 0) + p(10, 10, 0) + p(10, 10, 10) + p(10, 0, 10) + p(10, 0, 0),
                                       p(10, 10, 0) + p(0, 10, 0) + p(0, 10, 10) + p(10, 10, 10) + p(10, 10, 0),
                                       p(0, 10, 0) + p(0, 0, 0) + p(0, 0, 10) + p(0, 10, 10) + p(0, 10, 0)};
  std::ofstream out(file);
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<core:CityModel xmlns:core=\"http://www.opengis.net/citygml/2.0\" "
         "xmlns:bldg=\"http://www.opengis.net/citygml/building/2.0\" xmlns:gml=\"http://www.opengis.net/gml\">\n"
         "<core:cityObjectMember><bldg:Building gml:id=\"cube\"><bldg:lod1Solid><gml:Solid srsName=\"EPSG:25832\"><gml:exterior>"
         "<gml:CompositeSurface>\n";
  for (const std::string& f : faces)
    out << "<gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>" << f
        << "</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>\n";
  out << "</gml:CompositeSurface></gml:exterior></gml:Solid></bldg:lod1Solid></bldg:Building></core:cityObjectMember>\n"
         "</core:CityModel>\n";
}

}  // namespace

// The cube's closed forms (as in svf_cli_test): its top face sees the whole sky (SVF 1), an open
// wall facing away from it half (0.5), at projected coordinates kept verbatim.
BOOST_AUTO_TEST_CASE(svf_on_a_citygml_cube_closed_form) {
  const fs::path d = skyband::test::test_folder("citygml_cli_cube");
  const double x0 = 500000.5, y0 = 5400000.25;
  write_cube_gml(d / "cube.gml", x0, y0);
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
