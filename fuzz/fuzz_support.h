#pragma once
// What every skyband fuzz harness shares: the input handed to a reader that only takes paths,
// and the rule that decides what counts as a finding.
//
// A harness passes when the reader returns or throws skyband::InputError (the documented answer
// to bad input). Everything else is a finding: another exception escaping (reported here with
// its type and message, then abort()), a crash, a sanitizer report, a timeout or running out of
// memory (libFuzzer's -timeout and -rss_limit_mb).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <typeinfo>
#include <vector>

#include <cxxabi.h>
#include <unistd.h>

#include "geometry/core/input_error.h"

namespace skyband::fuzz {

// A per-process file in the temporary folder ($TMPDIR), overwritten by every run:
// skyband-fuzz-<pid>-<tag><ext>. The extension matters: read_mesh picks the format from it.
// Removed when the process exits normally (libFuzzer exits at the end of a run; after a crash
// the file stays, like the crash's own reproducer).
inline std::filesystem::path temp_path(std::string_view tag, std::string_view ext) {
  struct Registry {
    std::vector<std::filesystem::path> paths;
    ~Registry() {
      std::error_code ignored;
      for (const auto& p : paths) std::filesystem::remove(p, ignored);
    }
  };
  static Registry created;
  std::filesystem::path p = std::filesystem::temp_directory_path() /
                            ("skyband-fuzz-" + std::to_string(::getpid()) + "-" + std::string(tag) + std::string(ext));
  created.paths.push_back(p);
  return p;
}

// Writes the input verbatim (binary) to `path`, replacing what was there.
inline void write_input(const std::filesystem::path& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) {
    std::fprintf(stderr, "skyband-fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
}

// A finding that is not a crash of its own (an escaped exception, a broken round trip): say what
// and abort, so that libFuzzer saves the input.
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "skyband-fuzz: FINDING: %s\n", what.c_str());
  std::abort();
}

inline std::string type_name(const std::type_info& t) {
  int status = 0;
  char* n = abi::__cxa_demangle(t.name(), nullptr, nullptr, &status);
  std::string s = status == 0 && n ? n : t.name();
  std::free(n);
  return s;
}

// Runs f(); InputError is the expected answer to bad input, any other exception is a finding.
template <class F>
void expect_input_errors_only(const char* call, F&& f) {
  try {
    f();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    finding(std::string(call) + " let " + type_name(typeid(e)) + " escape: " + e.what());
  } catch (...) {
    finding(std::string(call) + " let an exception of unknown type escape");
  }
}

}  // namespace skyband::fuzz
