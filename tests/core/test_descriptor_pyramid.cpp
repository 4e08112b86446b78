#include <gtest/gtest.h>

#include <cmath>

#include "operators/cotan_laplacian.h"
#include "descriptors/descriptor_pyramid.h"
#include "base/error.h"
#include "synthetic_maps.h"

using namespace mcon;

TEST(DescriptorPyramid, SmoothsMoreAtLargerScalesAndKeepsConstants) {
  const TriMesh m = synthetic::make_jittered_disk(14, 0.3);
  const std::vector<Vec2> uv = synthetic::planar_uv(m);
  Eigen::MatrixXd values(m.num_vertices(), 2);
  for (int v = 0; v < m.num_vertices(); ++v) values.row(v) << std::sin(9 * uv[v].x()) * std::cos(7 * uv[v].y()), 3.0;
  const std::vector<Eigen::MatrixXd> levels = descriptor_pyramid(m, values, {0.3, 0.1, 0.0});
  ASSERT_EQ(levels.size(), 3u);
  EXPECT_EQ(levels[2], values);
  const Eigen::VectorXd area = vertex_areas(m);
  auto weighted_var = [&](const Eigen::VectorXd& f) {
    const double mean = area.dot(f) / area.sum();
    return area.dot((f.array() - mean).square().matrix()) / area.sum();
  };
  const double v0 = weighted_var(values.col(0)), v1 = weighted_var(levels[1].col(0)), v2 = weighted_var(levels[0].col(0));
  EXPECT_LT(v1, 0.8 * v0);
  EXPECT_LT(v2, 0.3 * v1);
  // Heat diffusion preserves constants and the area-weighted mean.
  EXPECT_LT((levels[0].col(1).array() - 3.0).abs().maxCoeff(), 1e-10);
  EXPECT_NEAR(area.dot(levels[0].col(0)), area.dot(values.col(0)), 1e-10);
}

TEST(DescriptorPyramid, RejectsBadInput) {
  const TriMesh m = test_meshes::make_disk(3);
  Eigen::MatrixXd values = Eigen::MatrixXd::Zero(m.num_vertices() - 1, 1);
  EXPECT_THROW(descriptor_pyramid(m, values, {0.1}), Error);
  values = Eigen::MatrixXd::Zero(m.num_vertices(), 1);
  EXPECT_THROW(descriptor_pyramid(m, values, {-0.1}), Error);
  values(0, 0) = std::nan("");
  try {
    descriptor_pyramid(m, values, {0.1});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), MCON_ERROR_NON_FINITE);
  }
}
