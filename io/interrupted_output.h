#pragma once
// Temporary output files that an interrupted run removes: while one is registered, SIGINT,
// SIGTERM or SIGHUP unlinks it before the process ends with that signal, so stopping a long run
// (Ctrl-C, a batch system's time limit) leaves neither a half-written target nor its temporary
// file. The targets themselves are only ever replaced by a rename (io/atomic_file.h).
#include <filesystem>

namespace skyband {

// Installs the handlers (once; later calls do nothing). The CLI calls it at start-up.
void remove_temporary_outputs_on_interrupt();

// Registers `path` for removal on an interrupt while the guard lives (up to 64 at once; beyond
// that a path is not registered, and an interrupt may leave it).
class TemporaryOutput {
 public:
  explicit TemporaryOutput(const std::filesystem::path& path);
  ~TemporaryOutput();
  TemporaryOutput(const TemporaryOutput&) = delete;
  TemporaryOutput& operator=(const TemporaryOutput&) = delete;

 private:
  int slot_ = -1;
};

}  // namespace skyband
