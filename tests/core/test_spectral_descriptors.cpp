#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Eigenvalues>

#include "retrieval/bag_of_features.h"
#include "operators/cotan_laplacian.h"
#include "base/error.h"
#include "retrieval/retrieval_index.h"
#include "descriptors/spectral_descriptors.h"
#include "test_meshes.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;

namespace {

// A spherical cap of geodesic radius exactly 1 on a sphere of radius 2: the polar-grid unit disk
// wrapped onto the sphere by the exponential map at the pole, so every resolution has the same
// boundary (a cap cut from an icosphere along edges would shrink with the resolution).
TriMesh sphere_cap(int rings) {
  const double radius = 2.0;
  TriMesh m = test_meshes::make_disk(rings);
  for (Vec3& p : m.positions) {
    const double r = std::hypot(p.x(), p.y()), phi = std::atan2(p.y(), p.x());
    p = radius * Vec3(std::sin(r / radius) * std::cos(phi), std::sin(r / radius) * std::sin(phi), std::cos(r / radius));
  }
  return m;
}

double relative_spread(const Eigen::VectorXd& v) { return (v.maxCoeff() - v.minCoeff()) / v.mean(); }

}  // namespace

TEST(SpectralDescriptors, UnitSphereEigenvaluesAreLTimesLPlusOne) {
  // 642 vertices: the iterative (Spectra shift-invert) path; 162 vertices: the dense path.
  for (int subdivisions : {3, 2}) {
    const TriMesh sphere = test_meshes::make_icosphere(subdivisions);
    const LaplacianSpectrum s = laplacian_spectrum(sphere, 25);
    ASSERT_EQ(s.eigenvalues.size(), 25);
    ASSERT_EQ(s.eigenvectors.rows(), sphere.num_vertices());
    EXPECT_NEAR(s.eigenvalues[0], 0.0, 1e-9);
    const double tolerance = subdivisions == 3 ? 0.03 : 0.11;  // second-order convergence
    int i = 1;
    for (int l = 1; l <= 4; ++l)
      for (int k = 0; k < 2 * l + 1; ++k, ++i)
        EXPECT_NEAR(s.eigenvalues[i], l * (l + 1), tolerance * l * (l + 1)) << "l = " << l << ", index " << i;
    // M-orthonormal eigenvectors.
    const Eigen::VectorXd mass = vertex_areas(sphere);
    const Eigen::MatrixXd gram = s.eigenvectors.transpose() * mass.asDiagonal() * s.eigenvectors;
    EXPECT_LT((gram - Eigen::MatrixXd::Identity(25, 25)).cwiseAbs().maxCoeff(), 1e-8);
    // And they are eigenvectors: L phi = lambda M phi.
    const SparseMatrix lap = cotan_laplacian(sphere);
    for (int j = 0; j < 25; ++j) {
      const Eigen::VectorXd r = lap * s.eigenvectors.col(j) - s.eigenvalues[j] * mass.cwiseProduct(s.eigenvectors.col(j));
      EXPECT_LT(r.norm(), 1e-7 * (1 + s.eigenvalues[j])) << "pair " << j;
    }
  }
}

TEST(SpectralDescriptors, IterativeSolverFindsEveryMemberOfDegenerateBands) {
  // On the icosphere's degenerate bands plain Lanczos returned, for these counts, a set with a band
  // member missing and a larger eigenvalue in its place; the inertia check must repair that.
  const TriMesh sphere = test_meshes::make_icosphere(3);
  const Eigen::VectorXd inv_sqrt_mass = vertex_areas(sphere).cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd a =
      inv_sqrt_mass.asDiagonal() * Eigen::MatrixXd(cotan_laplacian(sphere)) * inv_sqrt_mass.asDiagonal();
  const Eigen::VectorXd reference = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a, Eigen::EigenvaluesOnly).eigenvalues();
  for (int count : {9, 23, 52}) {
    const LaplacianSpectrum s = laplacian_spectrum(sphere, count);
    ASSERT_EQ(s.eigenvalues.size(), count);
    EXPECT_LT((s.eigenvalues - reference.head(count)).cwiseAbs().maxCoeff(), 1e-7) << "count " << count;
  }
}

TEST(SpectralDescriptors, CountIsCappedAtVerticesMinusOne) {
  const TriMesh grid = test_meshes::make_grid(3);
  const LaplacianSpectrum s = laplacian_spectrum(grid, 100);
  EXPECT_EQ(s.eigenvalues.size(), 8);
  EXPECT_EQ(s.eigenvectors.cols(), 8);
  for (int i = 1; i < 8; ++i) EXPECT_LE(s.eigenvalues[i - 1], s.eigenvalues[i]);
}

TEST(SpectralDescriptors, HeatKernelSignatureOfASphereIsConstant) {
  // 100 eigenpairs = the complete bands l = 0..9, so by the addition theorem sum_i phi_i(x)^2
  // per band is constant over the sphere.
  const TriMesh sphere = test_meshes::make_icosphere(3);
  const LaplacianSpectrum s = laplacian_spectrum(sphere);
  ASSERT_EQ(s.eigenvalues.size(), 100);
  const std::vector<double> times = hks_times(s, 20);
  ASSERT_EQ(times.size(), 20u);
  EXPECT_NEAR(times.back(), 4 * std::log(10.0) / s.eigenvalues[1], 1e-12);
  const Eigen::MatrixXd hks = heat_kernel_signature(s, times);
  ASSERT_EQ(hks.rows(), sphere.num_vertices());
  ASSERT_EQ(hks.cols(), 20);
  for (Eigen::Index j = 0; j < hks.cols(); ++j) {
    EXPECT_LT(relative_spread(hks.col(j)), 0.025) << "t = " << times[static_cast<std::size_t>(j)];
    // On the unit sphere k_t(x, x) = sum_l (2l + 1) / (4 pi) exp(-l(l+1) t): compare at late times.
    if (j == hks.cols() - 1) {
      double expected = 0;
      for (int l = 0; l <= 9; ++l) expected += (2 * l + 1) / (4 * M_PI) * std::exp(-l * (l + 1) * times[19]);
      EXPECT_NEAR(hks.col(j).mean(), expected, 0.03 * expected);
    }
  }
  // Scaled HKS: divided by the heat trace, it averages 1 / area.
  const Eigen::MatrixXd scaled = heat_kernel_signature(s, times, true);
  const Eigen::VectorXd mass = vertex_areas(sphere);
  for (Eigen::Index j = 0; j < scaled.cols(); ++j) EXPECT_NEAR(mass.dot(scaled.col(j)), 1.0, 1e-8);
}

TEST(SpectralDescriptors, WaveKernelSignatureIsNormalizedPerEnergy) {
  const TriMesh cap = sphere_cap(10);
  const LaplacianSpectrum s = laplacian_spectrum(cap, 60);
  const WksSampling sampling = wks_sampling(s, 100);
  ASSERT_EQ(sampling.log_energies.size(), 100u);
  EXPECT_GT(sampling.log_energies.front(), std::log(s.eigenvalues[1]));
  EXPECT_LT(sampling.log_energies.back(), std::log(s.eigenvalues[59]));
  const Eigen::MatrixXd wks = wave_kernel_signature(s, sampling);
  ASSERT_EQ(wks.rows(), cap.num_vertices());
  ASSERT_EQ(wks.cols(), 100);
  EXPECT_TRUE(wks.allFinite());
  EXPECT_GE(wks.minCoeff(), 0.0);
  // Each energy column integrates to one over the surface.
  const Eigen::VectorXd mass = vertex_areas(cap);
  for (Eigen::Index j = 0; j < 100; ++j) EXPECT_NEAR(mass.dot(wks.col(j)), 1.0, 1e-9) << "energy " << j;
  // Energies far outside the spectrum still give finite, normalized values.
  WksSampling far = sampling;
  far.log_energies = {-50.0, 80.0};
  const Eigen::MatrixXd edge = wave_kernel_signature(s, far);
  EXPECT_TRUE(edge.allFinite());
  EXPECT_NEAR(mass.dot(edge.col(0)), 1.0, 1e-9);
}

TEST(SpectralDescriptors, HksBagOfFeaturesIsStableUnderRefinement) {
  // A cap at two resolutions vs a bump and a saddle of the same size, with the fixed radius-1
  // patch sampling so the descriptors are comparable across meshes.
  const TriMesh coarse = sphere_cap(7), fine = sphere_cap(16);
  TriMesh bump = test_meshes::make_disk(10), saddle = test_meshes::make_disk(10);
  for (Vec3& p : bump.positions) p.z() = 0.5 * std::exp(-(p.x() * p.x() + p.y() * p.y()) / 0.1);
  for (Vec3& p : saddle.positions) p.z() = 0.4 * (p.x() * p.x() - p.y() * p.y());
  ASSERT_GT(fine.num_vertices(), 4 * coarse.num_vertices());
  auto describe = [](const TriMesh& m) {
    PatchDescriptors p;
    p.values = patch_hks(m, 40, 8);
    p.areas = vertex_areas(m);
    return p;
  };
  const PatchDescriptors a = describe(coarse), b = describe(fine), c = describe(bump), d = describe(saddle);
  RetrievalBuildOptions o;
  o.vocabulary_size = 16;
  o.descriptor = "hks";
  const RetrievalConfig config = build_retrieval_config({a.values, b.values, c.values, d.values}, o);
  const auto ha = bag_of_features(config, a), hb = bag_of_features(config, b);
  const float same = l1_distance(ha.data(), hb.data(), ha.size());
  for (const PatchDescriptors* other : {&c, &d}) {
    const auto h = bag_of_features(config, *other);
    EXPECT_GT(l1_distance(ha.data(), h.data(), ha.size()), 5 * same);
    EXPECT_GT(l1_distance(hb.data(), h.data(), ha.size()), 5 * same);
  }
}

TEST(SpectralDescriptors, BadInputGetsClearErrors) {
  const TriMesh sphere = test_meshes::make_icosphere(1);
  EXPECT_EQ(status_of([&] { laplacian_spectrum(sphere, 0); }), MCON_ERROR_INVALID_ARGUMENT);
  TriMesh broken = sphere;
  broken.positions[3].x() = std::nan("");
  EXPECT_EQ(status_of([&] { laplacian_spectrum(broken, 5); }), MCON_ERROR_NON_FINITE);
  const LaplacianSpectrum s = laplacian_spectrum(sphere, 5);
  EXPECT_EQ(status_of([&] { heat_kernel_signature(s, {}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { heat_kernel_signature(s, {1.0, -1.0}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { wks_sampling(2.0, 1.0); }), MCON_ERROR_INVALID_ARGUMENT);
  LaplacianSpectrum zero = s;
  zero.eigenvalues.setZero();
  EXPECT_EQ(status_of([&] { wks_sampling(zero); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { log_spaced(0.0, 1.0, 3); }), MCON_ERROR_INVALID_ARGUMENT);
}
