#pragma once
// Runs a measurement in a forked child process, so that its peak memory is its own, and returns a
// trivially copyable result through a pipe (the default-constructed result if the child fails).
#include <fstream>
#include <string>
#include <type_traits>

#include <sys/wait.h>
#include <unistd.h>

namespace skyband::bench {

// A field of /proc/self/status in kB ("VmRSS", "VmHWM"); -1 if absent.
inline long status_kb(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string key = std::string(field) + ":";
  while (std::getline(in, line))
    if (line.compare(0, key.size(), key) == 0) return std::stol(line.substr(key.size()));
  return -1;
}

// result = job() in a child process.
template <class Job>
auto in_child(Job&& job) -> decltype(job()) {
  using Result = decltype(job());
  static_assert(std::is_trivially_copyable_v<Result>);
  int fd[2];
  if (pipe(fd) != 0) return Result{};
  const pid_t pid = fork();
  if (pid < 0) {
    close(fd[0]), close(fd[1]);
    return Result{};
  }
  if (pid == 0) {
    close(fd[0]);
    const Result r = job();
    (void)!write(fd[1], &r, sizeof r);
    _exit(0);
  }
  close(fd[1]);
  Result r;
  if (read(fd[0], &r, sizeof r) != sizeof r) r = Result{};
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return r;
}

}  // namespace skyband::bench
