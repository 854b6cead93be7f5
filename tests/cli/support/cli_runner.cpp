#include "cli/support/cli_runner.h"

#include <boost/test/unit_test.hpp>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace skyband::test {

std::filesystem::path test_folder(const std::string& name) {
  const std::filesystem::path d = std::filesystem::path(SKYBAND_BINARY_DIR) / "test_output" / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

std::string shell_quote(const std::filesystem::path& p) {
  std::string s = "'";  // built with += : GCC 12 warns falsely on "'" + s + "'" (-Wrestrict)
  s += p.string();
  s += '\'';
  return s;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void check_bad_input(const std::vector<BadInputCase>& cases, const std::filesystem::path& must_not_exist) {
  for (const BadInputCase& c : cases) {
    const CliResult r = run_skyband(c.args);
    BOOST_TEST_INFO(c.args);
    BOOST_TEST(r.exit_code == 2);
    BOOST_TEST(r.err.find(c.must_mention) != std::string::npos, "stderr: " << r.err);
    for (const std::string& m : c.also_mention) BOOST_TEST(r.err.find(m) != std::string::npos, m << " in stderr: " << r.err);
    BOOST_TEST(!std::filesystem::exists(must_not_exist));
  }
}

void write_cube_obj(const std::filesystem::path& file) {
  std::ofstream f(file);
  f << "# cube\n";
  for (int i = 0; i < 8; ++i) f << "v " << (i & 1 ? 10 : 0) << ' ' << (i & 2 ? 10 : 0) << ' ' << (i & 4 ? 10 : 0) << '\n';
  f << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
}

void write_cube_citygml(const std::filesystem::path& file, double x0, double y0, const std::string& srs) {
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
         "<core:cityObjectMember><bldg:Building gml:id=\"cube\"><bldg:lod1Solid><gml:Solid srsName=\""
      << srs << "\"><gml:exterior><gml:CompositeSurface>\n";
  for (const std::string& f : faces)
    out << "<gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>" << f
        << "</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>\n";
  out << "</gml:CompositeSurface></gml:exterior></gml:Solid></bldg:lod1Solid></bldg:Building></core:cityObjectMember>\n"
         "</core:CityModel>\n";
}

CliResult run_skyband(const std::string& args) {
  const char* exe = std::getenv("SKYBAND_EXE");
  if (!exe) throw std::runtime_error("SKYBAND_EXE is not set (run the test through ctest)");
  static int counter = 0;
  const auto err_file = std::filesystem::path(SKYBAND_BINARY_DIR) / "test_output" /
                        ("cli_stderr_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ".txt");
  std::filesystem::create_directories(err_file.parent_path());
  const std::string cmd = std::string("'") + exe + "' " + args + " 2>'" + err_file.string() + "'";
  CliResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) throw std::runtime_error("popen failed: " + cmd);
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_file);
  std::stringstream ss;
  ss << e.rdbuf();
  r.err = ss.str();
  std::filesystem::remove(err_file);
  return r;
}

}  // namespace skyband::test
