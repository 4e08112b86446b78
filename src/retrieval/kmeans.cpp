#include "retrieval/kmeans.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

#include "retrieval/center_distances.h"
#include "base/counter_rng.h"
#include "base/error.h"
#include "base/parallel_blocks.h"

namespace mcon {
namespace {

// Counter-RNG streams: one per purpose so draws never collide.
constexpr std::uint64_t kStreamSubsample = 0x5355425341ull;  // "SUBSA"
constexpr std::uint64_t kStreamSeeding = 0x5345454453ull;    // "SEEDS"

// Points per chunk of every parallel loop and fixed-partition reduction.
constexpr std::size_t kChunk = 4096;

double squared_distance(const double* a, const double* b, std::size_t d) {
  double s = 0;
  for (std::size_t j = 0; j < d; ++j) {
    const double diff = a[j] - b[j];
    s += diff * diff;
  }
  return s;
}

// Sum of values[0..n) over the fixed partition, plus the per-chunk sums.
double chunked_sum(const std::vector<double>& values, std::vector<double>& chunk_sums) {
  const std::size_t n = values.size();
  chunk_sums.assign(block_count(n, kChunk), 0.0);
  for_each_block(n, kChunk, [&](std::size_t begin, std::size_t end, std::size_t) {
    double s = 0;
    for (std::size_t i = begin; i < end; ++i) s += values[i];
    chunk_sums[begin / kChunk] = s;
  });
  double total = 0;
  for (double s : chunk_sums) total += s;
  return total;
}

// k-means++: the first center uniformly, every next one with probability proportional to the
// squared distance to the nearest chosen center. Stops early once every point sits on a center.
std::vector<double> kmeans_plus_plus(const double* x, std::size_t m, std::size_t d, int k, std::uint64_t seed) {
  std::vector<double> centers;
  centers.reserve(static_cast<std::size_t>(k) * d);
  const std::size_t first = std::min(m - 1, static_cast<std::size_t>(counter_uniform(seed, kStreamSeeding, 0) * m));
  centers.insert(centers.end(), x + first * d, x + (first + 1) * d);

  std::vector<double> d2(m, std::numeric_limits<double>::infinity());
  std::vector<double> chunk_sums;
  for (int c = 1;; ++c) {
    const double* newest = centers.data() + static_cast<std::size_t>(c - 1) * d;
    for_each_block(m, kChunk, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i) d2[i] = std::min(d2[i], squared_distance(x + i * d, newest, d));
    });
    if (c == k) break;
    const double total = chunked_sum(d2, chunk_sums);
    if (!(total > 0)) break;  // fewer distinct points than k

    // Invert the cumulative distribution: first the chunk, then the point inside it.
    const double u = counter_uniform(seed, kStreamSeeding, static_cast<std::uint64_t>(c)) * total;
    std::size_t chunk = 0;
    double acc = 0;
    while (chunk + 1 < chunk_sums.size() && acc + chunk_sums[chunk] <= u) acc += chunk_sums[chunk++];
    std::size_t pick = m, last_positive = m;
    for (std::size_t i = chunk * kChunk; i < std::min(m, (chunk + 1) * kChunk); ++i) {
      if (!(d2[i] > 0)) continue;
      last_positive = i;
      acc += d2[i];
      if (acc > u) {
        pick = i;
        break;
      }
    }
    if (pick == m) pick = last_positive;  // round-off left u just past the chunk's end
    if (pick == m) {                      // the chunk was all zeros (round-off at the very end)
      for (std::size_t i = m; i-- > 0;)
        if (d2[i] > 0) {
          pick = i;
          break;
        }
    }
    centers.insert(centers.end(), x + pick * d, x + (pick + 1) * d);
  }
  return centers;
}

// Assigns all m points; returns how many assignments changed.
std::size_t assign_step(const double* x, std::size_t m, std::size_t d, const std::vector<double>& centers_t,
                        std::size_t k, std::vector<int>& assignment, std::vector<double>& d2) {
  return deterministic_reduce(
      m, kChunk, std::size_t{0},
      [&](std::size_t begin, std::size_t end) {
        std::vector<double> dist(k);
        std::size_t changed = 0;
        for (std::size_t i = begin; i < end; ++i) {
          squared_distances_to_centers(x + i * d, centers_t.data(), k, d, dist.data());
          const int best = static_cast<int>(argmin(dist.data(), k));
          changed += assignment[i] != best;
          assignment[i] = best;
          d2[i] = dist[best];
        }
        return changed;
      },
      [](std::size_t a, std::size_t b) { return a + b; });
}

// Per-cluster coordinate sums (k x d) followed by the k counts, over the fixed partition.
std::vector<double> cluster_sums(const double* x, std::size_t m, std::size_t d, std::size_t k,
                                 const std::vector<int>& assignment) {
  const std::size_t width = k * (d + 1);
  return deterministic_reduce(
      m, kChunk, std::vector<double>(width, 0.0),
      [&](std::size_t begin, std::size_t end) {
        std::vector<double> s(width, 0.0);
        for (std::size_t i = begin; i < end; ++i) {
          const std::size_t c = static_cast<std::size_t>(assignment[i]);
          for (std::size_t j = 0; j < d; ++j) s[c * d + j] += x[i * d + j];
          s[k * d + c] += 1.0;
        }
        return s;
      },
      [](std::vector<double> acc, const std::vector<double>& part) {
        for (std::size_t i = 0; i < acc.size(); ++i) acc[i] += part[i];
        return acc;
      });
}

// Moves each empty cluster's center onto the point farthest from its own center (ties: lowest
// index), farthest-first: after each pick the distances are updated so the next empty cluster
// does not land on the same spot. Returns how many were re-seeded.
int reseed_empty(const double* x, std::size_t m, std::size_t d, const std::vector<std::size_t>& empty,
                 std::vector<double>& centers, std::vector<double> d2) {
  int reseeded = 0;
  for (std::size_t c : empty) {
    std::size_t far = m;
    for (std::size_t i = 0; i < m; ++i)
      if (d2[i] > 0 && (far == m || d2[i] > d2[far])) far = i;
    if (far == m) break;  // every point sits on a center: nothing distinct left
    std::copy(x + far * d, x + (far + 1) * d, centers.begin() + static_cast<std::ptrdiff_t>(c * d));
    for_each_block(m, kChunk, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i) d2[i] = std::min(d2[i], squared_distance(x + i * d, x + far * d, d));
    });
    ++reseeded;
  }
  return reseeded;
}

void check_points(const double* points, std::size_t n, std::size_t d) {
  require(n >= 1, MCON_ERROR_INVALID_ARGUMENT, "k-means: no points");
  require(d >= 1, MCON_ERROR_INVALID_ARGUMENT, "k-means: dimension must be at least 1");
  require(points != nullptr, MCON_ERROR_NULL_POINTER, "k-means: points is null");
  for (std::size_t i = 0; i < n * d; ++i)
    require(std::isfinite(points[i]), MCON_ERROR_NON_FINITE,
            "k-means: point " + std::to_string(i / d) + " has a non-finite coordinate");
}

}  // namespace

std::vector<std::size_t> deterministic_subsample(std::size_t n, std::size_t count, std::uint64_t seed) {
  std::vector<std::size_t> out;
  if (count >= n) {
    out.resize(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = i;
    return out;
  }
  // Partial Fisher-Yates over a virtual identity permutation; only swapped slots are stored.
  out.resize(count);
  std::unordered_map<std::size_t, std::size_t> moved;
  moved.reserve(2 * count);
  auto at = [&moved](std::size_t i) {
    const auto it = moved.find(i);
    return it == moved.end() ? i : it->second;
  };
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t j = i + counter_hash(seed, kStreamSubsample, i) % (n - i);
    const std::size_t value_i = at(i);
    out[i] = at(j);
    moved[j] = value_i;  // slot i is never read again
  }
  std::sort(out.begin(), out.end());
  return out;
}

void assign_to_centers(const double* points, std::size_t n, std::size_t d, const double* centers, std::size_t k,
                       int* assignment, double* squared_distance_out) {
  const std::vector<double> centers_t = transpose_centers(centers, k, d);
  for_each_block(n, kChunk, [&](std::size_t begin, std::size_t end, std::size_t) {
    std::vector<double> dist(k);
    for (std::size_t i = begin; i < end; ++i) {
      squared_distances_to_centers(points + i * d, centers_t.data(), k, d, dist.data());
      const std::size_t best = argmin(dist.data(), k);
      assignment[i] = static_cast<int>(best);
      if (squared_distance_out) squared_distance_out[i] = dist[best];
    }
  });
}

namespace {

void check_options(const KMeansOptions& options, std::size_t d) {
  require(options.max_iterations >= 0, MCON_ERROR_INVALID_ARGUMENT, "k-means: max_iterations must be >= 0");
  require(options.max_training_points >= 1, MCON_ERROR_INVALID_ARGUMENT,
          "k-means: max_training_points must be at least 1");
  if (!options.initial_centers.empty()) {
    require(options.initial_centers.size() % d == 0, MCON_ERROR_INVALID_ARGUMENT,
            "k-means: initial_centers must hold k * d values");
    for (double v : options.initial_centers)
      require(std::isfinite(v), MCON_ERROR_NON_FINITE, "k-means: initial_centers has a non-finite value");
  } else {
    require(options.k >= 1, MCON_ERROR_INVALID_ARGUMENT,
            "k-means: k must be at least 1 (got " + std::to_string(options.k) + ")");
  }
}

// Training set: all points, or a deterministic subsample gathered contiguously into `sample`.
// Returns the training points; m is their count.
const double* training_set(const double* points, std::size_t n, std::size_t d, const KMeansOptions& options,
                           std::vector<double>& sample, std::size_t& m) {
  m = n;
  if (n <= options.max_training_points) return points;
  const std::vector<std::size_t> picked = deterministic_subsample(n, options.max_training_points, options.seed);
  m = picked.size();
  sample.resize(m * d);
  for (std::size_t i = 0; i < m; ++i) std::copy(points + picked[i] * d, points + (picked[i] + 1) * d, &sample[i * d]);
  return sample.data();
}

// Lloyd iterations from the current assignment until it no longer changes or the iteration cap.
void lloyd_iterations(const double* x, std::size_t m, std::size_t d, std::size_t k, int max_iterations,
                      std::vector<double>& centers, std::vector<int>& assignment, std::vector<double>& d2,
                      KMeansResult& result) {
  while (result.iterations < max_iterations) {
    // Update: every center moves to the mean of its points; empty ones are re-seeded.
    const std::vector<double> sums = cluster_sums(x, m, d, k, assignment);
    std::vector<std::size_t> empty;
    for (std::size_t c = 0; c < k; ++c) {
      const double count = sums[k * d + c];
      if (count == 0) {
        empty.push_back(c);
        continue;
      }
      for (std::size_t j = 0; j < d; ++j) centers[c * d + j] = sums[c * d + j] / count;
    }
    if (!empty.empty()) result.reseeded_clusters += reseed_empty(x, m, d, empty, centers, d2);
    ++result.iterations;

    const std::vector<double> centers_t = transpose_centers(centers.data(), k, d);
    if (assign_step(x, m, d, centers_t, k, assignment, d2) == 0) {
      result.converged = true;
      break;
    }
  }
}

// Drop clusters that stayed empty (only possible with fewer distinct points than k). Returns
// the number of clusters left.
std::size_t drop_empty_clusters(std::size_t k, std::size_t d, std::vector<double>& centers,
                                std::vector<int>& assignment) {
  std::vector<int> remap(k, -1);
  std::vector<char> used(k, 0);
  for (int a : assignment) used[static_cast<std::size_t>(a)] = 1;
  std::size_t kept = 0;
  for (std::size_t c = 0; c < k; ++c) {
    if (!used[c]) continue;
    if (kept != c) std::copy(centers.begin() + c * d, centers.begin() + (c + 1) * d, centers.begin() + kept * d);
    remap[c] = static_cast<int>(kept++);
  }
  if (kept != k) {
    centers.resize(kept * d);
    for (int& a : assignment) a = remap[static_cast<std::size_t>(a)];
  }
  return kept;
}

}  // namespace

KMeansResult kmeans(const double* points, std::size_t n, std::size_t d, const KMeansOptions& options) {
  check_points(points, n, d);
  check_options(options, d);
  const bool given = !options.initial_centers.empty();

  KMeansResult result;
  result.dimension = static_cast<int>(d);
  std::vector<double> sample;
  std::size_t m = n;
  const double* x = training_set(points, n, d, options, sample, m);
  result.training_points = m;

  std::vector<double> centers = given ? options.initial_centers : kmeans_plus_plus(x, m, d, options.k, options.seed);
  std::size_t k = centers.size() / d;

  std::vector<int> assignment(m, -1);
  std::vector<double> d2(m);
  assign_step(x, m, d, transpose_centers(centers.data(), k, d), k, assignment, d2);
  lloyd_iterations(x, m, d, k, options.max_iterations, centers, assignment, d2, result);
  k = drop_empty_clusters(k, d, centers, assignment);

  std::vector<double> unused;
  result.inertia = chunked_sum(d2, unused);
  result.k = static_cast<int>(k);
  result.centers = std::move(centers);
  if (options.assign_all) {
    if (m == n) {
      result.assignment = std::move(assignment);
    } else {
      result.assignment.resize(n);
      assign_to_centers(points, n, d, result.centers.data(), k, result.assignment.data());
    }
  }
  return result;
}

KMeansResult kmeans(const Eigen::MatrixXd& points, const KMeansOptions& options) {
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = points;
  return kmeans(rows.data(), static_cast<std::size_t>(rows.rows()), static_cast<std::size_t>(rows.cols()), options);
}

}  // namespace mcon
