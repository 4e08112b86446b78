#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <vector>

#include <tbb/task_arena.h>

#include "base/counter_rng.h"
#include "base/error.h"
#include "retrieval/kmeans.h"
#include "test_status.h"

using namespace mcon;

namespace {

// n points around `clusters` centers in d dims: center c at 10 * (c-th unit-ish direction), noise
// of size `spread`. Point i belongs to cluster i % clusters.
std::vector<double> blobs(std::size_t n, std::size_t d, std::size_t clusters, double spread,
                          std::vector<double>* true_centers = nullptr) {
  std::vector<double> centers(clusters * d);
  for (std::size_t c = 0; c < clusters; ++c)
    for (std::size_t j = 0; j < d; ++j) centers[c * d + j] = 20.0 * (counter_uniform(99, c, j) - 0.5) * 5;
  std::vector<double> x(n * d);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < d; ++j)
      x[i * d + j] = centers[(i % clusters) * d + j] + spread * (counter_uniform(7, i, j) - 0.5);
  if (true_centers) *true_centers = centers;
  return x;
}

KMeansResult run_in_arena(int threads, const std::vector<double>& x, std::size_t d, const KMeansOptions& o) {
  tbb::task_arena arena(threads);
  KMeansResult r;
  arena.execute([&] { r = kmeans(x.data(), x.size() / d, d, o); });
  return r;
}

mcon_status status_of(const std::vector<double>& x, std::size_t n, std::size_t d, const KMeansOptions& o) {
  return test::status_of([&] { kmeans(x.empty() ? nullptr : x.data(), n, d, o); });
}

}  // namespace

TEST(KMeans, BitIdenticalOnOneTwoAndEightThreads) {
  // Overlapping clusters so Lloyd takes many iterations and every sum has many terms; a
  // subsample cap below N exercises the deterministic subsampling and the final full assignment.
  const std::size_t d = 6;
  const std::vector<double> x = blobs(20000, d, 40, 60.0);
  KMeansOptions o;
  o.k = 16;
  o.seed = 12345;
  o.max_training_points = 16000;  // four chunks of the fixed partition
  const KMeansResult r1 = run_in_arena(1, x, d, o);
  const KMeansResult r2 = run_in_arena(2, x, d, o);
  const KMeansResult r8 = run_in_arena(8, x, d, o);
  ASSERT_EQ(r1.k, 16);
  EXPECT_EQ(r1.training_points, 16000u);
  EXPECT_GT(r1.iterations, 3);
  ASSERT_EQ(r1.assignment.size(), 20000u);
  for (const KMeansResult* r : {&r2, &r8}) {
    EXPECT_EQ(r->k, r1.k);
    EXPECT_EQ(r->iterations, r1.iterations);
    EXPECT_EQ(r->assignment, r1.assignment);
    ASSERT_EQ(r->centers.size(), r1.centers.size());
    // Bit-identical, not merely close.
    EXPECT_EQ(0, std::memcmp(r->centers.data(), r1.centers.data(), r1.centers.size() * sizeof(double)));
    EXPECT_EQ(0, std::memcmp(&r->inertia, &r1.inertia, sizeof(double)));
  }
  // A different seed gives a different (but equally valid) result.
  o.seed = 999;
  const KMeansResult other = run_in_arena(2, x, d, o);
  EXPECT_NE(other.centers, r1.centers);
}

TEST(KMeans, RecoversWellSeparatedClusters) {
  const std::size_t d = 3, clusters = 6;
  std::vector<double> truth;
  const std::vector<double> x = blobs(600, d, clusters, 0.5, &truth);
  KMeansOptions o;
  o.k = static_cast<int>(clusters);
  const KMeansResult r = kmeans(x.data(), 600, d, o);
  ASSERT_EQ(r.k, 6);
  EXPECT_TRUE(r.converged);
  // Every true cluster maps to exactly one found cluster...
  std::vector<int> label_of_truth(clusters, -1);
  for (std::size_t i = 0; i < 600; ++i) {
    int& label = label_of_truth[i % clusters];
    if (label < 0) label = r.assignment[i];
    EXPECT_EQ(r.assignment[i], label) << "point " << i;
  }
  EXPECT_EQ(std::set<int>(label_of_truth.begin(), label_of_truth.end()).size(), clusters);
  // ...and its center is the cluster's mean, within the noise.
  for (std::size_t c = 0; c < clusters; ++c)
    for (std::size_t j = 0; j < d; ++j)
      EXPECT_NEAR(r.centers[static_cast<std::size_t>(label_of_truth[c]) * d + j], truth[c * d + j], 0.1);
}

TEST(KMeans, MoreClustersThanDistinctPoints) {
  // 5 points, 3 distinct values, k = 8: three clusters, each point on its center.
  const std::vector<double> x = {1, 1, 2, 2, 1, 1, 5, 5, 2, 2};
  KMeansOptions o;
  o.k = 8;
  const KMeansResult r = kmeans(x.data(), 5, 2, o);
  ASSERT_EQ(r.k, 3);
  EXPECT_EQ(r.inertia, 0.0);
  EXPECT_EQ(r.assignment[0], r.assignment[2]);
  EXPECT_EQ(r.assignment[1], r.assignment[4]);
  for (std::size_t i = 0; i < 5; ++i) {
    const double* c = &r.centers[static_cast<std::size_t>(r.assignment[i]) * 2];
    EXPECT_EQ(c[0], x[2 * i]);
    EXPECT_EQ(c[1], x[2 * i + 1]);
  }
  // All points identical: one cluster.
  const std::vector<double> same(40, 3.25);
  const KMeansResult one = kmeans(same.data(), 10, 4, o);
  EXPECT_EQ(one.k, 1);
  EXPECT_EQ(one.centers, std::vector<double>(4, 3.25));
}

TEST(KMeans, EmptyClusterIsReseededDeterministically) {
  // Start with a center far from every point: its cluster is empty after the first assignment and
  // must be moved onto the point farthest from its center, splitting the wide cluster.
  const std::size_t d = 2;
  std::vector<double> x;
  for (int i = 0; i < 50; ++i) x.insert(x.end(), {0.01 * i, 0.0});        // cluster A near (0.25, 0)
  for (int i = 0; i < 50; ++i) x.insert(x.end(), {10.0 + 0.01 * i, 0.0});  // cluster B near (10.25, 0)
  KMeansOptions o;
  o.initial_centers = {0.0, 0.0, 1000.0, 1000.0, 5.0, 0.0};
  const KMeansResult r = kmeans(x.data(), 100, d, o);
  EXPECT_EQ(r.k, 3);
  EXPECT_GE(r.reseeded_clusters, 1);
  std::vector<int> sizes(3, 0);
  for (int a : r.assignment) sizes[static_cast<std::size_t>(a)]++;
  for (int s : sizes) EXPECT_GT(s, 0);
  for (std::size_t c = 0; c < 3; ++c) EXPECT_LT(std::abs(r.centers[c * d + 1]), 1e-12);  // all on the line
  const KMeansResult again = kmeans(x.data(), 100, d, o);
  EXPECT_EQ(again.centers, r.centers);
  EXPECT_EQ(again.assignment, r.assignment);
}

TEST(KMeans, SubsampleIsDeterministicDistinctAndSorted) {
  const auto a = deterministic_subsample(1000000, 1000, 5);
  EXPECT_EQ(a, deterministic_subsample(1000000, 1000, 5));
  EXPECT_NE(a, deterministic_subsample(1000000, 1000, 6));
  ASSERT_EQ(a.size(), 1000u);
  EXPECT_TRUE(std::is_sorted(a.begin(), a.end()));
  EXPECT_EQ(std::set<std::size_t>(a.begin(), a.end()).size(), 1000u);
  EXPECT_LT(a.back(), 1000000u);
  // Spread over the whole range, not a prefix.
  EXPECT_GT(a.back(), 900000u);
  EXPECT_LT(a.front(), 100000u);
  EXPECT_EQ(deterministic_subsample(7, 10, 1), (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6}));
}

TEST(KMeans, BadInputGetsClearErrors) {
  std::vector<double> x = {0, 1, 2, 3};
  KMeansOptions o;
  EXPECT_EQ(status_of(x, 0, 2, o), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of(x, 2, 0, o), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of({}, 2, 2, o), MCON_ERROR_NULL_POINTER);
  o.k = 0;
  EXPECT_EQ(status_of(x, 2, 2, o), MCON_ERROR_INVALID_ARGUMENT);
  o.k = 2;
  o.initial_centers = {1, 2, 3};  // not a multiple of d
  EXPECT_EQ(status_of(x, 2, 2, o), MCON_ERROR_INVALID_ARGUMENT);
  o.initial_centers.clear();
  x[3] = std::nan("");
  EXPECT_EQ(status_of(x, 2, 2, o), MCON_ERROR_NON_FINITE);
}

TEST(KMeans, EigenOverloadMatchesFlatArray) {
  const std::size_t d = 4;
  const std::vector<double> x = blobs(500, d, 5, 2.0);
  Eigen::MatrixXd m(500, static_cast<Eigen::Index>(d));
  for (Eigen::Index i = 0; i < 500; ++i)
    for (Eigen::Index j = 0; j < 4; ++j) m(i, j) = x[static_cast<std::size_t>(i) * d + static_cast<std::size_t>(j)];
  KMeansOptions o;
  o.k = 5;
  EXPECT_EQ(kmeans(m, o).centers, kmeans(x.data(), 500, d, o).centers);
}
