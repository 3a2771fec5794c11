// parallel_for / parallel_sum on oneTBB with fixed, thread-count-independent chunking.
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <vector>

#include "tessera/core.h"

namespace tessera {

int default_thread_count() { return std::max(1, tbb::info::default_concurrency()); }

void parallel_for(std::int64_t begin, std::int64_t end, std::int64_t grain,
                  const std::function<void(std::int64_t, std::int64_t)>& body,
                  const Parallel& parallel) {
  if (end <= begin) return;
  int threads = parallel.threads;
  grain = std::max<std::int64_t>(1, grain);
  const std::int64_t chunks = (end - begin + grain - 1) / grain;
  auto run_chunk = [&](std::int64_t c) {
    const std::int64_t b = begin + c * grain;
    body(b, std::min(end, b + grain));
  };
  if (threads == 1 || chunks == 1) {
    for (std::int64_t c = 0; c < chunks; ++c) run_chunk(c);
    return;
  }
  auto loop = [&] {
    // simple_partitioner with grainsize 1 over chunk indices: every chunk is one task, so the
    // sub-ranges the body sees never depend on how many threads there are.
    tbb::parallel_for(
        tbb::blocked_range<std::int64_t>(0, chunks, 1),
        [&](const tbb::blocked_range<std::int64_t>& r) {
          for (std::int64_t c = r.begin(); c != r.end(); ++c) run_chunk(c);
        },
        tbb::simple_partitioner());
  };
  // More threads than the hardware has would only make TBB warn that it ignores the request;
  // the chunking (and so the result) does not depend on the count anyway.
  threads = std::min(threads, default_thread_count());
  if (threads <= 0 || threads == default_thread_count()) {
    loop();
  } else {
    tbb::task_arena arena(threads);
    arena.execute(loop);
  }
}

double parallel_sum(std::int64_t begin, std::int64_t end, std::int64_t grain,
                    const std::function<double(std::int64_t, std::int64_t)>& chunk,
                    const Parallel& parallel) {
  if (end <= begin) return 0.0;
  grain = std::max<std::int64_t>(1, grain);
  const std::int64_t chunks = (end - begin + grain - 1) / grain;
  std::vector<double> partial(std::size_t(chunks), 0.0);
  parallel_for(
      0, chunks, 1,
      [&](std::int64_t c0, std::int64_t c1) {
        for (std::int64_t c = c0; c < c1; ++c) {
          const std::int64_t b = begin + c * grain;
          partial[std::size_t(c)] = chunk(b, std::min(end, b + grain));
        }
      },
      parallel);
  double sum = 0.0;
  for (double p : partial) sum += p;
  return sum;
}

}  // namespace tessera
