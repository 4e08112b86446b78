#include "retrieval/bag_of_features.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "retrieval/center_distances.h"
#include "descriptors/descriptor_normalization.h"
#include "base/error.h"
#include "base/parallel_blocks.h"
#include "retrieval/kmeans.h"

namespace mcon {
namespace {

constexpr std::size_t kVertexChunk = 1024;

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The words and the kernel width, ready for per-vertex evaluation.
struct SoftAssigner {
  const std::vector<double>& vocabulary;  // k x d, word-major
  std::vector<double> vocabulary_t;       // d x k
  std::size_t k, d;
  double inv_two_sigma2;  // 1 / (2 sigma^2); +inf for a sigma so small that sigma^2 underflows

  SoftAssigner(const std::vector<double>& words, std::size_t k_, std::size_t d_, double sigma)
      : vocabulary(words), vocabulary_t(transpose_centers(words.data(), k_, d_)), k(k_), d(d_),
        inv_two_sigma2(1.0 / (2.0 * sigma * sigma)) {}

  // theta[0..k) for the point x; dist is scratch of size k.
  void operator()(const double* x, double* dist, double* theta) const {
    squared_distances_to_centers(x, vocabulary_t.data(), k, d, dist);
    const double nearest = dist[argmin(dist, k)];
    bool finite = std::isfinite(nearest);
    for (std::size_t c = 0; c < k && finite; ++c) finite = std::isfinite(dist[c]);
    double scale = 1.0;
    if (!finite) {
      // |x - I_c|^2 overflowed: redo it with every coordinate divided by the largest magnitude,
      // and multiply the exponent back by scale^2 in two steps (which may round to inf: weight 0).
      scale = 0;
      for (std::size_t j = 0; j < d; ++j) scale = std::max(scale, std::abs(x[j]));
      for (double w : vocabulary) scale = std::max(scale, std::abs(w));
      for (std::size_t c = 0; c < k; ++c) {
        double s = 0;
        for (std::size_t j = 0; j < d; ++j) {
          const double diff = x[j] / scale - vocabulary[c * d + j] / scale;
          s += diff * diff;
        }
        dist[c] = s;
      }
    }
    const double base = dist[argmin(dist, k)];
    double sum = 0;
    for (std::size_t c = 0; c < k; ++c) {
      const double excess = dist[c] - base;  // >= 0; exactly 0 for the nearest word(s)
      theta[c] = excess > 0 ? std::exp(-((excess * inv_two_sigma2) * scale) * scale) : 1.0;
      sum += theta[c];
    }
    for (std::size_t c = 0; c < k; ++c) theta[c] /= sum;  // sum >= 1
  }
};

void check_sigma(double sigma) {
  require(std::isfinite(sigma) && sigma > 0, MCON_ERROR_INVALID_ARGUMENT,
          "bag-of-features: sigma_bof must be finite and positive (got " + std::to_string(sigma) + ")");
}

}  // namespace

double median_rule_sigma(const std::vector<double>& vocabulary, std::size_t k, std::size_t d) {
  require(vocabulary.size() == k * d, MCON_ERROR_INVALID_ARGUMENT, "median rule: vocabulary must hold k * d values");
  if (k < 2) return 1.0;
  std::vector<double> distances;
  distances.reserve(k * (k - 1) / 2);
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a + 1; b < k; ++b) {
      double s = 0;
      for (std::size_t j = 0; j < d; ++j) {
        const double diff = vocabulary[a * d + j] - vocabulary[b * d + j];
        s += diff * diff;
      }
      distances.push_back(std::sqrt(s));
    }
  const std::size_t half = distances.size() / 2;
  std::nth_element(distances.begin(), distances.begin() + static_cast<std::ptrdiff_t>(half), distances.end());
  double median = distances[half];
  if (distances.size() % 2 == 0)
    median = 0.5 * (median + *std::max_element(distances.begin(), distances.begin() + static_cast<std::ptrdiff_t>(half)));
  const double sigma = 2.0 * median;
  return std::isfinite(sigma) && sigma > 0 ? sigma : 1.0;
}

Eigen::MatrixXd soft_assignment(const Eigen::MatrixXd& normalized_values, const std::vector<double>& vocabulary,
                                std::size_t k, double sigma) {
  const std::size_t d = static_cast<std::size_t>(normalized_values.cols());
  require(k >= 1 && vocabulary.size() == k * d, MCON_ERROR_INVALID_ARGUMENT,
          "soft assignment: vocabulary must hold k * d values with k >= 1");
  check_sigma(sigma);
  require(normalized_values.allFinite(), MCON_ERROR_NON_FINITE, "soft assignment: a descriptor value is not finite");
  const RowMatrix x = normalized_values;
  const std::size_t n = static_cast<std::size_t>(x.rows());
  RowMatrix theta(x.rows(), static_cast<Eigen::Index>(k));
  const SoftAssigner assign(vocabulary, k, d, sigma);
  for_each_block(n, kVertexChunk, [&](std::size_t begin, std::size_t end, std::size_t) {
    std::vector<double> dist(k);
    for (std::size_t v = begin; v < end; ++v) assign(x.data() + v * d, dist.data(), theta.data() + v * k);
  });
  return theta;
}

void validate_retrieval_config(const RetrievalConfig& c) {
  const std::size_t d = c.dimension, k = c.vocabulary_size;
  auto bad = [](const std::string& what) { fail(MCON_ERROR_INVALID_ARGUMENT, "retrieval config: " + what); };
  if (d < 1) bad("dimension must be at least 1");
  if (k < 1) bad("vocabulary_size must be at least 1");
  if (c.rings < 1) bad("rings must be at least 1");
  if (c.normalization_mean.size() != d || c.normalization_scale.size() != d)
    bad("normalization needs " + std::to_string(d) + " means and scales");
  if (c.vocabulary.size() != k * d) bad("vocabulary needs k * d = " + std::to_string(k * d) + " values");
  for (std::size_t j = 0; j < d; ++j)
    if (!std::isfinite(c.normalization_mean[j]) || !std::isfinite(c.normalization_scale[j]) ||
        !(c.normalization_scale[j] > 0))
      bad("normalization of dimension " + std::to_string(j) + " is not finite and positive");
  for (double w : c.vocabulary)
    if (!std::isfinite(w)) bad("vocabulary has a non-finite value");
  if (!std::isfinite(c.sigma_bof) || !(c.sigma_bof > 0)) bad("sigma_bof must be finite and positive");
}

RetrievalConfig build_retrieval_config(const std::vector<Eigen::MatrixXd>& library, const RetrievalBuildOptions& options) {
  require(options.vocabulary_size >= 1, MCON_ERROR_INVALID_ARGUMENT, "retrieval config: vocabulary_size must be >= 1");
  require(options.rings >= 1, MCON_ERROR_INVALID_ARGUMENT, "retrieval config: rings must be >= 1");
  require(std::isfinite(options.sigma_bof) && options.sigma_bof >= 0, MCON_ERROR_INVALID_ARGUMENT,
          "retrieval config: sigma_bof must be 0 (median rule) or finite and positive");
  require(options.max_training_points >= 1, MCON_ERROR_INVALID_ARGUMENT,
          "retrieval config: max_training_points must be >= 1");

  const DescriptorNormalization norm = fit_descriptor_normalization(library);
  const std::size_t d = norm.mean.size();

  // Deterministic subsample of all library vertices, gathered normalized and row-major.
  std::vector<std::size_t> offsets{0};
  for (const Eigen::MatrixXd& m : library) offsets.push_back(offsets.back() + static_cast<std::size_t>(m.rows()));
  const std::vector<std::size_t> picked =
      deterministic_subsample(offsets.back(), options.max_training_points, options.seed);
  std::vector<double> sample(picked.size() * d);
  std::size_t patch = 0;
  for (std::size_t i = 0; i < picked.size(); ++i) {
    while (picked[i] >= offsets[patch + 1]) ++patch;  // picked is ascending
    const Eigen::Index row = static_cast<Eigen::Index>(picked[i] - offsets[patch]);
    for (std::size_t j = 0; j < d; ++j)
      sample[i * d + j] = (library[patch](row, static_cast<Eigen::Index>(j)) - norm.mean[j]) / norm.scale[j];
  }

  KMeansOptions km;
  km.k = options.vocabulary_size;
  km.max_iterations = options.max_iterations;
  km.seed = options.seed;
  km.max_training_points = picked.size();
  km.assign_all = false;
  KMeansResult words = kmeans(sample.data(), picked.size(), d, km);

  RetrievalConfig config;
  config.descriptor = options.descriptor;
  config.dimension = static_cast<std::uint32_t>(d);
  config.normalization_mean = norm.mean;
  config.normalization_scale = norm.scale;
  config.vocabulary_size = static_cast<std::uint32_t>(words.k);
  config.vocabulary = std::move(words.centers);
  config.sigma_bof = options.sigma_bof > 0 ? options.sigma_bof
                                           : median_rule_sigma(config.vocabulary, config.vocabulary_size, d);
  config.rings = options.rings;
  config.seed = options.seed;
  return config;
}

std::vector<float> bag_of_features(const RetrievalConfig& config, const PatchDescriptors& patch) {
  validate_retrieval_config(config);
  const std::size_t d = config.dimension, k = config.vocabulary_size, rings = config.rings;
  const Eigen::Index n = patch.values.rows();
  require(n >= 1, MCON_ERROR_INVALID_ARGUMENT, "bag-of-features: the patch has no vertices");
  require(static_cast<std::size_t>(patch.values.cols()) == d, MCON_ERROR_INVALID_ARGUMENT,
          "bag-of-features: descriptors have " + std::to_string(patch.values.cols()) +
              " dimensions, the library uses " + std::to_string(d));
  require(patch.areas.size() == n, MCON_ERROR_INVALID_ARGUMENT, "bag-of-features: need one area per vertex");
  require(patch.areas.allFinite(), MCON_ERROR_NON_FINITE, "bag-of-features: a vertex area is not finite");
  require(patch.areas.minCoeff() >= 0, MCON_ERROR_INVALID_ARGUMENT, "bag-of-features: a vertex area is negative");
  if (rings > 1) {
    require(patch.center_distance.size() == n, MCON_ERROR_INVALID_ARGUMENT,
            "bag-of-features: " + std::to_string(rings) + " rings need one center distance per vertex");
    require(patch.center_distance.allFinite(), MCON_ERROR_NON_FINITE,
            "bag-of-features: a center distance is not finite");
    require(patch.center_distance.minCoeff() >= 0, MCON_ERROR_INVALID_ARGUMENT,
            "bag-of-features: a center distance is negative");
  }
  double total_area = 0;
  for (Eigen::Index v = 0; v < n; ++v) total_area += patch.areas[v];
  require(total_area > 0, MCON_ERROR_INVALID_ARGUMENT, "bag-of-features: the patch has zero area");

  Eigen::MatrixXd normalized = patch.values;
  normalize_descriptors(config.normalization_mean, config.normalization_scale, normalized);
  const RowMatrix x = normalized;
  const SoftAssigner assign(config.vocabulary, k, d, config.sigma_bof);
  const std::size_t length = k * rings;

  // Theta(P) = sum_v theta(v) A_v per ring, summed over a fixed vertex partition.
  const std::vector<double> histogram = deterministic_reduce(
      static_cast<std::size_t>(n), kVertexChunk, std::vector<double>(length, 0.0),
      [&](std::size_t begin, std::size_t end) {
        std::vector<double> part(length, 0.0), dist(k), theta(k);
        for (std::size_t v = begin; v < end; ++v) {
          const Eigen::Index iv = static_cast<Eigen::Index>(v);
          assign(x.data() + v * d, dist.data(), theta.data());
          std::size_t ring = 0;
          if (rings > 1) {
            const double r = std::min(patch.center_distance[iv] * static_cast<double>(rings),
                                      static_cast<double>(rings - 1));
            ring = static_cast<std::size_t>(r);
          }
          double* bins = part.data() + ring * k;
          const double area = patch.areas[iv];
          for (std::size_t c = 0; c < k; ++c) bins[c] += theta[c] * area;
        }
        return part;
      },
      [](std::vector<double> acc, const std::vector<double>& part) {
        for (std::size_t i = 0; i < acc.size(); ++i) acc[i] += part[i];
        return acc;
      });

  std::vector<float> out(length);
  for (std::size_t i = 0; i < length; ++i) out[i] = static_cast<float>(histogram[i] / total_area);
  return out;
}

}  // namespace mcon
