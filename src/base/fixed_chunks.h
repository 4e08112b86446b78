// Parallel loops whose floating-point results do not depend on the thread count: the index range
// is cut into chunks of a FIXED size (never TBB's dynamic ranges), each chunk's partial result goes
// to its own slot, and the slots are combined sequentially in chunk order. The loops run in the
// caller's current tbb::task_arena.
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace mcon {

inline std::size_t chunk_count(std::size_t n, std::size_t chunk) { return (n + chunk - 1) / chunk; }

// body(begin, end) for every chunk [c * chunk, min(n, (c + 1) * chunk)), in parallel.
template <typename Body>
void fixed_chunk_for(std::size_t n, std::size_t chunk, Body&& body) {
  const std::size_t chunks = chunk_count(n, chunk);
  if (chunks == 0) return;
  if (chunks == 1) {
    body(std::size_t{0}, n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) body(c * chunk, std::min(n, (c + 1) * chunk));
  });
}

// partial(begin, end) -> T per chunk (in parallel); then result = combine(result, partial_c) for
// c = 0, 1, ... in order, starting from `identity`.
template <typename T, typename Partial, typename Combine>
T fixed_chunk_reduce(std::size_t n, std::size_t chunk, T identity, Partial&& partial, Combine&& combine) {
  std::vector<T> parts(chunk_count(n, chunk));
  fixed_chunk_for(n, chunk, [&](std::size_t begin, std::size_t end) { parts[begin / chunk] = partial(begin, end); });
  T result = std::move(identity);
  for (T& p : parts) result = combine(std::move(result), p);
  return result;
}

}  // namespace mcon
