// The query side of retrieval (thesis §3.2): exact top-n nearest histograms under the L1 distance,
// by a linear scan over one flat contiguous array of float histograms (entries x length). A scan
// is memory-bound (100,000 entries of 128 floats are 51 MB), so it needs no tree: the inner loop is
// written for SIMD, entries are scanned in parallel in fixed chunks, and ties are broken by entry
// index so the answer is the same on any thread count.
#pragma once

#include <cstddef>
#include <vector>

namespace mcon {

struct RetrievalHit {
  std::size_t entry = 0;
  float distance = 0;
};

// sum_i |a_i - b_i|, accumulated in 16 independent lanes then reduced pairwise (fixed order).
float l1_distance(const float* a, const float* b, std::size_t length);

// The min(n, count) entries nearest to `query`, sorted by (distance, entry index). `entries` holds
// count * length floats, entry-major; it can be any contiguous array (e.g. a library's histograms).
// A NaN distance (from NaN in an entry) ranks as +infinity. Throws mcon::Error: NULL_POINTER,
// INVALID_ARGUMENT (length 0), NON_FINITE (a query value).
std::vector<RetrievalHit> top_n_l1(const float* entries, std::size_t count, std::size_t length, const float* query,
                                   std::size_t n);

// An owning index: histograms appended in order, entry i = the i-th added.
class RetrievalIndex {
 public:
  explicit RetrievalIndex(std::size_t length);  // INVALID_ARGUMENT for length 0

  std::size_t length() const { return length_; }
  std::size_t size() const { return data_.size() / length_; }
  const float* entry(std::size_t i) const { return data_.data() + i * length_; }
  const std::vector<float>& data() const { return data_; }

  void reserve(std::size_t entries) { data_.reserve(entries * length_); }
  // Appends one histogram of length() values; returns its entry index. Throws INVALID_ARGUMENT for
  // a wrong length, NON_FINITE for a NaN or infinite value.
  std::size_t add(const std::vector<float>& histogram);

  std::vector<RetrievalHit> query(const std::vector<float>& histogram, std::size_t n) const;

 private:
  std::size_t length_;
  std::vector<float> data_;
};

}  // namespace mcon
