#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

#include <tbb/task_arena.h>

#include "retrieval/bag_of_features.h"
#include "operators/cotan_laplacian.h"
#include "base/error.h"
#include "retrieval/retrieval_index.h"
#include "test_meshes.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;

namespace {

using Height = std::function<double(double, double)>;

// Height fields over the unit disk: the patches the tests compare.
const Height kBump = [](double x, double y) { return 0.4 * std::exp(-(x * x + y * y) / 0.15); };
const Height kSaddle = [](double x, double y) { return 0.4 * (x * x - y * y); };
const Height kRidge = [](double x, double) { return 0.3 * std::exp(-x * x / 0.05); };
const Height kDome = [](double x, double y) { return -0.3 * (x * x + y * y); };

// A unit disk lifted onto z = h(x, y). `grade` > 1 moves vertices toward the center (r -> r^grade),
// a tessellation of the same surface with strongly non-uniform density.
TriMesh lifted_disk(int rings, const Height& h, double grade = 1.0) {
  TriMesh m = test_meshes::make_disk(rings);
  for (Vec3& p : m.positions) {
    const double r = std::hypot(p.x(), p.y());
    if (r > 0) p.head<2>() *= std::pow(r, grade) / r;
    p.z() = h(p.x(), p.y());
  }
  return m;
}

// Analytic per-vertex descriptor of a height field: height, slope and Laplacian (central
// differences of h), so the tests isolate the bag-of-features from descriptor discretization.
PatchDescriptors describe(const TriMesh& m, const Height& h) {
  const int n = m.num_vertices();
  const double e = 1e-4;
  PatchDescriptors p;
  p.values.resize(n, 3);
  p.center_distance.resize(n);
  for (int v = 0; v < n; ++v) {
    const double x = m.positions[v].x(), y = m.positions[v].y();
    const double hx = (h(x + e, y) - h(x - e, y)) / (2 * e), hy = (h(x, y + e) - h(x, y - e)) / (2 * e);
    const double lap = (h(x + e, y) + h(x - e, y) + h(x, y + e) + h(x, y - e) - 4 * h(x, y)) / (e * e);
    p.values.row(v) << h(x, y), std::hypot(hx, hy), lap;
    p.center_distance[v] = std::hypot(x, y);
  }
  p.areas = vertex_areas(m);
  return p;
}

RetrievalConfig library_config(std::uint32_t rings, int k = 16) {
  std::vector<Eigen::MatrixXd> library;
  for (const Height* h : {&kBump, &kSaddle, &kRidge, &kDome}) library.push_back(describe(lifted_disk(16, *h), *h).values);
  RetrievalBuildOptions o;
  o.vocabulary_size = k;
  o.rings = rings;
  o.seed = 3;
  return build_retrieval_config(library, o);
}

float l1(const std::vector<float>& a, const std::vector<float>& b) {
  EXPECT_EQ(a.size(), b.size());
  return l1_distance(a.data(), b.data(), a.size());
}

}  // namespace

TEST(BagOfFeatures, SoftAssignmentRowsSumToOneWithoutNaN) {
  // Words on a line; points near, between, far beyond and absurdly far from them.
  const std::vector<double> words = {0, 0, 1, 0, 2, 0, 3, 0};
  Eigen::MatrixXd x(6, 2);
  x << 0.1, 0,  //
      1.5, 0,   //
      1e3, 0,   //
      1e200, -1e200,  //
      -1e308, 1e308,  //
      2, 0;
  for (double sigma : {1e-300, 1e-3, 0.5, 1.0, 1e3, 1e300}) {
    const Eigen::MatrixXd theta = soft_assignment(x, words, 4, sigma);
    ASSERT_EQ(theta.rows(), 6);
    ASSERT_EQ(theta.cols(), 4);
    EXPECT_TRUE(theta.allFinite()) << "sigma " << sigma;
    EXPECT_GE(theta.minCoeff(), 0.0);
    for (Eigen::Index v = 0; v < 6; ++v) EXPECT_NEAR(theta.row(v).sum(), 1.0, 1e-12) << "sigma " << sigma;
    // Far points belong to the nearest (last) word unless sigma is astronomically large.
    if (sigma < 1e3) {
      EXPECT_NEAR(theta(2, 3), 1.0, 1e-9);
    }
  }
  // Hard limit: ties split evenly, a point on a word takes it all.
  const Eigen::MatrixXd hard = soft_assignment(x, words, 4, 1e-300);
  EXPECT_DOUBLE_EQ(hard(1, 1), 0.5);
  EXPECT_DOUBLE_EQ(hard(1, 2), 0.5);
  EXPECT_DOUBLE_EQ(hard(5, 2), 1.0);
  // Eq. 3.1 literally, where it does not underflow.
  const Eigen::MatrixXd soft = soft_assignment(x, words, 4, 0.7);
  double norm = 0;
  for (int i = 0; i < 4; ++i) norm += std::exp(-std::pow(0.1 - i, 2) / (2 * 0.49));
  EXPECT_NEAR(soft(0, 1), std::exp(-std::pow(0.9, 2) / (2 * 0.49)) / norm, 1e-14);
}

TEST(BagOfFeatures, MedianRuleIsTwiceTheMedianWordDistance) {
  // Words at 0, 1, 3 on a line: pairwise distances 1, 2, 3 -> median 2 -> sigma 4.
  EXPECT_DOUBLE_EQ(median_rule_sigma({0, 1, 3}, 3, 1), 4.0);
  // Four words: distances 1, 2, 3, 4, 5, 6... here 1,1,2 / 1,2 / 1 -> {1,1,1,2,2,3}: median 1.5.
  EXPECT_DOUBLE_EQ(median_rule_sigma({0, 1, 2, 3}, 4, 1), 2 * 1.5);
  EXPECT_DOUBLE_EQ(median_rule_sigma({5, 5}, 1, 2), 1.0);
}

TEST(BagOfFeatures, ConfigFromLibrary) {
  const RetrievalConfig c = library_config(1);
  EXPECT_NO_THROW(validate_retrieval_config(c));
  EXPECT_EQ(c.dimension, 3u);
  EXPECT_EQ(c.vocabulary_size, 16u);
  EXPECT_EQ(c.vocabulary.size(), 48u);
  EXPECT_EQ(c.histogram_length(), 16u);
  EXPECT_DOUBLE_EQ(c.sigma_bof, median_rule_sigma(c.vocabulary, 16, 3));
  EXPECT_GT(c.sigma_bof, 0.5);  // normalized space: words are O(1) apart
  EXPECT_LT(c.sigma_bof, 10);
  // Deterministic across thread counts, bit for bit.
  RetrievalConfig c1, c2;
  tbb::task_arena(1).execute([&] { c1 = library_config(1); });
  tbb::task_arena(2).execute([&] { c2 = library_config(1); });
  EXPECT_EQ(c1.vocabulary, c.vocabulary);
  EXPECT_EQ(c2.vocabulary, c.vocabulary);
  EXPECT_EQ(c2.normalization_scale, c.normalization_scale);
  // An explicit sigma overrides the median rule.
  RetrievalBuildOptions o;
  o.vocabulary_size = 4;
  o.sigma_bof = 11;
  EXPECT_EQ(build_retrieval_config({describe(lifted_disk(4, kBump), kBump).values}, o).sigma_bof, 11);
}

TEST(BagOfFeatures, SameSurfaceDifferentTessellationGivesCloseHistograms) {
  const RetrievalConfig c = library_config(1);
  const TriMesh coarse = lifted_disk(10, kBump), fine = lifted_disk(24, kBump), graded = lifted_disk(18, kBump, 1.8);
  const auto h_coarse = bag_of_features(c, describe(coarse, kBump));
  const auto h_fine = bag_of_features(c, describe(fine, kBump));
  const auto h_graded = bag_of_features(c, describe(graded, kBump));
  ASSERT_EQ(h_fine.size(), 16u);
  EXPECT_NEAR(std::accumulate(h_fine.begin(), h_fine.end(), 0.0), 1.0, 1e-5);

  const float same_coarse = l1(h_coarse, h_fine), same_graded = l1(h_graded, h_fine);
  const float to_saddle = l1(h_fine, bag_of_features(c, describe(lifted_disk(24, kSaddle), kSaddle)));
  const float to_ridge = l1(h_fine, bag_of_features(c, describe(lifted_disk(24, kRidge), kRidge)));
  const float to_dome = l1(h_fine, bag_of_features(c, describe(lifted_disk(24, kDome), kDome)));
  // The median rule (sigma = twice the median word distance) assigns softly: a word at the median
  // distance still gets exp(-1/8) = 0.88 of the nearest word's weight, so histograms are close to
  // uniform and L1 distances small in absolute terms; what matters for retrieval is the ranking.
  EXPECT_LT(same_coarse, 2e-3f);
  EXPECT_LT(same_graded, 2e-3f);
  for (float other : {to_saddle, to_ridge, to_dome}) EXPECT_GT(other, 20 * std::max(same_coarse, same_graded));
  // A harder assignment (sigma = 0.5 in normalized space) spreads the same ranking over a larger range.
  RetrievalConfig hard = c;
  hard.sigma_bof = 0.5;
  const auto hard_fine = bag_of_features(hard, describe(fine, kBump));
  EXPECT_LT(l1(bag_of_features(hard, describe(graded, kBump)), hard_fine), 0.05f);
  EXPECT_GT(l1(bag_of_features(hard, describe(lifted_disk(24, kSaddle), kSaddle)), hard_fine), 0.5f);

  // The area weights are what makes the graded mesh match: counting vertices instead is far off.
  PatchDescriptors counted = describe(graded, kBump);
  counted.areas.setOnes();
  EXPECT_GT(l1(bag_of_features(c, counted), h_fine), 20 * same_graded);
}

TEST(BagOfFeatures, RingHistogramsSumToThePlainOne) {
  const RetrievalConfig plain = library_config(1);
  RetrievalConfig ringed = plain;
  ringed.rings = 4;
  const PatchDescriptors p = describe(lifted_disk(16, kBump), kBump);
  const auto h = bag_of_features(plain, p);
  const auto r = bag_of_features(ringed, p);
  ASSERT_EQ(r.size(), 4u * 16u);
  ASSERT_EQ(ringed.histogram_length(), r.size());
  for (std::size_t c = 0; c < 16; ++c) {
    double sum = 0;
    for (std::size_t ring = 0; ring < 4; ++ring) sum += r[ring * 16 + c];
    EXPECT_NEAR(sum, h[c], 1e-6);
  }
  // Ring r's mass is the area share of the annulus [r/4, (r+1)/4): it grows outward.
  std::vector<double> mass(4, 0);
  for (std::size_t i = 0; i < r.size(); ++i) mass[i / 16] += r[i];
  for (std::size_t ring = 1; ring < 4; ++ring) EXPECT_GT(mass[ring], mass[ring - 1]);

  // Spatial layout: a central bump and a circular ridge further out (similar values, other place)
  // are told apart better with rings than without.
  const Height moved = [](double x, double y) {
    const double rr = std::hypot(x, y) - 0.6;
    return 0.4 * std::exp(-rr * rr / 0.02);
  };
  const PatchDescriptors q = describe(lifted_disk(24, moved), moved);
  const float plain_distance = l1(h, bag_of_features(plain, q));
  const float ring_distance = l1(r, bag_of_features(ringed, q));
  EXPECT_GT(ring_distance, plain_distance);
}

TEST(BagOfFeatures, BadInputGetsClearErrors) {
  const RetrievalConfig c = library_config(2, 4);
  const PatchDescriptors good = describe(lifted_disk(4, kBump), kBump);
  EXPECT_EQ(status_of([&] { bag_of_features(c, good); }), MCON_OK);
  PatchDescriptors p = good;
  p.values.conservativeResize(p.values.rows(), 2);
  EXPECT_EQ(status_of([&] { bag_of_features(c, p); }), MCON_ERROR_INVALID_ARGUMENT);
  p = good;
  p.areas[3] = -1;
  EXPECT_EQ(status_of([&] { bag_of_features(c, p); }), MCON_ERROR_INVALID_ARGUMENT);
  p = good;
  p.center_distance.resize(0);  // 2 rings need distances
  EXPECT_EQ(status_of([&] { bag_of_features(c, p); }), MCON_ERROR_INVALID_ARGUMENT);
  p = good;
  p.values(2, 1) = std::numeric_limits<double>::infinity();
  EXPECT_EQ(status_of([&] { bag_of_features(c, p); }), MCON_ERROR_NON_FINITE);
  p = good;
  p.areas.setZero();
  EXPECT_EQ(status_of([&] { bag_of_features(c, p); }), MCON_ERROR_INVALID_ARGUMENT);
  RetrievalConfig broken = c;
  broken.sigma_bof = 0;
  EXPECT_EQ(status_of([&] { bag_of_features(broken, good); }), MCON_ERROR_INVALID_ARGUMENT);
  broken = c;
  broken.vocabulary.pop_back();
  EXPECT_EQ(status_of([&] { bag_of_features(broken, good); }), MCON_ERROR_INVALID_ARGUMENT);
  broken = c;
  broken.normalization_scale[0] = 0;
  EXPECT_EQ(status_of([&] { bag_of_features(broken, good); }), MCON_ERROR_INVALID_ARGUMENT);
  RetrievalBuildOptions o;
  o.vocabulary_size = 0;
  EXPECT_EQ(status_of([&] { build_retrieval_config({good.values}, o); }), MCON_ERROR_INVALID_ARGUMENT);
}
