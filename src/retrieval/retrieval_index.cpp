#include "retrieval/retrieval_index.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/error.h"
#include "base/parallel_blocks.h"

namespace mcon {
namespace {

// Entries per parallel chunk: ~1 MB of 128-float histograms.
constexpr std::size_t kEntryChunk = 2048;
// Up to this n a chunk keeps its best list by insertion; beyond, by selection over every hit.
constexpr std::size_t kInsertionLimit = 64;

bool closer(const RetrievalHit& a, const RetrievalHit& b) {
  return a.distance < b.distance || (a.distance == b.distance && a.entry < b.entry);
}

// Keeps the `n` best of `hits` (by closer), sorted.
void keep_best(std::vector<RetrievalHit>& hits, std::size_t n) {
  if (hits.size() > n) {
    std::nth_element(hits.begin(), hits.begin() + static_cast<std::ptrdiff_t>(n), hits.end(), closer);
    hits.resize(n);
  }
  std::sort(hits.begin(), hits.end(), closer);
}

}  // namespace

float l1_distance(const float* a, const float* b, std::size_t length) {
  constexpr std::size_t kLanes = 16;
  float lane[kLanes] = {};
  std::size_t i = 0;
  for (; i + kLanes <= length; i += kLanes)
    for (std::size_t j = 0; j < kLanes; ++j) lane[j] += std::fabs(a[i + j] - b[i + j]);
  float tail = 0;
  for (; i < length; ++i) tail += std::fabs(a[i] - b[i]);
  for (std::size_t width = kLanes / 2; width > 0; width /= 2)
    for (std::size_t j = 0; j < width; ++j) lane[j] += lane[j + width];
  return lane[0] + tail;
}

std::vector<RetrievalHit> top_n_l1(const float* entries, std::size_t count, std::size_t length, const float* query,
                                   std::size_t n) {
  require(length >= 1, MCON_ERROR_INVALID_ARGUMENT, "retrieval: histogram length must be at least 1");
  require(query != nullptr, MCON_ERROR_NULL_POINTER, "retrieval: query is null");
  require(count == 0 || entries != nullptr, MCON_ERROR_NULL_POINTER, "retrieval: entries is null");
  for (std::size_t i = 0; i < length; ++i)
    require(std::isfinite(query[i]), MCON_ERROR_NON_FINITE,
            "retrieval: query value " + std::to_string(i) + " is not finite");
  n = std::min(n, count);
  if (n == 0) return {};

  // Each chunk keeps its own best n; the chunks' lists are merged in chunk order. Every entry's
  // distance is computed the same way whatever the chunking, and (distance, entry) is a total
  // order, so the result does not depend on the thread count.
  const std::size_t chunks = block_count(count, kEntryChunk);
  std::vector<std::vector<RetrievalHit>> best(chunks);
  for_each_block(count, kEntryChunk, [&](std::size_t begin, std::size_t end, std::size_t) {
    std::vector<RetrievalHit>& hits = best[begin / kEntryChunk];
    const auto hit = [&](std::size_t e) {
      const float dist = l1_distance(entries + e * length, query, length);
      return RetrievalHit{e, std::isnan(dist) ? std::numeric_limits<float>::infinity() : dist};
    };
    if (n > kInsertionLimit) {
      hits.resize(end - begin);
      for (std::size_t e = begin; e < end; ++e) hits[e - begin] = hit(e);
      keep_best(hits, n);
      return;
    }
    // A short top-n list: keep the chunk's best n sorted as they come (the same n, in the same
    // order, as keep_best of all of them), instead of writing every hit and selecting.
    hits.reserve(n + 1);
    for (std::size_t e = begin; e < end; ++e) {
      const RetrievalHit h = hit(e);
      if (hits.size() == n && !closer(h, hits.back())) continue;
      hits.insert(std::upper_bound(hits.begin(), hits.end(), h, closer), h);
      if (hits.size() > n) hits.pop_back();
    }
  });
  std::vector<RetrievalHit> merged;
  merged.reserve(std::min(count, chunks * n));
  for (const auto& hits : best) merged.insert(merged.end(), hits.begin(), hits.end());
  keep_best(merged, n);
  return merged;
}

RetrievalIndex::RetrievalIndex(std::size_t length) : length_(length) {
  require(length >= 1, MCON_ERROR_INVALID_ARGUMENT, "retrieval index: histogram length must be at least 1");
}

std::size_t RetrievalIndex::add(const std::vector<float>& histogram) {
  require(histogram.size() == length_, MCON_ERROR_INVALID_ARGUMENT,
          "retrieval index: histogram has " + std::to_string(histogram.size()) + " values, the index holds " +
              std::to_string(length_));
  for (std::size_t i = 0; i < length_; ++i)
    require(std::isfinite(histogram[i]), MCON_ERROR_NON_FINITE,
            "retrieval index: histogram value " + std::to_string(i) + " is not finite");
  data_.insert(data_.end(), histogram.begin(), histogram.end());
  return size() - 1;
}

std::vector<RetrievalHit> RetrievalIndex::query(const std::vector<float>& histogram, std::size_t n) const {
  require(histogram.size() == length_, MCON_ERROR_INVALID_ARGUMENT,
          "retrieval index: query has " + std::to_string(histogram.size()) + " values, the index holds " +
              std::to_string(length_));
  return top_n_l1(data_.data(), size(), length_, histogram.data(), n);
}

}  // namespace mcon
