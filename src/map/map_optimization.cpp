#include "map/map_optimization.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "base/error.h"
#include "map/injective_step.h"

namespace mcon {

namespace {

// The lower triangle of the 2n x 2n Hessian with the sparsity of the source mesh (2x2 blocks
// for every vertex pair sharing a triangle), and where each element's entries go in it.
class HessianPattern {
 public:
  HessianPattern(int num_vertices, const std::vector<Tri>& triangles) {
    const int n = 2 * num_vertices;
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(triangles.size() * 21 + static_cast<std::size_t>(num_vertices) * 3);
    for (const Tri& t : triangles)
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) {
          const int r = 2 * t[a / 2] + a % 2, c = 2 * t[b / 2] + b % 2;
          if (r >= c) trip.emplace_back(r, c, 0.0);
        }
    for (int v = 0; v < num_vertices; ++v) {
      trip.emplace_back(2 * v, 2 * v, 0.0);
      trip.emplace_back(2 * v + 1, 2 * v, 0.0);
      trip.emplace_back(2 * v + 1, 2 * v + 1, 0.0);
    }
    matrix.resize(n, n);
    matrix.setFromTriplets(trip.begin(), trip.end());
    matrix.makeCompressed();
    tri_slots.resize(triangles.size() * 36);
    for (std::size_t i = 0; i < triangles.size(); ++i)
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) {
          const int r = 2 * triangles[i][a / 2] + a % 2, c = 2 * triangles[i][b / 2] + b % 2;
          tri_slots[i * 36 + a * 6 + b] = r >= c ? slot(r, c) : -1;
        }
    vertex_slots.resize(static_cast<std::size_t>(num_vertices) * 3);
    diagonal_slots.resize(n);
    for (int v = 0; v < num_vertices; ++v) {
      vertex_slots[3 * v] = slot(2 * v, 2 * v);
      vertex_slots[3 * v + 1] = slot(2 * v + 1, 2 * v);
      vertex_slots[3 * v + 2] = slot(2 * v + 1, 2 * v + 1);
    }
    for (int i = 0; i < n; ++i) diagonal_slots[i] = slot(i, i);
  }

  int slot(int r, int c) const {
    const int* begin = matrix.innerIndexPtr() + matrix.outerIndexPtr()[c];
    const int* end = matrix.innerIndexPtr() + matrix.outerIndexPtr()[c + 1];
    const int* it = std::lower_bound(begin, end, r);
    return static_cast<int>(it - matrix.innerIndexPtr());
  }

  Eigen::SparseMatrix<double> matrix;
  std::vector<int> tri_slots, vertex_slots, diagonal_slots;
};

using Ldlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower>;

// Assemble: the elements' Hessian blocks into the pattern's matrix. Returns the mean diagonal
// entry (at least 1e-300), the scale of the shift.
double assemble_hessian(const MapEnergy::Derivatives& der, const SourceDisk& src, HessianPattern& pattern) {
  Eigen::SparseMatrix<double>& H = pattern.matrix;
  double* val = H.valuePtr();
  std::fill(val, val + H.nonZeros(), 0.0);
  for (std::size_t t = 0; t < src.triangles.size(); ++t) {
    const Matrix6d& h = der.triangle_hessians[t];
    const int* slots = &pattern.tri_slots[t * 36];
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b)
        if (slots[a * 6 + b] >= 0) val[slots[a * 6 + b]] += h(a, b);
  }
  for (int v = 0; v < src.num_vertices; ++v) {
    const Eigen::Matrix2d& h = der.vertex_hessians[v];
    val[pattern.vertex_slots[3 * v]] += h(0, 0);
    val[pattern.vertex_slots[3 * v + 1]] += h(1, 0);
    val[pattern.vertex_slots[3 * v + 2]] += h(1, 1);
  }
  double mean_diag = 0;
  for (int s : pattern.diagonal_slots) mean_diag += val[s];
  return std::max(mean_diag / static_cast<double>(pattern.diagonal_slots.size()), 1e-300);
}

// Factorize with a diagonal shift; raise it until the factorization is positive definite.
// shift_scale grows if factorizations fail, shrinks back after successes.
Eigen::VectorXd newton_direction(HessianPattern& pattern, Ldlt& ldlt, const Eigen::VectorXd& gradient,
                                 double mean_diag, double regularization, double& shift_scale) {
  Eigen::SparseMatrix<double>& H = pattern.matrix;
  double* val = H.valuePtr();
  Eigen::VectorXd dir;
  bool solved = false;
  for (int attempt = 0; attempt < 8 && !solved; ++attempt) {
    const double shift = regularization * shift_scale * mean_diag;
    for (int s : pattern.diagonal_slots) val[s] += shift;
    ldlt.factorize(H);
    for (int s : pattern.diagonal_slots) val[s] -= shift;
    if (ldlt.info() == Eigen::Success && ldlt.vectorD().minCoeff() > 0) {
      dir = -ldlt.solve(gradient);
      solved = dir.allFinite();
    }
    if (!solved) shift_scale *= 100;
  }
  require(solved, MCON_ERROR_NUMERICAL, "newton: the linear solve failed");
  shift_scale = std::max(1.0, shift_scale * 0.1);
  return dir;
}

// Inexact Newton step: solves (H + shift I) dir = -gradient by conjugate gradients preconditioned
// with an earlier factorization (of a nearby Hessian), to a residual <= tolerance |gradient|.
// Started at 0, every CG iterate decreases the quadratic model, so dir is a descent direction
// (Nocedal & Wright, Numerical Optimization, §7.1). Returns false (dir unusable) if the residual
// is not reached within max_iterations or the matrix shows a non-positive curvature.
bool preconditioned_direction(const HessianPattern& pattern, const Ldlt& preconditioner,
                              const Eigen::VectorXd& gradient, double shift, double tolerance, int max_iterations,
                              Eigen::VectorXd& dir, int& iterations) {
  const auto H = pattern.matrix.selfadjointView<Eigen::Lower>();
  Eigen::VectorXd r = -gradient;
  const double target = tolerance * r.norm();
  dir.setZero(r.size());
  Eigen::VectorXd z = preconditioner.solve(r), p = z, Ap(r.size());
  double rz = r.dot(z);
  for (iterations = 1; iterations <= max_iterations; ++iterations) {
    Ap.noalias() = H * p;
    Ap += shift * p;
    const double pAp = p.dot(Ap);
    if (!(pAp > 0)) return false;
    const double step = rz / pAp;
    dir += step * p;
    r -= step * Ap;
    if (r.norm() <= target) return dir.allFinite();
    z = preconditioner.solve(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  iterations = max_iterations;
  return false;
}

// Line search inside the flip-free region: halves the step from the largest flip-free one until
// the Armijo condition holds. Returns false if no step was accepted.
bool line_search(const MapEnergy& energy, const Eigen::VectorXd& x, const Eigen::VectorXd& dir, double E,
                 double slope, const NewtonOptions& options, Eigen::VectorXd& trial, MapEnergyTerms& trial_terms) {
  const double t_max = max_injective_step(energy.source().triangles, x, dir);
  double alpha = std::min(1.0, options.step_fraction * t_max);
  for (int k = 0; k < options.max_backtracks; ++k) {
    trial = x + alpha * dir;
    trial_terms = energy.evaluate(trial);
    if (trial_terms.total <= E + options.armijo * alpha * slope) return true;
    alpha *= 0.5;
  }
  return false;
}

// The last progress_window iterations gained at most progress_fraction of the whole decrease.
bool progress_stalled(const NewtonReport& report, const NewtonOptions& options) {
  const int w = options.progress_window;
  if (w > 0 && report.iterations > w) {
    const std::vector<double>& e = report.energy;
    const double recent = e[e.size() - 1 - w] - e.back(), total = e.front() - e.back();
    return recent <= options.progress_fraction * total;
  }
  return false;
}

}  // namespace

struct NewtonWarmStart::State {
  const std::vector<Tri>* triangles = nullptr;  // the disk it was built for
  int num_vertices = 0;
  HessianPattern pattern;
  Ldlt ldlt;
  bool factorized = false;
  State(int n, const std::vector<Tri>& tris) : triangles(&tris), num_vertices(n), pattern(n, tris) {
    ldlt.analyzePattern(pattern.matrix);
  }
};

NewtonWarmStart::NewtonWarmStart() = default;
NewtonWarmStart::~NewtonWarmStart() = default;
NewtonWarmStart::NewtonWarmStart(NewtonWarmStart&&) noexcept = default;
NewtonWarmStart& NewtonWarmStart::operator=(NewtonWarmStart&&) noexcept = default;

const char* stop_reason_name(StopReason reason) {
  switch (reason) {
    case StopReason::converged: return "converged";
    case StopReason::stalled: return "stalled";
    case StopReason::iteration_cap: return "iteration_cap";
    case StopReason::cancelled: return "cancelled";
  }
  return "unknown";
}

NewtonReport minimize_map_energy(const MapEnergy& energy, Eigen::VectorXd& x, const NewtonOptions& options,
                                 const std::function<bool(int, double)>& keep_going, NewtonWarmStart* warm) {
  const SourceDisk& src = energy.source();
  require(x.size() == energy.num_variables(), MCON_ERROR_INVALID_ARGUMENT, "newton: wrong variable count");
  require(!options.reuse_factorization || (options.inexact_tolerance > 0 && options.inexact_tolerance < 1 &&
                                            options.max_inner_iterations >= 1),
          MCON_ERROR_INVALID_ARGUMENT, "newton: inexact_tolerance must be in (0, 1) and max_inner_iterations >= 1");
  require(count_inverted(src.triangles, x) == 0, MCON_ERROR_NUMERICAL, "newton: the start has inverted triangles");

  NewtonReport report;
  NewtonWarmStart local;
  NewtonWarmStart& ws = warm ? *warm : local;
  if (!ws.state || ws.state->triangles != &src.triangles || ws.state->num_vertices != src.num_vertices)
    ws.state = std::make_unique<NewtonWarmStart::State>(src.num_vertices, src.triangles);
  HessianPattern& pattern = ws.state->pattern;
  Ldlt& ldlt = ws.state->ldlt;
  bool& factorized = ws.state->factorized;  // ldlt holds a factorization (the preconditioner of later steps)

  MapEnergy::Derivatives der;
  energy.derivatives(x, der);
  double E = der.terms.total;
  require(std::isfinite(E), MCON_ERROR_NUMERICAL, "newton: the start energy is not finite");
  report.energy.push_back(E);
  report.terms = der.terms;
  const double tolerance =
      options.relative_decrease * std::max(std::abs(E), options.energy_scale) + options.absolute_decrease;
  double shift_scale = 1.0;  // grows if factorizations fail, shrinks back after successes

  for (int iter = 0; iter < options.max_iterations; ++iter) {
    const double mean_diag = assemble_hessian(der, src, pattern);
    Eigen::VectorXd dir;
    int inner = 0;
    const bool reused = factorized && options.reuse_factorization &&
                        preconditioned_direction(pattern, ldlt, der.gradient,
                                                 options.regularization * shift_scale * mean_diag,
                                                 options.inexact_tolerance, options.max_inner_iterations, dir, inner);
    report.inner_iterations += inner;
    if (!reused) {
      factorized = false;  // until this factorization has succeeded
      dir = newton_direction(pattern, ldlt, der.gradient, mean_diag, options.regularization, shift_scale);
      factorized = true;
      ++report.factorizations;
    }
    const double slope = der.gradient.dot(dir);  // < 0 for a positive definite model
    if (!(slope < 0)) {
      report.reason = StopReason::converged;  // zero gradient
      break;
    }
    // Newton decrement: the model predicts a decrease of -slope / 2.
    if (-0.5 * slope <= tolerance) {
      report.reason = StopReason::converged;
      break;
    }

    Eigen::VectorXd trial;
    MapEnergyTerms trial_terms;
    if (!line_search(energy, x, dir, E, slope, options, trial, trial_terms)) {
      report.reason = StopReason::stalled;
      break;
    }
    const double decrease = E - trial_terms.total;
    x = trial;
    E = trial_terms.total;
    report.iterations = iter + 1;
    report.energy.push_back(E);
    energy.derivatives(x, der);
    report.terms = der.terms;
    if (keep_going && !keep_going(iter + 1, E)) {
      report.reason = StopReason::cancelled;
      break;
    }
    if (decrease <= tolerance || progress_stalled(report, options)) {
      report.reason = StopReason::converged;
      break;
    }
    if (iter + 1 == options.max_iterations) report.reason = StopReason::iteration_cap;
  }
  if (options.max_iterations <= 0) report.reason = StopReason::iteration_cap;
  return report;
}

}  // namespace mcon
