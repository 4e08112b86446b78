// Spectral descriptors of a patch (thesis §3.1 "Spectral descriptors"): the low end of the
// Laplace-Beltrami spectrum, L phi = lambda M phi (cotan L, lumped barycentric M; natural Neumann
// condition at the boundary), and from it the heat kernel signature (Sun, Ovsjanikov & Guibas
// 2009) and the wave kernel signature (Aubry, Schlickewei & Cremers 2011) per vertex.
//
// Comparable descriptors need one time/energy sampling for all shapes (ASC11; thesis §3.1): the
// per-spectrum samplings follow the papers, the patch_* ones are fixed for patches normalized to
// geodesic radius 1 and are what a library should use.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace mcon {

struct LaplacianSpectrum {
  Eigen::VectorXd eigenvalues;   // m values, ascending, >= 0 (the first is ~0: constant function)
  Eigen::MatrixXd eigenvectors;  // n x m, M-orthonormal: Phi^T M Phi = I
};

// The `count` smallest eigenpairs, capped at n - 1. Solved in symmetric standard form
// A = M^-1/2 L M^-1/2 (M is diagonal): densely for small meshes, otherwise with Spectra's
// shift-invert Lanczos around a small negative shift (A - shift I is positive definite, factored
// once with a sparse LDLT). Throws mcon::Error: the mesh's validation errors, INVALID_ARGUMENT
// (count < 1, fewer than 2 vertices), NUMERICAL (factorization failed, Lanczos did not converge).
LaplacianSpectrum laplacian_spectrum(const TriMesh& mesh, int count = 100);

// `count` values from `first` to `last`, evenly spaced in log scale (both > 0).
std::vector<double> log_spaced(double first, double last, int count);

// HKS(x, t) = sum_i exp(-lambda_i t) phi_i(x)^2, one column per time. With scale_by_heat_trace each
// column is divided by sum_i exp(-lambda_i t) (Sun et al.'s scaled HKS).
Eigen::MatrixXd heat_kernel_signature(const LaplacianSpectrum& spectrum, const std::vector<double>& times,
                                      bool scale_by_heat_trace = false);

// Sun et al.'s times for one shape: log-spaced over [4 ln 10 / lambda_max, 4 ln 10 / lambda_1]
// (lambda_1 = first non-zero eigenvalue).
std::vector<double> hks_times(const LaplacianSpectrum& spectrum, int count = 100);

struct WksSampling {
  std::vector<double> log_energies;  // e values (log of an eigenvalue scale)
  double sigma = 0;                  // width of the log-normal energy filter
};

// ASC11's sampling between eigenvalues lambda_min < lambda_max: delta = (log lambda_max -
// log lambda_min) / count, sigma = variance_factor * delta, energies evenly spaced over
// [log lambda_min + 2 sigma, log lambda_max - 2 sigma] (the whole range when that is empty).
WksSampling wks_sampling(double lambda_min, double lambda_max, int count = 100, double variance_factor = 7.0);
// The same for one shape: first non-zero and largest eigenvalue of its spectrum.
WksSampling wks_sampling(const LaplacianSpectrum& spectrum, int count = 100, double variance_factor = 7.0);

// WKS(x, e) = sum_k phi_k(x)^2 f_e(lambda_k) / sum_k f_e(lambda_k), f_e(l) = exp(-(e - log l)^2 /
// 2 sigma^2), over the non-zero eigenvalues: normalized per energy, so each column integrates to 1
// over the surface (sum_x A_x WKS(x, e) = 1 for M-orthonormal phi).
Eigen::MatrixXd wave_kernel_signature(const LaplacianSpectrum& spectrum, const WksSampling& sampling);

// Fixed samplings for patches at geodesic radius 1, derived from the flat unit disk (Neumann):
// lambda_1 = 1.8412^2 = 3.39 (first zero of J1'), lambda_100 ~ 363 (Weyl's law with its boundary
// term, N(l) = l/4 + sqrt(l)/2). Curved patches have more area and a somewhat lower spectrum,
// which these ranges cover with the filters' tails.
std::vector<double> patch_hks_times(int count = 100);
WksSampling patch_wks_sampling(int count = 100);

// Per-vertex descriptors of a radius-1 patch (rows = vertices), with the fixed samplings above.
Eigen::MatrixXd patch_hks(const TriMesh& patch, int eigenpairs = 100, int times = 100);
Eigen::MatrixXd patch_wks(const TriMesh& patch, int eigenpairs = 100, int energies = 100);

}  // namespace mcon
