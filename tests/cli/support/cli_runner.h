#pragma once
// Runs the built skyband CLI ($SKYBAND_EXE, set by CTest) and captures exit code, stdout, stderr.
#include <filesystem>
#include <string>

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

// A closed 10 m cube [0,10]³ as six OBJ quads (our own geometry; the closed forms of the CLI
// tests are computed for it).
void write_cube_obj(const std::filesystem::path& file);

}  // namespace skyband::test
