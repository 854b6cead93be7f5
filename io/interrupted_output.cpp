#include "io/interrupted_output.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>

namespace skyband {
namespace {

constexpr int kSlots = 64;
// Each slot holds a heap copy of a registered path, or null. The handler only reads the slots and
// calls unlink(), which is async-signal-safe.
std::atomic<char*> g_slots[kSlots];

extern "C" void remove_and_reraise(int signal_number) {
  for (auto& slot : g_slots)
    if (const char* path = slot.load()) ::unlink(path);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

}  // namespace

void remove_temporary_outputs_on_interrupt() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction action {};
      action.sa_handler = remove_and_reraise;
      sigemptyset(&action.sa_mask);
      ::sigaction(s, &action, nullptr);
    }
  });
}

TemporaryOutput::TemporaryOutput(const std::filesystem::path& path) {
  const std::string text = path.string();
  char* copy = new char[text.size() + 1];
  std::memcpy(copy, text.c_str(), text.size() + 1);
  for (int i = 0; i < kSlots; ++i) {
    char* empty = nullptr;
    if (g_slots[i].compare_exchange_strong(empty, copy)) {
      slot_ = i;
      return;
    }
  }
  delete[] copy;
}

TemporaryOutput::~TemporaryOutput() {
  if (slot_ >= 0) delete[] g_slots[slot_].exchange(nullptr);
}

}  // namespace skyband
