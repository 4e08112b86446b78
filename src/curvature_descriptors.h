// Curvature descriptors (thesis §3.1): the shape operator integrated with a Gaussian kernel of
// geodesic width sigma, then its principal curvatures. The per-edge shape operator follows
// Cohen-Steiner & Morvan (normal cycle): beta_e |e| e e^T; the geodesic Gaussian integration is
// done by heat diffusion for time sigma^2 / 2 (the heat kernel is that Gaussian to first order).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mesh.h"

namespace mcon {

struct PrincipalCurvatures {
  Eigen::VectorXd k1;  // larger principal curvature, per vertex
  Eigen::VectorXd k2;  // smaller principal curvature
  Eigen::VectorXd mean() const { return 0.5 * (k1 + k2); }
  Eigen::VectorXd gaussian() const { return k1.cwiseProduct(k2); }
  Eigen::VectorXd abs_max() const { return k1.cwiseAbs().cwiseMax(k2.cwiseAbs()); }
};

// Principal curvatures smoothed at geodesic scale sigma (mesh units). Positive mean curvature is
// convex with respect to the triangles' outward (counter-clockwise) normals, so a sphere has
// H = +1/R.
PrincipalCurvatures smoothed_principal_curvatures(const TriMesh& mesh, double sigma);

// CURV9 per vertex (rows), in the order K, H, |k|max for sigma = 0.025, 0.05, 0.1 (columns 0..8).
// Intended for patches normalized to geodesic radius 1.
Eigen::MatrixXd curv9_descriptor(const TriMesh& mesh);

// Mean curvature at sigma = 0.1: the re-embedding descriptor (thesis ch. 4).
Eigen::VectorXd mean_curvature_descriptor(const TriMesh& mesh);

}  // namespace mcon
