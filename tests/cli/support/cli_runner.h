#pragma once
// Runs the built skyband CLI ($SKYBAND_EXE, set by CTest) and captures exit code, stdout, stderr.
#include <filesystem>
#include <string>
#include <vector>

namespace skyband::test {

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

// `args` is appended to the executable path as shell words (quote paths yourself).
CliResult run_skyband(const std::string& args);

// A fresh folder under the build tree for one test's files.
std::filesystem::path test_folder(const std::string& name);

// A path single-quoted for the shell.
std::string shell_quote(const std::filesystem::path& p);

// The whole content of a file.
std::string slurp(const std::filesystem::path& p);

// A command that must fail on bad input: exit code 2, and stderr mentioning `must_mention` (the
// file, line, flag or value at fault) and each of `also_mention` (a second file, the value).
struct BadInputCase {
  std::string args, must_mention;
  std::vector<std::string> also_mention = {};
};

// Runs each case and checks it (Boost.Test assertions, each labelled with the command), and
// that `must_not_exist` (the output the command was asked to write) was never created.
void check_bad_input(const std::vector<BadInputCase>& cases, const std::filesystem::path& must_not_exist);

// A closed 10 m cube [0,10]³ as six OBJ quads (our own geometry; the closed forms of the CLI
// tests are computed for it).
void write_cube_obj(const std::filesystem::path& file);

// A CityGML 2.0 cube [x0, x0 + 10] × [y0, y0 + 10] × [0, 10] as an LoD 1 solid of six
// gml:posList rings, its srsName `srs`.
void write_cube_citygml(const std::filesystem::path& file, double x0, double y0, const std::string& srs = "EPSG:25832");

}  // namespace skyband::test
