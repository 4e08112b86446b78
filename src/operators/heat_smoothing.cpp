#include "operators/heat_smoothing.h"

#include <cmath>
#include <string>

#include "base/error.h"

namespace mcon {

HeatSmoother::HeatSmoother(const SparseMatrix& laplacian, const Eigen::VectorXd& mass, double time, int substeps)
    : laplacian_(laplacian), mass_(mass), substeps_(substeps) {
  require(substeps >= 1, MCON_ERROR_INVALID_ARGUMENT, "heat smoothing needs at least one substep");
  require(laplacian.rows() == mass.size() && laplacian.cols() == mass.size(), MCON_ERROR_INVALID_ARGUMENT,
          "heat smoothing: Laplacian and mass sizes differ");
  set_time(time);
}

void HeatSmoother::set_time(double time) {
  require(std::isfinite(time) && time >= 0, MCON_ERROR_INVALID_ARGUMENT,
          "heat smoothing time must be finite and >= 0, got " + std::to_string(time));
  time_ = time;
  if (time == 0) return;
  // M + dt L, with the diagonal written explicitly so the pattern is the same for every time.
  SparseMatrix system = (time / substeps_) * laplacian_;
  for (Eigen::Index v = 0; v < mass_.size(); ++v) system.coeffRef(v, v) += mass_[v];
  if (!analyzed_) {
    solver_.analyzePattern(system);
    analyzed_ = true;
  }
  solver_.factorize(system);
  require(solver_.info() == Eigen::Success, MCON_ERROR_NUMERICAL,
          "heat smoothing: factorization of M + t L failed (degenerate mesh?)");
}

Eigen::MatrixXd HeatSmoother::smooth(const Eigen::MatrixXd& values) const {
  require(values.rows() == mass_.size(), MCON_ERROR_INVALID_ARGUMENT,
          "heat smoothing: field has " + std::to_string(values.rows()) + " rows for " + std::to_string(mass_.size()) +
              " vertices");
  if (time_ == 0) return values;
  Eigen::MatrixXd x = values, rhs;
  for (int step = 0; step < substeps_; ++step) {
    rhs.noalias() = mass_.asDiagonal() * x;  // a named temporary: the solve must not alias x
    x = solver_.solve(rhs);
    require(solver_.info() == Eigen::Success && x.allFinite(), MCON_ERROR_NUMERICAL, "heat smoothing: solve failed");
  }
  return x;
}

}  // namespace mcon
