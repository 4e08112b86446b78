#include "descriptors/descriptor_normalization.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/error.h"

namespace mcon {

DescriptorNormalization fit_descriptor_normalization(const std::vector<Eigen::MatrixXd>& descriptors) {
  require(!descriptors.empty(), MCON_ERROR_INVALID_ARGUMENT, "descriptor normalization: no descriptor matrices");
  const Eigen::Index d = descriptors.front().cols();
  require(d >= 1, MCON_ERROR_INVALID_ARGUMENT, "descriptor normalization: descriptors have no columns");
  double count = 0;
  for (std::size_t p = 0; p < descriptors.size(); ++p) {
    require(descriptors[p].cols() == d, MCON_ERROR_INVALID_ARGUMENT,
            "descriptor normalization: matrix " + std::to_string(p) + " has " +
                std::to_string(descriptors[p].cols()) + " columns, expected " + std::to_string(d));
    require(descriptors[p].allFinite(), MCON_ERROR_NON_FINITE,
            "descriptor normalization: matrix " + std::to_string(p) + " has a non-finite value");
    count += static_cast<double>(descriptors[p].rows());
  }
  require(count > 0, MCON_ERROR_INVALID_ARGUMENT, "descriptor normalization: no vertices");

  // Two passes (mean, then squared deviations) in a fixed order: stable and reproducible.
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(d);
  for (const Eigen::MatrixXd& m : descriptors) sum += m.colwise().sum().transpose();
  const Eigen::VectorXd mean = sum / count;
  Eigen::VectorXd squares = Eigen::VectorXd::Zero(d);
  for (const Eigen::MatrixXd& m : descriptors)
    squares += (m.rowwise() - mean.transpose()).colwise().squaredNorm().transpose();

  DescriptorNormalization out;
  out.mean.assign(mean.data(), mean.data() + d);
  out.scale.resize(static_cast<std::size_t>(d));
  for (Eigen::Index j = 0; j < d; ++j) {
    const double stddev = std::sqrt(squares[j] / count);
    // Constant up to round-off: leave it unscaled rather than blow round-off up to unit size.
    const bool constant = !(stddev > 1e-12 * std::max(1.0, std::abs(mean[j])));
    out.scale[static_cast<std::size_t>(j)] = constant ? 1.0 : stddev;
  }
  return out;
}

void normalize_descriptors(const std::vector<double>& mean, const std::vector<double>& scale,
                           Eigen::MatrixXd& values) {
  const std::size_t d = mean.size();
  require(scale.size() == d, MCON_ERROR_INVALID_ARGUMENT, "descriptor normalization: mean and scale differ in size");
  require(static_cast<std::size_t>(values.cols()) == d, MCON_ERROR_INVALID_ARGUMENT,
          "descriptor normalization: descriptors have " + std::to_string(values.cols()) +
              " dimensions, the normalization has " + std::to_string(d));
  require(values.allFinite(), MCON_ERROR_NON_FINITE, "descriptor normalization: a descriptor value is not finite");
  for (std::size_t j = 0; j < d; ++j) {
    require(std::isfinite(mean[j]) && std::isfinite(scale[j]) && scale[j] > 0, MCON_ERROR_INVALID_ARGUMENT,
            "descriptor normalization: dimension " + std::to_string(j) + " has an invalid mean or scale");
    const Eigen::Index c = static_cast<Eigen::Index>(j);
    values.col(c) = (values.col(c).array() - mean[j]) / scale[j];
  }
}

}  // namespace mcon
