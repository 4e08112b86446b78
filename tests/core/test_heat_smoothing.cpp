#include <gtest/gtest.h>

#include <cmath>

#include "operators/cotan_laplacian.h"
#include "base/error.h"
#include "operators/heat_smoothing.h"
#include "test_meshes.h"

using namespace mcon;

TEST(HeatSmoothing, PreservesConstantsAndTheIntegral) {
  const TriMesh grid = test_meshes::make_grid(20, 1.0, 0.5);
  const SparseMatrix l = cotan_laplacian(grid);
  const Eigen::VectorXd m = vertex_areas(grid);
  const HeatSmoother smoother(l, m, 0.01);
  Eigen::MatrixXd field(grid.num_vertices(), 2);
  for (int v = 0; v < grid.num_vertices(); ++v) field.row(v) << 1.0, grid.positions[v].x() * grid.positions[v].y();
  const Eigen::MatrixXd smoothed = smoother.smooth(field);
  EXPECT_LT((smoothed.col(0).array() - 1.0).abs().maxCoeff(), 1e-12);  // Neumann: constants stay
  EXPECT_NEAR(m.dot(smoothed.col(1)), m.dot(field.col(1)), 1e-12);
  EXPECT_GT((smoothed.col(1) - field.col(1)).cwiseAbs().maxCoeff(), 1e-3);  // it did smooth
}

TEST(HeatSmoothing, KernelHasTheGaussianWidthSigma) {
  // Heat from one vertex of a fine flat grid for t = sigma^2 / 2 spreads with variance sigma^2 per
  // axis (backward Euler keeps the second moment exactly), so E[r^2] = 2 sigma^2.
  const TriMesh grid = test_meshes::make_grid(121, 2.0);
  const int center = 60 * 121 + 60;
  const SparseMatrix l = cotan_laplacian(grid);
  const Eigen::VectorXd m = vertex_areas(grid);
  for (double sigma : {0.05, 0.1}) {
    const HeatSmoother smoother(l, m, 0.5 * sigma * sigma);
    Eigen::MatrixXd delta = Eigen::MatrixXd::Zero(grid.num_vertices(), 1);
    delta(center, 0) = 1.0 / m[center];
    const Eigen::VectorXd u = smoother.smooth(delta).col(0);
    double mass = 0, second_moment = 0;
    for (int v = 0; v < grid.num_vertices(); ++v) {
      mass += m[v] * u[v];
      second_moment += m[v] * u[v] * (grid.positions[v] - grid.positions[center]).squaredNorm();
    }
    EXPECT_NEAR(mass, 1.0, 1e-10);
    EXPECT_NEAR(second_moment, 2 * sigma * sigma, 0.03 * 2 * sigma * sigma) << sigma;
  }
}

TEST(HeatSmoothing, SetTimeMatchesAFreshSmootherAndTimeZeroIsIdentity) {
  const TriMesh sphere = test_meshes::make_icosphere(3);
  const SparseMatrix l = cotan_laplacian(sphere);
  const Eigen::VectorXd m = vertex_areas(sphere);
  Eigen::MatrixXd field(sphere.num_vertices(), 1);
  for (int v = 0; v < sphere.num_vertices(); ++v) field(v, 0) = sphere.positions[v].z();
  HeatSmoother reused(l, m, 0.001);
  reused.set_time(0.02);
  const HeatSmoother fresh(l, m, 0.02);
  EXPECT_LT((reused.smooth(field) - fresh.smooth(field)).cwiseAbs().maxCoeff(), 1e-12);
  reused.set_time(0.0);
  EXPECT_EQ(reused.smooth(field), field);
  // z is a first spherical harmonic: the heat flow damps it by about exp(-2 t) on the unit sphere.
  const double damping =
      fresh.smooth(field).col(0).dot(m.asDiagonal() * field.col(0)) / field.col(0).dot(m.asDiagonal() * field.col(0));
  EXPECT_NEAR(damping, std::exp(-2 * 0.02), 2e-3);
}

TEST(HeatSmoothing, RejectsBadArguments) {
  const TriMesh grid = test_meshes::make_grid(4);
  const SparseMatrix l = cotan_laplacian(grid);
  const Eigen::VectorXd m = vertex_areas(grid);
  auto status = [](auto&& f) {
    try {
      f();
    } catch (const Error& e) {
      return e.status();
    }
    return MCON_OK;
  };
  EXPECT_EQ(status([&] { HeatSmoother(l, m, -1.0); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status([&] { HeatSmoother(l, m, std::nan("")); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status([&] { HeatSmoother(l, m, 0.1, 0); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status([&] { HeatSmoother(l, Eigen::VectorXd::Ones(3), 0.1); }), MCON_ERROR_INVALID_ARGUMENT);
  const HeatSmoother ok(l, m, 0.1);
  EXPECT_EQ(status([&] { ok.smooth(Eigen::MatrixXd::Zero(3, 1)); }), MCON_ERROR_INVALID_ARGUMENT);
}
