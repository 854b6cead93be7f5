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

}  // namespace skyband::test
