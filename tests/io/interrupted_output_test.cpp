#define BOOST_TEST_MODULE interrupted_output
#include <boost/test/unit_test.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/atomic_file.h"
#include "io/interrupted_output.h"

namespace fs = std::filesystem;
using namespace skyband;

namespace {

fs::path folder() {
  const fs::path d = fs::temp_directory_path() / ("skyband_interrupted_output_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// Runs body() in a child process and returns how it ended (waitpid status).
template <class F>
int in_child(F body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    body();
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

}  // namespace

// An interrupt while a temporary output is registered removes it, and the process still ends by
// that signal (a caller's shell sees the usual 128 + n); a file not registered stays.
BOOST_AUTO_TEST_CASE(an_interrupt_removes_the_registered_temporary_files) {
  const fs::path d = folder();
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const fs::path temp = d / ("partial_" + std::to_string(sig)), other = d / ("kept_" + std::to_string(sig));
    const int status = in_child([&] {
      remove_temporary_outputs_on_interrupt();
      std::ofstream(temp) << "half";
      std::ofstream(other) << "not an output";
      const TemporaryOutput guard(temp);
      std::raise(sig);
    });
    BOOST_TEST(WIFSIGNALED(status));
    BOOST_TEST(WTERMSIG(status) == sig);
    BOOST_TEST(!fs::exists(temp));
    BOOST_TEST(fs::exists(other));
  }
  fs::remove_all(d);
}

// A guard that has ended no longer removes its path; write_atomically registers its temporary
// file while the writer runs: interrupted inside it, neither the target nor the temporary remains.
BOOST_AUTO_TEST_CASE(guards_end_and_atomic_writes_are_covered) {
  const fs::path d = folder();
  const fs::path done = d / "done", target = d / "target.csv";
  const int status = in_child([&] {
    remove_temporary_outputs_on_interrupt();
    std::ofstream(done) << "complete";
    { const TemporaryOutput guard(done); }
    write_atomically(target, [&](const fs::path& temp) {
      std::ofstream(temp) << "x,y\n1,";
      std::raise(SIGTERM);
    });
  });
  BOOST_TEST(WIFSIGNALED(status));
  BOOST_TEST(fs::exists(done));
  BOOST_TEST(!fs::exists(target));
  std::size_t left = 0;
  for (const auto& e : fs::directory_iterator(d)) left += e.path().filename() != "done";
  BOOST_TEST(left == 0u);
  fs::remove_all(d);
}
