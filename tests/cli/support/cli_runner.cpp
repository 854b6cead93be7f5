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
    BOOST_TEST(!std::filesystem::exists(must_not_exist));
  }
}

void write_cube_obj(const std::filesystem::path& file) {
  std::ofstream f(file);
  f << "# cube\n";
  for (int i = 0; i < 8; ++i) f << "v " << (i & 1 ? 10 : 0) << ' ' << (i & 2 ? 10 : 0) << ' ' << (i & 4 ? 10 : 0) << '\n';
  f << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
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
