// Deterministic data parallelism: work is cut into fixed-size blocks that do not depend on the
// thread count, each block is processed serially, and reductions combine the block results in
// block order. So results are bit-identical on 1 or N threads (HELPERS.md), and everything runs
// in the caller's current tbb::task_arena.
#pragma once

#include <algorithm>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace mcon {

// Calls f(begin, end, block_index) for each block [b * block_size, min(n, (b + 1) * block_size)).
template <class F>
void for_each_block(int n, int block_size, F&& f) {
  if (n <= 0) return;
  const int blocks = (n + block_size - 1) / block_size;
  if (blocks == 1) {
    f(0, n, 0);
    return;
  }
  tbb::parallel_for(
      tbb::blocked_range<int>(0, blocks, 1),
      [&](const tbb::blocked_range<int>& r) {
        for (int b = r.begin(); b < r.end(); ++b) f(b * block_size, std::min(n, (b + 1) * block_size), b);
      },
      tbb::simple_partitioner());
}

// Sum of term(i) for i in [0, n): serial inside each block, block sums added in order.
template <class F>
double deterministic_sum(int n, int block_size, F&& term) {
  if (n <= 0) return 0.0;
  const int blocks = (n + block_size - 1) / block_size;
  std::vector<double> partial(static_cast<std::size_t>(blocks), 0.0);
  for_each_block(n, block_size, [&](int begin, int end, int b) {
    double s = 0;
    for (int i = begin; i < end; ++i) s += term(i);
    partial[b] = s;
  });
  double total = 0;
  for (double s : partial) total += s;
  return total;
}

}  // namespace mcon
