// Smoothing of per-vertex fields by heat diffusion: the intrinsic stand-in for convolving with a
// geodesic Gaussian. In the plane the heat kernel at time t is the Gaussian of variance 2t, so a
// kernel of width sigma is time t = sigma^2 / 2; on a surface it follows intrinsic distances.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include "operators/cotan_laplacian.h"

namespace mcon {

class HeatSmoother {
 public:
  // Default number of backward-Euler substeps: one step has the heavy-tailed kernel
  // 1 / (1 + t w^2); K steps give (1 + t w^2 / K)^-K, already close to exp(-t w^2) at K = 4.
  static constexpr int kDefaultSubsteps = 4;

  // `laplacian` is the PSD cotan Laplacian, `mass` the lumped vertex areas. Orders the sparsity
  // pattern once, then factors M + (t / K) L (SimplicialLDLT); time 0 gives the identity. Throws
  // mcon::Error (INVALID_ARGUMENT for a negative or non-finite time, K < 1 or mismatched sizes,
  // NUMERICAL if the factorization fails).
  HeatSmoother(const SparseMatrix& laplacian, const Eigen::VectorXd& mass, double time,
               int substeps = kDefaultSubsteps);

  // Another diffusion time on the same mesh: a numeric re-factorization only (the ordering and
  // symbolic analysis are kept), so several scales cost one analysis.
  void set_time(double time);

  // Diffuses every column of `values` (one row per vertex) for the whole time: K solves of
  // (M + dt L) x = M b. Neumann boundaries: the M-weighted integral of each column is preserved,
  // so constants stay constant.
  Eigen::MatrixXd smooth(const Eigen::MatrixXd& values) const;

  double time() const { return time_; }

 private:
  Eigen::SimplicialLDLT<SparseMatrix> solver_;
  SparseMatrix laplacian_;
  Eigen::VectorXd mass_;
  bool analyzed_ = false;
  double time_ = 0;
  int substeps_ = kDefaultSubsteps;
};

}  // namespace mcon
