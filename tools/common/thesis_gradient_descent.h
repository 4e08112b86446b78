// BASELINE, not the product: the thesis' own non-linear map optimization (macro-constraints-thesis
// ch. 4, §4.2-4.3.2 and §4.4 "Parameter Choice"), kept only so that `macrocon-eval eval-mapping` can
// compare the SDK's map (src/surface_map.h) against it in one run. Deliberately faithful,
// including its known defects:
//  - objective eq. 4.15: alpha_d * obj_descr (4.8) + alpha_l * obj_lscm (4.10) + alpha_f * obj_flip (4.12);
//  - obj_descr: the descriptor distance field d(v, w) = |I_S(v) - I_T(w)| of each source vertex
//    interpolated linearly in the target triangle under phi(v) (§4.2.1), 0 outside the overlap;
//    the "vertex case" of §4.3.2 (gradient 0 near a target vertex that is a local minimum);
//  - obj_lscm: LSCM of J_Phi = J_g^-1 J_phi J_f per triangle corner, with J_g^-1 constant per
//    target triangle (so the objective jumps at every target edge, C0-discontinuous), and LSCM of
//    J_phi alone for corners outside the target;
//  - obj_flip: max(0, -log(det J_phi / s_f)) per triangle, weighted by its 3D area;
//  - fixed-step gradient descent: the longest 2D vertex update is scaled to lambda_bar times the
//    mean edge length of g(T) (never scaled up), halved while any triangle would invert
//    (exponential back-off), a fixed number of iterations (15,000) since the thesis could not
//    detect convergence.
// Parameters (§4.4): alpha_d = 1, alpha_l = 10, alpha_f = 10000 (the value the thesis needed to
// keep the descent from getting stuck at the barrier), s_f = 0.5, lambda_bar = 0.05.
// Gradients are the exact piecewise gradients of the discretized objective (J_g^-1 held fixed
// inside a target triangle). Bit-identical for any thread count (fixed blocks, gathers).
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace mcon::tools {

struct ThesisDescentOptions {
  int iterations = 15000;
  double alpha_descriptor = 1.0;
  double alpha_lscm = 10.0;
  double alpha_flip = 10000.0;
  double barrier_start = 0.5;  // s_f
  double step_scale = 0.05;    // lambda_bar (times the mean edge length of g(T))
  int max_backoffs = 30;
  double vertex_case_epsilon = 1e-3;  // relative to the mean edge length of g(T)
};

struct ThesisDescentResult {
  std::vector<Vec2> phi;      // per source vertex
  int iterations = 0;         // iterations run (all of them: the method has no stopping rule)
  int rejected_steps = 0;     // iterations whose step stayed infeasible after all back-offs
  double seconds = 0;
};

// source/target: 3D patches with their unit-disk parametrizations f (source_uv) and g
// (target_uv); descriptors: one scalar per vertex (the thesis' mean curvature at sigma 0.1).
// start: phi(f(v)) per source vertex after the rigid initialization; if `reflected`, the start is
// orientation reversing and the source triangles are used with reversed corner order (as the
// thesis' half-edge implementation flips elements). Throws mcon::Error(INVALID_ARGUMENT) on
// inconsistent sizes and NUMERICAL if the start has inverted triangles.
ThesisDescentResult thesis_gradient_descent(const TriMesh& source, const std::vector<Vec2>& source_uv,
                                            const Eigen::VectorXd& source_descriptor, const TriMesh& target,
                                            const std::vector<Vec2>& target_uv,
                                            const Eigen::VectorXd& target_descriptor, const std::vector<Vec2>& start,
                                            bool reflected, const ThesisDescentOptions& options = {});

}  // namespace mcon::tools
