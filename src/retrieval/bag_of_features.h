// Bag-of-features (thesis §3.2, after Ovsjanikov et al. 2009 [OBBG09]): per-vertex soft assignment
// of normalized descriptors to a k-means vocabulary (eq. 3.1), integrated over the patch with
// vertex areas, optionally once per concentric geodesic ring around the patch center (the cheap
// spatial extension a disk with a known center allows; docs/design.md §1). Compared with L1.
//
// Histogram normalization: Θ(P) is divided by the patch's total area, so every histogram sums to 1
// (and its rings together sum to 1). Patches are already scaled to geodesic radius 1, so what area
// still varies is noise: scan noise and fine wrinkles inflate surface area, boundary snapping and
// hole filling change it by a few triangles. Unnormalized, those differences would add to every L1
// distance; normalized, the distance compares only how the surface is distributed over the words
// (and rings), is bounded by 2, and one sigma/vocabulary works across libraries. What the total
// area says about curvature is already carried by the curvature descriptors themselves.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "retrieval/retrieval_config.h"

namespace mcon {

// What one patch contributes: its raw (un-normalized) per-vertex descriptors and vertex weights.
struct PatchDescriptors {
  Eigen::MatrixXd values;           // n x d descriptor values, one row per vertex
  Eigen::VectorXd areas;            // n barycentric vertex areas (A_v), patch at geodesic radius 1
  Eigen::VectorXd center_distance;  // n geodesic distances from the center; needed when rings > 1
};

struct RetrievalBuildOptions {
  std::string descriptor = "curv9";
  int vocabulary_size = 128;                 // k
  std::uint32_t rings = 1;                   // 1 = plain bag-of-features
  double sigma_bof = 0;                      // > 0 overrides the median rule
  std::uint64_t seed = 0;
  std::size_t max_training_points = 200000;  // k-means training subsample (see kmeans.h)
  int max_iterations = 100;                  // Lloyd iteration cap
};

// Fits the normalization over all vertices of the library, the vocabulary by k-means on the
// normalized values (a deterministic subsample of at most max_training_points vertices), and
// sigma_bof (the option, or twice the median distance between words). vocabulary_size in the
// result can be smaller than asked when the library has fewer distinct descriptor values.
// Throws mcon::Error: INVALID_ARGUMENT, NON_FINITE.
RetrievalConfig build_retrieval_config(const std::vector<Eigen::MatrixXd>& library_descriptors,
                                       const RetrievalBuildOptions& options);

// OBBG09's rule: twice the median of the pairwise distances between the k words (vocabulary is
// k x d, word-major). 1 (the per-dimension std of the normalized space) when k < 2.
double median_rule_sigma(const std::vector<double>& vocabulary, std::size_t k, std::size_t d);

// Eq. 3.1 with the L1 normalization: row v holds theta(v), k non-negative values summing to 1.
// Computed relative to the nearest word (exp(-(|x-I_i|^2 - min_j |x-I_j|^2) / 2 sigma^2)), so the
// nearest word always gets exp(0) = 1 before normalizing: no underflow to 0/0, no NaN for
// distant points, tiny or huge sigma; squared distances that overflow are redone in a scaled frame.
Eigen::MatrixXd soft_assignment(const Eigen::MatrixXd& normalized_values, const std::vector<double>& vocabulary,
                                std::size_t k, double sigma);

// Throws MCON_ERROR_INVALID_ARGUMENT naming the first inconsistent field.
void validate_retrieval_config(const RetrievalConfig& config);

// The patch's histogram: k * rings floats, ring-major (ring r's k words at [r * k, (r + 1) * k)).
// Ring r holds vertices with center distance in [r / R, (r + 1) / R); distances >= 1 (geodesic
// round-off at the boundary) go to the last ring. Sums to 1 (see the normalization note above).
// Throws mcon::Error: INVALID_ARGUMENT (sizes, negative area, missing distances, zero total area),
// NON_FINITE.
std::vector<float> bag_of_features(const RetrievalConfig& config, const PatchDescriptors& patch);

}  // namespace mcon
