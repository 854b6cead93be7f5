#pragma once
// Points in chunks on a fixed number of workers, each with its own state (an evaluator that is
// not thread-safe), with progress reported from one thread at a time. Each item is processed
// alone, so results do not depend on the thread count.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace skyband {

// Calls chunk_body(state, first, last) for every chunk [first, last) of `chunk` consecutive items
// of [0, n) (the last one shorter) on `threads` workers (0 = all cores); `make_state()` returns a
// std::unique_ptr<State> for each worker that needs one. `progress(done, n)` after chunks, from one
// thread at a time (may be empty).
template <class MakeState, class ChunkBody>
void for_each_chunk(std::size_t n, std::size_t chunk, int threads, const std::function<void(std::size_t, std::size_t)>& progress,
                    MakeState&& make_state, ChunkBody&& chunk_body) {
  using StatePtr = decltype(make_state());
  tbb::enumerable_thread_specific<StatePtr> states;
  const std::size_t chunks = (n + chunk - 1) / chunk;
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& range) {
      StatePtr& state = states.local();
      if (!state) state = make_state();
      for (std::size_t c = range.begin(); c != range.end(); ++c) {
        const std::size_t first = c * chunk, last = std::min(n, first + chunk);
        chunk_body(*state, first, last);
        const std::size_t now = done += last - first;
        if (progress) {
          std::unique_lock lock(progress_mutex, std::try_to_lock);
          if (lock.owns_lock()) progress(now, n);
        }
      }
    });
  });
}

// Calls body(state, i) for every i in [0, n), in chunks as for_each_chunk.
template <class MakeState, class Body>
void for_each_in_chunks(std::size_t n, std::size_t chunk, int threads,
                        const std::function<void(std::size_t, std::size_t)>& progress, MakeState&& make_state, Body&& body) {
  for_each_chunk(n, chunk, threads, progress, std::forward<MakeState>(make_state),
                 [&](auto& state, std::size_t first, std::size_t last) {
                   for (std::size_t i = first; i < last; ++i) body(state, i);
                 });
}

}  // namespace skyband
