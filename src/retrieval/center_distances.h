// Squared Euclidean distances from one point to all k centers, the inner loop of k-means and of
// the bag-of-features soft assignment. Centers are stored transposed (dimension-major: entry
// [j * k + c] is coordinate j of center c) so the loop over centers is contiguous and the compiler
// vectorizes it; the sum over dimensions runs in a fixed order, so results are reproducible.
#pragma once

#include <cstddef>
#include <vector>

namespace mcon {

// centers: k x d row-major (word-major) -> d x k.
inline std::vector<double> transpose_centers(const double* centers, std::size_t k, std::size_t d) {
  std::vector<double> t(k * d);
  for (std::size_t c = 0; c < k; ++c)
    for (std::size_t j = 0; j < d; ++j) t[j * k + c] = centers[c * d + j];
  return t;
}

// out[c] = |x - center_c|^2 for the d-dimensional point x.
inline void squared_distances_to_centers(const double* x, const double* centers_t, std::size_t k, std::size_t d,
                                         double* out) {
  for (std::size_t c = 0; c < k; ++c) out[c] = 0.0;
  for (std::size_t j = 0; j < d; ++j) {
    const double xj = x[j];
    const double* row = centers_t + j * k;
    for (std::size_t c = 0; c < k; ++c) {
      const double diff = xj - row[c];
      out[c] += diff * diff;
    }
  }
}

// Index of the smallest entry (the lowest index among ties).
inline std::size_t argmin(const double* values, std::size_t k) {
  std::size_t best = 0;
  for (std::size_t c = 1; c < k; ++c)
    if (values[c] < values[best]) best = c;
  return best;
}

}  // namespace mcon
