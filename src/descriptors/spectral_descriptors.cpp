#include "descriptors/spectral_descriptors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Spectra/SymEigsShiftSolver.h>

#include "operators/cotan_laplacian.h"
#include "base/counter_rng.h"
#include "base/error.h"

namespace mcon {
namespace {

// Below this many vertices a dense symmetric eigensolver is faster and needs no convergence test.
constexpr int kDenseLimit = 500;

constexpr std::uint64_t kStartSeed = 0x4c414e43ull;  // "LANC"

constexpr double kFlatDiskLambda1 = 3.3900;  // 1.8412^2: first non-zero Neumann eigenvalue, unit disk
constexpr double kFlatDiskLambda100 = 363.0;  // l/4 + sqrt(l)/2 = 100

SparseMatrix shifted(const SparseMatrix& a, double shift) {
  SparseMatrix identity(a.rows(), a.cols());
  identity.setIdentity();
  return a - shift * identity;
}

// y = P (A - shift I)^-1 P x with P the projector onto the complement of the already found
// eigenvectors Q (orthonormal columns): the found pairs become nu = 0 and are not found again.
// A - shift I is factored once by a sparse LDLT (Spectra's own sparse shift-solve uses LU, which
// ignores the symmetry).
class DeflatedShiftInvertOp {
 public:
  using Scalar = double;
  DeflatedShiftInvertOp(const SparseMatrix& a, const Eigen::MatrixXd& found) : a_(a), found_(found) {}
  Eigen::Index rows() const { return a_.rows(); }
  Eigen::Index cols() const { return a_.cols(); }
  void set_shift(double shift) {
    if (factored_ && shift == shift_) return;
    ldlt_.compute(shifted(a_, shift));
    require(ldlt_.info() == Eigen::Success, MCON_ERROR_NUMERICAL,
            "Laplacian spectrum: factorization of the shifted operator failed");
    factored_ = true;
    shift_ = shift;
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, a_.rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, a_.rows());
    if (found_.cols() == 0) {
      y = ldlt_.solve(x);
      return;
    }
    y = ldlt_.solve(x - found_ * (found_.transpose() * x));
    y -= found_ * (found_.transpose() * y);
  }

 private:
  const SparseMatrix& a_;
  const Eigen::MatrixXd& found_;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
  bool factored_ = false;
  double shift_ = 0;
};

// Sylvester's law of inertia: the number of eigenvalues of A below mu is the number of negative
// pivots of an LDL^T factorization of A - mu I (the fill-reducing permutation keeps the inertia).
int eigenvalues_below(const SparseMatrix& a, double mu) {
  for (int attempt = 0; attempt < 3; ++attempt, mu *= 1 - 1e-7) {
    Eigen::SimplicialLDLT<SparseMatrix> ldlt(shifted(a, mu));
    if (ldlt.info() != Eigen::Success) continue;  // mu hit a pivot exactly: nudge it
    const Eigen::VectorXd d = ldlt.vectorD();
    if (!d.allFinite() || (d.array() == 0).any()) continue;
    return static_cast<int>((d.array() < 0).count());
  }
  fail(MCON_ERROR_NUMERICAL, "Laplacian spectrum: inertia count failed");
}

// The m smallest eigenpairs of the symmetric positive semi-definite A (n x n, n > m) by
// shift-invert Lanczos. A single-vector Krylov method can miss members of a degenerate eigenvalue
// cluster (spheres, symmetric disks: on a 642-vertex icosphere a quarter of the counts 2..120 came
// back with a band member missing). So every result is checked by an inertia count, and missing
// pairs are found by a further Lanczos run deflated by the known ones, from a fresh start vector
// (from Spectra's fixed one the deflated run missed the same pair again).
void iterative_smallest(const SparseMatrix& a, int m, double shift, Eigen::VectorXd& values,
                        Eigen::MatrixXd& vectors) {
  const int n = static_cast<int>(a.rows());
  values.resize(0);
  vectors.resize(n, 0);
  DeflatedShiftInvertOp op(a, vectors);  // factors A - shift I once, deflates the current `vectors`
  int want = m;
  for (int round = 0; round < 6; ++round) {
    const int nev = std::min(want, n - 1 - static_cast<int>(vectors.cols()));
    if (nev >= 1) {
      const int ncv = std::min(n, std::max(2 * nev + 1, nev + 20));
      Spectra::SymEigsShiftSolver<DeflatedShiftInvertOp> solver(op, nev, ncv, shift);
      // Deterministic start vectors, a fresh one per round (the first is Spectra's fixed-seed one).
      if (round == 0) {
        solver.init();
      } else {
        Eigen::VectorXd start(n);
        for (int i = 0; i < n; ++i)
          start[i] = counter_uniform(kStartSeed, static_cast<std::uint64_t>(round), static_cast<std::uint64_t>(i)) - 0.5;
        solver.init(start.data());
      }
      const Eigen::Index converged = solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-10);
      require(solver.info() == Spectra::CompInfo::Successful && converged == nev, MCON_ERROR_NUMERICAL,
              "Laplacian spectrum: Lanczos converged for " + std::to_string(converged) + " of " +
                  std::to_string(nev) + " eigenpairs");
      // Merge with what was found before, ascending; keep the m smallest.
      const Eigen::VectorXd new_values = solver.eigenvalues();
      const Eigen::MatrixXd new_vectors = solver.eigenvectors();
      Eigen::VectorXd all_values(values.size() + nev);
      all_values << values, new_values;
      Eigen::MatrixXd all_vectors(n, vectors.cols() + nev);
      all_vectors << vectors, new_vectors;
      std::vector<int> order(static_cast<std::size_t>(all_values.size()));
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return all_values[i] < all_values[j]; });
      order.resize(std::min<std::size_t>(order.size(), static_cast<std::size_t>(m)));
      values.resize(static_cast<Eigen::Index>(order.size()));
      vectors.resize(n, values.size());
      for (std::size_t i = 0; i < order.size(); ++i) {
        values[static_cast<Eigen::Index>(i)] = all_values[order[i]];
        vectors.col(static_cast<Eigen::Index>(i)) = all_vectors.col(order[i]);
      }
    }
    // Complete if no eigenvalue below mu (just under the largest kept value) is missing. Members
    // of the largest value's own cluster are interchangeable where the count cuts through it.
    const double top = values[values.size() - 1];
    const double mu = top - 1e-6 * std::max(std::abs(top), 1e-12);
    const int expected = static_cast<int>((values.array() < mu).count());
    const int actual = eigenvalues_below(a, mu);
    if (actual <= expected && values.size() == m) return;
    want = std::max(actual - expected, m - static_cast<int>(values.size())) + 2;
  }
  fail(MCON_ERROR_NUMERICAL, "Laplacian spectrum: could not find a complete set of eigenpairs");
}

// Eigenvalues below this are the (numerically) zero modes: one per connected component.
double zero_threshold(const LaplacianSpectrum& s) { return 1e-9 * std::max(1e-300, s.eigenvalues.maxCoeff()); }

double first_nonzero(const LaplacianSpectrum& s, const char* who) {
  require(s.eigenvalues.size() >= 1, MCON_ERROR_INVALID_ARGUMENT, std::string(who) + ": empty spectrum");
  const double zero = zero_threshold(s);
  for (Eigen::Index i = 0; i < s.eigenvalues.size(); ++i)
    if (s.eigenvalues[i] > zero) return s.eigenvalues[i];
  fail(MCON_ERROR_INVALID_ARGUMENT, std::string(who) + ": the spectrum has no non-zero eigenvalue");
}

void check_spectrum(const LaplacianSpectrum& s, const char* who) {
  require(s.eigenvalues.size() >= 1 && s.eigenvectors.cols() == s.eigenvalues.size() && s.eigenvectors.rows() >= 1,
          MCON_ERROR_INVALID_ARGUMENT, std::string(who) + ": inconsistent spectrum");
  require(s.eigenvalues.allFinite() && s.eigenvectors.allFinite(), MCON_ERROR_NON_FINITE,
          std::string(who) + ": spectrum has non-finite values");
}

}  // namespace

LaplacianSpectrum laplacian_spectrum(const TriMesh& mesh, int count) {
  validate_mesh(mesh);
  const int n = mesh.num_vertices();
  require(count >= 1, MCON_ERROR_INVALID_ARGUMENT, "Laplacian spectrum: count must be at least 1");
  require(n >= 2, MCON_ERROR_INVALID_ARGUMENT, "Laplacian spectrum: the mesh needs at least 2 vertices");
  const int m = std::min(count, n - 1);

  const Eigen::VectorXd mass = vertex_areas(mesh);
  require(mass.minCoeff() > 0, MCON_ERROR_NUMERICAL, "Laplacian spectrum: a vertex has zero area");
  const Eigen::VectorXd inv_sqrt_mass = mass.cwiseSqrt().cwiseInverse();
  // Symmetric standard form: A psi = lambda psi with psi = M^1/2 phi.
  const SparseMatrix a = inv_sqrt_mass.asDiagonal() * cotan_laplacian(mesh) * inv_sqrt_mass.asDiagonal();

  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
  if (n <= kDenseLimit) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense(Eigen::MatrixXd(a), Eigen::ComputeEigenvectors);
    require(dense.info() == Eigen::Success, MCON_ERROR_NUMERICAL, "Laplacian spectrum: dense eigensolver failed");
    values = dense.eigenvalues().head(m);  // ascending
    vectors = dense.eigenvectors().leftCols(m);
  } else {
    // Shift-invert around a negative shift finds the eigenvalues nearest to it, i.e. the smallest.
    // Its size only affects conditioning: a hundredth of Weyl's estimate of lambda_1 (4 pi / area).
    const double shift = -0.01 * 4.0 * M_PI / mass.sum();
    iterative_smallest(a, m, shift, values, vectors);
  }
  require(values.allFinite() && vectors.allFinite(), MCON_ERROR_NUMERICAL,
          "Laplacian spectrum: non-finite eigenpairs");

  LaplacianSpectrum out;
  out.eigenvalues = values.cwiseMax(0.0);  // the zero modes come out as +-1e-15
  out.eigenvectors = inv_sqrt_mass.asDiagonal() * vectors;
  return out;
}

std::vector<double> log_spaced(double first, double last, int count) {
  require(count >= 1, MCON_ERROR_INVALID_ARGUMENT, "log_spaced: count must be at least 1");
  require(std::isfinite(first) && std::isfinite(last) && first > 0 && last > 0, MCON_ERROR_INVALID_ARGUMENT,
          "log_spaced: bounds must be finite and positive");
  std::vector<double> out(static_cast<std::size_t>(count));
  const double a = std::log(first), b = std::log(last);
  for (int i = 0; i < count; ++i) out[static_cast<std::size_t>(i)] = std::exp(count == 1 ? a : a + (b - a) * i / (count - 1));
  return out;
}

Eigen::MatrixXd heat_kernel_signature(const LaplacianSpectrum& s, const std::vector<double>& times,
                                      bool scale_by_heat_trace) {
  check_spectrum(s, "HKS");
  require(!times.empty(), MCON_ERROR_INVALID_ARGUMENT, "HKS: no times");
  const Eigen::Index m = s.eigenvalues.size(), nt = static_cast<Eigen::Index>(times.size());
  Eigen::MatrixXd decay(m, nt);
  for (Eigen::Index j = 0; j < nt; ++j) {
    const double t = times[static_cast<std::size_t>(j)];
    require(std::isfinite(t) && t > 0, MCON_ERROR_INVALID_ARGUMENT, "HKS: times must be finite and positive");
    decay.col(j) = (-t * s.eigenvalues.array()).exp();
  }
  Eigen::MatrixXd hks = s.eigenvectors.array().square().matrix() * decay;
  if (scale_by_heat_trace) hks = hks * decay.colwise().sum().cwiseInverse().asDiagonal();
  return hks;
}

std::vector<double> hks_times(const LaplacianSpectrum& s, int count) {
  check_spectrum(s, "HKS");
  const double four_ln10 = 4.0 * std::log(10.0);
  return log_spaced(four_ln10 / s.eigenvalues.maxCoeff(), four_ln10 / first_nonzero(s, "HKS"), count);
}

WksSampling wks_sampling(double lambda_min, double lambda_max, int count, double variance_factor) {
  require(count >= 1, MCON_ERROR_INVALID_ARGUMENT, "WKS: count must be at least 1");
  require(std::isfinite(lambda_min) && std::isfinite(lambda_max) && lambda_min > 0 && lambda_max > lambda_min,
          MCON_ERROR_INVALID_ARGUMENT, "WKS: need 0 < lambda_min < lambda_max");
  require(std::isfinite(variance_factor) && variance_factor > 0, MCON_ERROR_INVALID_ARGUMENT,
          "WKS: variance factor must be positive");
  const double lo = std::log(lambda_min), hi = std::log(lambda_max);
  WksSampling out;
  out.sigma = variance_factor * (hi - lo) / count;
  double first = lo + 2 * out.sigma, last = hi - 2 * out.sigma;
  if (!(first < last)) first = lo, last = hi;  // too few energies for the margins
  out.log_energies.resize(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i)
    out.log_energies[static_cast<std::size_t>(i)] = count == 1 ? 0.5 * (first + last) : first + (last - first) * i / (count - 1);
  return out;
}

WksSampling wks_sampling(const LaplacianSpectrum& s, int count, double variance_factor) {
  check_spectrum(s, "WKS");
  return wks_sampling(first_nonzero(s, "WKS"), s.eigenvalues.maxCoeff(), count, variance_factor);
}

Eigen::MatrixXd wave_kernel_signature(const LaplacianSpectrum& s, const WksSampling& sampling) {
  check_spectrum(s, "WKS");
  require(!sampling.log_energies.empty(), MCON_ERROR_INVALID_ARGUMENT, "WKS: no energies");
  require(std::isfinite(sampling.sigma) && sampling.sigma > 0, MCON_ERROR_INVALID_ARGUMENT,
          "WKS: sigma must be finite and positive");
  first_nonzero(s, "WKS");
  const double zero = zero_threshold(s);
  const Eigen::Index m = s.eigenvalues.size(), ne = static_cast<Eigen::Index>(sampling.log_energies.size());
  // Filter weights per (eigenvalue, energy), each column relative to its largest exponent and then
  // normalized to sum 1: the same ratios as ASC11's C_e, without underflow for distant energies.
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(m, ne);
  for (Eigen::Index j = 0; j < ne; ++j) {
    const double e = sampling.log_energies[static_cast<std::size_t>(j)];
    require(std::isfinite(e), MCON_ERROR_INVALID_ARGUMENT, "WKS: energies must be finite");
    double closest = std::numeric_limits<double>::infinity();
    for (Eigen::Index k = 0; k < m; ++k)
      if (s.eigenvalues[k] > zero) closest = std::min(closest, std::abs(e - std::log(s.eigenvalues[k])));
    for (Eigen::Index k = 0; k < m; ++k) {
      if (!(s.eigenvalues[k] > zero)) continue;
      const double u = std::abs(e - std::log(s.eigenvalues[k]));
      weights(k, j) = std::exp(-(u - closest) * (u + closest) / (2 * sampling.sigma * sampling.sigma));
    }
    weights.col(j) /= weights.col(j).sum();
  }
  return s.eigenvectors.array().square().matrix() * weights;
}

std::vector<double> patch_hks_times(int count) {
  const double four_ln10 = 4.0 * std::log(10.0);
  return log_spaced(four_ln10 / kFlatDiskLambda100, four_ln10 / kFlatDiskLambda1, count);
}

WksSampling patch_wks_sampling(int count) { return wks_sampling(kFlatDiskLambda1, kFlatDiskLambda100, count); }

Eigen::MatrixXd patch_hks(const TriMesh& patch, int eigenpairs, int times) {
  return heat_kernel_signature(laplacian_spectrum(patch, eigenpairs), patch_hks_times(times));
}

Eigen::MatrixXd patch_wks(const TriMesh& patch, int eigenpairs, int energies) {
  return wave_kernel_signature(laplacian_spectrum(patch, eigenpairs), patch_wks_sampling(energies));
}

}  // namespace mcon
