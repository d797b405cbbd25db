#include "studies/parallel.h"

#include <algorithm>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace turbodyn::studies {

int run_threads(int requested, int configured) {
  if (requested > 0) return requested;
  if (configured > 0) return configured;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void parallel_runs(std::size_t n, int threads, const std::function<void(std::size_t)>& body) {
  // Grain 1: a run takes seconds to minutes, far more than handing it to a thread.
  auto loop = [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) body(i);
    });
  };
  if (threads > 0) tbb::task_arena(threads).execute(loop);
  else loop();
}

}  // namespace turbodyn::studies
