// Descriptor space normalization (thesis §3.2): per dimension, subtract the mean and divide by the
// standard deviation over every vertex of the library, so k-means and the soft assignment (both
// Euclidean) weigh all dimensions alike (e.g. curvature at a larger scale is smaller in magnitude).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace mcon {

struct DescriptorNormalization {
  std::vector<double> mean;   // d values
  std::vector<double> scale;  // d values: the population std, or 1 for a dimension that is
                              // constant over the library (it carries no information to scale)
};

// Fits over the rows (vertices) of all matrices, each vertex counting once (as in k-means).
// Throws mcon::Error: INVALID_ARGUMENT (no rows, mismatched column counts), NON_FINITE.
DescriptorNormalization fit_descriptor_normalization(const std::vector<Eigen::MatrixXd>& descriptors);

// values(v, j) = (values(v, j) - mean[j]) / scale[j], in place. Throws INVALID_ARGUMENT when the
// column count differs from mean/scale, NON_FINITE for a non-finite value.
void normalize_descriptors(const std::vector<double>& mean, const std::vector<double>& scale,
                           Eigen::MatrixXd& values);

}  // namespace mcon
