// Curvature descriptors (thesis §3.1): the shape operator integrated with a Gaussian kernel of
// geodesic width sigma, then its principal curvatures. The per-edge shape operator follows
// Cohen-Steiner & Morvan (normal cycle): beta_e |e| e e^T; the geodesic Gaussian integration is
// done by heat diffusion for time sigma^2 / 2 (the heat kernel is that Gaussian to first order).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.h"

namespace mcon {

struct PrincipalCurvatures {
  Eigen::VectorXd k1;  // larger principal curvature, per vertex
  Eigen::VectorXd k2;  // smaller principal curvature
  Eigen::VectorXd mean() const { return 0.5 * (k1 + k2); }
  Eigen::VectorXd gaussian() const { return k1.cwiseProduct(k2); }
  Eigen::VectorXd abs_max() const { return k1.cwiseAbs().cwiseMax(k2.cwiseAbs()); }
};

// How an open patch boundary was made, which decides what the folds missing along it are
// (curvature_descriptors.cpp explains; measured in tests/core/test_curvature_descriptors.cpp).
enum class PatchBoundary {
  // Cut exactly along an iso-line (extract_geodesic_disk): boundary edges lie inside flat host
  // triangles, so the fold along them is 0 and the patch's folds are the host's, restricted.
  kCutThroughTriangles,
  // Made of whole host faces (face selection, as the thesis' and the benchmark's patch files):
  // boundary edges are host edges whose fold is lost; it is filled in by normalized convolution.
  kAlongHostEdges,
};

// Principal curvatures smoothed at geodesic scale sigma (mesh units; 0 = the per-vertex estimate).
// Positive mean curvature is convex with respect to the triangles' outward (counter-clockwise)
// normals, so a sphere has H = +1/R. Per vertex: the edge tensors of Cohen-Steiner & Morvan as a
// density, heat-diffused for time sigma^2 / 2 (4 backward-Euler substeps), projected onto the
// tangent plane of the area-weighted vertex normal; k1 >= k2 are its two tangential eigenvalues.
// Throws mcon::Error(INVALID_ARGUMENT) for a negative or non-finite sigma.
PrincipalCurvatures smoothed_principal_curvatures(const TriMesh& mesh, double sigma,
                                                  PatchBoundary boundary = PatchBoundary::kCutThroughTriangles);

// CURV9 per vertex (rows), in the order K, H, |k|max for sigma = 0.025, 0.05, 0.1 (columns 0..8).
// Intended for patches normalized to geodesic radius 1. The edge tensors are built once.
Eigen::MatrixXd curv9_descriptor(const TriMesh& mesh, PatchBoundary boundary = PatchBoundary::kCutThroughTriangles);

// Mean curvature at sigma = 0.1: the re-embedding descriptor (thesis ch. 4).
Eigen::VectorXd mean_curvature_descriptor(const TriMesh& mesh,
                                          PatchBoundary boundary = PatchBoundary::kCutThroughTriangles);

}  // namespace mcon
