#include <gtest/gtest.h>

#include <cmath>

#include "descriptors/descriptor_normalization.h"
#include "base/error.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;

TEST(DescriptorNormalization, UnitStdAndZeroMeanOverTheWholeLibrary) {
  // Two "patches" whose dimensions differ in magnitude by 1e4; column 2 is constant.
  Eigen::MatrixXd a(3, 3), b(2, 3);
  a << 1e-3, 10, 7,  //
      2e-3, 30, 7,   //
      3e-3, 20, 7;
  b << 4e-3, 50, 7,  //
      5e-3, 40, 7;
  const DescriptorNormalization n = fit_descriptor_normalization({a, b});
  ASSERT_EQ(n.mean.size(), 3u);
  EXPECT_NEAR(n.mean[0], 3e-3, 1e-15);
  EXPECT_NEAR(n.mean[1], 30, 1e-12);
  EXPECT_DOUBLE_EQ(n.mean[2], 7);
  EXPECT_NEAR(n.scale[0], std::sqrt(2.0) * 1e-3, 1e-15);  // population std of 1..5 is sqrt(2)
  EXPECT_NEAR(n.scale[1], std::sqrt(2.0) * 10, 1e-12);
  EXPECT_EQ(n.scale[2], 1.0);  // constant: left unscaled

  Eigen::MatrixXd all(5, 3);
  all << a, b;
  normalize_descriptors(n.mean, n.scale, all);
  for (Eigen::Index j = 0; j < 2; ++j) {
    EXPECT_NEAR(all.col(j).mean(), 0, 1e-12);
    EXPECT_NEAR(std::sqrt(all.col(j).squaredNorm() / 5), 1, 1e-12);
  }
  EXPECT_EQ(all.col(2).cwiseAbs().maxCoeff(), 0.0);
}

TEST(DescriptorNormalization, BadInputGetsClearErrors) {
  EXPECT_EQ(status_of([] { fit_descriptor_normalization({}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([] { fit_descriptor_normalization({Eigen::MatrixXd(0, 3)}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([] { fit_descriptor_normalization({Eigen::MatrixXd::Ones(2, 3), Eigen::MatrixXd::Ones(2, 2)}); }),
            MCON_ERROR_INVALID_ARGUMENT);
  Eigen::MatrixXd nan = Eigen::MatrixXd::Ones(2, 2);
  nan(1, 1) = std::nan("");
  EXPECT_EQ(status_of([&] { fit_descriptor_normalization({nan}); }), MCON_ERROR_NON_FINITE);
  Eigen::MatrixXd v = Eigen::MatrixXd::Ones(2, 2);
  EXPECT_EQ(status_of([&] { normalize_descriptors({0, 0, 0}, {1, 1, 1}, v); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { normalize_descriptors({0, 0}, {1, 0}, v); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { normalize_descriptors({0, 0}, {1, 1}, nan); }), MCON_ERROR_NON_FINITE);
}
