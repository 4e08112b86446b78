// Coarse-to-fine descriptor levels for the re-embedding optimization (docs/design.md §2): the same
// per-vertex descriptor smoothed by heat diffusion at several geodesic scales, smoothest first.
// A smooth descriptor has few local minima, so the optimizer first aligns the broad shape and
// then the details (thesis §4.4 found smoothness decisive).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace mcon {

// One level per entry of `sigmas` (mesh units, in the given order; pass them decreasing): the
// values heat-diffused for time sigma^2 / 2 (HeatSmoother: the geodesic Gaussian of width sigma).
// sigma = 0 returns the values unchanged.
// Throws INVALID_ARGUMENT (row count, negative sigma), NON_FINITE, NUMERICAL.
std::vector<Eigen::MatrixXd> descriptor_pyramid(const TriMesh& mesh, const Eigen::MatrixXd& values,
                                                const std::vector<double>& sigmas);

}  // namespace mcon
