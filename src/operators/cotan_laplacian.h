// The cotangent Laplacian and the lumped (barycentric) mass matrix: the discrete operators behind
// heat geodesics and descriptor smoothing.
#pragma once

#include <Eigen/Sparse>

#include "mesh/mesh.h"

namespace mcon {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Positive semi-definite cotan Laplacian: L_ij = -(cot a_ij + cot b_ij) / 2, L_ii = -sum_j L_ij.
SparseMatrix cotan_laplacian(const TriMesh& mesh);

// Diagonal lumped mass: one third of the area of each incident triangle.
Eigen::VectorXd vertex_areas(const TriMesh& mesh);

}  // namespace mcon
