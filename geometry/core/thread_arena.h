#pragma once
// Runs `f` with its TBB parallel loops limited to `threads` workers (0 = TBB's default: all
// cores). The lighting passes take a thread count from RenderSettings::threads; the results never
// depend on it (every output element is written by one task).
#include <utility>

#include <tbb/task_arena.h>

namespace skyband {

template <class F>
void run_with_threads(int threads, F&& f) {
  if (threads > 0) {
    tbb::task_arena arena(threads);
    arena.execute(std::forward<F>(f));
  } else {
    std::forward<F>(f)();
  }
}

}  // namespace skyband
