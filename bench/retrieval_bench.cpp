// Retrieval speed (wall-clock; cpu_s = process CPU time, meaningful when the machine is shared):
// top-10 L1 query time over 100,000 library entries (plain and ring histograms; the default
// library is plain, as `macrocon-eval eval-retrieval` measured best, so "default_query_median_s" is the
// median top-10 query in seconds over 100,000 histograms of length k = 128),
// the vocabulary build on 1M 9-d descriptor points (normalization + k-means + sigma), and the
// bag-of-features of one query patch. Prints one JSON object.
//
//   retrieval_bench [--entries N] [--points N] [--rings R] [--queries Q] [--threads T]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <cstring>
#include <string>
#include <vector>

#include <tbb/task_arena.h>

#include "retrieval/bag_of_features.h"
#include "base/counter_rng.h"
#include "retrieval/kmeans.h"
#include "retrieval/retrieval_index.h"

using namespace mcon;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Random histograms that each sum to 1, like bag-of-features entries.
std::vector<float> random_histograms(std::size_t count, std::size_t length, std::uint64_t seed) {
  std::vector<float> h(count * length);
  for (std::size_t e = 0; e < count; ++e) {
    double sum = 0;
    for (std::size_t i = 0; i < length; ++i) sum += h[e * length + i] = static_cast<float>(counter_uniform(seed, e, i));
    for (std::size_t i = 0; i < length; ++i) h[e * length + i] = static_cast<float>(h[e * length + i] / sum);
  }
  return h;
}

struct QueryTiming {
  double median_ms, min_ms, median_cpu_ms;
};

QueryTiming time_queries(std::size_t entries, std::size_t length, int queries, std::size_t n) {
  const std::vector<float> library = random_histograms(entries, length, 1);
  std::vector<double> ms, cpu_ms;
  std::size_t checksum = 0;
  for (int q = 0; q < queries; ++q) {
    const std::vector<float> query = random_histograms(1, length, 1000 + static_cast<std::uint64_t>(q));
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    const auto hits = top_n_l1(library.data(), entries, length, query.data(), n);
    ms.push_back(1e3 * seconds_since(t0));
    cpu_ms.push_back(1e3 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    checksum += hits.front().entry;
  }
  if (checksum == static_cast<std::size_t>(-1)) std::puts("");  // keep the work observable
  return {median(ms), *std::min_element(ms.begin(), ms.end()), median(cpu_ms)};
}

// A library of 9-d descriptors as a mixture of Gaussian clusters with dimensions of very
// different magnitude (like CURV9 at three scales), split into patches of 1000 vertices.
std::vector<Eigen::MatrixXd> random_library(std::size_t points, std::size_t per_patch) {
  const int d = 9, modes = 300;
  std::vector<Eigen::MatrixXd> library;
  for (std::size_t start = 0; start < points; start += per_patch) {
    const std::size_t rows = std::min(per_patch, points - start);
    Eigen::MatrixXd m(static_cast<Eigen::Index>(rows), d);
    for (std::size_t r = 0; r < rows; ++r) {
      const std::size_t i = start + r;
      const std::uint64_t mode = counter_hash(5, 0, i) % modes;
      for (int j = 0; j < d; ++j) {
        const double magnitude = std::pow(10.0, -(j % 3));
        const double center = 4 * (counter_uniform(6, mode, static_cast<std::uint64_t>(j)) - 0.5);
        // Sum of two uniforms: a cheap bell-shaped spread around the mode.
        const double noise = counter_uniform(7, i, 2 * static_cast<std::uint64_t>(j)) +
                             counter_uniform(7, i, 2 * static_cast<std::uint64_t>(j) + 1) - 1;
        m(static_cast<Eigen::Index>(r), j) = magnitude * (center + 0.3 * noise);
      }
    }
    library.push_back(std::move(m));
  }
  return library;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t entries = 100000, points = 1000000;
  std::uint32_t rings = 4;  // the ringed variant compared with the plain (default) one
  int queries = 21, threads = -1;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    const long value = std::atol(argv[i + 1]);
    if (flag == "--entries") entries = static_cast<std::size_t>(value);
    else if (flag == "--points") points = static_cast<std::size_t>(value);
    else if (flag == "--rings") rings = static_cast<std::uint32_t>(value);
    else if (flag == "--queries") queries = static_cast<int>(value);
    else if (flag == "--threads") threads = static_cast<int>(value);
    else {
      std::fprintf(stderr, "unknown flag %s\n", argv[i]);
      return 2;
    }
  }
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    const int k = 128, top = 10;
    const QueryTiming plain = time_queries(entries, k, queries, top);
    const QueryTiming ringed = time_queries(entries, static_cast<std::size_t>(k) * rings, queries, top);

    const std::vector<Eigen::MatrixXd> library = random_library(points, 1000);
    RetrievalBuildOptions options;
    options.vocabulary_size = k;
    options.rings = rings;
    options.seed = 1;
    auto t0 = std::chrono::steady_clock::now();
    std::clock_t c0 = std::clock();
    const RetrievalConfig config = build_retrieval_config(library, options);
    const double build_s = seconds_since(t0);
    const double build_cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;

    // The same k-means alone, for its iteration count (on the normalized training sample).
    std::vector<double> sample;
    const auto picked = deterministic_subsample(points, options.max_training_points, options.seed);
    std::vector<std::size_t> offsets{0};
    for (const auto& m : library) offsets.push_back(offsets.back() + static_cast<std::size_t>(m.rows()));
    std::size_t patch = 0;
    for (std::size_t i : picked) {
      while (i >= offsets[patch + 1]) ++patch;
      for (int j = 0; j < 9; ++j)
        sample.push_back((library[patch](static_cast<Eigen::Index>(i - offsets[patch]), j) - config.normalization_mean[static_cast<std::size_t>(j)]) /
                         config.normalization_scale[static_cast<std::size_t>(j)]);
    }
    KMeansOptions km;
    km.k = k;
    km.seed = options.seed;
    km.assign_all = false;
    t0 = std::chrono::steady_clock::now();
    c0 = std::clock();
    const KMeansResult words = kmeans(sample.data(), picked.size(), 9, km);
    const double kmeans_s = seconds_since(t0);
    const double kmeans_cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;

    // One query patch of 2000 vertices: its ring histogram.
    PatchDescriptors query;
    query.values = random_library(2000, 2000).front();
    query.areas = Eigen::VectorXd::Constant(2000, M_PI / 2000);
    query.center_distance = Eigen::VectorXd::LinSpaced(2000, 0.0, 1.0);
    std::vector<double> bof_ms;
    for (int q = 0; q < queries; ++q) {
      t0 = std::chrono::steady_clock::now();
      const auto h = bag_of_features(config, query);
      bof_ms.push_back(1e3 * seconds_since(t0));
      if (h.empty()) return;
    }

    std::printf(
        "{\n  \"benchmark\": \"retrieval\",\n  \"threads\": %d,\n"
        "  \"query\": {\"entries\": %zu, \"top_n\": %d, \"queries\": %d,\n"
        "    \"length_%d\": {\"median_ms\": %.3f, \"min_ms\": %.3f, \"median_cpu_ms\": %.3f},\n"
        "    \"length_%zu_rings_%u\": {\"median_ms\": %.3f, \"min_ms\": %.3f, \"median_cpu_ms\": %.3f}},\n"
        "  \"vocabulary\": {\"points\": %zu, \"dimension\": 9, \"k\": %u, \"training_points\": %zu,\n"
        "    \"build_s\": %.3f, \"build_cpu_s\": %.3f, \"kmeans_s\": %.3f, \"kmeans_cpu_s\": %.3f,\n"
        "    \"kmeans_iterations\": %d, \"kmeans_converged\": %s,\n"
        "    \"sigma_bof\": %.4f},\n"
        "  \"bag_of_features\": {\"vertices\": 2000, \"length\": %zu, \"median_ms\": %.3f},\n"
        "  \"default_query_median_s\": %.6f, \"default_length\": %zu\n}\n",
        tbb::this_task_arena::max_concurrency(), entries, top, queries, k, plain.median_ms, plain.min_ms,
        plain.median_cpu_ms, static_cast<std::size_t>(k) * rings, rings, ringed.median_ms, ringed.min_ms,
        ringed.median_cpu_ms, points, config.vocabulary_size,
        words.training_points, build_s, build_cpu_s, kmeans_s, kmeans_cpu_s, words.iterations, words.converged ? "true" : "false",
        config.sigma_bof, config.histogram_length(), median(bof_ms), 1e-3 * plain.median_ms,
        static_cast<std::size_t>(k));
  });
  return 0;
}
