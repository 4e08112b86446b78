// Deterministic data parallelism: work is cut into fixed-size blocks that do not depend on the
// thread count, each block is processed serially, and reductions combine the block results in
// block order. So results are bit-identical on 1 or N threads, and everything runs in the
// caller's current tbb::task_arena (the context's, docs/design.md §5).
#pragma once

#include <algorithm>
#include <type_traits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace mcon {

// Number of blocks of block_size covering [0, n).
template <class I>
I block_count(I n, typename std::common_type<I>::type block_size) {
  return n <= 0 ? I(0) : (n + block_size - 1) / block_size;
}

// Calls f(begin, end, block_index) for each block [b * block_size, min(n, (b + 1) * block_size)),
// in parallel. I is the index type (int or std::size_t).
template <class I, class F>
void for_each_block(I n, typename std::common_type<I>::type block_size, F&& f) {
  const I blocks = block_count(n, block_size);
  if (blocks == 0) return;
  if (blocks == 1) {
    f(I(0), n, I(0));
    return;
  }
  tbb::parallel_for(
      tbb::blocked_range<I>(0, blocks, 1),
      [&](const tbb::blocked_range<I>& r) {
        for (I b = r.begin(); b < r.end(); ++b) f(b * block_size, std::min(n, (b + 1) * block_size), b);
      },
      tbb::simple_partitioner());
}

// partial(begin, end) -> T per block (in parallel); then result = combine(result, partial_b) for
// b = 0, 1, ... in order, starting from `identity`.
template <class I, class T, class Partial, class Combine>
T deterministic_reduce(I n, typename std::common_type<I>::type block_size, T identity, Partial&& partial,
                       Combine&& combine) {
  std::vector<T> parts(static_cast<std::size_t>(block_count(n, block_size)));
  for_each_block(n, block_size, [&](I begin, I end, I b) { parts[static_cast<std::size_t>(b)] = partial(begin, end); });
  T result = std::move(identity);
  for (T& p : parts) result = combine(std::move(result), p);
  return result;
}

// Sum of term(i) for i in [0, n): serial inside each block, block sums added in order.
template <class F>
double deterministic_sum(int n, int block_size, F&& term) {
  if (n <= 0) return 0.0;
  std::vector<double> partial(static_cast<std::size_t>(block_count(n, block_size)), 0.0);
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
