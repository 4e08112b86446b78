// k-means vector quantization (thesis §3.2 "Vocabulary generation"): k-means++ seeding
// (Arthur & Vassilvitskii 2007) followed by Lloyd iterations.
//
// Deterministic for any thread count: every random draw is a counter-based hash of
// (seed, purpose, index); per-point work (distances, assignment) is independent; every
// floating-point sum is taken over a fixed partition of the points and combined in a fixed order.
// Runs with oneTBB in the caller's current task arena.
//
// Large inputs: at most `max_training_points` points (default 200,000) are drawn without
// replacement (deterministically from the seed) for seeding and Lloyd iterations; all N points are
// then assigned to the final centers. 200k points in 9 dimensions is about 15 MB and an iteration
// costs ~0.1 s on one core at k = 128, while the centers of a 128-word vocabulary barely move with
// more samples than that.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace mcon {

struct KMeansOptions {
  int k = 128;
  int max_iterations = 100;                  // Lloyd iterations (each: assign, then update)
  std::uint64_t seed = 0;
  std::size_t max_training_points = 200000;  // subsample cap for seeding and training
  bool assign_all = true;                    // fill KMeansResult::assignment for all N points
  // Optional k x d row-major start centers instead of k-means++ (k is then their count).
  std::vector<double> initial_centers;
};

struct KMeansResult {
  // Number of clusters found. Fewer than requested when the training points have fewer distinct
  // values than k (k > N, duplicates): k-means++ stops when every point sits on a center, and a
  // cluster that stays empty because no distinct point is left to re-seed it is dropped.
  int k = 0;
  int dimension = 0;
  std::vector<double> centers;      // k x d, row-major (word-major)
  std::vector<int> assignment;      // per input point: index of its nearest center (ties: lowest)
  std::size_t training_points = 0;  // points used for seeding and Lloyd iterations
  int iterations = 0;               // Lloyd iterations run
  bool converged = false;           // assignments stopped changing before the cap
  int reseeded_clusters = 0;        // empty clusters re-seeded during the iterations
  double inertia = 0;               // sum of squared distances of the training points to their centers
};

// points: n x d, row-major. Throws mcon::Error: INVALID_ARGUMENT (n, d or k < 1, bad options),
// NON_FINITE (a NaN or infinite coordinate).
KMeansResult kmeans(const double* points, std::size_t n, std::size_t d, const KMeansOptions& options);

// Same for an Eigen matrix with one point per row.
KMeansResult kmeans(const Eigen::MatrixXd& points, const KMeansOptions& options);

// `count` distinct indices out of [0, n), drawn without replacement from the seed (a partial
// Fisher-Yates shuffle driven by counter-based hashes, O(count) memory), sorted ascending. All
// indices when count >= n.
std::vector<std::size_t> deterministic_subsample(std::size_t n, std::size_t count, std::uint64_t seed);

// Nearest center of every point (ties: lowest index), in parallel; squared distances optional.
void assign_to_centers(const double* points, std::size_t n, std::size_t d, const double* centers, std::size_t k,
                       int* assignment, double* squared_distance = nullptr);

}  // namespace mcon
