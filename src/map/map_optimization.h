// Projected Newton minimization of the map energy (docs/design.md §2): per-element Hessians with
// negative eigenvalues clamped (map_energy.h), assembled into one sparse matrix whose pattern is
// analyzed once, a tiny diagonal regularization, SimplicialLDLT (its factorization reused as the
// preconditioner of an inexact Newton solve while that converges fast; docs/design.md §13); the line search starts at
// min(1, 0.9 t_max) with t_max the largest flip-free step (injective_step.h) and backtracks
// until Armijo's condition holds, so every iterate is free of inverted triangles and the energy
// decreases monotonically.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "map/map_energy.h"

namespace mcon {

enum class StopReason {
  converged,      // decrease (or predicted decrease) below the tolerance
  stalled,        // the line search found no acceptable step
  iteration_cap,  // max_iterations reached
  cancelled       // the callback asked to stop
};

const char* stop_reason_name(StopReason reason);

struct NewtonOptions {
  int max_iterations = 100;
  // Stop when an iteration decreases the energy (or the Newton model predicts a decrease) by at
  // most relative_decrease * max(|E_0|, energy_scale) + absolute_decrease, E_0 the energy at the
  // start: relative to the problem's scale, not to the (possibly tiny) current energy, whose tail
  // the kinks of the piecewise-linear descriptor make converge only linearly. Later levels of a
  // coarse-to-fine run pass the first level's start energy as energy_scale.
  double relative_decrease = 1e-6;
  double absolute_decrease = 1e-12;  // (energies are area-normalized: O(1e-4 .. 1))
  double energy_scale = 0;           // if larger than |E_0|, the tolerance is relative to it
  // Also stop (converged) when the last progress_window iterations together decreased the energy
  // by at most progress_fraction of this run's decrease so far: past that point the descriptor's
  // kinks only allow slow linear progress whose gain is far below the map's accuracy, and on fine
  // meshes (10k vertices) that tail was most of the time (subdivided face: 59 of 76 iterations at
  // the finest level, 9.7 s; with 5 / 3e-3: 30 iterations; eval-mapping mean eps x 100 on seeds
  // 1, 2, 3 unchanged to +-0.03). progress_window 0 disables the test.
  int progress_window = 5;
  double progress_fraction = 3e-3;
  double armijo = 1e-4;
  int max_backtracks = 40;
  double step_fraction = 0.9;       // first trial step = min(1, step_fraction * t_max)
  double regularization = 1e-8;     // diagonal shift, relative to the mean diagonal entry
  // Inexact Newton: while a factorization is at hand, the step solves the current system by
  // conjugate gradients preconditioned with it, to a residual of inexact_tolerance |g| within
  // max_inner_iterations; only if that fails is the current Hessian factorized. Factorizing is
  // most of a map's time (docs/design.md §13). false: factorize every iteration.
  bool reuse_factorization = true;
  double inexact_tolerance = 0.1;
  int max_inner_iterations = 10;
};

struct NewtonReport {
  int iterations = 0;
  StopReason reason = StopReason::iteration_cap;
  std::vector<double> energy;       // energy[0] at the start, energy[k] after iteration k
  MapEnergyTerms terms;             // at the returned x
  int factorizations = 0;           // numeric factorizations of the Hessian
  int inner_iterations = 0;         // preconditioned conjugate-gradient iterations
};

// What one minimization leaves for the next on the same source disk (the stages of a
// coarse-to-fine run): the Hessian's pattern and symbolic analysis, and the last factorization,
// which then preconditions the next run's first steps (NewtonOptions::reuse_factorization).
// Empty until a run has used it; a run on another disk starts afresh.
class NewtonWarmStart {
 public:
  NewtonWarmStart();
  ~NewtonWarmStart();
  NewtonWarmStart(NewtonWarmStart&&) noexcept;
  NewtonWarmStart& operator=(NewtonWarmStart&&) noexcept;
  struct State;
  std::unique_ptr<State> state;
};

// Minimizes energy from x (which must have no inverted triangle) in place. keep_going(iteration,
// energy) runs on the calling thread after every iteration; returning false stops with
// StopReason::cancelled (x is then the last accepted iterate). Throws NUMERICAL if the start is
// infeasible or the linear solve keeps failing.
// `warm`, if given, is read at the start and holds this run's factorization at the end.
NewtonReport minimize_map_energy(const MapEnergy& energy, Eigen::VectorXd& x, const NewtonOptions& options,
                                 const std::function<bool(int, double)>& keep_going = {},
                                 NewtonWarmStart* warm = nullptr);

}  // namespace mcon
